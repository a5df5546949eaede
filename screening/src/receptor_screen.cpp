#include "surfcomp/screening/receptor_screen.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/screening/screen.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

namespace surfcomp::screening {
namespace {

/// The order of rows and poses: poses that do not intersect the receptor first, then by the
/// score, or by the score times the ligand's area (ReceptorRanking::total).
bool better(const ReceptorHit& a, const ReceptorHit& b, const ReceptorScreenOptions& options) {
  const bool ai = docking::intersects(a.score, options.dock.complementarity);
  const bool bi = docking::intersects(b.score, options.dock.complementarity);
  if (ai != bi) return !ai;
  if (options.ranking == ReceptorRanking::total)
    return a.score.score * a.area > b.score.score * b.area;
  return a.score.score > b.score.score;
}

/// The best optimum of a short search of the site with `entry`'s stored surface sample.
ReceptorHit fast_dock(const docking::DockSite& site, const LibraryEntry& entry,
                      const ReceptorScreenOptions& options) {
  const docking::LigandSample sample = docking::pooled_sample(entry.sample.points, entry.sample.esp,
                                                              entry.sample.lp, entry.info.name);
  docking::SearchOptions search = options.dock.search;
  search.chains = options.fast_chains;
  search.steps = options.fast_steps;
  ReceptorHit hit;
  hit.area = entry.sample.weights.sum();
  bool found = false;
  for (const docking::SearchedPose& p :
       docking::search_site(*site.field, sample, site.receptor.site, search)) {
    ReceptorHit candidate = hit;
    candidate.score = p.score;
    if (!found || better(candidate, hit, options)) {
      hit.score = p.score;
      hit.transform = p.pose.matrix();
      found = true;
    }
  }
  hit.fast_score = hit.score.score;
  return hit;
}

/// True when entries a and b are conformers of one molecule (one name, source and record).
bool same_molecule(const LibraryEntryInfo& a, const LibraryEntryInfo& b) {
  return std::tie(a.name, a.source, a.record) == std::tie(b.name, b.source, b.record);
}

}  // namespace

const options::Table<ReceptorScreenOptions>& receptor_screen_option_table() {
  using options::Kind;
  using R = ReceptorScreenOptions;
  static const options::Table<R> table = [] {
    options::Table<R> t;
    // A library holds the conformers, stage 2 keeps one pose of each candidate, and the
    // receptor is one structure read whole: the ligand file's and the meshes' options go.
    options::append(t, docking::dock_option_table(), [](auto& r) -> auto& { return r.dock; },
                    {"conformers", "conformer-seed", "poses", "local-only", "score-only", "record",
                     "ligand", "molecule", "repair", "scale", "unit"});
    t.push_back(options::field<R>(
        {"fast-chains", Kind::integer, "stage 1: Monte Carlo chains per conformer", "", 1, 10000},
        [](auto& r) -> auto& { return r.fast_chains; }));
    t.push_back(options::field<R>(
        {"fast-steps", Kind::integer, "stage 1: moves per chain", "", 0, 10000},
        [](auto& r) -> auto& { return r.fast_steps; }));
    t.push_back(options::field<R>(
        {"candidates", Kind::integer,
         "molecules, best stage-1 score first, whose best conformer gets the full dock", "", 0,
         1e6},
        [](auto& r) -> auto& { return r.candidates; }));
    t.push_back(options::field<R>(
        {"top", Kind::integer, "rows written (0: all)", "", 0, 1e12},
        [](auto& r) -> auto& { return r.top; }));
    t.push_back(options::choice<R>(
        {"rank-by", Kind::choice,
         "mean (the score, a mean over the ligand's surface) or total (the score times the "
         "ligand's surface area)"},
        [](auto& r) -> auto& { return r.ranking; }, receptor_ranking_names));
    return t;
  }();
  return table;
}

void validate(const ReceptorScreenOptions& options) {
  docking::validate(options.dock);
  if (options.dock.conformers > 0) {
    throw OptionError(options::named("conformers") +
                      " does not apply to a screen: the library holds the conformers");
  }
  if (options.dock.local_only || options.dock.score_only) {
    throw OptionError(options::named(options.dock.local_only ? "local_only" : "score_only") +
                      " does not apply to a screen: a library's conformers have no pose in the "
                      "receptor");
  }
  if (options.fast_chains < 1) {
    throw OptionError(options::named("fast_chains") + " must be at least 1, got " +
                      std::to_string(options.fast_chains));
  }
  if (options.fast_steps < 0 || options.candidates < 0 || options.top < 0) {
    throw OptionError(options::named(options.fast_steps < 0   ? "fast_steps"
                                     : options.candidates < 0 ? "candidates"
                                                              : "top") +
                      " must be >= 0");
  }
  docking::SearchOptions fast = options.dock.search;
  fast.chains = options.fast_chains;
  fast.steps = options.fast_steps;
  docking::validate(fast);
}

ReceptorScreenResult receptor_screen(const matching::MatchInput& receptor, const Library& library,
                                     const ReceptorScreenOptions& options) {
  validate(options);
  check_library_kind(library, false);
  ReceptorScreenResult result;
  Stopwatch clock;
  const docking::DockSite site = docking::prepare_dock_site(receptor, options.dock);
  result.timing_ms = site.timing_ms;

  // Stage 1: every conformer, in parallel, a chunk of the library at a time (its pages released
  // after it, so that memory does not grow with the library); each search is seeded alike, so
  // the rows do not depend on the threads. A molecule counts by its best conformer (the first of
  // equals).
  clock.restart();
  const std::size_t n = library.size();
  constexpr std::size_t chunk = 1024;
  std::vector<ReceptorHit> molecules;
  LibraryEntryInfo last;
  std::atomic<std::int64_t> done{0};
  for (std::size_t e0 = 0; e0 < n; e0 += chunk) {
    const std::size_t e1 = std::min(n, e0 + chunk);
    std::vector<ReceptorHit> fast(e1 - e0);
    tbb::parallel_for(e0, e1, [&](std::size_t i) {
      fast[i - e0] = fast_dock(site, library.entry(i), options);
      fast[i - e0].entry = i;
      const std::int64_t now = ++done;
      if (options.progress) options.progress(1, now, static_cast<std::int64_t>(n));
    });
    for (std::size_t i = e0; i < e1; ++i) {
      const LibraryEntryInfo info = library.info(i);
      const ReceptorHit& hit = fast[i - e0];
      if (molecules.empty() || !same_molecule(info, last)) {
        molecules.push_back(hit);
      } else if (better(hit, molecules.back(), options)) {
        molecules.back() = hit;
      }
      last = info;
    }
    library.release(e0, e1);
  }
  const auto order = [&options](const ReceptorHit& a, const ReceptorHit& b) {
    if (a.stage != b.stage) return a.stage > b.stage;
    if (better(a, b, options)) return true;
    if (better(b, a, options)) return false;
    return a.entry < b.entry;
  };
  std::sort(molecules.begin(), molecules.end(), order);
  result.timing_ms.emplace_back("stage 1 (fast docks)", clock.elapsed_ms());

  // Stage 2: the candidates' best conformers, each docked in full into the one site.
  clock.restart();
  const std::size_t candidates =
      std::min(molecules.size(), static_cast<std::size_t>(options.candidates));
  for (std::size_t k = 0; k < candidates; ++k) {
    ReceptorHit& hit = molecules[k];
    const LibraryEntry entry = library.entry(hit.entry);
    try {
      matching::MatchInput ligand;
      ligand.molecule = io::read_record_molecule(entry.molecule, options.dock.inputs.input.read);
      ligand.molecule->source = entry.info.name;
      docking::DockOptions one = options.dock;
      one.poses = 1;
      const docking::DockResult docked = docking::dock(ligand, site, one);
      if (!docked.poses.empty()) {
        hit.stage = 2;
        hit.score = docked.poses.front().score;
        hit.transform = docked.poses.front().transform;
        hit.area = mesh::measure_surface(docked.ligand.descriptors.surface).area;
      }
    } catch (const OptionError&) {
      throw;                        // the options, not this molecule
    } catch (const Error& error) {  // this molecule alone: it keeps its stage-1 row
      result.notes.push_back(entry.info.name + ": no full dock (" + error.what() + ")");
    }
    if (options.progress)
      options.progress(2, static_cast<std::int64_t>(k + 1), static_cast<std::int64_t>(candidates));
  }
  std::sort(molecules.begin(), molecules.end(), order);
  if (options.top > 0 && molecules.size() > static_cast<std::size_t>(options.top))
    molecules.resize(static_cast<std::size_t>(options.top));
  result.hits = std::move(molecules);
  result.timing_ms.emplace_back("stage 2 (full docks)", clock.elapsed_ms());
  return result;
}

}  // namespace surfcomp::screening
