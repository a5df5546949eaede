#include "analytic_meshes.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/decimate.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace surfcomp::mesh {
namespace {

static_assert(std::is_nothrow_move_constructible_v<Surface>);
static_assert(std::is_nothrow_move_assignable_v<Surface>);

/// An icosphere with one property and a file-like source.
Surface sample() {
  Surface s = test::icosphere(1.5, 2);
  s.set_source("sample.ply");
  Eigen::VectorXd esp =
      Eigen::VectorXd::LinSpaced(static_cast<Eigen::Index>(s.n_vertices()), -1, 1);
  s.set_property(property::esp, esp, ValueType::float32);
  s.compute_normals();
  return s;
}

void expect_empty(const Surface& s) {
  EXPECT_EQ(s.n_vertices(), 0u);
  EXPECT_EQ(s.n_faces(), 0u);
  EXPECT_EQ(s.positions().rows(), 0);
  EXPECT_EQ(s.faces().rows(), 0);
  EXPECT_TRUE(s.property_names().empty());
  EXPECT_FALSE(s.has_property(property::esp));
  EXPECT_FALSE(s.has_normals());
  EXPECT_EQ(s.source(), "<arrays>");
  EXPECT_EQ(s.position_type(), ValueType::float64);
}

TEST(SurfaceValue, CopiesAreDeep) {
  const Surface original = sample();
  Surface copy = original;
  EXPECT_EQ(copy.positions(), original.positions());
  EXPECT_EQ(copy.faces(), original.faces());
  EXPECT_EQ(copy.normals(), original.normals());
  EXPECT_EQ(copy.property(property::esp), original.property(property::esp));
  EXPECT_EQ(copy.property_type(property::esp), ValueType::float32);
  EXPECT_EQ(copy.source(), "sample.ply");

  // Changing the copy leaves the original as it was.
  const Eigen::MatrixX3d before = original.positions();
  transform_surface(copy, Eigen::Matrix3d::Identity(), Eigen::Vector3d(1.0, 2.0, 3.0));
  copy.set_property(property::esp,
                    Eigen::VectorXd::Zero(static_cast<Eigen::Index>(copy.n_vertices())));
  copy.set_property(property::lp,
                    Eigen::VectorXd::Ones(static_cast<Eigen::Index>(copy.n_vertices())));
  EXPECT_EQ(original.positions(), before);
  EXPECT_NE(copy.positions(), before);
  EXPECT_EQ(original.property(property::esp)(0), -1.0);
  EXPECT_FALSE(original.has_property(property::lp));
  EXPECT_EQ(original.property_names(), std::vector<std::string>{property::esp});

  // Copy assignment replaces everything, including the property list.
  copy = original;
  EXPECT_EQ(copy.positions(), before);
  EXPECT_EQ(copy.property_names(), std::vector<std::string>{property::esp});
  Surface self = original;
  const Surface& alias = self;
  self = alias;
  EXPECT_EQ(self.positions(), before);
}

TEST(SurfaceValue, MovesTakeTheStateAndLeaveTheSourceEmpty) {
  const Surface reference = sample();
  Surface from = sample();
  Surface to = std::move(from);
  expect_empty(from);  // NOLINT(bugprone-use-after-move): the documented moved-from state
  EXPECT_EQ(to.positions(), reference.positions());
  EXPECT_EQ(to.property(property::esp), reference.property(property::esp));
  EXPECT_EQ(to.source(), "sample.ply");

  Surface other = test::tetrahedron(1.0);
  other = std::move(to);
  expect_empty(to);  // NOLINT(bugprone-use-after-move)
  EXPECT_EQ(other.n_vertices(), reference.n_vertices());
  EXPECT_EQ(other.property(property::esp), reference.property(property::esp));

  // A moved-from surface is an ordinary empty one: it takes properties of its (zero) size and
  // can be filled again.
  to.set_property(property::lp, Eigen::VectorXd());
  EXPECT_TRUE(to.has_property(property::lp));
  EXPECT_THROW(to.property(property::esp), InputError);
  to = reference;
  EXPECT_EQ(to.positions(), reference.positions());
  expect_empty(Surface());
}

TEST(SurfaceValue, PropertiesFollowTheVertexCount) {
  Surface s = test::tetrahedron(1.0);
  EXPECT_THROW(s.set_property("x", Eigen::VectorXd::Zero(3)), InputError);
  EXPECT_THROW(s.set_normals(Eigen::MatrixX3d::Zero(5, 3)), InputError);
  s.set_property("x", Eigen::VectorXd::LinSpaced(4, 0, 3));
  EXPECT_EQ(s.property("x", 2), 2.0);
  s.remove_property("x");
  EXPECT_FALSE(s.has_property("x"));
  EXPECT_THROW(s.property_type("x"), InputError);
}

TEST(SurfaceFromArrays, RejectedFacesThrowWithoutWritingToStderr) {
  // Three triangles on one edge: the third cannot join a manifold half-edge mesh.
  Eigen::MatrixX3d p(5, 3);
  p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  Eigen::MatrixX3i f(3, 3);
  f << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  std::ostringstream captured;
  std::streambuf* const saved = std::cerr.rdbuf(captured.rdbuf());
  try {
    Surface::from_arrays(p, f, "fin");
    ADD_FAILURE() << "a complex edge was accepted";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("fin: face 2"), std::string::npos) << e.what();
  }
  std::cerr.rdbuf(saved);
  EXPECT_EQ(captured.str(), "");
}

// Decimation for display keeps a closed sphere within its vertex budget, every kept vertex one of
// the input's with its position and properties, and the area close to the sphere's.
TEST(Decimate, ASphereKeepsItsShapeAndItsVerticesProperties) {
  Surface sphere = test::icosphere(10.0, 24);
  const auto n = static_cast<Eigen::Index>(sphere.n_vertices());
  const Eigen::MatrixX3d positions = sphere.positions();
  sphere.set_property("height", positions.col(2), ValueType::float32);
  sphere.compute_normals();
  const DecimatedSurface small = decimate(sphere, 500);
  EXPECT_LE(small.surface.n_vertices(), 500u);
  EXPECT_GE(small.surface.n_vertices(), 450u);
  ASSERT_EQ(small.original.size(), small.surface.n_vertices());
  const SurfaceMeasures before = measure_surface(sphere);
  const SurfaceMeasures after = measure_surface(small.surface);
  EXPECT_EQ(after.euler_characteristic, 2);
  EXPECT_EQ(after.boundary_edges, 0u);
  EXPECT_NEAR(after.area / before.area, 1.0, 0.03);
  EXPECT_EQ(small.surface.property_type("height"), ValueType::float32);
  EXPECT_TRUE(small.surface.has_normals());
  const Eigen::MatrixX3d kept = small.surface.positions();
  const Eigen::VectorXd height = small.surface.property("height");
  for (std::size_t v = 0; v < small.original.size(); ++v) {
    const int o = small.original[v];
    ASSERT_GE(o, 0);
    ASSERT_LT(o, n);
    EXPECT_EQ(kept.row(static_cast<Eigen::Index>(v)), positions.row(o));
    EXPECT_EQ(height(static_cast<Eigen::Index>(v)), positions(o, 2));
  }
  // Within the budget already: unchanged, identity map.
  const DecimatedSurface same = decimate(small.surface, 500);
  EXPECT_EQ(same.surface.positions(), small.surface.positions());
  EXPECT_EQ(same.original[7], 7);
  EXPECT_THROW(decimate(sphere, 3), OptionError);
}

}  // namespace
}  // namespace surfcomp::mesh
