#include "surfcomp/matching/rigid_fit.hpp"

#include "surfcomp/core/error.hpp"

#include <Eigen/Geometry>
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

/// The proper rotation R maximising trace(R cross) (Kabsch, with the reflection corrected) and
/// the translation taking from_centroid onto to_centroid after it.
RigidTransform kabsch(const Eigen::Matrix3d& cross, const Eigen::Vector3d& from_centroid,
                      const Eigen::Vector3d& to_centroid) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d correction = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) correction(2, 2) = -1.0;
  RigidTransform transform;
  transform.rotation = svd.matrixV() * correction * svd.matrixU().transpose();
  transform.translation = to_centroid - transform.rotation * from_centroid;
  return transform;
}

}  // namespace

Eigen::Matrix4d RigidTransform::matrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = rotation;
  m.topRightCorner<3, 1>() = translation;
  return m;
}

RigidTransform RigidTransform::inverse() const {
  RigidTransform t;
  t.rotation = rotation.transpose();
  t.translation = -(t.rotation * translation);
  return t;
}

RigidTransform RigidTransform::from_matrix(const Eigen::Matrix4d& matrix) {
  RigidTransform t;
  t.rotation = matrix.topLeftCorner<3, 3>();
  t.translation = matrix.topRightCorner<3, 1>();
  return t;
}

Eigen::Matrix3Xd RigidTransform::apply(const Eigen::Ref<const Eigen::Matrix3Xd>& points) const {
  return (rotation * points).colwise() + translation;
}

RigidFit fit_rigid(const Eigen::Ref<const Eigen::Matrix3Xd>& from,
                   const Eigen::Ref<const Eigen::Matrix3Xd>& to) {
  require_same_size(from, to, "rigid fit");
  if (from.cols() < 3) {
    throw InputError("rigid fit: " + std::to_string(from.cols()) +
                     " corresponding points; a rigid fit needs at least 3");
  }
  if (!from.allFinite() || !to.allFinite()) {
    throw InputError("rigid fit: a coordinate is not finite; expected finite points (A)");
  }
  const Eigen::Vector3d from_centroid = from.rowwise().mean();
  const Eigen::Vector3d to_centroid = to.rowwise().mean();
  const Eigen::Matrix3d cross =
      (from.colwise() - from_centroid) * (to.colwise() - to_centroid).transpose();
  RigidFit fit;
  fit.transform = kabsch(cross, from_centroid, to_centroid);
  fit.rmsd = rmsd_under(fit.transform, from, to);
  fit.n_points = static_cast<std::size_t>(from.cols());
  return fit;
}

RigidFit fit_rigid_weighted(const Eigen::Ref<const Eigen::Matrix3Xd>& from,
                            const Eigen::Ref<const Eigen::Matrix3Xd>& to,
                            const Eigen::Ref<const Eigen::VectorXd>& weights) {
  if (from.cols() != to.cols() || from.cols() != weights.size()) {
    throw InputError("rigid fit: " + std::to_string(from.cols()) + " points, " +
                     std::to_string(to.cols()) + " targets and " + std::to_string(weights.size()) +
                     " weights; expected one target and one weight per point");
  }
  if (!from.allFinite() || !to.allFinite() || !weights.allFinite() ||
      (weights.array() < 0.0).any()) {
    throw InputError("rigid fit: a coordinate or weight is not finite or a weight is negative");
  }
  const double total = weights.sum();
  if (!(total > 0.0))
    throw InputError("rigid fit: the weights sum to zero; expected a positive sum");
  const Eigen::Vector3d from_centroid = from * weights / total;
  const Eigen::Vector3d to_centroid = to * weights / total;
  const Eigen::Matrix3d cross = (from.colwise() - from_centroid) * weights.asDiagonal() *
                                (to.colwise() - to_centroid).transpose();
  RigidFit fit;
  fit.transform = kabsch(cross, from_centroid, to_centroid);
  fit.rmsd =
      std::sqrt((fit.transform.apply(from) - to).colwise().squaredNorm().dot(weights) / total);
  fit.n_points = static_cast<std::size_t>(from.cols());
  return fit;
}

double rmsd_under(const RigidTransform& transform, const Eigen::Ref<const Eigen::Matrix3Xd>& from,
                  const Eigen::Ref<const Eigen::Matrix3Xd>& to) {
  require_same_size(from, to, "overlay");
  if (from.cols() == 0) throw InputError("overlay: no points; expected at least one");
  const double sum = (transform.apply(from) - to).colwise().squaredNorm().sum();
  return std::sqrt(sum / static_cast<double>(from.cols()));
}

double rotation_angle_degrees(const Eigen::Matrix3d& rotation) {
  const Eigen::Vector3d axis(rotation(2, 1) - rotation(1, 2), rotation(0, 2) - rotation(2, 0),
                             rotation(1, 0) - rotation(0, 1));
  return std::atan2(axis.norm(), rotation.trace() - 1.0) * 180.0 / M_PI;
}

RigidTransform extrapolate_motion(const RigidTransform& current, const RigidTransform& step,
                                  const Eigen::Vector3d& centre, double alpha) {
  const Eigen::Matrix3d relative = step.rotation * current.rotation.transpose();
  const Eigen::Vector3d shift =
      relative * centre + (step.translation - relative * current.translation) - centre;
  const Eigen::AngleAxisd angle_axis(relative);
  const Eigen::Matrix3d scaled =
      Eigen::AngleAxisd(alpha * angle_axis.angle(), angle_axis.axis()).toRotationMatrix();
  RigidTransform out;
  out.rotation = scaled * current.rotation;
  out.translation = scaled * (current.translation - centre) + centre + alpha * shift;
  return out;
}

}  // namespace surfcomp::matching
