// Principal-axes starts for the whole-surface overlay: the superpositions of two samples'
// principal axes that Gaussian-overlay tools (Shape-it, ROCS) refine, independent of any
// critical point. Why: docs/decisions.md#principal-axes-starts.
#pragma once

#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/matching/rigid_fit.hpp"

#include <vector>

namespace surfcomp::matching {

/// A sample's area-weighted centroid (A) and principal axes (columns, by increasing variance,
/// right-handed).
struct PrincipalFrame {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
};

/// The principal frame of `sample`. Throws InputError when it is empty.
PrincipalFrame principal_frame(const SurfaceSample& sample);

/// The proper rotations that superpose the probe sample's area-weighted principal axes on the
/// reference sample's, with the weighted centroids coincident. With `all_orders` false, the
/// four that pair the axes in order of their variance (signs taken in the four ways that keep
/// a right-handed frame); with it true, the 24 that pair them in any order (for samples whose
/// variances are too close for the order to mean much, as pockets' often are). Throws
/// InputError when a sample is empty.
std::vector<RigidTransform> principal_axes_starts(const SurfaceSample& reference,
                                                  const SurfaceSample& probe,
                                                  bool all_orders = false);

/// Whether `n` is a number of principal-axes starts there are: 0 (none), 4 or 24.
inline bool is_axes_start_count(int n) { return n == 0 || n == 4 || n == 24; }

}  // namespace surfcomp::matching
