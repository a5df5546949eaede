// The coverage score and the ICP polish (surface_fit.hpp) against what geometry fixes: a
// hemisphere lies wholly on its sphere however the sphere turns about its centre, and covers
// half of it; an ellipsoid displaced a little comes back onto itself.
#include "surfcomp/matching/surface_fit.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/surface.hpp"

#include "analytic_meshes.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <vector>

namespace surfcomp {
namespace {

/// The faces of `full` whose centroids have z > `height`, as a mesh of their own.
mesh::Surface cap_above(const mesh::Surface& full, double height) {
  const Eigen::MatrixX3d v = full.positions();
  const Eigen::MatrixX3i f = full.faces();
  std::vector<int> index(static_cast<std::size_t>(v.rows()), -1);
  std::vector<Eigen::RowVector3d> points;
  std::vector<Eigen::RowVector3i> faces;
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    if ((v(f(i, 0), 2) + v(f(i, 1), 2) + v(f(i, 2), 2)) / 3.0 <= height) continue;
    Eigen::RowVector3i face;
    for (int c = 0; c < 3; ++c) {
      int& at = index[static_cast<std::size_t>(f(i, c))];
      if (at < 0) {
        at = static_cast<int>(points.size());
        points.push_back(v.row(f(i, c)));
      }
      face(c) = at;
    }
    faces.push_back(face);
  }
  Eigen::MatrixX3d positions(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t k = 0; k < points.size(); ++k)
    positions.row(static_cast<Eigen::Index>(k)) = points[k];
  Eigen::MatrixX3i triangles(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t k = 0; k < faces.size(); ++k)
    triangles.row(static_cast<Eigen::Index>(k)) = faces[k];
  return mesh::Surface::from_arrays(positions, triangles, "cap");
}

matching::RigidTransform motion(double degrees, const Eigen::Vector3d& axis,
                                const Eigen::Vector3d& shift) {
  matching::RigidTransform t;
  t.rotation = Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  t.translation = shift;
  return t;
}

TEST(SurfaceFit, AHemisphereLiesWhollyOnItsSphereAndCoversHalfOfIt) {
  const mesh::Surface sphere = test::icosphere(10.0, 24);
  const mesh::Surface cap = cap_above(sphere, 0.0);
  const matching::SurfaceFit fit(sphere, cap);
  EXPECT_NEAR(fit.probe_area() / fit.reference_area(), 0.5, 0.02);
  // Any turn about the centre keeps the cap on the sphere.
  for (const auto& pose :
       {matching::RigidTransform{}, motion(180.0, {1, 0, 0}, Eigen::Vector3d::Zero()),
        motion(67.0, {0.3, -0.8, 0.5}, Eigen::Vector3d::Zero())}) {
    const matching::CoverageScore c = fit.coverage(pose, 0.5);
    EXPECT_GT(c.probe, 0.999);
    EXPECT_EQ(c.score, c.probe);  // the part's fraction
    // Half the sphere, and the band within 0.5 below the cap's rim: 0.5 / (2 r) more of it (up
    // to the rim's ragged edge, about one triangle).
    EXPECT_NEAR(c.reference, 0.525, 0.012);
  }
  // Moved off by more than the distance, nothing lies on the other.
  const matching::CoverageScore away = fit.coverage(motion(0.0, {0, 0, 1}, {30, 0, 0}), 1.0);
  EXPECT_EQ(away.score, 0.0);
  EXPECT_EQ(away.reference, 0.0);
  // Pushed out along z by 2, the cap's point at polar angle t lies sqrt(104 + 40 cos t) - 10
  // from the sphere: within 1 where cos t <= 0.425, and the cap's area is uniform in cos t.
  const matching::CoverageScore lifted = fit.coverage(motion(0.0, {0, 0, 1}, {0, 0, 2}), 1.0);
  EXPECT_NEAR(lifted.probe, 0.425, 0.02);
}

TEST(SurfaceFit, IcpBringsADisplacedEllipsoidBackOntoItself) {
  const mesh::Surface ellipsoid = test::ellipsoid(12.0, 8.0, 5.0, 20);
  const mesh::Surface half = cap_above(ellipsoid, -1.0);
  for (const mesh::Surface* probe : {&ellipsoid, &half}) {
    const matching::SurfaceFit fit(ellipsoid, *probe);
    const matching::RigidTransform start = motion(4.0, {0.2, 0.9, -0.4}, {0.4, -0.3, 0.3});
    const matching::RigidTransform polished = fit.icp(start);
    EXPECT_LT(matching::rotation_angle_degrees(polished.rotation), 0.05) << probe->source();
    EXPECT_LT(polished.translation.norm(), 0.01) << probe->source();
    EXPECT_GT(fit.coverage(polished, 0.1).probe, 0.999) << probe->source();
    EXPECT_LT(fit.coverage(start, 0.1).probe, 0.5) << probe->source();
  }
}

TEST(SurfaceFit, IcpLeavesAPoseWithNoPairsWithinReachAsItIs) {
  const mesh::Surface ellipsoid = test::ellipsoid(12.0, 8.0, 5.0, 8);
  const matching::SurfaceFit fit(ellipsoid, ellipsoid);
  const matching::RigidTransform far = motion(10.0, {0, 0, 1}, {50, 0, 0});
  const matching::RigidTransform kept = fit.icp(far);
  EXPECT_EQ(kept.rotation, far.rotation);
  EXPECT_EQ(kept.translation, far.translation);
}

TEST(SurfaceFit, RefusesAMaskOfTheWrongSizeAndOptionsOutOfRange) {
  const mesh::Surface sphere = test::icosphere(5.0, 4);
  const std::vector<bool> short_mask(3, true);
  EXPECT_THROW(matching::SurfaceFit(sphere, sphere, &short_mask), InputError);
  const std::vector<bool> none(sphere.n_vertices(), false);
  EXPECT_THROW(matching::SurfaceFit(sphere, sphere, nullptr, &none), InputError);
  const matching::SurfaceFit fit(sphere, sphere);
  EXPECT_THROW((void)fit.coverage({}, 0.0), OptionError);
  EXPECT_THROW((void)fit.coverage({}, std::nan("")), OptionError);
  matching::IcpOptions bad;
  bad.max_distance = -1.0;
  EXPECT_THROW((void)fit.icp({}, bad), OptionError);
}

}  // namespace
}  // namespace surfcomp
