#include "analytic_meshes.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/geodesic.hpp"
#include "surfcomp/mesh/patch.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <thread>

namespace surfcomp::mesh {
namespace {

// ---------------------------------------------------------------------------------------------
// A 7 x 7 grid in the plane z = 0, spacing 1 A: vertex (i, j) has index 7 j + i; square (i, j)
// (0 <= i, j < 6) holds face 2 (6 j + i) = (i,j) (i+1,j) (i+1,j+1) and face 2 (6 j + i) + 1 =
// (i,j) (i+1,j+1) (i,j+1), both counter-clockwise seen from +z. The diagonals run from (i, j)
// to (i+1, j+1).
int gv(int i, int j) { return 7 * j + i; }
int lower_face(int i, int j) { return 2 * (6 * j + i); }
int upper_face(int i, int j) { return 2 * (6 * j + i) + 1; }

Surface grid() {
  Eigen::MatrixX3d p(49, 3);
  for (int j = 0; j < 7; ++j) {
    for (int i = 0; i < 7; ++i) p.row(gv(i, j)) << i, j, 0.0;
  }
  Eigen::MatrixX3i f(72, 3);
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 6; ++i) {
      f.row(lower_face(i, j)) << gv(i, j), gv(i + 1, j), gv(i + 1, j + 1);
      f.row(upper_face(i, j)) << gv(i, j), gv(i + 1, j + 1), gv(i, j + 1);
    }
  }
  return Surface::from_arrays(p, f, "grid");
}

/// The 3 x 3 block of vertices around the centre (3, 3).
std::vector<int> block() {
  std::vector<int> out;
  for (int j = 2; j <= 4; ++j) {
    for (int i = 2; i <= 4; ++i) out.push_back(gv(i, j));
  }
  return out;
}

/// The six triangles around (3, 3): the 2 x 2 block of squares without the two corner
/// triangles at (4, 2) and (2, 4) that have two border edges.
std::vector<int> hexagon() {
  return {lower_face(2, 2), upper_face(2, 2), upper_face(3, 2),
          lower_face(2, 3), lower_face(3, 3), upper_face(3, 3)};
}

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// ---------------------------------------------------------------------------------------------
// Checks on an extracted patch.

/// Directed edges of the patch faces -> how many faces traverse them.
std::map<std::pair<int, int>, int> directed_edges(const Patch& patch) {
  std::map<std::pair<int, int>, int> out;
  for (Eigen::Index f = 0; f < patch.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) ++out[{patch.faces(f, k), patch.faces(f, (k + 1) % 3)}];
  }
  return out;
}

int euler_characteristic(const Patch& patch) {
  std::set<std::pair<int, int>> edges;
  for (const auto& [e, count] : directed_edges(patch)) {
    edges.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
  }
  return static_cast<int>(patch.surface_vertex.size()) - static_cast<int>(edges.size()) +
         static_cast<int>(patch.faces.rows());
}

double patch_area(const Patch& patch) {
  double area = 0.0;
  for (Eigen::Index f = 0; f < patch.faces.rows(); ++f) {
    const Eigen::Vector3d a = patch.positions.row(patch.faces(f, 0));
    const Eigen::Vector3d b = patch.positions.row(patch.faces(f, 1));
    const Eigen::Vector3d c = patch.positions.row(patch.faces(f, 2));
    area += (b - a).cross(c - a).norm() / 2.0;
  }
  return area;
}

/// Signed area of `loop` projected on the plane through the centre orthogonal to `normal`,
/// positive for a counter-clockwise loop seen from the side `normal` points to.
double projected_signed_area(const Patch& patch, const std::vector<int>& loop,
                             const Eigen::Vector3d& normal) {
  const Eigen::Vector3d c = patch.positions.row(patch.center);
  double twice = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Eigen::Vector3d a = patch.positions.row(loop[i]).transpose() - c;
    const Eigen::Vector3d b = patch.positions.row(loop[(i + 1) % loop.size()]).transpose() - c;
    twice += a.cross(b).dot(normal);
  }
  return twice / 2.0;
}

/// Asserts the invariants every patch has: back-references, distances, a connected mesh whose
/// faces have at most one border edge and whose border loops pass every border vertex once,
/// along border edges with the patch on the left; Euler characteristic 2 - 2 genus - #loops.
void expect_valid_patch(const Surface& surface, const Patch& patch, const PatchOptions& options) {
  const auto n = static_cast<int>(patch.surface_vertex.size());
  ASSERT_EQ(patch.positions.rows(), n);
  ASSERT_EQ(patch.distance.size(), n);
  ASSERT_GE(patch.center, 0);
  ASSERT_LT(patch.center, n);
  EXPECT_EQ(patch.distance(patch.center), 0.0);
  const Eigen::MatrixX3d p = surface.positions();
  for (int i = 0; i < n; ++i) {
    if (i > 0) {
      EXPECT_LT(patch.surface_vertex[static_cast<std::size_t>(i - 1)],
                patch.surface_vertex[static_cast<std::size_t>(i)]);
    }
    EXPECT_EQ(patch.positions.row(i), p.row(patch.surface_vertex[static_cast<std::size_t>(i)]));
    EXPECT_LE(patch.distance(i), options.radius * (1.0 + options.margin) + 1e-12);
  }
  // Faces keep the surface's orientation.
  const Eigen::MatrixX3i surface_faces = surface.faces();
  std::set<std::array<int, 3>> oriented;
  for (Eigen::Index f = 0; f < surface_faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      oriented.insert(
          {surface_faces(f, k), surface_faces(f, (k + 1) % 3), surface_faces(f, (k + 2) % 3)});
    }
  }
  for (Eigen::Index f = 0; f < patch.faces.rows(); ++f) {
    const std::array<int, 3> back = {
        patch.surface_vertex[static_cast<std::size_t>(patch.faces(f, 0))],
        patch.surface_vertex[static_cast<std::size_t>(patch.faces(f, 1))],
        patch.surface_vertex[static_cast<std::size_t>(patch.faces(f, 2))]};
    EXPECT_EQ(oriented.count(back), 1U) << "patch face " << f;
  }
  const auto edges = directed_edges(patch);
  std::set<std::pair<int, int>> border;
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 1);
    if (edges.count({e.second, e.first}) == 0) border.insert(e);
  }
  for (Eigen::Index f = 0; f < patch.faces.rows(); ++f) {
    int on_border = 0;
    for (int k = 0; k < 3; ++k) {
      on_border += border.count({patch.faces(f, k), patch.faces(f, (k + 1) % 3)}) > 0;
    }
    EXPECT_LE(on_border, 1) << "patch face " << f << " is dangling";
  }
  std::vector<std::vector<int>> loops = patch.holes;
  if (!patch.outer_boundary.empty()) loops.push_back(patch.outer_boundary);
  std::set<int> seen;
  std::size_t walked = 0;
  for (const auto& loop : loops) {
    ASSERT_GE(loop.size(), 3U);
    EXPECT_EQ(loop.front(), *std::min_element(loop.begin(), loop.end()));
    for (std::size_t i = 0; i < loop.size(); ++i) {
      EXPECT_TRUE(seen.insert(loop[i]).second) << "vertex " << loop[i] << " passed twice";
      EXPECT_EQ(border.count({loop[i], loop[(i + 1) % loop.size()]}), 1U)
          << loop[i] << " -> " << loop[(i + 1) % loop.size()] << " is not a border edge";
    }
    walked += loop.size();
  }
  EXPECT_EQ(walked, border.size());
  EXPECT_EQ(euler_characteristic(patch), 2 - 2 * patch.genus - static_cast<int>(loops.size()));
  // Connected through shared edges.
  std::map<std::pair<int, int>, std::vector<Eigen::Index>> faces_of_edge;
  for (Eigen::Index f = 0; f < patch.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = patch.faces(f, k), b = patch.faces(f, (k + 1) % 3);
      faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  }
  std::vector<char> reached(static_cast<std::size_t>(patch.faces.rows()), 0);
  std::vector<Eigen::Index> stack = {0};
  reached[0] = 1;
  std::size_t count = 1;
  while (!stack.empty()) {
    const Eigen::Index f = stack.back();
    stack.pop_back();
    for (int k = 0; k < 3; ++k) {
      const int a = patch.faces(f, k), b = patch.faces(f, (k + 1) % 3);
      for (const Eigen::Index g : faces_of_edge[{std::min(a, b), std::max(a, b)}]) {
        if (!reached[static_cast<std::size_t>(g)]) {
          reached[static_cast<std::size_t>(g)] = 1;
          ++count;
          stack.push_back(g);
        }
      }
    }
  }
  EXPECT_EQ(count, static_cast<std::size_t>(patch.faces.rows())) << "patch is not connected";
}

void expect_identical(const Patch& a, const Patch& b) {
  EXPECT_EQ(a.center, b.center);
  EXPECT_EQ(a.surface_vertex, b.surface_vertex);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.distance, b.distance);
  EXPECT_EQ(a.outer_boundary, b.outer_boundary);
  EXPECT_EQ(a.holes, b.holes);
}

// ---------------------------------------------------------------------------------------------
// The steps on the grid.

TEST(PatchSteps, PreselectEuclideanKeepsTheBall) {
  const Surface g = grid();
  EXPECT_EQ(preselect_euclidean(g, gv(3, 3), 1.5), block());
  EXPECT_EQ(preselect_euclidean(g, gv(3, 3), 0.0), std::vector<int>{gv(3, 3)});
  EXPECT_EQ(preselect_euclidean(g, gv(0, 0), 1.0),
            (std::vector<int>{gv(0, 0), gv(1, 0), gv(0, 1)}));
}

TEST(PatchSteps, PatchDistancesRunDijkstraInsideThePreselection) {
  const Surface g = grid();
  const auto d = patch_distances(g, gv(3, 3), block(), 10.0);
  ASSERT_EQ(d.size(), 9U);
  const std::map<int, double> expected = {{gv(2, 2), std::sqrt(2.0)},
                                          {gv(3, 2), 1.0},
                                          {gv(4, 2), 2.0},
                                          {gv(2, 3), 1.0},
                                          {gv(3, 3), 0.0},
                                          {gv(4, 3), 1.0},
                                          {gv(2, 4), 2.0},
                                          {gv(3, 4), 1.0},
                                          {gv(4, 4), std::sqrt(2.0)}};
  for (const auto& [v, dist] : d) EXPECT_DOUBLE_EQ(dist, expected.at(v)) << "vertex " << v;
  // Without (4, 3) and (3, 2) the corner (4, 2) cannot be reached inside the preselection.
  std::vector<int> cut = block();
  cut.erase(std::find(cut.begin(), cut.end(), gv(4, 3)));
  cut.erase(std::find(cut.begin(), cut.end(), gv(3, 2)));
  const auto confined = patch_distances(g, gv(3, 3), cut, 10.0);
  EXPECT_EQ(confined.size(), 6U);
  for (const auto& [v, dist] : confined) EXPECT_NE(v, gv(4, 2));
  // The bound: only distance <= 1.
  EXPECT_EQ(patch_distances(g, gv(3, 3), block(), 1.0).size(), 5U);
  EXPECT_THROW(patch_distances(g, gv(0, 0), block(), 1.0), InputError);  // centre not preselected
}

TEST(PatchSteps, SelectWithinRadiusAddsOnlyMarginVerticesNextToTheCore) {
  const Surface g = grid();
  // (5, 3) is within the 5 % margin and next to (4, 3); (6, 3) is within the margin but only
  // next to (5, 3); (4, 4) is beyond the margin.
  const std::vector<std::pair<int, double>> d = {
      {gv(3, 3), 0.0}, {gv(4, 3), 1.0}, {gv(5, 3), 1.04}, {gv(6, 3), 1.05}, {gv(4, 4), 1.2}};
  EXPECT_EQ(select_within_radius(g, d, 1.0, 0.05),
            (std::vector<int>{gv(3, 3), gv(4, 3), gv(5, 3)}));
  EXPECT_EQ(select_within_radius(g, d, 1.0, 0.0), (std::vector<int>{gv(3, 3), gv(4, 3)}));
  EXPECT_EQ(select_within_radius(g, d, 1.0, 0.25),
            (std::vector<int>{gv(3, 3), gv(4, 3), gv(5, 3), gv(4, 4)}));
}

TEST(PatchSteps, FacesWithThreeSelectedVertices) {
  const Surface g = grid();
  EXPECT_EQ(faces_with_three_selected(g, block()),
            sorted({lower_face(2, 2), upper_face(2, 2), lower_face(3, 2), upper_face(3, 2),
                    lower_face(2, 3), upper_face(2, 3), lower_face(3, 3), upper_face(3, 3)}));
  // Three vertices of one square's lower triangle and one more: one face.
  EXPECT_EQ(faces_with_three_selected(g, {gv(2, 2), gv(3, 2), gv(2, 3), gv(3, 3)}).size(), 2U);
  EXPECT_TRUE(faces_with_three_selected(g, {gv(2, 2), gv(3, 2)}).empty());
}

TEST(PatchSteps, DanglingTrianglesAreRemovedPassByPass) {
  const Surface g = grid();
  // The 2 x 2 block has two corner triangles with two border edges each.
  const std::vector<int> square = faces_with_three_selected(g, block());
  EXPECT_EQ(remove_dangling_triangles(g, square), sorted(hexagon()));
  // A chain sticking out of the hexagon at edge (4,3)-(4,4): (4,3) (5,4) (4,4) has one border
  // edge while (4,3) (5,3) (5,4) hangs on, then two once the first pass removed its neighbour.
  std::vector<int> chain = hexagon();
  chain.push_back(upper_face(4, 3));
  chain.push_back(lower_face(4, 3));
  chain = sorted(chain);
  std::vector<int> once = hexagon();
  once.push_back(upper_face(4, 3));
  once = sorted(once);
  EXPECT_EQ(remove_dangling_triangles(g, chain), once);
  EXPECT_EQ(remove_dangling_triangles(g, once), sorted(hexagon()));
  EXPECT_EQ(remove_dangling_triangles(g, sorted(hexagon())), sorted(hexagon()));
  // A lone triangle has three border edges.
  EXPECT_TRUE(remove_dangling_triangles(g, {lower_face(0, 0)}).empty());
}

TEST(PatchSteps, IsolatedVerticesAreRemoved) {
  const Surface g = grid();
  std::vector<int> expected = block();
  expected.erase(std::find(expected.begin(), expected.end(), gv(4, 2)));
  expected.erase(std::find(expected.begin(), expected.end(), gv(2, 4)));
  EXPECT_EQ(remove_isolated_vertices(g, block(), sorted(hexagon())), expected);
}

TEST(PatchSteps, BowTieKeepsTheLargerFanAndComponentKeepsTheCentre) {
  const Surface g = grid();
  // Hexagons around (3, 3) and (5, 5) touch at (4, 4): there the border passes twice.
  const std::vector<int> second = {lower_face(4, 4), upper_face(4, 4), upper_face(5, 4),
                                   lower_face(4, 5), lower_face(5, 5), upper_face(5, 5)};
  std::vector<int> both = hexagon();
  both.insert(both.end(), second.begin(), second.end());
  both = sorted(both);
  EXPECT_THROW(boundary_loops(g, both), TopologyError);
  // Both fans at (4, 4) have two triangles; the one with the lower face index stays.
  std::vector<int> expected = hexagon();
  expected.insert(expected.end(),
                  {upper_face(5, 4), lower_face(4, 5), lower_face(5, 5), upper_face(5, 5)});
  EXPECT_EQ(resolve_nonmanifold_vertices(g, both), sorted(expected));
  EXPECT_EQ(keep_component(g, sorted(expected), gv(3, 3)), sorted(hexagon()));
  EXPECT_TRUE(keep_component(g, sorted(hexagon()), gv(6, 6)).empty());
  // Fans of one and two triangles at (4, 4): the larger stays although the single triangle
  // has the lower face index.
  EXPECT_EQ(resolve_nonmanifold_vertices(g, {upper_face(3, 3), lower_face(4, 4), upper_face(4, 4)}),
            (std::vector<int>{lower_face(4, 4), upper_face(4, 4)}));
  // refine_patch ends at the hexagon around the centre whatever the tie-break did.
  PatchSelection selection;
  selection.faces = both;
  const Eigen::MatrixX3i g_faces = g.faces();
  for (const int f : both) {
    for (int k = 0; k < 3; ++k) selection.vertices.push_back(g_faces(f, k));
  }
  std::sort(selection.vertices.begin(), selection.vertices.end());
  selection.vertices.erase(std::unique(selection.vertices.begin(), selection.vertices.end()),
                           selection.vertices.end());
  const PatchSelection refined = refine_patch(g, selection, gv(3, 3));
  EXPECT_EQ(refined.faces, sorted(hexagon()));
  EXPECT_EQ(refined.vertices,
            sorted({gv(2, 2), gv(3, 2), gv(4, 3), gv(4, 4), gv(3, 4), gv(2, 3), gv(3, 3)}));
}

TEST(PatchSteps, BoundaryLoopsWalkTheOuterBorderCounterClockwise) {
  const Surface g = grid();
  const BoundaryLoops hex = boundary_loops(g, sorted(hexagon()));
  // Seen from +z, counter-clockwise around (3, 3), starting at the lowest index.
  EXPECT_EQ(hex.outer,
            (std::vector<int>{gv(2, 2), gv(3, 2), gv(4, 3), gv(4, 4), gv(3, 4), gv(2, 3)}));
  EXPECT_TRUE(hex.holes.empty());
  // The 4 x 4 block of squares around (3, 3) without the hexagon: an annulus. Its outer
  // border (perimeter 16 A) beats the hexagonal hole (4 + 2 sqrt 2 A), which is walked with the
  // patch on its left, i.e. clockwise seen from +z.
  std::vector<int> ring;
  for (int j = 1; j <= 4; ++j) {
    for (int i = 1; i <= 4; ++i) {
      ring.push_back(lower_face(i, j));
      ring.push_back(upper_face(i, j));
    }
  }
  std::vector<int> annulus;
  const std::vector<int> hex_faces = sorted(hexagon());
  std::set_difference(ring.begin(), ring.end(), hex_faces.begin(), hex_faces.end(),
                      std::back_inserter(annulus));
  annulus = sorted(annulus);
  const BoundaryLoops loops = boundary_loops(g, annulus);
  ASSERT_EQ(loops.holes.size(), 1U);
  EXPECT_EQ(loops.holes[0],
            (std::vector<int>{gv(2, 2), gv(2, 3), gv(3, 4), gv(4, 4), gv(4, 3), gv(3, 2)}));
  EXPECT_EQ(loops.outer.size(), 16U);
  EXPECT_EQ(loops.outer.front(), gv(1, 1));
  EXPECT_EQ(loops.outer[1], gv(2, 1));  // counter-clockwise: along +x first
}

// ---------------------------------------------------------------------------------------------
// Whole patches.

TEST(ExtractPatch, GridPatchIsTheExpectedHexagon) {
  const Surface g = grid();
  PatchOptions options;
  options.radius = 1.5;
  const Patch patch = extract_patch(g, gv(3, 3), options);
  expect_valid_patch(g, patch, options);
  // Distance <= 1.5: the centre, its four axis neighbours and the diagonal (2,2), (4,4); the
  // margin adds nothing (the next vertices are at 2). Faces with three of them: the hexagon.
  EXPECT_EQ(patch.surface_vertex,
            sorted({gv(2, 2), gv(3, 2), gv(2, 3), gv(3, 3), gv(4, 3), gv(3, 4), gv(4, 4)}));
  EXPECT_EQ(patch.faces.rows(), 6);
  EXPECT_EQ(patch.surface_vertex[static_cast<std::size_t>(patch.center)], gv(3, 3));
  EXPECT_EQ(patch.outer_boundary.size(), 6U);
  EXPECT_GT(projected_signed_area(patch, patch.outer_boundary, Eigen::Vector3d::UnitZ()), 0.0);
  EXPECT_EQ(euler_characteristic(patch), 1);
}

TEST(ExtractPatch, SphereCapMatchesTheSphericalCap) {
  const double r = 5.0;
  const Surface sphere = test::icosphere(r, 9);  // 812 vertices, 2.6 per A^2
  for (const GeodesicMethod method : {GeodesicMethod::dijkstra, GeodesicMethod::fast_marching}) {
    const bool dijkstra = method == GeodesicMethod::dijkstra;
    for (const double rho : {2.5, 5.0}) {
      PatchOptions options;
      options.radius = rho;
      options.distance = method;
      double lowest = 2.0, highest = 0.0;
      for (const int centre : {0, 100, 333, 811}) {
        const Patch patch = extract_patch(sphere, centre, options);
        expect_valid_patch(sphere, patch, options);
        EXPECT_EQ(euler_characteristic(patch), 1);
        EXPECT_TRUE(patch.holes.empty());
        EXPECT_EQ(patch.genus, 0);
        const Eigen::Vector3d normal = sphere.positions().row(centre).normalized();
        EXPECT_GT(projected_signed_area(patch, patch.outer_boundary, normal), 0.0);
        const double cap = 2.0 * M_PI * r * r * (1.0 - std::cos(rho / r));
        const double ratio = patch_area(patch) / cap;
        double farthest_arc = 0.0;
        for (Eigen::Index i = 0; i < patch.positions.rows(); ++i) {
          const double cosine =
              patch.positions.row(i).dot(sphere.positions().row(centre)) / (r * r);
          farthest_arc = std::max(farthest_arc, r * std::acos(std::clamp(cosine, -1.0, 1.0)));
        }
        std::cout << (dijkstra ? "dijkstra" : "fast marching") << ", sphere r 5, rho " << rho
                  << ", centre " << centre << ": " << patch.surface_vertex.size() << " vertices, "
                  << patch.faces.rows() << " faces, area / cap " << ratio
                  << ", farthest great-circle distance " << farthest_arc << " A, outer border "
                  << patch.outer_boundary.size() << " vertices\n";
        lowest = std::min(lowest, ratio);
        highest = std::max(highest, ratio);
        // Fast marching is within 1.2 % of the great circle (geodesic_test), either way.
        EXPECT_LE(farthest_arc, rho * 1.05 * (dijkstra ? 1.0 : 1.012));
      }
      if (dijkstra) {
        // Dijkstra's balls are polygons with corners at rho along the straight edge chains:
        // measured 0.80-0.88 of the cap at rho = 5, 0.64-0.74 at rho = 2.5 (2-3 edges).
        EXPECT_GT(lowest, rho > 3.0 ? 0.78 : 0.6);
        EXPECT_LT(highest, 0.9);
      } else {
        // Fast marching gives round patches: measured 0.97-1.02 of the cap at rho = 5; at
        // rho = 2.5 (4 edges) the jagged border loses a band of half an edge: 0.74-0.86.
        EXPECT_GT(lowest, rho > 3.0 ? 0.95 : 0.7);
        EXPECT_LT(highest, 1.05);
      }
    }
  }
}

TEST(ExtractPatch, TorusPatchWrappingTheTubeIsAnAnnulus) {
  const Surface torus = test::torus(4.0, 1.5, 64, 24);
  // Around the tube is 2 pi 1.5 = 9.4 A: a 6 A patch meets itself behind the tube and becomes
  // a band (one hole); around the central hole is >= 2 pi 2.5 = 15.7 A, so no handle forms.
  for (const int centre : {0, 12, 6}) {  // outer equator, inner equator, top
    PatchOptions options;
    options.radius = 6.0;
    const Patch patch = extract_patch(torus, centre, options);
    expect_valid_patch(torus, patch, options);
    std::cout << "torus (4, 1.5), centre " << centre
              << ", radius 6: " << patch.surface_vertex.size() << " vertices, "
              << patch.holes.size() << " holes, Euler characteristic "
              << euler_characteristic(patch) << ", genus " << patch.genus << "\n";
    EXPECT_EQ(patch.genus, 0);
    EXPECT_EQ(euler_characteristic(patch), 1 - static_cast<int>(patch.holes.size()));
  }
  // The outer-equator patch is a band around the tube.
  PatchOptions options;
  options.radius = 6.0;
  EXPECT_EQ(extract_patch(torus, 0, options).holes.size(), 1U);
  // A patch larger than half the way around the central hole gets a handle.
  options.radius = 12.0;
  const Patch big = extract_patch(torus, 0, options);
  expect_valid_patch(torus, big, options);
  std::cout << "torus, centre 0, radius 12: genus " << big.genus << ", " << big.holes.size() + 1
            << " border loops\n";
  EXPECT_EQ(big.genus, 1);
}

TEST(ExtractPatch, DeterministicAndThreadSafe) {
  const Surface sphere = test::icosphere(6.2, 11);  // 1,212 vertices, 2.5 per A^2
  const int n = static_cast<int>(sphere.n_vertices());
  PatchOptions options;  // 5 A
  std::vector<Patch> sequential(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v)
    sequential[static_cast<std::size_t>(v)] = extract_patch(sphere, v, options);
  std::vector<Patch> threaded(static_cast<std::size_t>(n));
  std::vector<std::thread> workers;
  for (int t = 0; t < 3; ++t) {
    workers.emplace_back([&, t] {
      for (int v = t; v < n; v += 3) {
        threaded[static_cast<std::size_t>(v)] = extract_patch(sphere, v, options);
      }
    });
  }
  for (auto& w : workers) w.join();
  for (int v = 0; v < n; v += 37)
    expect_identical(sequential[static_cast<std::size_t>(v)],
                     threaded[static_cast<std::size_t>(v)]);
  for (int v = 0; v < n; ++v) {
    ASSERT_EQ(sequential[static_cast<std::size_t>(v)].surface_vertex,
              threaded[static_cast<std::size_t>(v)].surface_vertex);
  }
  expect_valid_patch(sphere, sequential[0], options);
}

TEST(ExtractPatch, RejectsBadInput) {
  const Surface sphere = test::icosphere(5.0, 4);
  PatchOptions options;
  EXPECT_THROW(extract_patch(sphere, -1, options), InputError);
  EXPECT_THROW(extract_patch(sphere, static_cast<int>(sphere.n_vertices()), options), InputError);
  EXPECT_THROW(extract_patch(Surface(), 0, options), TopologyError);
  for (const double radius : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::nan("")}) {
    options.radius = radius;
    EXPECT_THROW(extract_patch(sphere, 0, options), OptionError) << radius;
  }
  options.radius = 5.0;
  options.margin = -0.1;
  EXPECT_THROW(extract_patch(sphere, 0, options), OptionError);
  // A radius shorter than every edge at the centre leaves no triangle.
  options.margin = 0.05;
  options.radius = 0.1;
  try {
    extract_patch(sphere, 0, options);
    FAIL() << "no exception";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("icosphere"), std::string::npos) << e.what();
  }
  EXPECT_THROW(faces_with_three_selected(sphere, {3, 2}), InputError);  // not sorted
  EXPECT_THROW(remove_dangling_triangles(sphere, {100000}), InputError);
}

}  // namespace
}  // namespace surfcomp::mesh
