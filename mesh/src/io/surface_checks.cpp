#include "surface_checks.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"

namespace surfcomp::mesh::io::detail {

void check_read_surface(const Surface& surface, const std::string& file) {
  const auto vertex = [](Eigen::Index i) { return "vertex " + std::to_string(i); };
  const Eigen::MatrixX3d positions = surface.positions();
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    surfcomp::io::check_read_position(positions.row(i).transpose(), file, vertex(i));
  }
  if (surface.has_normals()) {
    const Eigen::MatrixX3d normals = surface.normals();
    for (Eigen::Index i = 0; i < normals.rows(); ++i) {
      for (Eigen::Index c = 0; c < 3; ++c) {
        surfcomp::io::check_read_value(normals(i, c), file, vertex(i), "normal");
      }
    }
  }
  for (const std::string& name : surface.property_names()) {
    const Eigen::VectorXd values = surface.property(name);
    for (Eigen::Index i = 0; i < values.size(); ++i) {
      surfcomp::io::check_read_value(values(i), file, vertex(i), "property '" + name + "'");
    }
  }
}

void check_has_triangles(std::size_t n_vertices, std::size_t n_triangles, const std::string& file) {
  if (n_triangles > 0) return;
  if (n_vertices == 0) {
    throw FormatError(file, "no vertices and no faces; surfcomp needs a triangle mesh");
  }
  throw FormatError(file, "a point cloud (" + std::to_string(n_vertices) +
                              (n_vertices == 1 ? " vertex" : " vertices") +
                              ", no faces); surfcomp needs a triangle mesh: reconstruct a "
                              "surface first (e.g. Poisson or ball pivoting)");
}

}  // namespace surfcomp::mesh::io::detail
