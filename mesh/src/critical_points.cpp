#include "surfcomp/mesh/critical_points.hpp"

#include "surface_mesh.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/geodesic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

namespace surfcomp::mesh {
namespace {

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void check_options(const Surface& surface, const CriticalPointOptions& o) {
  const std::string caller = surface.source() + ": detect_critical_points: ";
  if (!std::isfinite(o.radius) || o.radius <= 0.0) {
    throw OptionError(caller + "radius is " + format_number(o.radius) +
                      ", expected a finite number > 0 A");
  }
  if (!std::isfinite(o.property_disc_radius) || o.property_disc_radius < 0.0) {
    throw OptionError(caller + "property_disc_radius is " + format_number(o.property_disc_radius) +
                      ", expected a finite number >= 0 A");
  }
}

/// Which critical point a vertex may become, from the signs of its canonical curvatures.
enum class Kind : unsigned char { none, convex, concave };

Kind kind_of(double cc1, double cc2) {
  if (cc1 < 0.0 && cc2 < 0.0) return Kind::convex;
  if (cc1 > 0.0 && cc2 > 0.0) return Kind::concave;
  return Kind::none;
}

/// Unit normal at `v`: the stored one when the surface has normals, else the area-weighted
/// normal of the incident triangles (zero for a vertex in no triangle of non-zero area).
Eigen::Vector3d vertex_normal(const Surface& surface, TriMesh::VertexHandle v) {
  const TriMesh& mesh = tri_mesh(surface);
  OpenMesh::Vec3d n(0.0, 0.0, 0.0);
  if (surface.has_normals()) {
    n = mesh.normal(v);
  } else {
    for (const auto f : mesh.vf_range(v)) {
      const auto h = mesh.halfedge_handle(f);
      const auto& a = mesh.point(mesh.from_vertex_handle(h));
      const auto& b = mesh.point(mesh.to_vertex_handle(h));
      const auto& c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
      n += OpenMesh::cross(b - a, c - a);
    }
  }
  const Eigen::Vector3d out(n[0], n[1], n[2]);
  return out.norm() > 0.0 ? out.normalized() : out;
}

/// Area-weighted mean of `values` over the (vertex, distance) list `disc`; the plain mean when
/// every vertex of the disc has zero area.
double disc_average(const std::vector<std::pair<int, double>>& disc, const Eigen::VectorXd& values,
                    const Eigen::VectorXd& area) {
  double weighted = 0.0, total = 0.0, plain = 0.0;
  for (const auto& [v, d] : disc) {
    weighted += area(v) * values(v);
    total += area(v);
    plain += values(v);
  }
  return total > 0.0 ? weighted / total : plain / static_cast<double>(disc.size());
}

}  // namespace

std::vector<CriticalPoint> detect_critical_points(const Surface& surface,
                                                  const CriticalPointOptions& options) {
  check_options(surface, options);
  for (const char* name : {property::cc1, property::cc2}) {
    if (!surface.has_property(name)) {
      throw InputError(surface.source() + ": detect_critical_points needs the vertex property " +
                       name + " (compute principal_curvatures first)");
    }
  }
  if (surface.n_vertices() == 0) return {};
  const TriMesh& mesh = tri_mesh(surface);
  const Eigen::VectorXd cc1 = surface.property(property::cc1);
  const Eigen::VectorXd cc2 = surface.property(property::cc2);
  const auto n = static_cast<std::size_t>(cc1.size());
  std::vector<Kind> kind(n);
  for (std::size_t v = 0; v < n; ++v) {
    kind[v] = kind_of(cc1(static_cast<Eigen::Index>(v)), cc2(static_cast<Eigen::Index>(v)));
  }
  // p beats q when |cc1_p| > |cc1_q|, or they are equal and p has the lower index (method §2.1).
  const auto beats = [&cc1](int p, int q) {
    const double a = std::abs(cc1(p)), b = std::abs(cc1(q));
    return a > b || (a == b && p < q);
  };

  GeodesicSolver solver(surface, options.distance);
  std::vector<int> found;
  for (std::size_t vi = 0; vi < n; ++vi) {
    if (kind[vi] == Kind::none) continue;
    const int v = static_cast<int>(vi);
    const auto vh = TriMesh::VertexHandle(v);
    // Cheap rejection by the one-ring (its members within the radius are in N(p, r_cp)).
    bool candidate = true;
    for (const auto w : mesh.vv_range(vh)) {
      if (kind[static_cast<std::size_t>(w.idx())] == kind[vi] &&
          (mesh.point(w) - mesh.point(vh)).norm() <= options.radius && !beats(v, w.idx())) {
        candidate = false;
        break;
      }
    }
    if (!candidate) continue;
    for (const auto& [q, d] : solver.within(v, options.radius)) {
      if (q != v && kind[static_cast<std::size_t>(q)] == kind[vi] && !beats(v, q)) {
        candidate = false;
        break;
      }
    }
    if (candidate) found.push_back(v);
  }

  Eigen::VectorXd shape_index, curvedness;
  if (surface.has_property(property::shape_index)) {
    shape_index = surface.property(property::shape_index);
  }
  if (surface.has_property(property::curvedness)) {
    curvedness = surface.property(property::curvedness);
  }
  if (shape_index.size() == 0 || curvedness.size() == 0) {
    // Koenderink with k = -cc (convex positive), as in curvature.hpp.
    Eigen::VectorXd s(static_cast<Eigen::Index>(n)), c(static_cast<Eigen::Index>(n));
    for (Eigen::Index v = 0; v < static_cast<Eigen::Index>(n); ++v) {
      const double k1 = -cc1(v), k2 = -cc2(v);
      const double k_max = std::max(k1, k2), k_min = std::min(k1, k2);
      s(v) = 2.0 / M_PI * std::atan2(k_max + k_min, k_max - k_min);
      c(v) = std::sqrt((k1 * k1 + k2 * k2) / 2.0);
    }
    if (shape_index.size() == 0) shape_index = s;
    if (curvedness.size() == 0) curvedness = c;
  }
  const bool has_esp = surface.has_property(property::esp);
  const bool has_lp = surface.has_property(property::lp);
  const Eigen::VectorXd esp = has_esp ? surface.property(property::esp) : Eigen::VectorXd();
  const Eigen::VectorXd lp = has_lp ? surface.property(property::lp) : Eigen::VectorXd();
  const Eigen::VectorXd area = vertex_areas(surface);
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();

  std::vector<CriticalPoint> out;
  out.reserve(found.size());
  for (const CriticalPointType type : {CriticalPointType::peak, CriticalPointType::valley}) {
    const Kind wanted = type == CriticalPointType::peak ? Kind::convex : Kind::concave;
    for (const int v : found) {
      if (kind[static_cast<std::size_t>(v)] != wanted) continue;
      const auto vh = TriMesh::VertexHandle(v);
      const auto disc = solver.within(v, options.property_disc_radius);
      CriticalPoint cp;
      cp.type = type;
      cp.vertex = v;
      const auto& p = mesh.point(vh);
      cp.position = Eigen::Vector3d(p[0], p[1], p[2]);
      cp.normal = vertex_normal(surface, vh);
      cp.cc1 = cc1(v);
      cp.cc2 = cc2(v);
      cp.shape_index = disc_average(disc, shape_index, area);
      cp.curvedness = curvedness(v);
      cp.esp = has_esp ? disc_average(disc, esp, area) : nan;
      cp.lp = has_lp ? disc_average(disc, lp, area) : nan;
      out.push_back(cp);
    }
  }
  return out;
}

const options::Table<CriticalPointOptions>& critical_point_option_table() {
  using options::Kind;
  using C = CriticalPointOptions;
  static const options::Table<C> table = {
      options::field<C>(
          {"critical-point-radius", Kind::real, "critical point radius r_cp (on-surface)", "A",
           1e-3, 100.0},
          [](auto& c) -> auto& { return c.radius; }),
      options::field<C>(
          {"disc-radius", Kind::real,
           "geodesic disc over which shape index, ESP and LP are averaged", "A", 0.0, 100.0},
          [](auto& c) -> auto& { return c.property_disc_radius; }),
  };
  return table;
}

std::vector<CriticalPoint> detect_critical_points_in_unit(const Surface& surface, double unit,
                                                          const CriticalPointOptions& options) {
  if (unit == 1.0) return detect_critical_points(surface, options);
  Surface in_units = surface;
  scale_surface(in_units, 1.0 / unit);  // checks the unit
  std::vector<CriticalPoint> points = detect_critical_points(in_units, options);
  for (CriticalPoint& point : points) scale_critical_point(point, unit);
  return points;
}

void scale_critical_point(CriticalPoint& point, double factor) {
  point.position *= factor;
  point.cc1 /= factor;
  point.cc2 /= factor;
  point.curvedness /= factor;
}

}  // namespace surfcomp::mesh
