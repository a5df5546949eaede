#include "ses_region.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace surfcomp::molsurf::detail {
namespace {

/// A sphere point deeper than this fraction of the radius inside another ball is buried.
constexpr double burial_tolerance = 1e-9;

}  // namespace

BallUnion::BallUnion(const SesRegion& region)
    : lower_(Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity())), upper_(-lower_) {
  centers_.reserve(static_cast<std::size_t>(region.centers.rows()));
  for (Eigen::Index i = 0; i < region.centers.rows(); ++i) {
    centers_.emplace_back(region.centers.row(i).transpose());
    radii_.push_back(region.radii(i));
    lower_ = lower_.cwiseMin(centers_.back() - Eigen::Vector3d::Constant(radii_.back()));
    upper_ = upper_.cwiseMax(centers_.back() + Eigen::Vector3d::Constant(radii_.back()));
  }
}

double BallUnion::value(const Eigen::Vector3d& x) const {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < centers_.size(); ++i)
    best = std::min(best, (x - centers_[i]).norm() - radii_[i]);
  return best;
}

bool BallUnion::boundary_point(const Eigen::Vector3d& x, Eigen::Vector3d& point,
                               Eigen::Vector3d& normal, double& mean_curvature) const {
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < centers_.size(); ++i) {
    const Eigen::Vector3d offset = x - centers_[i];
    const double length = offset.norm();
    if (!(length > 0.0)) continue;  // the centre: every point of the sphere is as near
    const double distance = std::abs(length - radii_[i]);
    if (!(distance < nearest)) continue;
    const Eigen::Vector3d radial = offset / length;
    const Eigen::Vector3d on_sphere = centers_[i] + radii_[i] * radial;
    // On the boundary unless another ball holds it (rounding: a hair inside counts as on).
    if (value(on_sphere) < -burial_tolerance * radii_[i]) continue;
    nearest = distance;
    point = on_sphere;
    normal = radial;
    mean_curvature = 1.0 / radii_[i];
  }
  return nearest < std::numeric_limits<double>::infinity();
}

}  // namespace surfcomp::molsurf::detail
