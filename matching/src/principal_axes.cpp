#include "surfcomp/matching/principal_axes.hpp"

#include "surfcomp/core/error.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <string>
#include <utility>

namespace surfcomp::matching {
PrincipalFrame principal_frame(const SurfaceSample& sample) {
  if (sample.size() == 0) throw InputError("principal axes: the sample has no points");
  const double total = sample.weights.sum();
  PrincipalFrame frame;
  frame.centroid = sample.points * sample.weights / total;
  const Eigen::Matrix3Xd centred = sample.points.colwise() - frame.centroid;
  const Eigen::Matrix3d covariance =
      centred * sample.weights.asDiagonal() * centred.transpose() / total;
  frame.axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors();
  if (frame.axes.determinant() < 0.0) frame.axes.col(0) = -frame.axes.col(0);
  return frame;
}

std::vector<RigidTransform> principal_axes_starts(const SurfaceSample& reference,
                                                  const SurfaceSample& probe, bool all_orders) {
  if (reference.size() == 0 || probe.size() == 0) {
    throw InputError(std::string("principal axes: the ") +
                     (reference.size() == 0 ? "reference" : "probe") + " sample has no points");
  }
  const auto [reference_centroid, reference_axes] = principal_frame(reference);
  const auto [probe_centroid, probe_axes] = principal_frame(probe);
  // Signed permutation matrices P with det +1: probe axis j goes onto reference axis perm[j].
  std::array<int, 3> perm{0, 1, 2};
  std::vector<RigidTransform> starts;
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
      for (int j = 0; j < 3; ++j)
        p(perm[static_cast<std::size_t>(j)], j) = (signs >> j) & 1 ? -1.0 : 1.0;
      if (p.determinant() < 0.0) continue;
      RigidTransform t;
      t.rotation = reference_axes * p * probe_axes.transpose();
      t.translation = reference_centroid - t.rotation * probe_centroid;
      starts.push_back(t);
    }
  } while (all_orders && std::next_permutation(perm.begin(), perm.end()));
  return starts;
}

}  // namespace surfcomp::matching
