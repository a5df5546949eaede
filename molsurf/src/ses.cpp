// build_ses and build_sas: the stages in order. The exact geometry is sas_geometry.cpp, the
// sampled and meshed field ses_grid.cpp (storage sparse_grid.cpp, mesher
// dual_marching_cubes.cpp), the component filter ses_components.cpp, the remeshing remesh.cpp
// (CGAL), the vertex placement ses_vertices.cpp (SES) and sas_creases.cpp (SAS).
#include "surfcomp/molsurf/ses.hpp"

#include "ses_components.hpp"
#include "ses_distance_transform.hpp"
#include "ses_grid.hpp"
#include "ses_region.hpp"
#include "ses_vertices.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/mesh/remesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace surfcomp::molsurf {
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
/// Grid coordinates (centre +- reach, in voxels) must stay below this in magnitude: the grid
/// indexes nodes with 32-bit integers, and the sampler multiplies box indices by its box size.
constexpr double max_grid_coordinate = 1073741824.0;  // 2^30

/// `value` in the shortest form that reads back, for messages.
std::string number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Throws OptionError unless the limit in option `field` is at least 1.
void require_limit(const std::string& what, const char* field, double value) {
  if (!(value >= 1.0)) {
    throw OptionError(what + ": " + options::named(field) + " " + number(value) +
                      "; expected a limit >= 1");
  }
}

/// Throws InputError "<what>: <description>; the limit is L (raise it with OPTION)" when
/// `estimate` exceeds `limit`, the value of option `field`; `description` states the estimate.
void require_within(const std::string& what, const std::string& description, double estimate,
                    double limit, const char* field) {
  if (estimate > limit) {
    throw InputError(what + ": " + description + "; the limit is " + number(limit) +
                     " (raise it with " + options::named(field) + ")");
  }
}

void validate(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
              const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options,
              const std::string& what) {
  if (centers.rows() == 0) throw InputError(what + ": no atoms; expected at least one");
  if (centers.rows() != radii.size()) {
    throw InputError(what + ": " + std::to_string(centers.rows()) + " centres but " +
                     std::to_string(radii.size()) + " radii; expected one radius per centre");
  }
  if (!(options.vertex_density >= min_vertex_density &&
        options.vertex_density <= max_vertex_density)) {
    throw OptionError(what + ": vertex density " + number(options.vertex_density) +
                      " per A^2 is outside [" + number(min_vertex_density) + ", " +
                      number(max_vertex_density) + "]");
  }
  require_limit(what, "max_atoms", static_cast<double>(options.max_atoms));
  require_limit(what, "max_grid_cells", options.max_grid_cells);
  require_limit(what, "max_vertices", static_cast<double>(options.max_vertices));
  require_within(what, std::to_string(centers.rows()) + " atoms",
                 static_cast<double>(centers.rows()), static_cast<double>(options.max_atoms),
                 "max_atoms");
  for (Eigen::Index i = 0; i < centers.rows(); ++i) {
    if (!centers.row(i).allFinite()) {
      throw InputError(what + ": atom " + std::to_string(i + 1) +
                       " has a non-finite centre; expected finite coordinates");
    }
    if (!std::isfinite(radii(i)) || radii(i) <= 0.0) {
      throw InputError(what + ": atom " + std::to_string(i + 1) + " has radius " +
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
  if (!std::isfinite(options.voxel_size) || options.voxel_size < 0.0 ||
      (options.voxel_size > 0.0 && options.voxel_size < min_voxel_size)) {
    throw OptionError(what + ": voxel size " + number(options.voxel_size) +
                      " A; expected a finite value >= " + number(min_voxel_size) +
                      " A, or 0 for automatic");
  }
}

/// options.voxel_size, or the automatic choice documented in SesOptions.
double choose_voxel_size(const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options,
                         double edge_length, const std::string& what) {
  Eigen::Index which = 0;
  const double smallest = radii.minCoeff(&which);
  if (options.voxel_size == 0.0) {
    if (smallest < min_atom_voxels * min_voxel_size) {
      throw InputError(what + ": atom " + std::to_string(which + 1) + " has radius " +
                       number(smallest) + " A; expected at least " +
                       number(min_atom_voxels * min_voxel_size) +
                       " A (the grid needs 2 voxels per radius, voxels of at least " +
                       number(min_voxel_size) + " A)");
    }
    return std::min(auto_voxel_per_edge * edge_length, smallest / min_atom_voxels);
  }
  if (smallest < min_atom_voxels * options.voxel_size) {
    throw OptionError(what + ": voxel size " + std::to_string(options.voxel_size) +
                      " A is too coarse for the smallest atom (radius " + std::to_string(smallest) +
                      " A); expected at most " + std::to_string(smallest / min_atom_voxels) + " A");
  }
  return options.voxel_size;
}

/// The rows of (centers, radii) that are not an exact copy of an earlier row, in order.
std::vector<Eigen::Index> distinct_atoms(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                                         const Eigen::Ref<const Eigen::VectorXd>& radii) {
  const auto key = [&](Eigen::Index i) {
    return std::make_tuple(centers(i, 0), centers(i, 1), centers(i, 2), radii(i), i);
  };
  std::vector<Eigen::Index> order(static_cast<std::size_t>(centers.rows()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::sort(order.begin(), order.end(),
            [&](Eigen::Index a, Eigen::Index b) { return key(a) < key(b); });
  std::vector<bool> copy(order.size(), false);
  for (std::size_t k = 1; k < order.size(); ++k) {
    const Eigen::Index a = order[k - 1], b = order[k];
    copy[static_cast<std::size_t>(b)] = centers.row(a) == centers.row(b) && radii(a) == radii(b);
  }
  std::vector<Eigen::Index> kept;
  for (std::size_t i = 0; i < copy.size(); ++i) {
    if (!copy[i]) kept.push_back(static_cast<Eigen::Index>(i));
  }
  return kept;
}

/// Refuses atoms beyond the grid's index range and a sampling region over the cell limit. The
/// sampler visits the grid nodes within `reach` of some atom: at most the nodes of the bounding
/// box of those balls and at most the sum of their bounding cubes.
void check_grid_size(const Eigen::Ref<const Eigen::MatrixX3d>& centers, double reach, double voxel,
                     double max_cells, const std::string& what) {
  for (Eigen::Index i = 0; i < centers.rows(); ++i) {
    if (centers.row(i).cwiseAbs().maxCoeff() + reach > max_grid_coordinate * voxel) {
      throw InputError(what + ": atom " + std::to_string(i + 1) + " lies " +
                       number(centers.row(i).cwiseAbs().maxCoeff()) +
                       " A from the origin; at voxel size " + number(voxel) +
                       " A the grid reaches " + number(max_grid_coordinate * voxel - reach) + " A");
    }
  }
  const Eigen::Array3d extent =
      (centers.colwise().maxCoeff() - centers.colwise().minCoeff()).transpose().array() +
      2.0 * reach;
  const double box = ((extent / voxel).floor() + 1.0).prod();
  const double cube = std::pow(std::floor(2.0 * reach / voxel) + 1.0, 3);
  const double cells = std::min(box, cube * static_cast<double>(centers.rows()));
  require_within(
      what,
      "the surface grid would span about " + number(cells) + " cells of " + number(voxel) + " A",
      cells, max_cells, "max_grid_cells");
}

/// The vertex count the surface will have: the grid mesh's, or after remeshing its area times
/// the target density.
double expected_vertices(const detail::TriangleSoup& soup, const SesOptions& options) {
  if (!options.remesh) return static_cast<double>(soup.positions.rows());
  double area = 0.0;
  for (Eigen::Index f = 0; f < soup.faces.rows(); ++f) {
    const Eigen::Vector3d a = soup.positions.row(soup.faces(f, 0));
    const Eigen::Vector3d b = soup.positions.row(soup.faces(f, 1));
    const Eigen::Vector3d c = soup.positions.row(soup.faces(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area * options.vertex_density;
}

/// `surface` with the components of `soup` added after its own vertices and faces.
mesh::Surface with_components(const mesh::Surface& surface, const detail::TriangleSoup& soup,
                              const std::string& what) {
  const Eigen::Index nv = static_cast<Eigen::Index>(surface.n_vertices());
  Eigen::MatrixX3d positions(nv + soup.positions.rows(), 3);
  positions << surface.positions(), soup.positions;
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(surface.n_faces()) + soup.faces.rows(), 3);
  faces << surface.faces(), soup.faces.array() + static_cast<int>(nv);
  return mesh::Surface::from_arrays(positions, faces, what);
}

void validate_region(const SesRegion& region, const std::string& what) {
  if (region.centers.rows() == 0) throw InputError(what + ": the surface's region has no ball");
  if (region.centers.rows() != region.radii.size()) {
    throw InputError(what + ": the surface's region has " + std::to_string(region.centers.rows()) +
                     " centres but " + std::to_string(region.radii.size()) +
                     " radii; expected one radius per centre");
  }
  for (Eigen::Index i = 0; i < region.centers.rows(); ++i) {
    if (!region.centers.row(i).allFinite() || !std::isfinite(region.radii(i)) ||
        !(region.radii(i) > 0.0)) {
      throw InputError(what + ": ball " + std::to_string(i + 1) +
                       " of the surface's region has radius " + number(region.radii(i)) +
                       " A; expected a finite centre and a finite radius > 0");
    }
  }
}

/// The SES (excluded) or SAS of the atoms, cut to `region` when it is given (SES only).
mesh::Surface build_surface(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                            const Eigen::Ref<const Eigen::VectorXd>& radii,
                            const SesOptions& options, bool excluded, const std::string& what,
                            const SesRegion* region = nullptr) {
  validate(centers, radii, options, what);
  if (region != nullptr) validate_region(*region, what);
  const std::optional<detail::BallUnion> balls =
      region != nullptr ? std::optional<detail::BallUnion>(*region) : std::nullopt;
  const detail::BallUnion* clip = balls ? &*balls : nullptr;
  const double edge_length = mesh::edge_length_for_density(options.vertex_density);
  const double voxel = choose_voxel_size(radii, options, edge_length, what);
  // Both surfaces lie inside the spheres R_i (SAS on them), the band a little beyond.
  const double reach = radii.maxCoeff() + options.probe_radius + 2.0 * voxel;
  check_grid_size(centers, reach, voxel, options.max_grid_cells, what);
  if (excluded && options.method == SesMethod::distance_transform) {
    // The distance transform fills a dense box, 16 bytes a node, indexed by 32-bit integers.
    const double nodes =
        detail::distance_transform_nodes(centers, radii, options.probe_radius, voxel, clip);
    const std::string description = "the distance transform's grid would span about " +
                                    number(nodes) + " cells of " + number(voxel) + " A";
    require_within(what, description, nodes, options.max_grid_cells, "max_grid_cells");
    if (nodes > static_cast<double>(std::numeric_limits<std::int32_t>::max())) {
      throw InputError(what + ": " + description + "; it indexes at most 2^31 - 1 (use " +
                       options::named("ses_method") + " exact)");
    }
  }
  const auto stage_done = [&](std::int64_t stage) {
    if (options.progress) options.progress(stage, 4);
  };
  stage_done(0);

  // An exact copy of an atom leaves the union unchanged but would make each copy bury the
  // other's sphere; the geometry sees each distinct atom once.
  const std::vector<Eigen::Index> kept = distinct_atoms(centers, radii);
  Eigen::MatrixX3d distinct_centers(static_cast<Eigen::Index>(kept.size()), 3);
  Eigen::VectorXd distinct_radii(static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    distinct_centers.row(static_cast<Eigen::Index>(k)) = centers.row(kept[k]);
    distinct_radii(static_cast<Eigen::Index>(k)) = radii(kept[k]);
  }
  const bool transform = excluded && options.method == SesMethod::distance_transform;
  std::optional<detail::SasGeometry> sas;
  detail::TransformField transform_field;
  detail::TriangleSoup soup;
  if (transform) {
    detail::TransformMesh meshed = detail::distance_transform_mesh(
        distinct_centers, distinct_radii, options.probe_radius, voxel, clip);
    soup = std::move(meshed.soup);
    transform_field = std::move(meshed.field);
  } else {
    sas.emplace(distinct_centers, distinct_radii, options.probe_radius);
    soup = detail::grid_mesh(
        *sas, excluded ? detail::SurfaceKind::excluded : detail::SurfaceKind::accessible,
        distinct_centers, reach, voxel, clip);
  }
  stage_done(1);
  // A component holding an atom holds its whole van der Waals ball, and a cavity the probe's.
  const double fraction = options.min_component_volume_fraction;
  detail::ComponentVolumes limits;
  limits.outward = fraction * 4.0 / 3.0 * M_PI * std::pow(radii.minCoeff(), 3);
  limits.cavity = fraction * 4.0 / 3.0 * M_PI * std::pow(options.probe_radius, 3);
  limits.keep_cavities = options.keep_cavities;
  soup = detail::kept_components(soup, limits);
  if (soup.faces.rows() == 0 && region != nullptr) {
    throw InputError(what + ": no part of the surface lies within the region it is cut to (" +
                     std::to_string(region->centers.rows()) +
                     " balls), or only pieces smaller than half the smallest atom");
  }
  if (soup.faces.rows() == 0) {
    throw TopologyError(what + ": the isosurface is empty at voxel size " + std::to_string(voxel) +
                        " A");
  }
  stage_done(2);
  const double vertices = expected_vertices(soup, options);
  require_within(what, "the surface would have about " + number(std::round(vertices)) + " vertices",
                 vertices, static_cast<double>(options.max_vertices), "max_vertices");
  mesh::Surface surface;
  if (!options.remesh) {
    surface = mesh::Surface::from_arrays(soup.positions, soup.faces, what);
  } else {
    // Components within one voxel (the grid's trace of a neck thinner than a voxel, when every
    // component is kept) stay as the grid meshed them: remeshing would shrink each to a
    // tetrahedron, and the grid mesh of a lone inside node is an axis-aligned box whose two
    // collapsed space diagonals land on one point.
    const detail::ComponentsBySize parts = detail::split_by_extent(soup, voxel);
    surface = mesh::isotropic_remesh(
        mesh::Surface::from_arrays(parts.large.positions, parts.large.faces, what), edge_length,
        remesh_iterations, false);
    if (parts.small.faces.rows() > 0) surface = with_components(surface, parts.small, what);
  }
  stage_done(3);
  // Grid and remeshed vertices lie within a voxel of the surface; search a little wider.
  const double projection_reach = reach_voxels * voxel;
  if (transform) {
    detail::place_on_field(surface, transform_field);
  } else if (excluded) {
    detail::place_ses_vertices(surface, *sas, projection_reach, options.compensate_chords, clip);
  } else {
    detail::place_sas_vertices(surface, *sas, projection_reach, edge_length,
                               options.compensate_chords);
  }
  mesh::require_closed_manifold(surface);
  stage_done(4);
  return surface;
}

}  // namespace

double ses_voxel_size(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                      const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options) {
  validate(centers, radii, options, "<ses>");
  return choose_voxel_size(radii, options, mesh::edge_length_for_density(options.vertex_density),
                           "<ses>");
}

mesh::Surface build_ses(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                        const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options,
                        const std::string& source) {
  return build_surface(centers, radii, options, true, source);
}

mesh::Surface build_ses(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                        const Eigen::Ref<const Eigen::VectorXd>& radii, const SesRegion& region,
                        const SesOptions& options, const std::string& source) {
  return build_surface(centers, radii, options, true, source, &region);
}

mesh::Surface build_sas(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                        const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options) {
  return build_surface(centers, radii, options, false, "<sas>");
}

}  // namespace surfcomp::molsurf
