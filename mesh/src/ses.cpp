// build_ses and build_sas: the stages in order. The exact geometry is sas_geometry.cpp, the
// sampled and meshed field ses_grid.cpp (OpenVDB stays there), the component filter
// ses_components.cpp, the remeshing remesh.cpp (CGAL), the vertex placement ses_vertices.cpp
// (SES) and sas_creases.cpp (SAS).
#include "surfcomp/mesh/ses.hpp"

#include "ses_components.hpp"
#include "ses_grid.hpp"
#include "ses_vertices.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/remesh.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace surfcomp::mesh {
namespace {

/// Automatic voxel size as a fraction of the target edge length: the grid mesh then has a
/// little more than the target density, so remeshing mostly flips, collapses and relaxes. The
/// grid decides only the topology; vertices are projected onto the exact surface.
constexpr double auto_voxel_per_edge = 1.0;
/// The smallest atom must span this many voxels (radius / voxel).
constexpr double min_atom_voxels = 2.0;
/// Vertices are searched for their surface point this many voxels away.
constexpr double reach_voxels = 3.0;
/// Rounds of isotropic remeshing: the grid mesh is already close to the target.
constexpr int remesh_iterations = 2;

void validate(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
              const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options,
              const std::string& what) {
  if (centers.rows() == 0) throw InputError(what + ": no atoms; expected at least one");
  if (centers.rows() != radii.size()) {
    throw InputError(what + ": " + std::to_string(centers.rows()) + " centres but " +
                     std::to_string(radii.size()) + " radii; expected one radius per centre");
  }
  for (Eigen::Index i = 0; i < centers.rows(); ++i) {
    if (!centers.row(i).allFinite()) {
      throw InputError(what + ": atom " + std::to_string(i) +
                       " has a non-finite centre; expected finite coordinates");
    }
    if (!std::isfinite(radii(i)) || radii(i) <= 0.0) {
      throw InputError(what + ": atom " + std::to_string(i) + " has radius " +
                       std::to_string(radii(i)) + "; expected a finite radius > 0 A");
    }
  }
  if (!std::isfinite(options.probe_radius) || options.probe_radius < 0.0) {
    throw OptionError(what + ": probe radius " + std::to_string(options.probe_radius) +
                      " A; expected a finite value >= 0");
  }
  if (!(options.min_component_volume_fraction >= 0.0 &&
        options.min_component_volume_fraction <= 1.0)) {
    throw OptionError(what + ": min_component_volume_fraction " +
                      std::to_string(options.min_component_volume_fraction) +
                      "; expected a value in [0, 1]");
  }
  if (!std::isfinite(options.voxel_size) || options.voxel_size < 0.0) {
    throw OptionError(what + ": voxel size " + std::to_string(options.voxel_size) +
                      " A; expected a finite value > 0, or 0 for automatic");
  }
}

/// options.voxel_size, or the automatic choice documented in SesOptions.
double choose_voxel_size(const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options,
                         double edge_length, const std::string& what) {
  const double smallest = radii.minCoeff();
  if (options.voxel_size == 0.0) {
    return std::min(auto_voxel_per_edge * edge_length, smallest / min_atom_voxels);
  }
  if (smallest < min_atom_voxels * options.voxel_size) {
    throw OptionError(what + ": voxel size " + std::to_string(options.voxel_size) +
                      " A is too coarse for the smallest atom (radius " + std::to_string(smallest) +
                      " A); expected at most " + std::to_string(smallest / min_atom_voxels) + " A");
  }
  return options.voxel_size;
}

Surface build_surface(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                      const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options,
                      bool excluded, const std::string& what) {
  validate(centers, radii, options, what);
  const double edge_length = edge_length_for_density(options.vertex_density);
  const double voxel = choose_voxel_size(radii, options, edge_length, what);
  const detail::SasGeometry sas(centers, radii, options.probe_radius);

  // Both surfaces lie inside the spheres R_i (SAS on them), the band a little beyond.
  const double reach = radii.maxCoeff() + options.probe_radius + 2.0 * voxel;
  detail::TriangleSoup soup = detail::grid_mesh(
      sas, excluded ? detail::SurfaceKind::excluded : detail::SurfaceKind::accessible, centers,
      reach, voxel);
  // A component holding an atom holds its whole van der Waals ball, and a cavity the probe's.
  const double fraction = options.min_component_volume_fraction;
  detail::ComponentVolumes limits;
  limits.outward = fraction * 4.0 / 3.0 * M_PI * std::pow(radii.minCoeff(), 3);
  limits.cavity = fraction * 4.0 / 3.0 * M_PI * std::pow(options.probe_radius, 3);
  limits.keep_cavities = options.keep_cavities;
  soup = detail::kept_components(soup, limits);
  if (soup.faces.rows() == 0) {
    throw TopologyError(what + ": the isosurface is empty at voxel size " + std::to_string(voxel) +
                        " A");
  }
  Surface surface = Surface::from_arrays(soup.positions, soup.faces, what);
  if (options.remesh) surface = isotropic_remesh(surface, edge_length, remesh_iterations, false);
  // Grid and remeshed vertices lie within a voxel of the surface; search a little wider.
  const double projection_reach = reach_voxels * voxel;
  if (excluded) {
    detail::place_ses_vertices(surface, sas, projection_reach, options.compensate_chords);
  } else {
    detail::place_sas_vertices(surface, sas, projection_reach, edge_length,
                               options.compensate_chords);
  }
  require_closed_manifold(surface);
  return surface;
}

}  // namespace

Surface build_ses(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                  const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options) {
  return build_surface(centers, radii, options, true, "<ses>");
}

Surface build_sas(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                  const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options) {
  return build_surface(centers, radii, options, false, "<sas>");
}

}  // namespace surfcomp::mesh
