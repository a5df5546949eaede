// Test-only: the vertex-connected components of a surface with their vertex counts and enclosed
// volumes, to check what the SES builder keeps.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <vector>

namespace surfcomp::test {

struct SurfaceComponent {
  int vertices = 0;
  double volume = 0.0;  ///< A^3, signed (divergence theorem); positive for outward faces
};

/// The components in order of their lowest vertex index.
inline std::vector<SurfaceComponent> surface_components(const mesh::Surface& surface) {
  const mesh::TriMesh& mesh = surface.mesh();
  std::vector<int> label(mesh.n_vertices(), -1);
  std::vector<SurfaceComponent> out;
  for (const auto seed : mesh.vertices()) {
    if (label[static_cast<std::size_t>(seed.idx())] >= 0) continue;
    const int id = static_cast<int>(out.size());
    out.emplace_back();
    label[static_cast<std::size_t>(seed.idx())] = id;
    std::vector<mesh::TriMesh::VertexHandle> stack{seed};
    while (!stack.empty()) {
      const auto v = stack.back();
      stack.pop_back();
      ++out.back().vertices;
      for (const auto u : mesh.vv_range(v)) {
        if (label[static_cast<std::size_t>(u.idx())] >= 0) continue;
        label[static_cast<std::size_t>(u.idx())] = id;
        stack.push_back(u);
      }
    }
  }
  const Eigen::MatrixX3d p = surface.positions();
  const Eigen::MatrixX3i f = surface.faces();
  for (Eigen::Index t = 0; t < f.rows(); ++t) {
    const Eigen::Vector3d a = p.row(f(t, 0)), b = p.row(f(t, 1)), c = p.row(f(t, 2));
    out[static_cast<std::size_t>(label[static_cast<std::size_t>(f(t, 0))])].volume +=
        a.dot(b.cross(c)) / 6.0;
  }
  return out;
}

}  // namespace surfcomp::test
