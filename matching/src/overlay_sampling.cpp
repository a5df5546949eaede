#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "surfcomp/molsurf/ses_points.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::matching {

namespace {

/// Points pooled in cubic cells of `spacing`: per cell the weighted mean position, the
/// normalised weighted sum of normals, the weighted mean ESP and LP (zero without them) and the
/// sum of weights, cells ordered by their integer coordinates. Points of weight <= 0 (or NaN)
/// and unset mask flags are left out; a cell's points are summed in their order.
SurfaceSample pool_in_cells(const Eigen::Ref<const Eigen::Matrix3Xd>& points,
                            const Eigen::Ref<const Eigen::Matrix3Xd>& normals,
                            const Eigen::Ref<const Eigen::VectorXd>& weights,
                            const Eigen::VectorXd* esp, const Eigen::VectorXd* lp, double spacing,
                            const std::vector<bool>* mask) {
  using Key = std::array<long, 3>;
  std::vector<std::pair<Key, Eigen::Index>> keyed;
  keyed.reserve(static_cast<std::size_t>(points.cols()));
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    if (mask != nullptr && !(*mask)[static_cast<std::size_t>(i)]) continue;
    if (!(weights(i) > 0.0)) continue;
    keyed.push_back({{static_cast<long>(std::floor(points(0, i) / spacing)),
                      static_cast<long>(std::floor(points(1, i) / spacing)),
                      static_cast<long>(std::floor(points(2, i) / spacing))},
                     i});
  }
  std::sort(keyed.begin(), keyed.end());
  Eigen::Index cells = 0;
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    if (k == 0 || keyed[k].first != keyed[k - 1].first) ++cells;
  }
  SurfaceSample sample;
  sample.points.resize(3, cells);
  sample.normals.resize(3, cells);
  sample.weights.resize(cells);
  sample.esp.resize(cells);
  sample.lp.resize(cells);
  Eigen::Index c = -1;
  Eigen::Vector3d position, normal;
  double weight = 0.0, esp_sum = 0.0, lp_sum = 0.0;
  const auto close_cell = [&] {
    sample.points.col(c) = position / weight;
    const double length = normal.norm();
    sample.normals.col(c) =
        length > 0.0 ? Eigen::Vector3d(normal / length) : Eigen::Vector3d::Zero();
    sample.esp(c) = esp_sum / weight;
    sample.lp(c) = lp_sum / weight;
    sample.weights(c) = weight;
  };
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    if (k == 0 || keyed[k].first != keyed[k - 1].first) {
      if (c >= 0) close_cell();
      ++c;
      position.setZero();
      normal.setZero();
      weight = esp_sum = lp_sum = 0.0;
    }
    const Eigen::Index i = keyed[k].second;
    const double w = weights(i);
    position += w * points.col(i);
    normal += w * normals.col(i);
    esp_sum += w * (esp != nullptr ? (*esp)(i) : 0.0);
    lp_sum += w * (lp != nullptr ? (*lp)(i) : 0.0);
    weight += w;
  }
  if (c >= 0) close_cell();
  return sample;
}

}  // namespace

SurfaceSample sample_surface(const mesh::Surface& surface, double spacing,
                             const std::vector<bool>* vertex_mask) {
  detail::check_overlay_spacing(spacing, {"sample_surface", ""});
  const std::size_t n = surface.n_vertices();
  if (vertex_mask != nullptr && vertex_mask->size() != n) {
    throw InputError(surface.source() + ": overlay vertex mask has " +
                     std::to_string(vertex_mask->size()) + " flags for " + std::to_string(n) +
                     " vertices");
  }
  const Eigen::Matrix3Xd positions = surface.positions().transpose();
  Eigen::Matrix3Xd normals;
  if (surface.has_normals()) {
    normals = surface.normals().transpose();
  } else {
    mesh::Surface copy = surface;
    copy.compute_normals();
    normals = copy.normals().transpose();
  }
  const Eigen::VectorXd area = mesh::vertex_areas(surface);
  const bool has_esp = surface.has_property(mesh::property::esp);
  const bool has_lp = surface.has_property(mesh::property::lp);
  const Eigen::VectorXd esp = has_esp ? surface.property(mesh::property::esp) : Eigen::VectorXd();
  const Eigen::VectorXd lp = has_lp ? surface.property(mesh::property::lp) : Eigen::VectorXd();
  return pool_in_cells(positions, normals, area, has_esp ? &esp : nullptr, has_lp ? &lp : nullptr,
                       spacing, vertex_mask);
}

SurfaceSample sample_molecule(const Molecule& molecule, double spacing,
                              const molsurf::MolecularSurfaceOptions& surface,
                              double grid_spacing) {
  detail::check_overlay_spacing(spacing, {"sample_molecule", ""});
  validate_molecule(molecule);
  molsurf::SesPointOptions options;
  options.probe_radius = surface.ses.probe_radius;
  options.grid_spacing = grid_spacing;
  options.max_grid_cells = surface.ses.max_grid_cells;
  const molsurf::AtomBalls balls = molsurf::atom_balls(molecule);
  const molsurf::SurfacePoints points = molsurf::ses_points(balls.centers, balls.radii, options);
  SurfaceSample sample = pool_in_cells(points.points, points.normals, points.areas, nullptr,
                                       nullptr, spacing, nullptr);
  if (sample.size() > 0) {
    const Eigen::MatrixX3d at = sample.points.transpose();
    sample.esp = molsurf::electrostatic_potential(at, molecule, surface.esp);
    sample.lp = molsurf::lipophilic_potential(at, molecule, surface.lp);
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
