// The three stages of a screen on a range of molecules: the fast score of every entry, the
// refinement of each molecule's best, the full match of a candidate; the checks of a library's
// entries as they are read.
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/screening/screen.hpp"

#include "screen_stages.hpp"

#include "surfcomp/screening/hit_files.hpp"
#include "surfcomp/screening/shape_screen.hpp"

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
#include <cstdlib>
#include <map>
#include <numeric>
#include <optional>
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

/// The query's packed sample of an entry's kind.
const matching::PackedQuery& packed_query(const ScreenQuery& query, matching::SampleKind kind) {
  return kind == matching::SampleKind::atoms ? *query.atom_packed : *query.packed;
}

/// The overlay options of stages 1 and 2: the query's mode's.
matching::OverlayOptions overlay_options(const ScreenQuery& query, const ScreenOptions& options) {
  return matching::mode_overlay_options(query_match_options(query, options));
}

/// An entry's packed sample, or `sample` and `atoms` packed now.
matching::PackedSample packed_entry(const LibraryEntry& entry, double sigma) {
  if (entry.packed.header().points > 0 && entry.packed.header().sigma == sigma) return entry.packed;
  return matching::PackedSample(entry.sample, entry.atoms, sigma, entry.kind);
}

/// Whether two entries are conformers of one molecule (name, source and record shared).
bool same_molecule(const LibraryEntryInfo& a, const LibraryEntryInfo& b) {
  return a.record == b.record && a.name == b.name && a.source == b.source;
}

/// Entries a block of stage 1 scores before its molecules are refined and its pages released.
constexpr std::size_t kBlockEntries = 1024;

/// The `count` best entries of [begin, end) by their fast score against query q (ties to the
/// lower index), in entry order; `fast` holds the block's scores from entry `block`, q_count per
/// entry.
std::vector<std::size_t> best_by_fast(const std::vector<HitScore>& fast, std::size_t q,
                                      std::size_t q_count, std::size_t block, std::size_t begin,
                                      std::size_t end, std::size_t count) {
  std::vector<std::size_t> entries(end - begin);
  std::iota(entries.begin(), entries.end(), begin);
  const std::size_t k = std::min(count, entries.size());
  const auto score = [&](std::size_t e) { return fast[(e - block) * q_count + q].score; };
  std::partial_sort(entries.begin(), entries.begin() + static_cast<std::ptrdiff_t>(k),
                    entries.end(), [&](std::size_t x, std::size_t y) {
                      if (score(x) != score(y)) return score(x) > score(y);
                      return x < y;
                    });
  entries.resize(k);
  std::sort(entries.begin(), entries.end());
  return entries;
}

/// Throws InputError naming the library when its site entries cannot give the site surfaces the
/// screen asks for. From format 5 an entry keeps its site's neighbourhood: the atoms within the
/// build's surface margin (molsurf::site_surface_margin of the settings' surface_margin and the
/// default patch radius) + molsurf::neighbourhood_beyond_margin of its spheres. A screen whose
/// margin is 0 (every atom) or wider would build its surface from a part of the structure.
void check_site_margin(const Library& library, double margin, double patch_radius) {
  if (library.version() < 5) return;  // whole structures
  const std::string& settings = library.settings();
  const std::string key = "surface_margin ";
  const std::size_t at = settings.find(key);
  if (at == std::string::npos) return;
  const double built =
      molsurf::site_surface_margin(std::strtod(settings.c_str() + at + key.size(), nullptr),
                                   harmonic::DescriptorOptions{}.patch.radius);
  if (built == 0.0) return;  // every atom kept
  const double asked = molsurf::site_surface_margin(margin, patch_radius);
  if (asked != 0.0 && asked <= built) return;
  char wanted[32] = "every atom";
  if (asked != 0.0) std::snprintf(wanted, sizeof wanted, "a %g A margin", asked);
  char text[200];
  std::snprintf(text, sizeof text,
                ": its sites keep the atoms within %g A of their spheres (a site margin of %g A); "
                "a site surface of %s needs a library built with that margin",
                built + molsurf::neighbourhood_beyond_margin, built, wanted);
  throw InputError(library.path().string() + text);
}

/// Throws InputError unless entry `e` of `library` (its index record `info`) is a binding site
/// when `site_query` and a molecule otherwise.
void check_entry_kind(const Library& library, std::size_t e, const LibraryEntryInfo& info,
                      bool site_query) {
  const bool site_entry = info.site_spheres > 0;
  if (site_entry == site_query) return;
  throw InputError(
      library.path().string() + ": entry " + std::to_string(e + 1) + " (" + info.name + ") is " +
      (site_entry ? "a binding site: a pocket library needs a site query (" +
                        options::named("site_ligand") + " or " + options::named("site_sphere") + ")"
                  : "a molecule: a site query needs a pocket library (built with " +
                        options::named("sites") + ")"));
}

}  // namespace

void check_library_kind(const Library& library, bool site_query) {
  if (is_mesh_library(library)) {
    throw InputError(library.path().string() +
                     ": a library of meshes: its query is a mesh, screened by shape "
                     "(screen_shapes)");
  }
  if (library.size() > 0) check_entry_kind(library, 0, library.info(0), site_query);
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

std::size_t molecule_start_at(const Library& library, std::size_t entry) {
  if (entry == 0 || entry >= library.size()) return std::min(entry, library.size());
  LibraryEntryInfo previous = library.info(entry - 1);
  for (; entry < library.size(); ++entry) {
    LibraryEntryInfo info = library.info(entry);
    if (!same_molecule(previous, info)) break;
    previous = std::move(info);
  }
  return entry;
}

std::size_t kept_molecules(const ScreenOptions& options) {
  return options.top == 0 ? 0 : std::max(options.top, options.candidates);
}

std::size_t fused_molecules(const ScreenOptions& options, std::size_t queries) {
  return options.top == 0 ? 0 : options.top + queries * options.candidates;
}

StreamedScores score_molecules(const std::vector<const ScreenQuery*>& queries,
                               const Library& library, std::size_t begin, std::size_t end,
                               const ScreenOptions& options) {
  if (queries.empty()) throw InputError("screen: no query");
  const bool sites = !queries.front()->site.empty();
  for (const ScreenQuery* query : queries) {
    if (query->site.empty() == sites)
      throw InputError("a screen's queries are all molecules or all binding sites");
    if (query->shape_weight != queries.front()->shape_weight)
      throw InputError(
          "a screen's queries are all ranked by one mix of shape and score "
          "(agree_on_chemistry)");
  }
  if (begin > end || end > library.size()) throw InputError("screen: entries outside the library");
  check_library_kind(library, sites);
  if (sites) {
    check_site_margin(library, options.site.surface_margin,
                      queries.front()->descriptors.options.patch.radius);
  }
  const std::size_t q_count = queries.size();
  const bool fusing = q_count > 1;
  const double shape_weight = queries.front()->shape_weight;
  const double sigma = overlay_options(*queries.front(), options).sigma;
  std::vector<KeptMolecules<KeptHit>> kept(q_count, KeptMolecules<KeptHit>(options, shape_weight));
  BestItems<FusedMolecule, BetterFused> fused(fused_molecules(options, q_count));
  StreamedScores result;
  result.queries.resize(q_count);
  const auto total = static_cast<std::int64_t>(end - begin);
  for (std::size_t e0 = begin; e0 < end;) {
    // The block: whole molecules from e0, until one would begin past kBlockEntries entries.
    std::vector<std::size_t> starts{e0};  // its molecules', then its end
    LibraryEntryInfo previous = library.info(e0);
    check_entry_kind(library, e0, previous, sites);
    std::size_t e1 = e0 + 1;
    for (; e1 < end; ++e1) {
      LibraryEntryInfo info = library.info(e1);
      if (!same_molecule(previous, info)) {
        if (e1 - e0 >= kBlockEntries) break;
        starts.push_back(e1);
      }
      check_entry_kind(library, e1, info, sites);
      previous = std::move(info);
    }
    starts.push_back(e1);
    const std::size_t molecules = starts.size() - 1;
    Stopwatch clock;
    // Stage 1: every entry of the block against every query, the block read from the file
    // once. A thread takes a run of one query's entries, so that the query's packed sample and
    // grid stay in its caches, not evicted by the other queries'.
    const std::size_t block = e1 - e0;
    std::vector<HitScore> fast(block * q_count);
    tbb::parallel_for(std::size_t{0}, block * q_count, [&](std::size_t i) {
      const std::size_t q = i / block, e = e0 + i % block;
      fast[(e - e0) * q_count + q] =
          fast_score(*queries[q], library.packed(e, sigma).view, options);
    });
    result.stage1_seconds += clock.elapsed_s();
    clock = Stopwatch();
    // Stage 2: each molecule's best conformers by fast score, refined.
    std::vector<std::pair<std::size_t, std::size_t>> chosen;  // (query, entry)
    for (std::size_t q = 0; q < q_count; ++q) {
      for (std::size_t m = 0; m < molecules; ++m) {
        for (const std::size_t e :
             best_by_fast(fast, q, q_count, e0, starts[m], starts[m + 1], options.refine))
          chosen.emplace_back(q, e);
      }
    }
    std::vector<HitScore> refined(chosen.size());
    tbb::parallel_for(std::size_t{0}, chosen.size(), [&](std::size_t i) {
      const auto [q, e] = chosen[i];
      refined[i] = refined_score(*queries[q], library.packed(e, sigma).view, options);
    });
    // Each molecule's best entry: fast scores, refined ones in their place where not lower.
    std::vector<Hit> scores(block * q_count);
    for (std::size_t e = e0; e < e1; ++e) {
      for (std::size_t q = 0; q < q_count; ++q) {
        const HitScore& f = fast[(e - e0) * q_count + q];
        scores[(e - e0) * q_count + q] = {e, 1, f, f.score};
      }
    }
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      const auto [q, e] = chosen[i];
      Hit& hit = scores[(e - e0) * q_count + q];
      if (refined[i].score >= hit.score.score) hit.score = refined[i];
      hit.stage = 2;
    }
    for (std::size_t m = 0; m < molecules; ++m) {
      std::vector<const Hit*> best(q_count, nullptr);
      MoleculeScores all{starts[m], {}};
      for (std::size_t q = 0; q < q_count; ++q) {
        for (std::size_t e = starts[m]; e < starts[m + 1]; ++e) {
          const Hit& hit = scores[(e - e0) * q_count + q];
          if (best[q] == nullptr || hit.score.score > best[q]->score.score) best[q] = &hit;
        }
        if (fusing)
          all.scores.push_back({best[q]->entry, ranking_score(best[q]->score, shape_weight)});
      }
      for (std::size_t q = 0; q < q_count; ++q) kept[q].add({*best[q], all});
      if (fusing) {
        const double score = fused_score(all.scores, options.fusion).first;
        fused.add({score, std::move(all)});
      }
    }
    result.stage2_seconds += clock.elapsed_s();
    library.release(e0, e1);
    if (options.progress) options.progress(1, static_cast<std::int64_t>(e1 - begin), total);
    e0 = e1;
  }
  std::map<std::size_t, MoleculeScores> needed;  // by molecule: library order, each once
  for (std::size_t q = 0; q < q_count; ++q) {
    for (KeptHit& kept_hit : kept[q].sorted()) {
      result.queries[q].best.push_back(kept_hit.hit);
      if (fusing) needed.emplace(kept_hit.all.molecule, std::move(kept_hit.all));
    }
  }
  for (FusedMolecule& molecule : fused.sorted())
    needed.emplace(molecule.all.molecule, std::move(molecule.all));
  for (auto& [molecule, all] : needed) result.molecules.push_back(std::move(all));
  return result;
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
        harmonic::describe_surface(molsurf::build_molecular_surface(molecule, options.surface),
                                   molecule, query.descriptors.options);
    result = matching::match_surfaces(query.descriptors, described, match);
  } else {
    molsurf::BindingSite site;
    site.structure =
        io::read_record_molecule(entry.molecule, site_entry_read_options(options.read));
    site.spheres = entry.site;
    site.surface_margin = molsurf::site_surface_margin(options.site.surface_margin,
                                                       query.descriptors.options.patch.radius);
    const harmonic::SurfaceDescriptors described =
        matching::describe_site(molsurf::build_site_surface(site, options.surface), site.structure,
                                entry.site, query.descriptors.options);
    const std::vector<bool> in_site = matching::critical_points_in_site(described, entry.site);
    result =
        matching::match_surfaces(query.descriptors, described, match, &query.site_points, &in_site);
    const auto lining = matching::lining_composition(site.structure, entry.site);
    if (!result.alignments.empty() && query.lining && lining) {
      const matching::Alignment& top = result.alignments.front();
      HitScore hit = from_overlay(top.overlay, top.transform);
      hit.score = matching::site_score(top.overlay.score,
                                       matching::lining_similarity(*query.lining, *lining),
                                       matching::shape_only_options(match).site.lining_weight);
      return hit;
    }
  }
  if (result.alignments.empty()) return {};
  const matching::Alignment& top = result.alignments.front();
  return from_overlay(top.overlay, top.transform);
}

}  // namespace surfcomp::screening
