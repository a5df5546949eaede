#include "surfcomp/mesh/length_unit.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace surfcomp::mesh {

double rms_radius(const Surface& surface) {
  const Eigen::MatrixX3d v = surface.positions();
  const Eigen::MatrixX3i f = surface.faces();
  Eigen::VectorXd area(f.rows());
  Eigen::MatrixX3d centroid(f.rows(), 3);
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    const Eigen::RowVector3d a = v.row(f(i, 0)), b = v.row(f(i, 1)), c = v.row(f(i, 2));
    area(i) = 0.5 * (b - a).cross(c - a).norm();
    centroid.row(i) = (a + b + c) / 3.0;
  }
  const double total = area.sum();
  if (!(total > 0.0)) return 0.0;
  const Eigen::RowVector3d centre =
      (centroid.array().colwise() * area.array()).colwise().sum() / total;
  return std::sqrt((centroid.rowwise() - centre).rowwise().squaredNorm().dot(area) / total);
}

LengthUnit general_mesh_unit(const std::vector<const Surface*>& surfaces, LengthScale scale,
                             double unit, const std::string& names) {
  if (unit > 0.0) return {unit, "given"};
  if (scale == LengthScale::none) return {1.0, "none"};
  double radius = 0.0;
  for (const Surface* surface : surfaces) radius = std::max(radius, rms_radius(*surface));
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw InputError(names + ": the surface has no extent to take a length unit from (" +
                     options::named("scale") + " auto); give " + options::named("unit"));
  }
  return {radius / auto_unit_divisor, "auto"};
}

bool is_molecular_mesh(const Surface& surface, const std::string& file_extension) {
  if (file_extension == ".vert" || file_extension == ".face") return true;
  return surface.has_property(property::esp) && surface.has_property(property::lp);
}

}  // namespace surfcomp::mesh
