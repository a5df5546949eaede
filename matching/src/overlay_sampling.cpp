#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/matching/overlay_sample.hpp"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <map>
#include <string>

namespace surfcomp::matching {

SurfaceSample sample_surface(const mesh::Surface& surface, double spacing,
                             const std::vector<bool>* vertex_mask) {
  detail::check_overlay_spacing(spacing, {"sample_surface", ""});
  const std::size_t n = surface.n_vertices();
  if (vertex_mask != nullptr && vertex_mask->size() != n) {
    throw InputError(surface.source() + ": overlay vertex mask has " +
                     std::to_string(vertex_mask->size()) + " flags for " + std::to_string(n) +
                     " vertices");
  }
  const Eigen::MatrixX3d positions = surface.positions();
  Eigen::MatrixX3d normals;
  if (surface.has_normals()) {
    normals = surface.normals();
  } else {
    mesh::Surface copy = surface;
    copy.compute_normals();
    normals = copy.normals();
  }
  const Eigen::VectorXd area = mesh::vertex_areas(surface);
  const auto property_or_zero = [&](const char* name) {
    return surface.has_property(name)
               ? surface.property(name)
               : Eigen::VectorXd(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n)));
  };
  const Eigen::VectorXd esp = property_or_zero(mesh::property::esp);
  const Eigen::VectorXd lp = property_or_zero(mesh::property::lp);

  struct Cell {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    double esp = 0.0, lp = 0.0, weight = 0.0;
  };
  std::map<std::array<long, 3>, Cell> cells;
  for (std::size_t v = 0; v < n; ++v) {
    if (vertex_mask != nullptr && !(*vertex_mask)[v]) continue;
    const Eigen::Index i = static_cast<Eigen::Index>(v);
    const double w = area(i);
    if (!(w > 0.0)) continue;
    const Eigen::Vector3d p = positions.row(i);
    const std::array<long, 3> key{static_cast<long>(std::floor(p.x() / spacing)),
                                  static_cast<long>(std::floor(p.y() / spacing)),
                                  static_cast<long>(std::floor(p.z() / spacing))};
    Cell& cell = cells[key];
    cell.position += w * p;
    cell.normal += w * Eigen::Vector3d(normals.row(i));
    cell.esp += w * esp(i);
    cell.lp += w * lp(i);
    cell.weight += w;
  }
  SurfaceSample sample;
  const Eigen::Index m = static_cast<Eigen::Index>(cells.size());
  sample.points.resize(3, m);
  sample.normals.resize(3, m);
  sample.weights.resize(m);
  sample.esp.resize(m);
  sample.lp.resize(m);
  Eigen::Index k = 0;
  for (const auto& [key, cell] : cells) {
    sample.points.col(k) = cell.position / cell.weight;
    const double length = cell.normal.norm();
    sample.normals.col(k) =
        length > 0.0 ? Eigen::Vector3d(cell.normal / length) : Eigen::Vector3d::Zero();
    sample.esp(k) = cell.esp / cell.weight;
    sample.lp(k) = cell.lp / cell.weight;
    sample.weights(k) = cell.weight;
    ++k;
  }
  return sample;
}

AtomSample sample_atoms(const std::vector<harmonic::SurfaceAtom>& atoms) {
  std::vector<const harmonic::SurfaceAtom*> kept;
  for (const harmonic::SurfaceAtom& atom : atoms) {
    if (atom.element != "H" && atom.element != "C") kept.push_back(&atom);
  }
  AtomSample sample;
  sample.points.resize(3, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    sample.points.col(static_cast<Eigen::Index>(k)) = kept[k]->position;
    sample.elements.push_back(kept[k]->element);
  }
  return sample;
}

}  // namespace surfcomp::matching
