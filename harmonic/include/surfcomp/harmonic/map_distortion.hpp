// How far a map of a patch onto the plane (a harmonic disk map) is from preserving angles and
// areas, for comparing parameterizations (surfcomp patch-map --compare-cgal): per-corner angle
// differences (a conformal map has none) and per-triangle area ratios normalised by the totals (an
// authalic map has all 1), and the flipped triangles (an embedding has none).
#pragma once

#include <Eigen/Core>

namespace surfcomp::harmonic {

struct MapDistortion {
  /// |angle in the map - angle on the patch| over every corner of every triangle, degrees: the
  /// mean and the largest.
  double angle_mean_degrees = 0.0;
  double angle_max_degrees = 0.0;
  /// |ln r_t|, r_t = (map area of t / map area) / (patch area of t / patch area), weighted by
  /// the triangles' patch areas (mean), and the largest; 0 for a map that keeps area ratios.
  double area_mean_log = 0.0;
  double area_max_log = 0.0;
  /// Triangles with signed map area <= 0 (count_flipped_triangles).
  int flipped = 0;
};

/// The distortion of the map `uv` (#V by 2) of the patch `positions` (#V by 3, A), `faces`
/// (#F by 3, counter-clockwise from outside; the map's border counter-clockwise). A flipped or
/// degenerate triangle counts in `flipped` and in the angle terms (its map angles are measured
/// unsigned), not in the area terms, which are NaN when no triangle has a positive area on both
/// sides. Throws InputError for sizes that differ or an index out of range.
MapDistortion map_distortion(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                             const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                             const Eigen::Ref<const Eigen::MatrixX2d>& uv);

/// |angle in the map - angle on the patch| at every corner, degrees: #F by 3, entry (f, k) the
/// corner at vertex faces(f, k); the terms whose mean and largest value map_distortion reports.
/// A corner with an edge of zero length has angle 0 on that side. Arguments and throws as
/// map_distortion.
Eigen::MatrixX3d corner_angle_distortion(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                         const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                         const Eigen::Ref<const Eigen::MatrixX2d>& uv);

}  // namespace surfcomp::harmonic
