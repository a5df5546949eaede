// Least-squares rigid fits (method §6.3): exact recovery of a known motion, the RMSD of a noisy
// fit against its analytic expectation, and proper rotations for mirror-image targets.
#include "surfcomp/matching/rigid_fit.hpp"
#include "surfcomp/core/error.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace surfcomp::matching {
namespace {

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> gauss;
  return Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng))
      .normalized()
      .toRotationMatrix();
}

Eigen::Matrix3Xd random_points(std::mt19937& rng, int n, double spread) {
  std::uniform_real_distribution<double> uniform(-spread, spread);
  Eigen::Matrix3Xd points(3, n);
  for (int i = 0; i < n; ++i) points.col(i) << uniform(rng), uniform(rng), uniform(rng);
  return points;
}

TEST(RigidFit, RecoversAKnownMotionExactly) {
  std::mt19937 rng(20240401u);
  std::printf("[ seed     ] 20240401\n");
  double worst_rotation = 0.0, worst_translation = 0.0, worst_rmsd = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d rotation = random_rotation(rng);
    const Eigen::Vector3d translation = 30.0 * Eigen::Vector3d::Random();
    const Eigen::Matrix3Xd from = random_points(rng, 5 + 50 * trial, 10.0);
    const Eigen::Matrix3Xd to = (rotation * from).colwise() + translation;
    const RigidFit fit = fit_rigid(from, to);
    worst_rotation =
        std::max(worst_rotation, (fit.transform.rotation - rotation).cwiseAbs().maxCoeff());
    worst_translation = std::max(worst_translation,
                                 (fit.transform.translation - translation).cwiseAbs().maxCoeff());
    worst_rmsd = std::max(worst_rmsd, fit.rmsd);
    EXPECT_EQ(fit.n_points, static_cast<std::size_t>(from.cols()));
    EXPECT_NEAR(fit.transform.rotation.determinant(), 1.0, 1e-12);
    const Eigen::Matrix4d m = fit.transform.matrix();
    EXPECT_TRUE(m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)));
    EXPECT_LT((m.topLeftCorner<3, 3>() * from.col(0) + m.topRightCorner<3, 1>() - to.col(0)).norm(),
              1e-10);
  }
  std::printf("[ exact    ] worst |dR| %.2e, |dt| %.2e A, RMSD %.2e A\n", worst_rotation,
              worst_translation, worst_rmsd);
  EXPECT_LT(worst_rotation, 1e-10);
  EXPECT_LT(worst_translation, 1e-10);
  EXPECT_LT(worst_rmsd, 1e-10);
}

// Targets with isotropic Gaussian noise sigma per coordinate: the least-squares fit absorbs 6
// degrees of freedom, so E[RMSD^2] = sigma^2 (3N - 6) / N. With N = 10 that is 2.4 sigma^2,
// clearly below the 3 sigma^2 of the true motion; 4000 trials estimate it to about 0.5 %.
TEST(RigidFit, NoisyRmsdMatchesTheLeastSquaresExpectation) {
  std::mt19937 rng(77u);
  std::normal_distribution<double> gauss;
  const double sigma = 0.3;
  const int n = 10, trials = 4000;
  double fitted = 0.0, true_motion = 0.0;
  for (int trial = 0; trial < trials; ++trial) {
    RigidTransform motion;
    motion.rotation = random_rotation(rng);
    motion.translation = 5.0 * Eigen::Vector3d::Random();
    const Eigen::Matrix3Xd from = random_points(rng, n, 6.0);
    Eigen::Matrix3Xd to = motion.apply(from);
    for (int i = 0; i < n; ++i)
      to.col(i) += sigma * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    const RigidFit fit = fit_rigid(from, to);
    fitted += fit.rmsd * fit.rmsd / trials;
    true_motion += std::pow(rmsd_under(motion, from, to), 2) / trials;
    EXPECT_LE(fit.rmsd, rmsd_under(motion, from, to) + 1e-12) << "the fit is not least squares";
  }
  const double expected = sigma * sigma * (3.0 * n - 6.0) / n;
  std::printf(
      "[ noise    ] seed 77: mean RMSD^2 %.5f (expected %.5f), under the true motion %.5f "
      "(expected %.5f)\n",
      fitted, expected, true_motion, 3.0 * sigma * sigma);
  EXPECT_NEAR(fitted / expected, 1.0, 0.02);
  EXPECT_NEAR(true_motion / (3.0 * sigma * sigma), 1.0, 0.02);
}

// A point set and its mirror image: the fit must still be a rotation. For a planar set the
// mirror is reached by a half turn (RMSD 0); for a general set the best rotation leaves a
// residual, and it is a minimum: small rotations about any axis do not lower it.
TEST(RigidFit, MirrorImagesGiveProperRotations) {
  std::mt19937 rng(5u);
  const Eigen::Matrix3d mirror = Eigen::Vector3d(-1.0, 1.0, 1.0).asDiagonal();

  Eigen::Matrix3Xd planar = random_points(rng, 40, 8.0);
  planar.row(2).setZero();
  const RigidFit flat = fit_rigid(planar, mirror * planar);
  EXPECT_NEAR(flat.transform.rotation.determinant(), 1.0, 1e-12);
  EXPECT_LT(flat.rmsd, 1e-10);
  EXPECT_NEAR(rotation_angle_degrees(flat.transform.rotation), 180.0, 1e-8);

  const Eigen::Matrix3Xd solid = random_points(rng, 40, 8.0);
  const RigidFit fit = fit_rigid(solid, mirror * solid);
  EXPECT_NEAR(fit.transform.rotation.determinant(), 1.0, 1e-12);
  EXPECT_LT(
      (fit.transform.rotation.transpose() * fit.transform.rotation - Eigen::Matrix3d::Identity())
          .cwiseAbs()
          .maxCoeff(),
      1e-12);
  EXPECT_GT(fit.rmsd, 1.0);
  EXPECT_NEAR(rmsd_under(fit.transform, solid, mirror * solid), fit.rmsd, 1e-12);
  double lowest_neighbour = 1e300;
  for (int axis = 0; axis < 3; ++axis) {
    for (double angle : {-1e-3, 1e-3}) {
      RigidTransform moved = fit.transform;
      moved.rotation =
          Eigen::AngleAxisd(angle, Eigen::Vector3d::Unit(axis)).toRotationMatrix() * moved.rotation;
      moved.translation =
          (mirror * solid).rowwise().mean() - moved.rotation * solid.rowwise().mean();
      lowest_neighbour = std::min(lowest_neighbour, rmsd_under(moved, solid, mirror * solid));
    }
  }
  std::printf("[ mirror   ] solid set: RMSD %.6f A, lowest after a 1 mrad turn %.6f A\n", fit.rmsd,
              lowest_neighbour);
  EXPECT_GT(lowest_neighbour, fit.rmsd);
}

TEST(RigidFit, RotationAngleIsAccurateForSmallAndLargeAngles) {
  for (double degrees : {1e-7, 0.5, 90.0, 179.0, 180.0}) {
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized())
            .toRotationMatrix();
    EXPECT_NEAR(rotation_angle_degrees(r), degrees, 1e-9 * std::max(1.0, degrees));
  }
}

TEST(RigidFit, BadInputsAreRejected) {
  const Eigen::Matrix3Xd three = Eigen::Matrix3Xd::Random(3, 3);
  EXPECT_THROW(fit_rigid(three, Eigen::Matrix3Xd::Random(3, 4)), InputError);
  EXPECT_THROW(fit_rigid(three.leftCols(2), three.leftCols(2)), InputError);
  Eigen::Matrix3Xd bad = three;
  bad(1, 1) = std::nan("");
  EXPECT_THROW(fit_rigid(bad, three), InputError);
  EXPECT_THROW(rmsd_under(RigidTransform{}, Eigen::Matrix3Xd(3, 0), Eigen::Matrix3Xd(3, 0)),
               InputError);
}

}  // namespace
}  // namespace surfcomp::matching
