// Internal to the matching module: the climb of the overlay refinement (overlay.hpp), shared by
// SurfaceOverlay and PackedQuery, which differ only in how a step's sums and targets are taken.
#pragma once

#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/rigid_fit.hpp"

#include <Eigen/Core>

#include <algorithm>

namespace surfcomp::matching::detail {

/// Where a climb ended.
struct Climb {
  RigidTransform transform;
  OverlayScore score;  ///< as `step` gave it at `transform`
  bool abandoned = false;
};

/// Expectation-maximisation steps from `start`, over-relaxed: each fits `from` (3 x N, the probe
/// points, A) onto the targets that `step(t, targets, weights)` fills at the current transform t
/// (it returns the score climbed there), the motion stretched (alpha doubling up to 8) while the
/// stretched steps keep raising the score, retried plain when one does not. The climb stops when
/// a step does not raise the score, after options.iterations steps, when no surface point has
/// a neighbour (the first `surface` weights sum to 0), when a step moves no point of `moved` (3 x
/// M, A) by more than options.tolerance, or when `abandon(t)` returns true after a step (the
/// climb is then marked abandoned). `centre` is the point the stretch turns about (probe frame).
template <class Step, class Abandon>
Climb em_climb(const Eigen::Matrix3Xd& from, Eigen::Index surface,
               const Eigen::Ref<const Eigen::Matrix3Xd>& moved, const Eigen::Vector3d& centre,
               const RigidTransform& start, const OverlayOptions& options, const Step& step,
               const Abandon& abandon) {
  constexpr double kMaxAlpha = 8.0;
  const Eigen::Index n = from.cols();
  Eigen::Matrix3Xd targets(3, n), next_targets(3, n);
  Eigen::VectorXd weights(n), next_weights(n);
  Climb climb;
  climb.transform = start;
  climb.score = step(climb.transform, targets, weights);
  double alpha = 1.0;
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    if (!(weights.head(surface).sum() > 0.0)) break;  // no surface contact: nothing to climb
    const RigidTransform em = fit_rigid_weighted(from, targets, weights).transform;
    RigidTransform next =
        extrapolate_motion(climb.transform, em, climb.transform.apply(centre), alpha);
    OverlayScore next_score = step(next, next_targets, next_weights);
    if (!(next_score.score > climb.score.score) && alpha > 1.0) {
      alpha = 1.0;
      next = em;
      next_score = step(next, next_targets, next_weights);
    } else {
      alpha = std::min(2.0 * alpha, kMaxAlpha);
    }
    if (!(next_score.score > climb.score.score)) break;
    const double largest_move =
        (next.apply(moved) - climb.transform.apply(moved)).colwise().norm().maxCoeff();
    climb.transform = next;
    climb.score = next_score;
    targets.swap(next_targets);
    weights.swap(next_weights);
    if (abandon(climb.transform)) {
      climb.abandoned = true;
      break;
    }
    if (largest_move <= options.tolerance) break;
  }
  return climb;
}

}  // namespace surfcomp::matching::detail
