#include "surfcomp/screening/hit_files.hpp"

#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/write_molecule.hpp"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace surfcomp::screening {
namespace {

std::string score_text(double score) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6f", score);
  return text;
}

}  // namespace

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

std::string aligned_hit_record(const Library& library, const Hit& hit, std::size_t rank) {
  const LibraryEntry entry = library.entry(hit.entry);
  const Eigen::Matrix3d rotation = hit.score.transform.topLeftCorner<3, 3>();
  const Eigen::Vector3d translation = hit.score.transform.topRightCorner<3, 1>();
  std::ostringstream out;
  out << io::moved_record_block(entry.molecule, rotation, translation) << ">  <surfcomp_rank>\n"
      << rank << "\n\n"
      << ">  <surfcomp_entry>\n"
      << hit.entry + 1 << "\n\n"
      << ">  <surfcomp_name>\n"
      << entry.info.name << "\n\n"
      << ">  <surfcomp_conformer>\n"
      << entry.info.conformer << "\n\n"
      << ">  <surfcomp_score>\n"
      << score_text(hit.score.score) << "\n\n$$$$\n";
  return out.str();
}

void write_aligned_hits_sdf(std::ostream& out, const Library& library, const std::vector<Hit>& hits,
                            std::size_t count) {
  for (std::size_t i = 0; i < hits.size() && i < count; ++i)
    out << aligned_hit_record(library, hits[i], i + 1);
}

std::string aligned_site_model(const Library& library, const Hit& hit, std::size_t rank,
                               const io::MoleculeReadOptions& read) {
  const LibraryEntry entry = library.entry(hit.entry);
  Molecule structure = io::read_record_molecule(entry.molecule, site_entry_read_options(read));
  const Eigen::Matrix3d rotation = hit.score.transform.topLeftCorner<3, 3>();
  const Eigen::Vector3d translation = hit.score.transform.topRightCorner<3, 1>();
  for (Atom& atom : structure.atoms) atom.position = rotation * atom.position + translation;
  std::ostringstream pdb;
  io::write_pdb(structure, pdb);
  std::string text = pdb.str();
  if (text.size() >= 4 && text.compare(text.size() - 4, 4, "END\n") == 0)
    text.resize(text.size() - 4);
  std::ostringstream out;
  out << "MODEL     " << std::setw(4) << rank << "\nREMARK   1 surfcomp rank " << rank << " entry "
      << hit.entry + 1 << " " << entry.info.name << " score " << score_text(hit.score.score) << "\n"
      << text << "ENDMDL\n";
  return out.str();
}

void write_aligned_sites_pdb(std::ostream& out, const Library& library,
                             const std::vector<Hit>& hits, std::size_t count,
                             const io::MoleculeReadOptions& read) {
  for (std::size_t i = 0; i < hits.size() && i < count; ++i)
    out << aligned_site_model(library, hits[i], i + 1, read);
  out << "END\n";
}

void write_library_sdf(std::ostream& out, const Library& library) {
  for (std::size_t e = 0; e < library.size(); ++e) {
    const LibraryEntry entry = library.entry(e);
    out << io::moved_record_block(entry.molecule, Eigen::Matrix3d::Identity(),
                                  Eigen::Vector3d::Zero())
        << ">  <surfcomp_entry>\n"
        << e + 1 << "\n\n"
        << ">  <surfcomp_name>\n"
        << entry.info.name << "\n\n"
        << ">  <surfcomp_conformer>\n"
        << entry.info.conformer << "\n\n$$$$\n";
  }
}

LibrarySummary summarize_library(const Library& library) {
  LibrarySummary summary;
  summary.entries = library.size();
  summary.file_bytes = library.file_bytes();
  for (std::size_t e = 0; e < library.size(); ++e) {
    ++summary.entries_per_source[library.info(e).source];
    summary.largest_entry_bytes = std::max(summary.largest_entry_bytes, library.entry_bytes(e));
  }
  for (std::size_t e = 0; e < library.size(); e = molecule_start_at(library, e + 1))
    ++summary.molecules;
  return summary;
}

}  // namespace surfcomp::screening
