#include "ses_vertices.hpp"

#include "surface_mesh.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

namespace surfcomp::molsurf::detail {
namespace {

/// Passes that split (or snap onto the crease) the SAS edges whose ends lie on no common sphere.
constexpr int crease_rounds = 3;
/// A crease point this close to an edge's end (in edge lengths L) moves that end instead.
constexpr double snap_fraction = 0.2;
/// SAS edges shorter than this (in L) after the crease splits are collapsed.
constexpr double collapse_fraction = 0.5;
/// Passes over the edges collapsing the short ones (stops early when one changes nothing).
constexpr int collapse_passes = 3;
/// Triangles of the crease splits and collapses keep at least this area (in L^2).
constexpr double crease_min_area = 1e-4;
/// Edge ends closer than this (in L) are one point: two vertices projected onto one SAS vertex,
/// apart by rounding.
constexpr double coincident_fraction = 1e-9;

Vec3 to_vec(const mesh::TriMesh::Point& p) { return Vec3(p[0], p[1], p[2]); }
mesh::TriMesh::Point to_point(const Vec3& x) { return mesh::TriMesh::Point(x.x(), x.y(), x.z()); }

/// True when moving vertex v to p keeps every triangle around it (except those that also hold
/// `ignore`, which a collapse removes) turning the same way, with an area above `min_area`.
bool move_keeps_orientation(const mesh::TriMesh& mesh, mesh::TriMesh::VertexHandle v, const Vec3& p,
                            mesh::TriMesh::VertexHandle ignore, double min_area) {
  for (auto h : mesh.voh_range(v)) {
    if (mesh.is_boundary(h)) return false;
    const auto b = mesh.to_vertex_handle(h);
    const auto c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
    if (b == ignore || c == ignore) continue;
    const Vec3 pb = to_vec(mesh.point(b));
    const Vec3 pc = to_vec(mesh.point(c));
    const Vec3 before = (pb - to_vec(mesh.point(v))).cross(pc - to_vec(mesh.point(v)));
    const Vec3 after = (pb - p).cross(pc - p);
    if (0.5 * after.norm() <= min_area || after.dot(before) <= 0.0) return false;
  }
  return true;
}

/// A crease point or SAS vertex and the spheres it lies on.
struct CreasePoint {
  Vec3 point;
  Spheres spheres;
};

/// The crease point or SAS vertex of a sphere of `a` with a sphere of `b` nearest `middle` and
/// within `within` A of it; `middle` on no spheres (all -1) when there is none.
CreasePoint nearest_crease(const SasGeometry& sas, const Spheres& a, const Spheres& b,
                           const Vec3& middle, double within) {
  const Spheres none{-1, -1, -1};
  CreasePoint nearest{middle, none};
  double best = within;
  const auto consider = [&](const Vec3& p, const Spheres& s) {
    const double d = (p - middle).norm();
    if (d < best) {
      best = d;
      nearest = {p, s};
    }
  };
  std::vector<int> all;
  for (const int x : a) {
    if (x < 0) continue;
    all.push_back(x);
    for (const int y : b) {
      Vec3 p;
      if (y >= 0 && sas.crease_point(x, y, middle, p)) consider(p, sorted_spheres(x, y));
    }
  }
  for (const int y : b) {
    if (y >= 0) all.push_back(y);
  }
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (std::size_t j = i + 1; j < all.size(); ++j) {
      for (std::size_t k = j + 1; k < all.size(); ++k) {
        const Spheres s = sorted_spheres(all[i], all[j], all[k]);
        Vec3 p;
        if (sas.vertex_point(s, middle, best, p)) consider(p, s);
      }
    }
  }
  return nearest;
}

/// Collapses the short edges the crease splits left (shorter than collapse_fraction *
/// `edge_length`), keeping the vertex on more spheres, where the collapse keeps every triangle's
/// orientation and area (`min_area`); a collapse can shorten edges already visited, so it passes
/// again while any changes. Marks the removed elements deleted (no garbage collection).
void collapse_short_edges(mesh::TriMesh& mesh, const OpenMesh::VPropHandleT<Spheres>& label,
                          double edge_length, double min_area) {
  const Spheres none{-1, -1, -1};
  const double shortest = collapse_fraction * edge_length;
  for (int pass = 0; pass < collapse_passes; ++pass) {
    bool changed = false;
    for (auto e : mesh.edges()) {
      if (mesh.status(e).deleted()) continue;
      const double length = mesh.calc_edge_length(e);
      if (length >= shortest) continue;
      const bool coincident = length <= coincident_fraction * edge_length;
      auto h = mesh.halfedge_handle(e, 0);
      const Spheres& a = mesh.property(label, mesh.from_vertex_handle(h));
      const Spheres& b = mesh.property(label, mesh.to_vertex_handle(h));
      if (a == none || b == none) continue;
      // Ends with as many spheres but different ones are distinct crease points, unless they
      // coincide: two labels of one point where more than three spheres meet.
      if (sphere_count(a) > sphere_count(b)) {
        h = mesh.opposite_halfedge_handle(h);
      } else if (sphere_count(a) == sphere_count(b) && a != b && !coincident) {
        continue;
      }
      const auto removed = mesh.from_vertex_handle(h);
      const auto kept = mesh.to_vertex_handle(h);
      if (!mesh.is_collapse_ok(h)) continue;
      bool compatible = true;
      for (auto w : mesh.vv_range(removed)) {
        if (!share_sphere(mesh.property(label, w), mesh.property(label, kept))) compatible = false;
      }
      // Coincident ends collapse unconditionally.
      if (!coincident &&
          (!compatible ||
           !move_keeps_orientation(mesh, removed, to_vec(mesh.point(kept)), kept, min_area))) {
        continue;
      }
      mesh.collapse(h);
      changed = true;
    }
    if (!changed) break;
  }
}

}  // namespace

void place_sas_vertices(mesh::Surface& surface, const SasGeometry& sas, double reach,
                        double edge_length, bool compensate) {
  mesh::TriMesh& mesh = mesh::tri_mesh(surface);
  const Spheres none{-1, -1, -1};
  OpenMesh::VPropHandleT<Spheres> label;
  mesh.add_property(label);
  {
    const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
    Eigen::MatrixX3d positions = surface.positions();
    std::vector<Spheres> on(static_cast<std::size_t>(n));
    tbb::parallel_for(Eigen::Index{0}, n, [&](Eigen::Index v) {
      Vec3 x = positions.row(v).transpose();
      on[static_cast<std::size_t>(v)] = sas.nearest_sas_point(x, reach);
      positions.row(v) = x.transpose();
    });
    for (auto v : mesh.vertices()) {
      mesh.set_point(v, to_point(positions.row(v.idx()).transpose()));
      mesh.property(label, v) = on[static_cast<std::size_t>(v.idx())];
    }
  }
  const double min_area = crease_min_area * edge_length * edge_length;
  for (int round = 0; round < crease_rounds; ++round) {
    std::vector<mesh::TriMesh::EdgeHandle> crossing;
    for (auto e : mesh.edges()) {
      const Spheres& a = mesh.property(label, mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)));
      const Spheres& b = mesh.property(label, mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)));
      if (a != none && b != none && !share_sphere(a, b)) crossing.push_back(e);
    }
    if (crossing.empty()) break;
    for (const auto e : crossing) {
      const auto va = mesh.from_vertex_handle(mesh.halfedge_handle(e, 0));
      const auto vb = mesh.to_vertex_handle(mesh.halfedge_handle(e, 0));
      const Spheres a = mesh.property(label, va);
      const Spheres b = mesh.property(label, vb);
      if (share_sphere(a, b)) continue;  // an earlier move fixed it
      const Vec3 pa = to_vec(mesh.point(va));
      const Vec3 pb = to_vec(mesh.point(vb));
      const Vec3 middle = 0.5 * (pa + pb);
      const double length = (pb - pa).norm();
      auto [point, spheres] = nearest_crease(sas, a, b, middle, length);
      if (spheres == none) {
        // No crease of these spheres nearby: a third sphere lies between; split at the
        // surface point nearest the midpoint, a later round finds the creases on each side.
        spheres = sas.nearest_sas_point(point, reach);
        if (spheres == none) continue;
      }
      const double da = (point - pa).norm();
      const double db = (point - pb).norm();
      const auto nearer = da <= db ? va : vb;
      if (std::min(da, db) < snap_fraction * edge_length &&
          move_keeps_orientation(mesh, nearer, point, mesh::TriMesh::VertexHandle(), min_area)) {
        mesh.set_point(nearer, to_point(point));
        mesh.property(label, nearer) = spheres;
        continue;
      }
      if (std::min(da, db) < snap_fraction * edge_length) continue;
      const auto v = mesh.split(e, to_point(point));
      mesh.property(label, v) = spheres;
    }
  }
  collapse_short_edges(mesh, label, edge_length, min_area);
  mesh.garbage_collection();

  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  Eigen::MatrixX3d normals = Eigen::MatrixX3d::Zero(n, 3);
  Eigen::VectorXd curvature = Eigen::VectorXd::Zero(n);
  for (auto v : mesh.vertices()) {
    const Spheres& s = mesh.property(label, v);
    const Vec3 p = to_vec(mesh.point(v));
    Vec3 sum = Vec3::Zero();
    for (const int i : s) {
      if (i >= 0) sum += (p - sas.center(i)).normalized();
    }
    if (sum.squaredNorm() > 0.0) normals.row(v.idx()) = sum.normalized().transpose();
    if (sphere_count(s) == 1) curvature(v.idx()) = 1.0 / sas.radius(s[0]);
  }
  mesh.remove_property(label);
  finish_placement(surface, normals, curvature, compensate);
}

}  // namespace surfcomp::molsurf::detail
