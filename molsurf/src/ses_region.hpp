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

  double value(const Eigen::Vector3d& x) const;

  /// The corners of the union's bounding box.
  Eigen::Vector3d lower() const { return lower_; }
  Eigen::Vector3d upper() const { return upper_; }

  /// The nearest point to x on a sphere patch of the union's boundary: the radial points of x
  /// on the balls' spheres that lie in no other ball, the nearest of them, with its outward
  /// unit normal and mean curvature (1 / radius). False, and the arguments unchanged, when
  /// every such point is buried (x nearest to a crease where spheres meet).
  bool boundary_point(const Eigen::Vector3d& x, Eigen::Vector3d& point, Eigen::Vector3d& normal,
                      double& mean_curvature) const;

 private:
  std::vector<Eigen::Vector3d> centers_;
  std::vector<double> radii_;
  Eigen::Vector3d lower_, upper_;
};

}  // namespace surfcomp::molsurf::detail
