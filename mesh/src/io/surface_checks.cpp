#include "surface_checks.hpp"

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

}  // namespace surfcomp::mesh::io::detail
