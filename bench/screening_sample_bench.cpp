// The screening sample (matching::sample_molecule: SES points straight from the atoms) against
// the sample of the full surface (build_molecular_surface + sample_surface), on the same
// molecules in one run: the time of each on one thread, the area each finds, how well the two
// samples of one molecule overlay each other, and how closely the overlay scores of pairs
// agree (at the molecules' own coordinates, which are aligned in both default sets, and at the
// best of the four principal-axes starts, as a screen's first stage scores them).
//
// Usage: screening_sample_bench [--grid H] [--pairs N] [--seed S] [--profile N] [SDF...]
//   --grid H    the sample's grid spacing (default matching::screening_grid_spacing)
//   --profile N only the screening samples, N times over the molecules, timed (for a profiler)
//   --pairs N   random pairs per file for the score comparison (default 300)
//   SDF...      molecule files (default: sutherland/therm_3dqsar.sdf of the shared data sets and
//               bzr.sdf of Debian's rdkit-data, fetched by datasets/fetch.sh)
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/matching/packed_overlay.hpp"
#include "surfcomp/matching/principal_axes.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "test_support.hpp"

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace surfcomp;

struct Molecules {
  std::string file;
  std::vector<Molecule> molecules;
  std::vector<matching::SurfaceSample> full, fast;
  std::vector<matching::AtomSample> atoms;
  double full_ms = 0.0, fast_ms = 0.0;  ///< per molecule, one thread
};

double pearson(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n;
  const double my = std::accumulate(y.begin(), y.end(), 0.0) / n;
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  return sxy / std::sqrt(sxx * syy);
}

std::vector<double> ranks(const std::vector<double>& x) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  std::vector<double> r(x.size());
  for (std::size_t i = 0; i < order.size(); ++i) r[order[i]] = static_cast<double>(i);
  return r;
}

double best_start_score(const matching::SurfaceSample& a, const matching::AtomSample& aa,
                        const matching::SurfaceSample& b, const matching::AtomSample& ba) {
  const matching::SurfaceOverlay overlay(a, b, {}, aa, ba);
  double best = 0.0;
  for (const matching::RigidTransform& start : matching::principal_axes_starts(a, b))
    best = std::max(best, overlay.score(start).score);
  return best;
}

Molecules load(const std::filesystem::path& file, double grid) {
  Molecules set;
  set.file = file.filename().string();
  for (const io::MoleculeRecord& record : io::read_molecule_records(file))
    set.molecules.push_back(io::read_record_molecule(record));
  const matching::OverlayOptions overlay;
  Stopwatch clock;
  for (const Molecule& m : set.molecules)
    set.full.push_back(
        matching::sample_surface(molsurf::build_molecular_surface(m), overlay.spacing));
  set.full_ms = clock.elapsed_s() * 1e3 / static_cast<double>(set.molecules.size());
  clock.restart();
  for (const Molecule& m : set.molecules)
    set.fast.push_back(matching::sample_molecule(m, overlay.spacing, {}, grid));
  set.fast_ms = clock.elapsed_s() * 1e3 / static_cast<double>(set.molecules.size());
  for (const Molecule& m : set.molecules)
    set.atoms.push_back(matching::sample_atoms(harmonic::surface_atoms(m)));
  return set;
}

void report(const Molecules& set, std::size_t pairs, unsigned seed) {
  const std::size_t n = set.molecules.size();
  std::vector<double> area_ratio, self_shape, self_score, points_full, points_fast;
  for (std::size_t i = 0; i < n; ++i) {
    area_ratio.push_back(set.fast[i].weights.sum() / set.full[i].weights.sum());
    const matching::SurfaceOverlay cross(set.full[i], set.fast[i], {}, set.atoms[i], set.atoms[i]);
    const matching::OverlayScore s = cross.score({});
    self_shape.push_back(s.shape);
    self_score.push_back(s.score);
    points_full.push_back(static_cast<double>(set.full[i].size()));
    points_fast.push_back(static_cast<double>(set.fast[i].size()));
  }
  std::printf(
      "%s: %zu molecules; ms per molecule, one thread: full surface + sample %.2f, "
      "screening sample %.3f (%.1fx)\n",
      set.file.c_str(), n, set.full_ms, set.fast_ms, set.full_ms / set.fast_ms);
  std::printf(
      "  points: full %.0f, screening %.0f (medians); area screening / full: median "
      "%.4f, min %.4f, max %.4f\n",
      test::median(points_full), test::median(points_fast), test::median(area_ratio),
      *std::min_element(area_ratio.begin(), area_ratio.end()),
      *std::max_element(area_ratio.begin(), area_ratio.end()));
  std::printf(
      "  one molecule's two samples overlaid in place: shape Tanimoto median %.4f "
      "(min %.4f), score median %.4f (min %.4f)\n",
      test::median(self_shape), *std::min_element(self_shape.begin(), self_shape.end()),
      test::median(self_score), *std::min_element(self_score.begin(), self_score.end()));

  std::mt19937 random(seed);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  std::vector<double> full_in_place, fast_in_place, full_axes, fast_axes;
  for (std::size_t p = 0; p < pairs; ++p) {
    const std::size_t i = pick(random);
    std::size_t j = pick(random);
    if (i == j) j = (j + 1) % n;
    const matching::SurfaceOverlay full(set.full[i], set.full[j], {}, set.atoms[i], set.atoms[j]);
    const matching::SurfaceOverlay fast(set.fast[i], set.fast[j], {}, set.atoms[i], set.atoms[j]);
    full_in_place.push_back(full.score({}).score);
    fast_in_place.push_back(fast.score({}).score);
    full_axes.push_back(best_start_score(set.full[i], set.atoms[i], set.full[j], set.atoms[j]));
    fast_axes.push_back(best_start_score(set.fast[i], set.atoms[i], set.fast[j], set.atoms[j]));
  }
  const auto mean_abs = [](const std::vector<double>& x, const std::vector<double>& y) {
    double s = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) s += std::abs(x[i] - y[i]);
    return s / static_cast<double>(x.size());
  };
  std::printf(
      "  %zu pairs, score with the full samples against the screening samples: in place "
      "Pearson %.4f, Spearman %.4f, mean |difference| %.4f; best principal-axes start "
      "Pearson %.4f, Spearman %.4f, mean |difference| %.4f\n",
      pairs, pearson(full_in_place, fast_in_place),
      pearson(ranks(full_in_place), ranks(fast_in_place)), mean_abs(full_in_place, fast_in_place),
      pearson(full_axes, fast_axes), pearson(ranks(full_axes), ranks(fast_axes)),
      mean_abs(full_axes, fast_axes));
}

/// The first stage's score of every molecule against each of the first few, in double precision
/// (SurfaceOverlay sharing the query's index) and packed (single
/// precision, SIMD): their agreement and their speed.
void first_stage(const Molecules& set) {
  const matching::OverlayOptions options;
  std::vector<matching::PackedSample> packed;
  for (std::size_t i = 0; i < set.fast.size(); ++i)
    packed.emplace_back(set.fast[i], set.atoms[i], options.sigma, matching::SampleKind::atoms);
  std::vector<matching::PackedQuery> indexed;
  for (std::size_t q = 0; q < std::min<std::size_t>(5, set.fast.size()); ++q)
    indexed.emplace_back(packed[q]);
  const std::size_t queries = std::min<std::size_t>(5, set.fast.size());
  double largest = 0.0, sum = 0.0;
  std::size_t pairs = 0;
  double double_s = 0.0, packed_s = 0.0;
  for (std::size_t q = 0; q < queries; ++q) {
    const auto shared =
        matching::SurfaceOverlay::for_many_probes(set.fast[q], options, set.atoms[q]);
    std::vector<double> reference(set.fast.size()), fast(set.fast.size());
    Stopwatch clock;
    for (std::size_t e = 0; e < set.fast.size(); ++e) {
      const matching::SurfaceOverlay overlay(shared, set.fast[e], set.atoms[e]);
      double best = 0.0;
      for (const auto& start : matching::principal_axes_starts(set.fast[q], set.fast[e]))
        best = std::max(best, overlay.score(start).score);
      reference[e] = best;
    }
    double_s += clock.elapsed_s();
    clock.restart();
    for (std::size_t e = 0; e < set.fast.size(); ++e)
      fast[e] = indexed[q].fast_score(packed[e].view(), options).score.score;
    packed_s += clock.elapsed_s();
    for (std::size_t e = 0; e < set.fast.size(); ++e) {
      largest = std::max(largest, std::abs(fast[e] - reference[e]));
      sum += std::abs(fast[e] - reference[e]);
      ++pairs;
    }
  }
  std::printf(
      "  first stage, %zu queries x %zu entries: packed against double, mean |difference| "
      "%.2e, largest %.2e; entries/s on one thread: double %.0f, packed %.0f (%.1fx)\n",
      queries, set.fast.size(), sum / static_cast<double>(pairs), largest,
      static_cast<double>(pairs) / double_s, static_cast<double>(pairs) / packed_s,
      double_s / packed_s);
  // The second stage: each entry's starts refined against the first query, at the default
  // tolerance and coarser ones (the mean loss of the best refined score against the default).
  std::vector<double> reference_best;
  for (const double tolerance : {options.tolerance, 0.2, 0.3}) {
    matching::OverlayOptions refining = options;
    refining.tolerance = tolerance;
    const Stopwatch refine_clock;
    std::size_t refined = 0;
    double loss = 0.0;
    for (std::size_t e = 0; e < packed.size(); ++e) {
      double best = 0.0;
      for (const auto& start : indexed[0].start_scores(packed[e].view(), refining)) {
        best =
            std::max({best, start.score.score,
                      indexed[0].refine(packed[e].view(), start.transform, refining).score.score});
        ++refined;
      }
      if (reference_best.size() < packed.size()) reference_best.push_back(best);
      loss += reference_best[e] - best;
    }
    std::printf(
        "  second stage, tolerance %.2f A: %.3f ms per refined start on one thread (%zu "
        "starts), best score lower by %.5f on average\n",
        tolerance, refine_clock.elapsed_ms() / static_cast<double>(refined), refined,
        loss / static_cast<double>(packed.size()));
  }
}

}  // namespace

int main(int argc, char** argv) {
  double grid = matching::screening_grid_spacing;
  std::size_t pairs = 300;
  int profile = 0;
  unsigned seed = 20261127;
  std::vector<std::filesystem::path> files;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--grid" && a + 1 < argc) {
      grid = std::atof(argv[++a]);
    } else if (arg == "--pairs" && a + 1 < argc) {
      pairs = static_cast<std::size_t>(std::atol(argv[++a]));
    } else if (arg == "--profile" && a + 1 < argc) {
      profile = std::atoi(argv[++a]);
    } else if (arg == "--seed" && a + 1 < argc) {
      seed = static_cast<unsigned>(std::atol(argv[++a]));
    } else if (arg.rfind("--", 0) == 0) {
      std::fprintf(stderr,
                   "usage: screening_sample_bench [--grid H] [--pairs N] [--seed S] "
                   "[--profile N] [SDF...]\n");
      return 2;
    } else {
      files.emplace_back(arg);
    }
  }
  if (files.empty()) {
    if (const auto therm = test::shared_dataset_or_report("sutherland/therm_3dqsar.sdf"))
      files.push_back(*therm);
    if (const auto bzr = test::fetched_dataset("rdkit-data/bzr.sdf"))
      files.push_back(*bzr);
    else
      std::printf("skipped bzr: %s\n", test::fetched_absent_message("rdkit-data/bzr.sdf").c_str());
  }
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  std::printf("grid spacing %.3f A\n", grid);
  for (const std::filesystem::path& file : files) {
    if (profile < 0) {  // the packed first stage alone, -profile times over the molecules
      std::vector<matching::PackedSample> packed;
      const matching::OverlayOptions options;
      for (const io::MoleculeRecord& record : io::read_molecule_records(file)) {
        const Molecule m = io::read_record_molecule(record);
        packed.emplace_back(matching::sample_molecule(m, options.spacing, {}, grid),
                            matching::sample_atoms(harmonic::surface_atoms(m)), options.sigma,
                            matching::SampleKind::atoms);
      }
      const matching::PackedQuery query(packed[0]);
      const Stopwatch clock;
      double total = 0.0;
      for (int r = 0; r < -profile; ++r) {
        for (const auto& e : packed) total += query.fast_score(e.view(), options).score.score;
      }
      std::printf("%s: packed first stage %.0f entries/s (%.3f)\n", file.filename().c_str(),
                  -profile * static_cast<double>(packed.size()) / clock.elapsed_s(), total);
      continue;
    }
    if (profile > 0) {
      std::vector<Molecule> molecules;
      for (const io::MoleculeRecord& record : io::read_molecule_records(file))
        molecules.push_back(io::read_record_molecule(record));
      const Stopwatch clock;
      for (int r = 0; r < profile; ++r) {
        for (const Molecule& m : molecules) matching::sample_molecule(m, 1.5, {}, grid);
      }
      std::printf("%s: screening sample %.3f ms per molecule\n", file.filename().c_str(),
                  clock.elapsed_ms() / profile / static_cast<double>(molecules.size()));
      continue;
    }
    const Molecules set = load(file, grid);
    report(set, pairs, seed);
    first_stage(set);
  }
  return 0;
}
