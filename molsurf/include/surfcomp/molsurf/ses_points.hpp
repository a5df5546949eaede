// The solvent-excluded surface as area-weighted points, straight from the atoms: no mesh, no
// remeshing, no curvature. A screen's first two stages compare surfaces only through such
// points (matching/overlay_sample.hpp), so they need nothing more; the full surface (ses.hpp)
// stays for everything else. Why this construction: docs/decisions.md#screening-surface.
#pragma once

#include <Eigen/Core>

#include <cstddef>

namespace surfcomp::molsurf {

struct SesPointOptions {
  /// Default 1.4 A. Probe radius; >= 0 (0: the van der Waals surface).
  double probe_radius = 1.4;
  /// Default 0.5 A. Spacing of the grid whose edges the surface crosses: each crossing is one
  /// point. Finite, > 0.
  double grid_spacing = 0.5;
  /// Default 2e8. Limit on the grid's nodes (the bounding box of the atoms' probe-grown
  /// spheres, in grid spacings); a larger input is refused before anything is allocated. >= 1.
  double max_grid_cells = 2e8;
};

/// Points on a surface with their unit outward normals and the area (A^2) each stands for.
struct SurfacePoints {
  Eigen::Matrix3Xd points;   ///< A
  Eigen::Matrix3Xd normals;  ///< unit, outward
  Eigen::VectorXd areas;     ///< A^2; they sum to about the surface's area

  std::size_t size() const { return static_cast<std::size_t>(points.cols()); }
};

/// Points on the SES of the balls (`centers` #A by 3, `radii` #A, A), one where the surface
/// crosses an edge of a grid of `grid_spacing`:
///  1. the nodes inside the solvent-accessible region U (the union of balls r_i + probe) are
///     marked row by row; the nodes outside U that are connected to the grid's border are the
///     solvent (internal cavities are left out, as build_ses leaves them out by default);
///  2. each solvent node next to U is moved to its nearest point of U's boundary (a probe
///     centre exactly on the SAS), and near a crease also to the crease's nearest point;
///  3. each node of U gets its distance to the nearest such probe centre; the SES is where that
///     distance equals the probe radius (Richards' definition), and a grid edge whose ends lie
///     on either side gives a point: on an atom's sphere with its radial normal where the probe
///     rolling over that atom touches it there (exact), else on its nearest probe's sphere, the
///     probe's centre giving the normal (re-entrant surface, to within the probes' spacing);
///  4. a point on an edge along axis k stands for grid_spacing^2 |n_k| of area (n its normal):
///     a surface element dA crosses dA |n_k| / grid_spacing^2 edges along axis k, so over the
///     three axes the areas sum to the surface's area without bias, and grazing crossings,
///     whose count depends most on where the grid's lines fall, weigh least.
/// With probe 0 the surface is the van der Waals surface. Points are in grid order
/// (deterministic). Throws InputError for no atoms, mismatched sizes, a non-finite centre or
/// radius, a radius <= 0, a grid over max_grid_cells; OptionError for a probe < 0 or a spacing
/// that is not finite and > 0.
SurfacePoints ses_points(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                         const Eigen::Ref<const Eigen::VectorXd>& radii,
                         const SesPointOptions& options = {});

}  // namespace surfcomp::molsurf
