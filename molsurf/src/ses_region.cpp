#include "ses_region.hpp"

#include <limits>

namespace surfcomp::molsurf::detail {

BallUnion::BallUnion(const SesRegion& region) {
  centers_.reserve(static_cast<std::size_t>(region.centers.rows()));
  for (Eigen::Index i = 0; i < region.centers.rows(); ++i) {
    centers_.emplace_back(region.centers.row(i).transpose());
    radii_.push_back(region.radii(i));
  }
}

double BallUnion::value(const Eigen::Vector3d& x, std::size_t* which) const {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < centers_.size(); ++i) {
    const double v = (x - centers_[i]).norm() - radii_[i];
    if (v < best) {
      best = v;
      if (which != nullptr) *which = i;
    }
  }
  return best;
}

Eigen::Vector3d BallUnion::boundary_point(const Eigen::Vector3d& x, Eigen::Vector3d& normal,
                                          double& mean_curvature) const {
  std::size_t which = 0;
  value(x, &which);
  const Eigen::Vector3d offset = x - centers_[which];
  const double length = offset.norm();
  normal = length > 0.0 ? Eigen::Vector3d(offset / length) : Eigen::Vector3d::UnitZ();
  mean_curvature = 1.0 / radii_[which];
  return centers_[which] + radii_[which] * normal;
}

}  // namespace surfcomp::molsurf::detail
