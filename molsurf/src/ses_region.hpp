// Internal to the molsurf module (not installed): the union of balls a surface is confined to
// (build_ses with a SesRegion), as a field the grid samples and a surface vertices are placed on.
#pragma once

#include "surfcomp/molsurf/ses.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace surfcomp::molsurf::detail {

/// A union of balls: value() is min_i (|x - c_i| - r_i), 1-Lipschitz, exact outside the union
/// and never deeper than the true depth inside, so that max(surface field, value) is the field
/// of the surface's region cut to the union (CSG intersection).
class BallUnion {
 public:
  explicit BallUnion(const SesRegion& region);

  double value(const Eigen::Vector3d& x) const { return value(x, nullptr); }

  /// The point of the boundary of the ball whose value at x is least (the nearest boundary
  /// point from outside), its outward unit normal and mean curvature (1 / radius).
  Eigen::Vector3d boundary_point(const Eigen::Vector3d& x, Eigen::Vector3d& normal,
                                 double& mean_curvature) const;

 private:
  double value(const Eigen::Vector3d& x, std::size_t* which) const;

  std::vector<Eigen::Vector3d> centers_;
  std::vector<double> radii_;
};

}  // namespace surfcomp::molsurf::detail
