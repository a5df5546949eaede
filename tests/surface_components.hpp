// Test-only: the vertex-connected components of a surface with their vertex counts and enclosed
// volumes, to check what the SES builder keeps.
#pragma once

#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/mesh/topology.hpp"

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
  const mesh::SurfaceComponents components = mesh::connected_components(surface);
  const std::vector<int>& label = components.component;
  std::vector<SurfaceComponent> out(static_cast<std::size_t>(components.count));
  for (const int c : label) ++out[static_cast<std::size_t>(c)].vertices;
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
