// Finding the poses a complementarity score ranks best
// (docs/method.md#153-search-refinement-and-ranking): a local optimiser (BFGS on the score's
// analytic gradient over the six rigid motions) and a Monte Carlo search over the site that runs it
// after each random move.
#pragma once

#include "surfcomp/docking/complementarity.hpp"
#include "surfcomp/matching/rigid_fit.hpp"
#include "surfcomp/molsurf/site.hpp"

#include <cstdint>
#include <vector>

namespace surfcomp::docking {

/// How the Monte Carlo search samples the site.
struct SearchOptions {
  /// Default 48. Independent chains, each from a random orientation at a random point of the
  /// site's spheres. >= 0.
  int chains = 48;
  /// Default 40. Moves per chain: a random translation of up to 2 A or rotation of up to
  /// 60 degrees about the ligand's centre, then refine_pose; kept by the Metropolis rule.
  /// >= 0.
  int steps = 40;
  /// Default 0.05 (score units). The Metropolis temperature: a move that lowers the score by
  /// this much is kept with probability 1/e. Finite, > 0.
  double temperature = 0.05;
  /// Default 1e-5. The chains' local optimisations stop when a step gains less than this
  /// (refine_pose's min_gain; dock optimises its best candidates further). Finite, > 0.
  double min_gain = 1e-5;
  /// Default 2 A. The spacing of the ligand surface sample (sample_ligand) that dock's search
  /// chains and its clique poses' first optimisation score: coarser than the score's
  /// sample_spacing (1 A), a quarter of its points and of the search's cost. dock then scores
  /// every candidate on the score's own sample and optimises the best further on it. Finite,
  /// > 0.
  double sample_spacing = 2.0;
  /// Default 1. Seeds the chains' random numbers: the same seed, the same poses, whatever the
  /// number of threads.
  std::uint64_t seed = 1;
};

/// The most optima a search keeps, chains x (steps + 1): 2 million, about 400 MB.
inline constexpr long long kMaxSearchOptima = 2'000'000;

/// Throws OptionError naming the first option outside its domain, or chains x (steps + 1)
/// above kMaxSearchOptima.
void validate(const SearchOptions& options);

/// `start` moved to a local maximum of `field`'s score of `sample`: BFGS over three translations
/// and three rotations about the moved sample's centroid (the rotations scaled by the sample's
/// radius of gyration), with a backtracking line search whose steps are at most 1 A in those
/// scaled variables (a rotation's step of 1 moves a point at the radius of gyration 1 A). Ends
/// after `max_iterations` or when a step gains less than `min_gain`. Deterministic.
matching::RigidTransform refine_pose(const ReceptorField& field, const LigandSample& sample,
                                     const matching::RigidTransform& start, double min_gain = 1e-7,
                                     int max_iterations = 200);

/// A local maximum the search found, with its score.
struct SearchedPose {
  matching::RigidTransform pose;
  ComplementarityScore score;
};

/// The Monte Carlo search of `site` (options.chains chains of options.steps moves, in parallel
/// under the caller's thread limit): every local maximum each chain visits, in chain order.
std::vector<SearchedPose> search_site(const ReceptorField& field, const LigandSample& sample,
                                      const std::vector<molsurf::SiteSphere>& site,
                                      const SearchOptions& options);

}  // namespace surfcomp::docking
