// On-surface distances by Dijkstra's algorithm over the mesh edges, each edge weighted by its
// Euclidean length (seed section 3.4, step 2; METHOD section 2). The edge path zig-zags, so
// it is longer than the true geodesic except along straight chains of edges: measured +8 % on
// average (at most +12 %) on a flat ring-triangulated disk, +8 % on average on icosphere
// triangulations and +5.7 % between antipodes (tests/geodesic_test.cpp); refining the mesh
// does not reduce it.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <limits>
#include <utility>
#include <vector>

namespace surfcomp::mesh {

/// How on-surface distances are computed.
enum class GeodesicMethod {
  /// Dijkstra over the mesh edges, edge weight = Euclidean length (the seed's choice). Its
  /// balls are polygons, not discs: a 5 A patch on a sphere of radius 5 A has 80-88 % of the
  /// spherical cap's area.
  dijkstra,
  /// Dijkstra ordering with the fast-marching triangle update (Kimmel & Sethian 1998): a
  /// vertex is also reached straight across a triangle whose other two vertices are done,
  /// from the virtual source their distances define in the triangle's plane (when that ray
  /// crosses the opposite edge; obtuse triangles fall back to the edges). Exact on a plane,
  /// within about 1-2 % of the great-circle distance on a sphere. METHOD section 2 allows it.
  fast_marching,
};

/// Dijkstra distances (A) from vertex `source` to every vertex of `surface` (#V values).
/// Vertices farther than `max_distance` (A), or in another connected component, are +inf and
/// are not expanded, so a bounded run only visits the vertices within the bound and their
/// neighbours. Throws TopologyError for a surface without vertices, InputError when `source`
/// is not a vertex index, OptionError when max_distance is negative or NaN (+inf is allowed).
/// With method fast_marching the distances are those of the fast-marching update instead.
Eigen::VectorXd edge_geodesic_distances(
    const Surface& surface, int source,
    double max_distance = std::numeric_limits<double>::infinity(),
    GeodesicMethod method = GeodesicMethod::dijkstra);

/// Reusable state for many bounded Dijkstra runs on one surface: the per-vertex buffers are
/// allocated once and only the entries a run touched are reset, so a run costs time in
/// proportion to the vertices it reaches, not to the surface. Ties in the priority queue are
/// broken by vertex index, so results and visiting order are deterministic.
/// The solver keeps a reference to `surface`, which must outlive it and not change. One solver
/// serves one thread; give each thread its own solver.
class GeodesicSolver {
 public:
  /// Throws TopologyError for a surface without vertices.
  explicit GeodesicSolver(const Surface& surface, GeodesicMethod method = GeodesicMethod::dijkstra);

  /// The vertices whose Dijkstra distance from `source` is at most `max_distance` (A), as
  /// (vertex, distance) pairs sorted by vertex; the source itself is included at distance 0.
  /// When `allowed` is given (one entry per vertex), the paths only pass through vertices
  /// whose entry is non-zero (the source is always allowed). Throws InputError when `source`
  /// is not a vertex index or `allowed` has the wrong size, OptionError when max_distance is
  /// negative or NaN.
  std::vector<std::pair<int, double>> within(int source, double max_distance,
                                             const std::vector<char>* allowed = nullptr);

  const Surface& surface() const { return *surface_; }

 private:
  const Surface* surface_;
  GeodesicMethod method_;
  std::vector<double> distance_;  ///< +inf except at the vertices the running query touched
  std::vector<char> done_;        ///< 1 at the vertices whose distance is final in this query
  std::vector<int> touched_;      ///< vertices whose distance_ entry is finite
  std::vector<std::pair<double, int>> heap_;  ///< (tentative distance, vertex), min-heap
};

}  // namespace surfcomp::mesh
