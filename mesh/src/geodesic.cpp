#include "surfcomp/mesh/geodesic.hpp"

#include "surface_mesh.hpp"
#include "surfcomp/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>

namespace surfcomp::mesh {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void check_source(const Surface& surface, int source, const char* caller) {
  if (source < 0 || static_cast<std::size_t>(source) >= surface.n_vertices()) {
    throw InputError(surface.source() + ": " + caller + ": source vertex " +
                     std::to_string(source) + " is outside 0.." +
                     std::to_string(static_cast<long long>(surface.n_vertices()) - 1));
  }
}

void check_max_distance(const Surface& surface, double max_distance, const char* caller) {
  if (std::isnan(max_distance) || max_distance < 0.0) {
    throw OptionError(surface.source() + ": " + caller + ": max_distance is " +
                      format_number(max_distance) + ", expected a number >= 0 A");
  }
}

void check_not_empty(const Surface& surface, const char* caller) {
  if (surface.n_vertices() == 0) {
    throw TopologyError(surface.source() + ": " + caller + " needs a surface with vertices");
  }
}

/// The fast-marching update of vertex c across triangle (a, b, c) from the distances d_a, d_b
/// of a and b: the triangle is laid in its plane with a at the origin and b on the x axis, the
/// virtual point source s at distances d_a, d_b from a, b on the far side of ab from c, and
/// the result is |c - s| if the segment s-c crosses ab, else +inf (the edges then apply).
double triangle_update(const TriMesh::Point& a, const TriMesh::Point& b, const TriMesh::Point& c,
                       double d_a, double d_b) {
  const TriMesh::Point ab = b - a, ac = c - a;
  const double length = ab.norm();
  if (length <= 0.0) return infinity;
  const double cx = OpenMesh::dot(ac, ab) / length;
  const double cy = OpenMesh::cross(ac, ab).norm() / length;
  const double sx = (d_a * d_a - d_b * d_b + length * length) / (2.0 * length);
  const double sy2 = d_a * d_a - sx * sx;
  if (sy2 < 0.0 || cy <= 0.0) return infinity;  // no source consistent with d_a, d_b
  const double sy = -std::sqrt(sy2);
  const double cross_x = sx + (cx - sx) * (-sy / (cy - sy));  // where s-c meets y = 0
  if (cross_x < 0.0 || cross_x > length) return infinity;
  return std::hypot(cx - sx, cy - sy);
}

}  // namespace

GeodesicSolver::GeodesicSolver(const Surface& surface, GeodesicMethod method)
    : surface_(&surface),
      method_(method),
      distance_(surface.n_vertices(), infinity),
      done_(surface.n_vertices(), 0) {
  check_not_empty(surface, "GeodesicSolver");
}

std::vector<std::pair<int, double>> GeodesicSolver::within(int source, double max_distance,
                                                           const std::vector<char>* allowed) {
  const Surface& surface = *surface_;
  check_source(surface, source, "GeodesicSolver::within");
  check_max_distance(surface, max_distance, "GeodesicSolver::within");
  if (allowed != nullptr && allowed->size() != surface.n_vertices()) {
    throw InputError(surface.source() + ": GeodesicSolver::within: the allowed mask has " +
                     std::to_string(allowed->size()) + " entries, expected one per vertex (" +
                     std::to_string(surface.n_vertices()) + ")");
  }
  const TriMesh& mesh = tri_mesh(surface);
  // Min-heap on (distance, vertex): equal distances pop the lower vertex index first.
  const auto later = std::greater<std::pair<double, int>>();
  std::vector<std::pair<int, double>> result;
  heap_.clear();
  distance_[static_cast<std::size_t>(source)] = 0.0;
  touched_.push_back(source);
  heap_.emplace_back(0.0, source);
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    const auto [d, v] = heap_.back();
    heap_.pop_back();
    if (done_[static_cast<std::size_t>(v)]) continue;  // a stale entry
    done_[static_cast<std::size_t>(v)] = 1;
    result.emplace_back(v, d);
    const auto vh = TriMesh::VertexHandle(v);
    const TriMesh::Point& p = mesh.point(vh);
    const auto relax = [&](TriMesh::VertexHandle w, double candidate) {
      const auto wi = static_cast<std::size_t>(w.idx());
      if (candidate > max_distance || candidate >= distance_[wi]) return;
      if (distance_[wi] == infinity) touched_.push_back(w.idx());
      distance_[wi] = candidate;
      heap_.emplace_back(candidate, w.idx());
      std::push_heap(heap_.begin(), heap_.end(), later);
    };
    for (const auto h : mesh.voh_range(vh)) {
      const auto w = mesh.to_vertex_handle(h);
      const auto wi = static_cast<std::size_t>(w.idx());
      if (done_[wi] || (allowed != nullptr && (*allowed)[wi] == 0)) continue;
      relax(w, d + (mesh.point(w) - p).norm());
      if (method_ != GeodesicMethod::fast_marching) continue;
      // Across the (up to two) triangles of edge v-w whose third vertex u is done already.
      for (const auto side : {h, mesh.opposite_halfedge_handle(h)}) {
        if (mesh.is_boundary(side)) continue;
        const auto u = mesh.to_vertex_handle(mesh.next_halfedge_handle(side));
        const auto ui = static_cast<std::size_t>(u.idx());
        if (!done_[ui]) continue;
        const double across = triangle_update(p, mesh.point(u), mesh.point(w), d, distance_[ui]);
        // Dijkstra order needs candidates no smaller than the vertex being expanded.
        if (across < infinity) relax(w, std::max(across, d));
      }
    }
  }
  for (const int v : touched_) {
    distance_[static_cast<std::size_t>(v)] = infinity;
    done_[static_cast<std::size_t>(v)] = 0;
  }
  touched_.clear();
  std::sort(result.begin(), result.end());
  return result;
}

Eigen::VectorXd geodesic_distances(const Surface& surface, int source,
                                   const GeodesicOptions& options) {
  check_not_empty(surface, "geodesic_distances");
  check_source(surface, source, "geodesic_distances");
  check_max_distance(surface, options.max_distance, "geodesic_distances");
  GeodesicSolver solver(surface, options.method);
  Eigen::VectorXd out =
      Eigen::VectorXd::Constant(static_cast<Eigen::Index>(surface.n_vertices()), infinity);
  for (const auto& [v, d] : solver.within(source, options.max_distance)) out(v) = d;
  return out;
}

}  // namespace surfcomp::mesh
