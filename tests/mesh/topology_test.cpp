#include "analytic_meshes.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/topology.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace surfcomp::mesh {
namespace {

/// Each vertex's neighbours as the triangles' edges give them.
std::vector<std::set<int>> neighbours_from_faces(const Surface& surface) {
  std::vector<std::set<int>> out(surface.n_vertices());
  const Eigen::MatrixX3i f = surface.faces();
  for (Eigen::Index t = 0; t < f.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      out[static_cast<std::size_t>(f(t, k))].insert(f(t, (k + 1) % 3));
      out[static_cast<std::size_t>(f(t, (k + 1) % 3))].insert(f(t, k));
    }
  }
  return out;
}

/// True when face `t` lists (a, b, c) in this cyclic order, i.e. turns the same way.
bool face_is(const Eigen::MatrixX3i& f, int t, int a, int b, int c) {
  for (int k = 0; k < 3; ++k) {
    if (f(t, k) == a && f(t, (k + 1) % 3) == b && f(t, (k + 2) % 3) == c) return true;
  }
  return false;
}

/// On every vertex of a surface made of one fan per vertex: the ring holds exactly the
/// neighbours the faces give, and face i of the ring is (vertex, ring i, ring i + 1) in the
/// stored counter-clockwise order, so the ring turns counter-clockwise seen from outside. Returns
/// the number of boundary vertices (rings that do not close).
int check_rings(const Surface& surface) {
  const std::vector<std::set<int>> expected = neighbours_from_faces(surface);
  const Eigen::MatrixX3i f = surface.faces();
  int boundary = 0;
  for (int v = 0; v < static_cast<int>(surface.n_vertices()); ++v) {
    const std::vector<int> ring = one_ring_vertices(surface, v);
    const std::vector<int> fan = one_ring_faces(surface, v);
    EXPECT_EQ(std::set<int>(ring.begin(), ring.end()), expected[static_cast<std::size_t>(v)])
        << "vertex " << v;
    EXPECT_EQ(ring.size(), expected[static_cast<std::size_t>(v)].size()) << "vertex " << v;
    const bool closed = fan.size() == ring.size();
    if (!closed) {
      ++boundary;
      EXPECT_EQ(fan.size() + 1, ring.size()) << "vertex " << v;
    }
    for (std::size_t i = 0; i < fan.size(); ++i) {
      const int next = ring[(i + 1) % ring.size()];
      EXPECT_TRUE(face_is(f, fan[i], v, ring[i], next))
          << "vertex " << v << ": face " << fan[i] << " is not (" << v << ", " << ring[i] << ", "
          << next << ")";
    }
  }
  return boundary;
}

TEST(OneRing, ClosedSurfacesTurnCounterClockwiseFromOutside) {
  EXPECT_EQ(check_rings(test::icosphere(2.0, 4)), 0);
  EXPECT_EQ(check_rings(test::torus(3.0, 1.0, 24, 12)), 0);
  EXPECT_EQ(check_rings(test::tetrahedron(1.0)), 0);
  // Inside out, the stored order turns the other way and the rings follow it.
  EXPECT_EQ(check_rings(test::with_flipped_faces(test::octahedron(1.0))), 0);
}

TEST(OneRing, DiskCentreAndBoundary) {
  // disk(2, 2): centre 0, ring 1 = vertices 1..6 at angles 0, 60, ..., ring 2 = 7..18 at
  // angles 0, 30, ..., 330 degrees, all in z = 0 with the faces turning counter-clockwise seen
  // from +z.
  const Surface disk = test::disk(2.0, 2);
  EXPECT_EQ(check_rings(disk), 12);  // the outer ring is the boundary
  std::vector<int> centre = one_ring_vertices(disk, 0);
  ASSERT_EQ(centre.size(), 6u);
  std::rotate(centre.begin(), std::find(centre.begin(), centre.end(), 1), centre.end());
  EXPECT_EQ(centre, (std::vector<int>{1, 2, 3, 4, 5, 6}));  // increasing angle
  EXPECT_EQ(one_ring_faces(disk, 0).size(), 6u);
  // Vertex 7 at (2, 0): the surface lies towards -x, so counter-clockwise the ring runs from the
  // boundary neighbour above (8, at 30 degrees) through the inside to the one below (18).
  const std::vector<int> edge = one_ring_vertices(disk, 7);
  ASSERT_GE(edge.size(), 3u);
  EXPECT_EQ(edge.front(), 8);
  EXPECT_EQ(edge.back(), 18);
  const Eigen::MatrixX3d p = disk.positions();
  double previous = 0.0;
  for (const int w : edge) {
    const Eigen::Vector3d d = p.row(w) - p.row(7);
    const double angle = std::atan2(d.y(), d.x());  // in (0, pi) then (-pi, 0): make it rise
    const double rising = angle < 0.0 ? angle + 2.0 * M_PI : angle;
    EXPECT_GT(rising, previous) << "vertex " << w;
    previous = rising;
  }
  EXPECT_EQ(one_ring_faces(disk, 7).size(), edge.size() - 1);
}

TEST(OneRing, IsolatedVertexAndBadIndex) {
  Eigen::MatrixX3d p(4, 3);
  p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5;
  Eigen::MatrixX3i f(1, 3);
  f << 0, 1, 2;
  const Surface s = Surface::from_arrays(p, f, "triangle and a point");
  EXPECT_TRUE(one_ring_vertices(s, 3).empty());
  EXPECT_TRUE(one_ring_faces(s, 3).empty());
  EXPECT_EQ(one_ring_vertices(s, 0), (std::vector<int>{1, 2}));
  EXPECT_EQ(one_ring_faces(s, 0), (std::vector<int>{0}));
  EXPECT_THROW(one_ring_vertices(s, 4), InputError);
  EXPECT_THROW(one_ring_faces(s, -1), InputError);
  try {
    one_ring_vertices(s, 4);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle and a point"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("0..3"), std::string::npos) << e.what();
  }
}

TEST(ConnectedComponents, CountsAndNumbersByLowestVertex) {
  const Surface one = test::icosphere(1.0, 3);
  const SurfaceComponents single = connected_components(one);
  EXPECT_EQ(single.count, 1);
  EXPECT_EQ(single.component, std::vector<int>(one.n_vertices(), 0));

  const Surface a = test::icosphere(1.0, 2);
  const Surface b = test::icosphere(1.0, 3, Eigen::Vector3d(5.0, 0.0, 0.0));
  const Surface two = test::merged(a, b);
  const SurfaceComponents pair = connected_components(two);
  EXPECT_EQ(pair.count, 2);
  ASSERT_EQ(pair.component.size(), two.n_vertices());
  for (std::size_t v = 0; v < two.n_vertices(); ++v) {
    EXPECT_EQ(pair.component[v], v < a.n_vertices() ? 0 : 1) << "vertex " << v;
  }
  // Three parts, the first starting after the others' lowest vertex: numbering follows the
  // lowest vertex of each component, and a lone vertex is a component of its own.
  Eigen::MatrixX3d p(7, 3);
  p << 0, 0, 0, 9, 9, 9, 1, 0, 0, 5, 0, 0, 0, 1, 0, 6, 0, 0, 5, 1, 0;
  Eigen::MatrixX3i f(2, 3);
  f << 3, 5, 6, 0, 2, 4;
  const SurfaceComponents three = connected_components(Surface::from_arrays(p, f));
  EXPECT_EQ(three.count, 3);
  EXPECT_EQ(three.component, (std::vector<int>{0, 1, 0, 2, 0, 2, 2}));

  EXPECT_EQ(connected_components(Surface()).count, 0);
}

}  // namespace
}  // namespace surfcomp::mesh
