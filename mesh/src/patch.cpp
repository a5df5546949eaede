#include "surfcomp/mesh/patch.hpp"

#include "surface_mesh.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/geodesic.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>

namespace surfcomp::mesh {
namespace {

using VertexHandle = TriMesh::VertexHandle;
using FaceHandle = TriMesh::FaceHandle;
using HalfedgeHandle = TriMesh::HalfedgeHandle;

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string where(const Surface& surface, const char* caller) {
  return surface.source() + ": " + caller + ": ";
}

void check_vertex(const Surface& surface, int vertex, const char* caller) {
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= surface.n_vertices()) {
    throw InputError(where(surface, caller) + "vertex " + std::to_string(vertex) +
                     " is outside 0.." +
                     std::to_string(static_cast<long long>(surface.n_vertices()) - 1));
  }
}

void check_length(const Surface& surface, double value, const char* name, const char* caller) {
  if (!std::isfinite(value) || value < 0.0) {
    throw OptionError(where(surface, caller) + name + " is " + format_number(value) +
                      ", expected a finite number >= 0");
  }
}

/// Throws InputError unless `indices` is strictly increasing within 0..count-1.
void check_index_list(const Surface& surface, const std::vector<int>& indices, std::size_t count,
                      const char* what, const char* caller) {
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const int x = indices[i];
    if (x < 0 || static_cast<std::size_t>(x) >= count) {
      throw InputError(where(surface, caller) + what + " index " + std::to_string(x) +
                       " is outside 0.." + std::to_string(static_cast<long long>(count) - 1));
    }
    if (i > 0 && indices[i - 1] >= x) {
      throw InputError(where(surface, caller) + what + " indices must be sorted and unique, " +
                       "found " + std::to_string(indices[i - 1]) + " before " + std::to_string(x));
    }
  }
}

void check_distance_list(const Surface& surface,
                         const std::vector<std::pair<int, double>>& distances, const char* caller) {
  for (std::size_t i = 0; i < distances.size(); ++i) {
    const int v = distances[i].first;
    if (v < 0 || static_cast<std::size_t>(v) >= surface.n_vertices() ||
        (i > 0 && distances[i - 1].first >= v)) {
      throw InputError(where(surface, caller) + "distance entry " + std::to_string(i) +
                       " has vertex " + std::to_string(v) +
                       ", expected vertex indices in range, sorted and unique");
    }
  }
}

bool contains(const std::vector<int>& sorted, int x) {
  return std::binary_search(sorted.begin(), sorted.end(), x);
}

/// Membership in a list of mesh elements (faces or vertices) in constant time: a flag per
/// element of the mesh, set for the listed ones.
class Membership {
 public:
  Membership(std::size_t elements, const std::vector<int>& listed) : in_(elements, 0) {
    for (const int i : listed) in_[static_cast<std::size_t>(i)] = 1;
  }
  bool operator()(int i) const { return i >= 0 && in_[static_cast<std::size_t>(i)] != 0; }
  void remove(int i) { in_[static_cast<std::size_t>(i)] = 0; }

 private:
  std::vector<char> in_;
};

/// True when the edge of `h` is a border edge of the patch `faces`: the face across it is
/// missing or not in the patch.
bool is_border(const TriMesh& mesh, HalfedgeHandle h, const Membership& faces) {
  const FaceHandle across = mesh.face_handle(mesh.opposite_halfedge_handle(h));
  return !across.is_valid() || !faces(across.idx());
}

/// The halfedges of a patch border: those of patch faces whose edge is a border edge, with
/// the patch on their left, sorted by their start vertex.
std::vector<std::pair<int, HalfedgeHandle>> border_halfedges(const TriMesh& mesh,
                                                             const std::vector<int>& faces) {
  const Membership in_patch(mesh.n_faces(), faces);
  std::vector<std::pair<int, HalfedgeHandle>> out;
  for (const int f : faces) {
    for (const auto h : mesh.fh_range(FaceHandle(f))) {
      if (is_border(mesh, h, in_patch)) out.emplace_back(mesh.from_vertex_handle(h).idx(), h);
    }
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

/// The fans of patch faces around `v`: each starts at an outgoing border halfedge of v and
/// turns around v through patch faces until the next border edge. Empty for an interior vertex.
std::vector<std::vector<int>> fans_at(const TriMesh& mesh, VertexHandle v,
                                      const Membership& faces) {
  std::vector<std::vector<int>> fans;
  for (const auto h0 : mesh.voh_range(v)) {
    const FaceHandle f0 = mesh.face_handle(h0);
    if (!f0.is_valid() || !faces(f0.idx()) || !is_border(mesh, h0, faces)) continue;
    std::vector<int> fan;
    HalfedgeHandle h = h0;
    while (true) {
      fan.push_back(mesh.face_handle(h).idx());
      const HalfedgeHandle incoming = mesh.prev_halfedge_handle(h);  // u -> v in the same face
      if (is_border(mesh, incoming, faces)) break;
      h = mesh.opposite_halfedge_handle(incoming);  // v -> u in the next patch face
    }
    fans.push_back(std::move(fan));
  }
  return fans;
}

/// The border loops of a patch from its border halfedges (border_halfedges), as
/// boundary_loops describes them.
BoundaryLoops loops_of_border(const Surface& surface,
                              const std::vector<std::pair<int, HalfedgeHandle>>& border) {
  const char* caller = "boundary_loops";
  const TriMesh& mesh = tri_mesh(surface);
  for (std::size_t i = 1; i < border.size(); ++i) {
    if (border[i].first == border[i - 1].first) {
      throw TopologyError(where(surface, caller) + "vertex " + std::to_string(border[i].first) +
                          " is on the border twice (a bow-tie); refine the patch first");
    }
  }
  const auto outgoing = [&border](int v) {
    const auto it = std::lower_bound(
        border.begin(), border.end(), v,
        [](const std::pair<int, HalfedgeHandle>& e, int x) { return e.first < x; });
    return static_cast<std::size_t>(it - border.begin());
  };
  std::vector<char> walked(border.size(), 0);
  std::vector<std::vector<int>> loops;
  std::vector<double> perimeters;
  for (std::size_t start = 0; start < border.size(); ++start) {
    if (walked[start]) continue;
    std::vector<int> loop;
    double perimeter = 0.0;
    std::size_t i = start;
    while (!walked[i]) {
      walked[i] = 1;
      const HalfedgeHandle h = border[i].second;
      loop.push_back(border[i].first);
      const VertexHandle next = mesh.to_vertex_handle(h);
      perimeter += (mesh.point(next) - mesh.point(mesh.from_vertex_handle(h))).norm();
      i = outgoing(next.idx());
      // Every border vertex has exactly one outgoing border halfedge (checked above) and, on
      // a subset of a manifold surface, exactly one incoming one, so the walk returns to start.
    }
    loops.push_back(std::move(loop));
    perimeters.push_back(perimeter);
  }
  BoundaryLoops out;
  if (loops.empty()) return out;
  std::size_t outer = 0;
  for (std::size_t i = 1; i < loops.size(); ++i) {
    if (perimeters[i] > perimeters[outer]) outer = i;
  }
  for (std::size_t i = 0; i < loops.size(); ++i) {
    if (i == outer) {
      out.outer = std::move(loops[i]);
    } else {
      out.holes.push_back(std::move(loops[i]));
    }
  }
  return out;
}

}  // namespace

std::vector<int> preselect_euclidean(const Surface& surface, int center_vertex, double radius) {
  const char* caller = "preselect_euclidean";
  check_vertex(surface, center_vertex, caller);
  check_length(surface, radius, "radius", caller);
  const TriMesh& mesh = tri_mesh(surface);
  const TriMesh::Point c = mesh.point(VertexHandle(center_vertex));
  const double r2 = radius * radius;
  std::vector<int> out;
  for (const auto v : mesh.vertices()) {
    if ((mesh.point(v) - c).sqrnorm() <= r2) out.push_back(v.idx());
  }
  return out;
}

std::vector<std::pair<int, double>> patch_distances(const Surface& surface, int center_vertex,
                                                    const std::vector<int>& preselected,
                                                    double max_distance, GeodesicMethod method) {
  const char* caller = "patch_distances";
  check_vertex(surface, center_vertex, caller);
  check_length(surface, max_distance, "max_distance", caller);
  check_index_list(surface, preselected, surface.n_vertices(), "vertex", caller);
  if (!contains(preselected, center_vertex)) {
    throw InputError(where(surface, caller) +
                     "the preselected vertices do not contain the "
                     "centre vertex " +
                     std::to_string(center_vertex));
  }
  std::vector<char> allowed(surface.n_vertices(), 0);
  for (const int v : preselected) allowed[static_cast<std::size_t>(v)] = 1;
  GeodesicSolver solver(surface, method);
  return solver.within(center_vertex, max_distance, &allowed);
}

std::vector<int> select_within_radius(const Surface& surface,
                                      const std::vector<std::pair<int, double>>& distances,
                                      double radius, double margin) {
  const char* caller = "select_within_radius";
  check_length(surface, radius, "radius", caller);
  check_length(surface, margin, "margin", caller);
  check_distance_list(surface, distances, caller);
  const TriMesh& mesh = tri_mesh(surface);
  std::vector<int> core_list;
  for (const auto& [v, d] : distances) {
    if (d <= radius) core_list.push_back(v);
  }
  const Membership core(mesh.n_vertices(), core_list);
  const double outer = radius * (1.0 + margin);
  std::vector<int> out;
  for (const auto& [v, d] : distances) {
    if (d <= radius) {
      out.push_back(v);
    } else if (d <= outer) {
      for (const auto w : mesh.vv_range(VertexHandle(v))) {
        if (core(w.idx())) {
          out.push_back(v);
          break;
        }
      }
    }
  }
  return out;
}

std::vector<int> faces_with_three_selected(const Surface& surface,
                                           const std::vector<int>& selected) {
  check_index_list(surface, selected, surface.n_vertices(), "vertex", "faces_with_three_selected");
  const TriMesh& mesh = tri_mesh(surface);
  const Membership is_selected(mesh.n_vertices(), selected);
  std::vector<int> out;
  out.reserve(2 * selected.size());
  for (const int v : selected) {
    for (const auto f : mesh.vf_range(VertexHandle(v))) {
      // Each face once, from its lowest vertex.
      bool all = true, lowest = true;
      for (const auto w : mesh.fv_range(f)) {
        all = all && is_selected(w.idx());
        lowest = lowest && w.idx() >= v;
      }
      if (all && lowest) out.push_back(f.idx());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<int> remove_dangling_triangles(const Surface& surface, const std::vector<int>& faces) {
  check_index_list(surface, faces, surface.n_faces(), "face", "remove_dangling_triangles");
  const TriMesh& mesh = tri_mesh(surface);
  const Membership in_patch(mesh.n_faces(), faces);
  std::vector<int> out;
  for (const int f : faces) {
    int border = 0;
    for (const auto h : mesh.fh_range(FaceHandle(f)))
      border += is_border(mesh, h, in_patch) ? 1 : 0;
    if (border <= 1) out.push_back(f);
  }
  return out;
}

std::vector<int> remove_isolated_vertices(const Surface& surface, const std::vector<int>& vertices,
                                          const std::vector<int>& faces) {
  const char* caller = "remove_isolated_vertices";
  check_index_list(surface, vertices, surface.n_vertices(), "vertex", caller);
  check_index_list(surface, faces, surface.n_faces(), "face", caller);
  const TriMesh& mesh = tri_mesh(surface);
  const Membership in_patch(mesh.n_faces(), faces);
  std::vector<int> out;
  for (const int v : vertices) {
    for (const auto f : mesh.vf_range(VertexHandle(v))) {
      if (in_patch(f.idx())) {
        out.push_back(v);
        break;
      }
    }
  }
  return out;
}

std::vector<int> resolve_nonmanifold_vertices(const Surface& surface,
                                              const std::vector<int>& faces) {
  check_index_list(surface, faces, surface.n_faces(), "face", "resolve_nonmanifold_vertices");
  const TriMesh& mesh = tri_mesh(surface);
  Membership in_out(mesh.n_faces(), faces);
  // A vertex has as many fans as outgoing border halfedges (each fan starts at one), so only
  // vertices with two of them need resolving. Vertices are visited in increasing order; removing
  // a fan changes the border only at the vertices of its faces, which are looked at again when
  // they come later in the order.
  const auto outgoing_border = [&](VertexHandle v) {
    int count = 0;
    for (const auto h : mesh.voh_range(v)) {
      const FaceHandle f = mesh.face_handle(h);
      count += f.is_valid() && in_out(f.idx()) && is_border(mesh, h, in_out) ? 1 : 0;
    }
    return count;
  };
  std::vector<int> starts;
  for (const int f : faces) {
    for (const auto h : mesh.fh_range(FaceHandle(f))) {
      if (is_border(mesh, h, in_out)) starts.push_back(mesh.from_vertex_handle(h).idx());
    }
  }
  std::sort(starts.begin(), starts.end());
  std::vector<int> pending;  // a min-heap of vertices to look at
  for (std::size_t i = 1; i < starts.size(); ++i) {
    if (starts[i] == starts[i - 1] && (pending.empty() || pending.back() != starts[i])) {
      pending.push_back(starts[i]);  // ascending: already a heap
    }
  }
  const auto later = std::greater<int>();
  std::make_heap(pending.begin(), pending.end(), later);
  bool changed = false;
  int last = -1;
  while (!pending.empty()) {
    std::pop_heap(pending.begin(), pending.end(), later);
    const int v = pending.back();
    pending.pop_back();
    if (v <= last) continue;  // queued twice
    last = v;
    const auto fans = fans_at(mesh, VertexHandle(v), in_out);
    if (fans.size() < 2) continue;
    // Keep the fan with the most faces; ties go to the fan holding the lowest face index.
    std::size_t keep = 0;
    for (std::size_t i = 1; i < fans.size(); ++i) {
      const auto& a = fans[i];
      const auto& b = fans[keep];
      if (a.size() > b.size() ||
          (a.size() == b.size() &&
           *std::min_element(a.begin(), a.end()) < *std::min_element(b.begin(), b.end()))) {
        keep = i;
      }
    }
    for (std::size_t i = 0; i < fans.size(); ++i) {
      if (i != keep) {
        for (const int f : fans[i]) in_out.remove(f);
      }
    }
    changed = true;
    for (std::size_t i = 0; i < fans.size(); ++i) {
      if (i == keep) continue;
      for (const int f : fans[i]) {
        for (const auto u : mesh.fv_range(FaceHandle(f))) {
          if (u.idx() > v && outgoing_border(u) >= 2) {
            pending.push_back(u.idx());
            std::push_heap(pending.begin(), pending.end(), later);
          }
        }
      }
    }
  }
  if (!changed) return faces;
  std::vector<int> out;
  out.reserve(faces.size());
  for (const int f : faces) {
    if (in_out(f)) out.push_back(f);
  }
  return out;
}

std::vector<int> keep_component(const Surface& surface, const std::vector<int>& faces, int vertex) {
  const char* caller = "keep_component";
  check_vertex(surface, vertex, caller);
  check_index_list(surface, faces, surface.n_faces(), "face", caller);
  const TriMesh& mesh = tri_mesh(surface);
  Membership unreached(mesh.n_faces(), faces);  // patch faces not reached yet
  int seed = -1;
  for (const auto f : mesh.vf_range(VertexHandle(vertex))) {
    if (unreached(f.idx()) && (seed < 0 || f.idx() < seed)) seed = f.idx();
  }
  if (seed < 0) return {};
  std::vector<int> stack = {seed};
  unreached.remove(seed);
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    for (const auto h : mesh.fh_range(FaceHandle(f))) {
      const FaceHandle g = mesh.face_handle(mesh.opposite_halfedge_handle(h));
      if (!g.is_valid() || !unreached(g.idx())) continue;
      unreached.remove(g.idx());
      stack.push_back(g.idx());
    }
  }
  std::vector<int> out;
  for (const int f : faces) {
    if (!unreached(f)) out.push_back(f);
  }
  return out;
}

PatchSelection refine_patch(const Surface& surface, PatchSelection selection, int center_vertex) {
  while (true) {
    std::vector<int> faces = remove_dangling_triangles(surface, selection.faces);
    faces = resolve_nonmanifold_vertices(surface, faces);
    faces = keep_component(surface, faces, center_vertex);
    selection.vertices = remove_isolated_vertices(surface, selection.vertices, faces);
    if (faces == selection.faces) break;
    selection.faces = std::move(faces);
  }
  return selection;
}

BoundaryLoops boundary_loops(const Surface& surface, const std::vector<int>& faces) {
  check_index_list(surface, faces, surface.n_faces(), "face", "boundary_loops");
  return loops_of_border(surface, border_halfedges(tri_mesh(surface), faces));
}

Patch assemble_patch(const Surface& surface, int center_vertex, const std::vector<int>& faces,
                     const std::vector<std::pair<int, double>>& distances) {
  const char* caller = "assemble_patch";
  check_vertex(surface, center_vertex, caller);
  check_index_list(surface, faces, surface.n_faces(), "face", caller);
  check_distance_list(surface, distances, caller);
  const TriMesh& mesh = tri_mesh(surface);
  Patch patch;
  for (const int f : faces) {
    for (const auto v : mesh.fv_range(FaceHandle(f))) patch.surface_vertex.push_back(v.idx());
  }
  std::sort(patch.surface_vertex.begin(), patch.surface_vertex.end());
  patch.surface_vertex.erase(std::unique(patch.surface_vertex.begin(), patch.surface_vertex.end()),
                             patch.surface_vertex.end());
  const auto local = [&patch](int v) {
    return static_cast<int>(
        std::lower_bound(patch.surface_vertex.begin(), patch.surface_vertex.end(), v) -
        patch.surface_vertex.begin());
  };
  if (!contains(patch.surface_vertex, center_vertex)) {
    throw InputError(where(surface, caller) + "the centre vertex " + std::to_string(center_vertex) +
                     " is in none of the " + std::to_string(faces.size()) + " faces");
  }
  patch.center = local(center_vertex);
  const auto n = static_cast<Eigen::Index>(patch.surface_vertex.size());
  patch.positions.resize(n, 3);
  patch.distance.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const int v = patch.surface_vertex[static_cast<std::size_t>(i)];
    const auto& p = mesh.point(VertexHandle(v));
    patch.positions.row(i) << p[0], p[1], p[2];
    const auto it =
        std::lower_bound(distances.begin(), distances.end(), v,
                         [](const std::pair<int, double>& e, int x) { return e.first < x; });
    if (it == distances.end() || it->first != v) {
      throw InputError(where(surface, caller) + "patch vertex " + std::to_string(v) +
                       " has no distance");
    }
    patch.distance(i) = it->second;
  }
  patch.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    int k = 0;
    for (const auto v : mesh.fv_range(FaceHandle(faces[f]))) {
      patch.faces(static_cast<Eigen::Index>(f), k++) = local(v.idx());
    }
  }
  // Euler characteristic V - E + F; every interior edge is shared by two faces, every border
  // edge (one per border halfedge) by one.
  const auto border = border_halfedges(mesh, faces);
  const long long edges =
      (3 * static_cast<long long>(faces.size()) + static_cast<long long>(border.size())) / 2;
  const long long euler = static_cast<long long>(n) - edges + static_cast<long long>(faces.size());
  BoundaryLoops loops = loops_of_border(surface, border);
  const long long n_loops =
      static_cast<long long>(loops.holes.size()) + (loops.outer.empty() ? 0 : 1);
  patch.genus = static_cast<int>((2 - euler - n_loops) / 2);
  for (const int v : loops.outer) patch.outer_boundary.push_back(local(v));
  for (const auto& hole : loops.holes) {
    std::vector<int> walk;
    walk.reserve(hole.size());
    for (const int v : hole) walk.push_back(local(v));
    patch.holes.push_back(std::move(walk));
  }
  return patch;
}

Patch extract_patch(const Surface& surface, int center_vertex, const PatchOptions& options) {
  const char* caller = "extract_patch";
  if (surface.n_vertices() == 0 || surface.n_faces() == 0) {
    throw TopologyError(where(surface, caller) + "the surface has " +
                        std::to_string(surface.n_vertices()) + " vertices and " +
                        std::to_string(surface.n_faces()) + " faces, expected a triangle mesh");
  }
  check_vertex(surface, center_vertex, caller);
  if (!std::isfinite(options.radius) || options.radius <= 0.0) {
    throw OptionError(where(surface, caller) + "radius is " + format_number(options.radius) +
                      ", expected a finite number > 0 A");
  }
  check_length(surface, options.margin, "margin", caller);
  const double reach = options.radius * (1.0 + options.margin);
  const std::vector<int> preselected = preselect_euclidean(surface, center_vertex, reach);
  const auto distances =
      patch_distances(surface, center_vertex, preselected, reach, options.distance);
  PatchSelection selection;
  selection.vertices = select_within_radius(surface, distances, options.radius, options.margin);
  selection.faces = faces_with_three_selected(surface, selection.vertices);
  selection = refine_patch(surface, std::move(selection), center_vertex);
  if (selection.faces.empty()) {
    throw TopologyError(where(surface, caller) + "no triangle is left around vertex " +
                        std::to_string(center_vertex) + " within radius " +
                        format_number(options.radius) +
                        " A; expected a radius longer than the vertex's edges");
  }
  return assemble_patch(surface, center_vertex, selection.faces, distances);
}

void scale_patch(Patch& patch, double factor) {
  patch.positions *= factor;
  patch.distance *= factor;
}

Patch extract_patch_in_unit(const Surface& surface, int center_vertex, double unit,
                            const PatchOptions& options) {
  if (unit == 1.0) return extract_patch(surface, center_vertex, options);
  Surface in_units = surface;
  scale_surface(in_units, 1.0 / unit);  // checks the unit
  Patch patch = extract_patch(in_units, center_vertex, options);
  scale_patch(patch, unit);
  return patch;
}

}  // namespace surfcomp::mesh
