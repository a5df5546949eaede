#include "surfcomp/matching/rigid_fit.hpp"

#include "surfcomp/core/error.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <cmath>
#include <string>

namespace surfcomp::matching {

namespace {

void require_same_size(const Eigen::Ref<const Eigen::Matrix3Xd>& from,
                       const Eigen::Ref<const Eigen::Matrix3Xd>& to, const char* function) {
  if (from.cols() != to.cols()) {
    throw InputError(std::string(function) + ": " + std::to_string(from.cols()) +
                     " points to move but " + std::to_string(to.cols()) +
                     " target points; expected one target per point");
  }
}

}  // namespace

Eigen::Matrix4d RigidTransform::matrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = rotation;
  m.topRightCorner<3, 1>() = translation;
  return m;
}

Eigen::Matrix3Xd RigidTransform::apply(const Eigen::Ref<const Eigen::Matrix3Xd>& points) const {
  return (rotation * points).colwise() + translation;
}

RigidFit fit_rigid(const Eigen::Ref<const Eigen::Matrix3Xd>& from,
                   const Eigen::Ref<const Eigen::Matrix3Xd>& to) {
  require_same_size(from, to, "fit_rigid");
  if (from.cols() < 3) {
    throw InputError("fit_rigid: " + std::to_string(from.cols()) +
                     " corresponding points; a rigid fit needs at least 3");
  }
  if (!from.allFinite() || !to.allFinite()) {
    throw InputError("fit_rigid: a coordinate is not finite; expected finite points (A)");
  }
  const Eigen::Vector3d from_centroid = from.rowwise().mean();
  const Eigen::Vector3d to_centroid = to.rowwise().mean();
  const Eigen::Matrix3d cross =
      (from.colwise() - from_centroid) * (to.colwise() - to_centroid).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d correction = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) correction(2, 2) = -1.0;
  RigidFit fit;
  fit.transform.rotation = svd.matrixV() * correction * svd.matrixU().transpose();
  fit.transform.translation = to_centroid - fit.transform.rotation * from_centroid;
  fit.rmsd = rmsd_under(fit.transform, from, to);
  fit.n_points = static_cast<std::size_t>(from.cols());
  return fit;
}

double rmsd_under(const RigidTransform& transform, const Eigen::Ref<const Eigen::Matrix3Xd>& from,
                  const Eigen::Ref<const Eigen::Matrix3Xd>& to) {
  require_same_size(from, to, "rmsd_under");
  if (from.cols() == 0) throw InputError("rmsd_under: no points; expected at least one");
  const double sum = (transform.apply(from) - to).colwise().squaredNorm().sum();
  return std::sqrt(sum / static_cast<double>(from.cols()));
}

double rotation_angle_degrees(const Eigen::Matrix3d& rotation) {
  const Eigen::Vector3d axis(rotation(2, 1) - rotation(1, 2), rotation(0, 2) - rotation(2, 0),
                             rotation(1, 0) - rotation(0, 1));
  return std::atan2(axis.norm(), rotation.trace() - 1.0) * 180.0 / M_PI;
}

}  // namespace surfcomp::matching
