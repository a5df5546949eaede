#include "surfcomp/screening/screen.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/protein_lipophilicity.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/principal_axes.hpp"
#include "surfcomp/matching/site.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <tuple>
#include <utility>

namespace surfcomp::screening {
namespace {

HitScore from_overlay(const matching::OverlayScore& s, const Eigen::Matrix4d& transform) {
  HitScore hit;
  hit.score = s.score;
  hit.shape = s.shape;
  hit.chem = s.chem;
  hit.atoms = s.atoms;
  hit.transform = transform;
  return hit;
}

/// A CSV field: quoted (inner quotes doubled) when it holds a comma, quote or line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

/// %.6f of a value, with -0.000000 written as 0.000000 so that equal results give equal bytes.
std::string fixed(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", value);
  std::string s = text;
  if (s == "-0.000000") s = "0.000000";
  return s;
}

/// score(i) for i in [0, count), in parallel into slots, reporting progress as `stage`.
template <class Score>
std::vector<HitScore> score_in_parallel(std::size_t count, int stage, const ScreenOptions& options,
                                        const Score& score) {
  std::vector<HitScore> scores(count);
  const auto total = static_cast<std::int64_t>(count);
  std::atomic<std::int64_t> done{0};
  tbb::parallel_for(std::size_t{0}, count, [&](std::size_t i) {
    scores[i] = score(i);
    if (options.progress) options.progress(stage, ++done, total);
  });
  if (options.progress) options.progress(stage, total, total);
  return scores;
}

/// The query's packed sample of an entry's kind.
const matching::PackedQuery& packed_query(const ScreenQuery& query, matching::SampleKind kind) {
  return kind == matching::SampleKind::atoms ? *query.atom_packed : *query.packed;
}

/// The overlay options of the query's mode.
matching::OverlayOptions overlay_options(const ScreenQuery& query, const ScreenOptions& options) {
  return matching::mode_overlay_options(query_match_options(query, options));
}

/// An entry's packed sample, or `sample` and `atoms` packed now.
matching::PackedSample packed_entry(const LibraryEntry& entry, double sigma) {
  if (entry.packed.header().points > 0 && entry.packed.header().sigma == sigma) return entry.packed;
  return matching::PackedSample(entry.sample, entry.atoms, sigma, entry.kind);
}

/// The molecules of a library (entries sharing source, record and name; not necessarily
/// adjacent), each as its entries in index order, the molecules in order of their first entry.
std::vector<std::vector<std::size_t>> molecules(const Library& library) {
  std::map<std::tuple<std::string, std::uint32_t, std::string>, std::size_t> index;
  std::vector<std::vector<std::size_t>> out;
  for (std::size_t e = 0; e < library.size(); ++e) {
    const LibraryEntryInfo& info = library.info(e);
    const auto [it, inserted] =
        index.emplace(std::make_tuple(info.source, info.record, info.name), out.size());
    if (inserted) out.emplace_back();
    out[it->second].push_back(e);
  }
  return out;
}

void check_score_count(const Library& library, std::size_t count, const char* function) {
  if (count != library.size()) {
    throw InputError(std::string(function) + ": " + std::to_string(count) +
                     " scores for a library of " + std::to_string(library.size()) + " entries");
  }
}

}  // namespace

void check_library_kind(const Library& library, bool site_query) {
  for (std::size_t e = 0; e < library.size(); ++e) {
    const bool site_entry = library.info(e).site_spheres > 0;
    if (site_entry != site_query) {
      throw InputError(library.path().string() + ": entry " + std::to_string(e + 1) + " (" +
                       library.info(e).name + ") is " +
                       (site_entry ? "a binding site: a pocket library needs a site query "
                                     "(--site-ligand or --site-sphere)"
                                   : "a molecule: a site query needs a pocket library "
                                     "(library build --sites)"));
    }
  }
}

matching::MatchOptions query_match_options(const ScreenQuery& query, const ScreenOptions& options) {
  matching::MatchOptions match = options.match;
  match.mode =
      query.site.empty() ? matching::MatchMode::whole_surfaces : matching::MatchMode::binding_sites;
  return match;
}

std::string macromolecule_query_warning(const Molecule& query, const std::string& source) {
  std::size_t heavy = 0;
  std::map<std::string, std::set<std::pair<int, std::string>>> chain_residues;
  for (const Atom& atom : query.atoms) {
    if (atom.element != "H") ++heavy;
    if (protein_atom_lipophilicity(atom.residue_name, "CA"))
      chain_residues[atom.chain].emplace(atom.residue_number, atom.residue_name);
  }
  std::size_t longest = 0;
  for (const auto& [chain, residues] : chain_residues) longest = std::max(longest, residues.size());
  if (heavy <= macromolecule_heavy_atoms && longest < macromolecule_chain_residues) return {};
  return source + ": the query is a macromolecule (" + std::to_string(heavy) + " heavy atoms" +
         (longest >= macromolecule_chain_residues
              ? ", a chain of " + std::to_string(longest) + " amino-acid residues"
              : std::string()) +
         "): its whole surface is compared with the library's molecules";
}

ScreenQuery make_screen_query(harmonic::SurfaceDescriptors descriptors,
                              const ScreenOptions& options, std::vector<matching::SiteSphere> site,
                              const Molecule* molecule) {
  ScreenQuery query;
  query.site = std::move(site);
  const matching::OverlayOptions overlay =
      matching::mode_overlay_options(query_match_options(query, options));
  if (query.site.empty()) {
    query.sample = matching::sample_surface(descriptors.surface, overlay.spacing);
    query.atoms = matching::sample_atoms(descriptors.atoms);
  } else {
    query.site_points = matching::critical_points_in_site(descriptors, query.site);
    const std::vector<bool> lining =
        matching::pocket_lining(descriptors, &query.site_points, options.match.site.overlay_radius);
    query.sample = matching::sample_surface(descriptors.surface, overlay.spacing, &lining);
  }
  if (query.sample.size() == 0) {
    throw InputError(descriptors.surface.source() + (query.site.empty()
                                                         ? ": the query's surface has no vertex"
                                                         : ": the query site's pocket lining has "
                                                           "no vertex"));
  }
  query.atom_sample = molecule != nullptr && query.site.empty()
                          ? matching::sample_molecule(*molecule, overlay.spacing, options.surface)
                          : query.sample;
  if (query.atom_sample.size() == 0) query.atom_sample = query.sample;
  query.packed = std::make_shared<const matching::PackedQuery>(matching::PackedSample(
      query.sample, query.atoms, overlay.sigma, matching::SampleKind::surface));
  query.atom_packed = std::make_shared<const matching::PackedQuery>(matching::PackedSample(
      query.atom_sample, query.atoms, overlay.sigma, matching::SampleKind::atoms));
  query.descriptors = std::move(descriptors);
  return query;
}

HitScore fast_score(const ScreenQuery& query, const matching::PackedSampleView& entry,
                    const ScreenOptions& options) {
  if (entry.header.points == 0) return {};
  const matching::PackedQuery::Score best =
      packed_query(query, entry.header.kind)
          .fast_score(entry, overlay_options(query, options), !query.site.empty());
  return from_overlay(best.score, best.transform.matrix());
}

HitScore fast_score(const ScreenQuery& query, const LibraryEntry& entry,
                    const ScreenOptions& options) {
  if (entry.sample.size() == 0 && entry.packed.header().points == 0) return {};
  return fast_score(query, packed_entry(entry, overlay_options(query, options).sigma).view(),
                    options);
}

HitScore refined_score(const ScreenQuery& query, const matching::PackedSampleView& entry,
                       const ScreenOptions& options) {
  if (entry.header.points == 0) return {};
  const matching::OverlayOptions overlay = overlay_options(query, options);
  const matching::PackedQuery& packed = packed_query(query, entry.header.kind);
  const std::vector<matching::PackedQuery::Score> starts =
      packed.start_scores(entry, overlay, !query.site.empty());
  std::vector<std::size_t> order(starts.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return starts[x].score.score > starts[y].score.score;
  });
  const std::size_t refined =
      options.refine_starts == 0 ? starts.size() : std::min(options.refine_starts, starts.size());
  HitScore best = from_overlay(starts[order[0]].score, starts[order[0]].transform.matrix());
  // In start order, so that ties go to the earlier start whatever refine_starts is.
  std::sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(refined));
  for (std::size_t k = 0; k < refined; ++k) {
    const matching::RefineResult r = packed.refine(entry, starts[order[k]].transform, overlay);
    if (r.score.score > best.score) best = from_overlay(r.score, r.transform.matrix());
  }
  return best;
}

HitScore refined_score(const ScreenQuery& query, const LibraryEntry& entry,
                       const ScreenOptions& options) {
  if (entry.sample.size() == 0 && entry.packed.header().points == 0) return {};
  return refined_score(query, packed_entry(entry, overlay_options(query, options).sigma).view(),
                       options);
}

std::vector<HitScore> fast_scores(const ScreenQuery& query, const Library& library,
                                  std::size_t begin, std::size_t end,
                                  const ScreenOptions& options) {
  check_library_kind(library, !query.site.empty());
  end = std::min(end, library.size());
  begin = std::min(begin, end);
  const double sigma = overlay_options(query, options).sigma;
  return score_in_parallel(end - begin, 1, options, [&](std::size_t i) {
    return fast_score(query, library.packed(begin + i, sigma).view, options);
  });
}

std::vector<std::size_t> entries_to_refine(const Library& library,
                                           const std::vector<HitScore>& fast,
                                           std::size_t per_molecule) {
  check_score_count(library, fast.size(), "entries_to_refine");
  std::vector<std::size_t> chosen;
  for (std::vector<std::size_t>& entries : molecules(library)) {
    const std::size_t k = std::min(per_molecule, entries.size());
    std::partial_sort(entries.begin(), entries.begin() + static_cast<std::ptrdiff_t>(k),
                      entries.end(), [&](std::size_t x, std::size_t y) {
                        if (fast[x].score != fast[y].score) return fast[x].score > fast[y].score;
                        return x < y;
                      });
    chosen.insert(chosen.end(), entries.begin(), entries.begin() + static_cast<std::ptrdiff_t>(k));
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

std::vector<EntryScore> merge_refined(const std::vector<HitScore>& fast,
                                      const std::vector<std::size_t>& refined_entries,
                                      const std::vector<HitScore>& refined) {
  if (refined.size() != refined_entries.size()) {
    throw InputError("merge_refined: " + std::to_string(refined.size()) + " scores for " +
                     std::to_string(refined_entries.size()) + " refined entries");
  }
  std::vector<EntryScore> scores(fast.size());
  for (std::size_t e = 0; e < fast.size(); ++e) scores[e] = {fast[e], 1, fast[e].score};
  for (std::size_t i = 0; i < refined_entries.size(); ++i) {
    if (refined_entries[i] >= scores.size()) {
      throw InputError("merge_refined: entry " + std::to_string(refined_entries[i]) +
                       " of a library of " + std::to_string(scores.size()) + " entries");
    }
    EntryScore& s = scores[refined_entries[i]];
    if (refined[i].score >= s.score.score) s.score = refined[i];
    s.stage = 2;
  }
  return scores;
}

std::vector<std::size_t> best_entry_per_molecule(const Library& library,
                                                 const std::vector<EntryScore>& scores) {
  check_score_count(library, scores.size(), "best_entry_per_molecule");
  const auto score = [&](std::size_t e) { return scores[e].score.score; };
  std::vector<std::size_t> best;
  for (const std::vector<std::size_t>& entries : molecules(library)) {
    best.push_back(
        *std::min_element(entries.begin(), entries.end(), [&](std::size_t x, std::size_t y) {
          if (score(x) != score(y)) return score(x) > score(y);
          return x < y;
        }));
  }
  std::sort(best.begin(), best.end(), [&](std::size_t x, std::size_t y) {
    if (score(x) != score(y)) return score(x) > score(y);
    return x < y;
  });
  return best;
}

HitScore full_score(const ScreenQuery& query, const LibraryEntry& entry,
                    const ScreenOptions& options) {
  const matching::MatchOptions match = query_match_options(query, options);
  matching::MatchResult result;
  if (!entry.surface.empty()) {  // from a .hsi file: describe its stored surface
    harmonic::SurfaceDescriptors stored =
        harmonic::io::decode_hsi(entry.surface, entry.info.source + " (library entry)");
    harmonic::SurfaceDescriptors described =
        harmonic::describe_surface(std::move(stored.surface), query.descriptors.options);
    described.atoms = std::move(stored.atoms);
    result = matching::match_surfaces(query.descriptors, described, match);
  } else if (entry.site.empty()) {
    const Molecule molecule = io::read_record_molecule(entry.molecule, options.read);
    const harmonic::SurfaceDescriptors described =
        harmonic::describe_surface(mesh::build_molecular_surface(molecule, options.surface),
                                   molecule, query.descriptors.options);
    result = matching::match_surfaces(query.descriptors, described, match);
  } else {
    matching::BindingSite site;
    site.structure = io::read_record_molecule(entry.molecule, options.read);
    site.spheres = entry.site;
    site.surface_margin = matching::site_surface_margin(options.site.surface_margin,
                                                        query.descriptors.options.patch.radius);
    const harmonic::SurfaceDescriptors described =
        matching::describe_site(matching::build_site_surface(site, options.surface), site.structure,
                                entry.site, query.descriptors.options);
    const std::vector<bool> in_site = matching::critical_points_in_site(described, entry.site);
    result =
        matching::match_surfaces(query.descriptors, described, match, &query.site_points, &in_site);
  }
  if (result.alignments.empty()) return {};
  const matching::Alignment& top = result.alignments.front();
  return from_overlay(top.overlay, top.transform);
}

std::vector<Hit> rank_hits(const std::vector<std::size_t>& best,
                           const std::vector<EntryScore>& scores, const std::vector<HitScore>& full,
                           std::size_t top) {
  const std::size_t k = std::min(full.size(), best.size());
  std::vector<Hit> candidates;
  for (std::size_t i = 0; i < k; ++i)
    candidates.push_back({best[i], 3, full[i], scores[best[i]].fast_score});
  std::sort(candidates.begin(), candidates.end(), [](const Hit& x, const Hit& y) {
    if (x.score.score != y.score.score) return x.score.score > y.score.score;
    return x.entry < y.entry;
  });
  std::vector<Hit> hits = std::move(candidates);
  for (std::size_t i = k; i < best.size(); ++i) {
    const EntryScore& s = scores[best[i]];
    hits.push_back({best[i], s.stage, s.score, s.fast_score});
  }
  if (top > 0 && hits.size() > top) hits.resize(top);
  return hits;
}

ScreenResult screen(const ScreenQuery& query, const Library& library,
                    const ScreenOptions& options) {
  matching::validate(query_match_options(query, options));
  ScreenResult result;
  const Stopwatch clock;
  const std::vector<HitScore> fast = fast_scores(query, library, 0, library.size(), options);
  result.stage1_seconds = clock.elapsed_s();

  const std::vector<std::size_t> to_refine = entries_to_refine(library, fast, options.refine);
  const double sigma = overlay_options(query, options).sigma;
  const std::vector<HitScore> refined =
      score_in_parallel(to_refine.size(), 2, options, [&](std::size_t i) {
        return refined_score(query, library.packed(to_refine[i], sigma).view, options);
      });
  const std::vector<EntryScore> scores = merge_refined(fast, to_refine, refined);
  const std::vector<std::size_t> best = best_entry_per_molecule(library, scores);
  result.stage2_seconds = clock.elapsed_s() - result.stage1_seconds;

  const std::vector<HitScore> full = score_in_parallel(
      std::min(options.candidates, best.size()), 3, options,
      [&](std::size_t i) { return full_score(query, library.entry(best[i]), options); });
  result.stage3_seconds = clock.elapsed_s() - result.stage1_seconds - result.stage2_seconds;
  result.hits = rank_hits(best, scores, full, options.top);
  return result;
}

void write_hits_csv(std::ostream& out, const Library& library, const std::vector<Hit>& hits) {
  out << "rank,entry,name,source,record,conformer,score,stage,shape,chem,atoms,fast_score";
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out << ",t" << r << c;
  }
  out << "\n";
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const Hit& hit = hits[i];
    const LibraryEntryInfo& info = library.info(hit.entry);
    out << i + 1 << ',' << hit.entry + 1 << ',' << csv_field(info.name) << ','
        << csv_field(info.source) << ',' << info.record << ',' << info.conformer << ','
        << fixed(hit.score.score) << ',' << hit.stage << ',' << fixed(hit.score.shape) << ','
        << fixed(hit.score.chem) << ',' << fixed(hit.score.atoms) << ',' << fixed(hit.fast_score);
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) out << ',' << fixed(hit.score.transform(r, c));
    }
    out << "\n";
  }
}

}  // namespace surfcomp::screening
