// On-surface distances from a vertex, in Dijkstra order over the mesh edges, each edge weighted
// by its Euclidean length (method §3.1, step 2; method §2), optionally with the
// fast-marching triangle update. Edge paths zig-zag, so plain Dijkstra distances are longer
// than the true geodesic except along straight chains of edges, and refining the mesh does not
// remove that; the fast-marching update also reaches a vertex straight across a triangle
// (docs/decisions.md#patch-distances).
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <array>
#include <limits>
#include <utility>
#include <vector>

namespace surfcomp::mesh {

/// How on-surface distances are computed.
enum class GeodesicMethod {
  /// Dijkstra over the mesh edges, edge weight = Euclidean length (the seed's choice). Its
  /// balls are polygons, not discs, so a patch covers less than the geodesic disc.
  dijkstra,
  /// Dijkstra ordering with the fast-marching triangle update (Kimmel & Sethian 1998): a
  /// vertex is also reached straight across a triangle whose other two vertices are done,
  /// from the virtual source their distances define in the triangle's plane (when that ray
  /// crosses the opposite edge; obtuse triangles fall back to the edges). Exact on a plane,
  /// close to the great-circle distance on a sphere. method §2 allows it.
  fast_marching,
};

/// The names of GeodesicMethod's values, as options and Python's `method=` take them.
inline constexpr std::array<const char*, 2> geodesic_method_names = {"dijkstra", "fast-marching"};

struct GeodesicOptions {
  /// Default +inf (no bound), A. Vertices farther than this are +inf and are not expanded, so a
  /// bounded run only visits the vertices within the bound and their neighbours. Not NaN, >= 0.
  double max_distance = std::numeric_limits<double>::infinity();
  /// Default dijkstra (over the edges); fast_marching adds the triangle update.
  GeodesicMethod method = GeodesicMethod::dijkstra;
};

/// On-surface distances (A) from vertex `source` to every vertex of `surface` (#V values), by
/// options.method, up to options.max_distance; vertices beyond the bound, or in another
/// connected component, are +inf. One GeodesicSolver run: use a solver for many sources.
/// Throws TopologyError for a surface without vertices, InputError when `source` is not a
/// vertex index, OptionError when max_distance is negative or NaN.
Eigen::VectorXd geodesic_distances(const Surface& surface, int source,
                                   const GeodesicOptions& options = {});

/// Reusable state for many bounded distance runs on one surface (Dijkstra order; edge updates,
/// plus the fast-marching update when the method is fast_marching): the per-vertex buffers are
/// allocated once and only the entries a run touched are reset, so a run costs time in
/// proportion to the vertices it reaches, not to the surface. Ties in the priority queue are
/// broken by vertex index, so results and visiting order are deterministic.
/// The solver keeps a reference to `surface`, which must outlive it and not change. One solver
/// serves one thread; give each thread its own solver.
class GeodesicSolver {
 public:
  /// Throws TopologyError for a surface without vertices.
  explicit GeodesicSolver(const Surface& surface, GeodesicMethod method = GeodesicMethod::dijkstra);

  /// The vertices whose distance (by the solver's method) from `source` is at most
  /// `max_distance` (A), as (vertex, distance) pairs sorted by vertex; the source itself is
  /// included at distance 0. When `allowed` is given (one entry per vertex), the paths only
  /// pass through vertices whose entry is non-zero (the source is always allowed). Throws
  /// InputError when `source` is not a vertex index or `allowed` has the wrong size,
  /// OptionError when max_distance is negative or NaN.
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
