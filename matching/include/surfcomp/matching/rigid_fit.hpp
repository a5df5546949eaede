// Least-squares rigid superposition of corresponding point sets (method §6.3;
// method §6): the rotation about the centroids that minimises the sum of squared
// distances (Kabsch 1976; Horn 1987), restricted to proper rotations.
#pragma once

#include <Eigen/Core>

#include <cstddef>

namespace surfcomp::matching {

/// x -> rotation * x + translation (A).
struct RigidTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< proper: R^T R = I, det R = +1
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();   ///< A

  /// The homogeneous 4x4 matrix [R t; 0 0 0 1].
  Eigen::Matrix4d matrix() const;
  /// The transform applied to each column of `points` (3 by N, A).
  Eigen::Matrix3Xd apply(const Eigen::Ref<const Eigen::Matrix3Xd>& points) const;
  /// The inverse transform: R^T, -R^T t (R taken for a rotation).
  RigidTransform inverse() const;
  /// The transform of a homogeneous matrix [R t; 0 0 0 1] (R is taken as it is).
  static RigidTransform from_matrix(const Eigen::Matrix4d& matrix);
};

/// A fitted transform and its quality.
struct RigidFit {
  RigidTransform transform;
  double rmsd = 0.0;         ///< A, method §6.3 over the n_points correspondences
  std::size_t n_points = 0;  ///< correspondences fitted
};

/// The proper rigid transform T minimising sum_i |T from_i - to_i|^2 over the columns of two
/// 3 by N arrays (A), and its RMSD sqrt(sum_i |T from_i - to_i|^2 / N) (method §6.3 with
/// q = from, p = to). Kabsch: centroids removed, SVD of the cross-covariance H = sum (from_i -
/// from_c)(to_i - to_c)^T = U S V^T, R = V diag(1, 1, d) U^T with d = sign det(V U^T), so a
/// point set that best matches its mirror image still gets a rotation (det +1), never a
/// reflection. When the points are collinear or coincident the rotation about that line is
/// not determined; the SVD's choice is returned (deterministic).
/// Throws InputError when the arrays differ in size, hold fewer than 3 points, or a coordinate
/// is not finite.
RigidFit fit_rigid(const Eigen::Ref<const Eigen::Matrix3Xd>& from,
                   const Eigen::Ref<const Eigen::Matrix3Xd>& to);

/// Weighted least-squares rigid fit: the proper T minimising sum_i weights_i |T from_i - to_i|^2
/// (Kabsch with weights); rmsd is the weighted RMS distance. Throws InputError when sizes differ,
/// the weights sum to zero or less, or a value is not finite.
RigidFit fit_rigid_weighted(const Eigen::Ref<const Eigen::Matrix3Xd>& from,
                            const Eigen::Ref<const Eigen::Matrix3Xd>& to,
                            const Eigen::Ref<const Eigen::VectorXd>& weights);

/// sqrt(sum_i |transform(from_i) - to_i|^2 / N) (A) for any transform. Throws InputError when
/// the arrays differ in size or are empty.
double rmsd_under(const RigidTransform& transform, const Eigen::Ref<const Eigen::Matrix3Xd>& from,
                  const Eigen::Ref<const Eigen::Matrix3Xd>& to);

/// The angle (degrees, [0, 180]) of the rotation `rotation`, i.e. of R_1^T R_2 when given the
/// product: atan2(2 sin, 2 cos) from the antisymmetric part and the trace, accurate for small
/// angles too. Used to state how far a recovered rotation is from a known one.
double rotation_angle_degrees(const Eigen::Matrix3d& rotation);

/// `current` followed by `alpha` times the motion that takes `current` to `step` (its rotation
/// angle and its translation scaled about `centre`, a point in the moved frame); alpha 1 gives
/// `step`. The over-relaxation of the overlay refinement's EM steps.
RigidTransform extrapolate_motion(const RigidTransform& current, const RigidTransform& step,
                                  const Eigen::Vector3d& centre, double alpha);

}  // namespace surfcomp::matching
