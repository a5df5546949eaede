// The hit tables of a screen, as CSV.
#include "surfcomp/screening/receptor_screen.hpp"
#include "surfcomp/screening/screen.hpp"

#include "surfcomp/screening/hit_files.hpp"

#include <cstdio>
#include <ostream>
#include <string>

namespace surfcomp::screening {
namespace {

/// %.6f of a value, with -0.000000 written as 0.000000 so that equal results give equal bytes.
std::string fixed(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", value);
  std::string s = text;
  if (s == "-0.000000") s = "0.000000";
  return s;
}

/// The first columns of a row of hits: rank, entry (1-based), name, source, record, conformer,
/// each followed by a comma.
void write_entry_columns(std::ostream& out, const Library& library, std::size_t rank,
                         std::size_t entry) {
  const LibraryEntryInfo info = library.info(entry);
  out << rank << ',' << entry + 1 << ',' << csv_field(info.name) << ',' << csv_field(info.source)
      << ',' << info.record << ',' << info.conformer << ',';
}

}  // namespace

void write_hits_csv(std::ostream& out, const Library& library, const std::vector<Hit>& hits) {
  out << "rank,entry,name,source,record,conformer,score,stage,shape,chem,atoms,fast_score";
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out << ",t" << r << c;
  }
  out << "\n";
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const Hit& hit = hits[i];
    write_entry_columns(out, library, i + 1, hit.entry);
    out << fixed(hit.score.score) << ',' << hit.stage << ',' << fixed(hit.score.shape) << ','
        << fixed(hit.score.chem) << ',' << fixed(hit.score.atoms) << ',' << fixed(hit.fast_score);
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) out << ',' << fixed(hit.score.transform(r, c));
    }
    out << "\n";
  }
}

void write_receptor_hits_csv(std::ostream& out, const Library& library,
                             const std::vector<ReceptorHit>& hits) {
  out << "rank,entry,name,source,record,conformer,score,stage,contact,clash,esp,lp,deepest,area,"
         "fast_score";
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out << ",t" << r << c;
  }
  out << "\n";
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const ReceptorHit& hit = hits[i];
    write_entry_columns(out, library, i + 1, hit.entry);
    out << fixed(hit.score.score) << ',' << hit.stage << ',' << fixed(hit.score.contact) << ','
        << fixed(hit.score.clash) << ',' << fixed(hit.score.esp) << ',' << fixed(hit.score.lp)
        << ',' << fixed(hit.score.deepest) << ',' << fixed(hit.area) << ','
        << fixed(hit.fast_score);
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) out << ',' << fixed(hit.transform(r, c));
    }
    out << "\n";
  }
}

void write_fused_csv(std::ostream& out, const Library& library,
                     const std::vector<FusedHit>& fused) {
  const std::size_t queries = fused.empty() ? 0 : fused.front().scores.size();
  out << "rank,entry,name,source,record,conformer,score,query";
  for (std::size_t q = 0; q < queries; ++q) out << ",score_" << q + 1;
  out << "\n";
  for (std::size_t i = 0; i < fused.size(); ++i) {
    const FusedHit& hit = fused[i];
    write_entry_columns(out, library, i + 1, hit.entry);
    out << fixed(hit.score) << ',' << hit.query + 1;
    for (const double score : hit.scores) out << ',' << fixed(score);
    out << "\n";
  }
}

}  // namespace surfcomp::screening
