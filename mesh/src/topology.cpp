#include "surfcomp/mesh/topology.hpp"

#include "surface_mesh.hpp"
#include "surfcomp/core/error.hpp"

#include <algorithm>
#include <string>

namespace surfcomp::mesh {
namespace {

TriMesh::VertexHandle checked_vertex(const Surface& surface, int vertex, const char* caller) {
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= surface.n_vertices()) {
    throw InputError(surface.source() + ": " + caller + ": vertex " + std::to_string(vertex) +
                     " is outside 0.." +
                     std::to_string(static_cast<long long>(surface.n_vertices()) - 1));
  }
  return TriMesh::VertexHandle(vertex);
}

}  // namespace

// OpenMesh starts the circulation around a boundary vertex at its outgoing boundary halfedge,
// so the clockwise walk crosses the surface from one boundary neighbour to the other without
// passing the gap; reversed, it is counter-clockwise.
std::vector<int> one_ring_vertices(const Surface& surface, int vertex) {
  const TriMesh& mesh = tri_mesh(surface);
  std::vector<int> out;
  for (const auto w : mesh.vv_cw_range(checked_vertex(surface, vertex, "one_ring_vertices"))) {
    out.push_back(w.idx());
  }
  std::reverse(out.begin(), out.end());
  return out;
}

std::vector<int> one_ring_faces(const Surface& surface, int vertex) {
  const TriMesh& mesh = tri_mesh(surface);
  std::vector<int> out;
  for (const auto f : mesh.vf_cw_range(checked_vertex(surface, vertex, "one_ring_faces"))) {
    out.push_back(f.idx());
  }
  std::reverse(out.begin(), out.end());
  return out;
}

SurfaceComponents connected_components(const Surface& surface) {
  const TriMesh& mesh = tri_mesh(surface);
  SurfaceComponents out;
  out.component.assign(mesh.n_vertices(), -1);
  std::vector<TriMesh::VertexHandle> stack;
  for (const auto seed : mesh.vertices()) {
    if (out.component[static_cast<std::size_t>(seed.idx())] >= 0) continue;
    const int id = out.count++;
    out.component[static_cast<std::size_t>(seed.idx())] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      const auto v = stack.back();
      stack.pop_back();
      for (const auto w : mesh.vv_range(v)) {
        int& label = out.component[static_cast<std::size_t>(w.idx())];
        if (label < 0) {
          label = id;
          stack.push_back(w);
        }
      }
    }
  }
  return out;
}

std::vector<bool> border_vertices(const Surface& surface) {
  const TriMesh& mesh = tri_mesh(surface);
  std::vector<bool> out(mesh.n_vertices(), false);
  for (const auto v : mesh.vertices()) out[static_cast<std::size_t>(v.idx())] = mesh.is_boundary(v);
  return out;
}

}  // namespace surfcomp::mesh
