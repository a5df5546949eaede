// The solvent-excluded (SES) and solvent-accessible (SAS) surfaces of a set of atoms, built on
// a sparse signed-distance grid (dual marching cubes) and remeshed isotropically (CGAL)
// (method §1.2).
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <string>

namespace surfcomp::molsurf {

/// The vertex densities build_ses accepts, vertices per A^2. The upper end (edges of 0.24 A,
/// eight times the default's vertices) bounds the build's time: the SES of the 2,472 atoms of
/// 1THL takes about 30 s at 20, and would take many minutes at 100.
inline constexpr double min_vertex_density = 0.05;
inline constexpr double max_vertex_density = 20.0;

/// How build_ses finds the SES. `exact`: the exact distance to the SAS's exposed pieces near the
/// surface, and every vertex on the exact SES with its exact normal (all of build_ses's
/// description). `distance_transform`: a Euclidean distance transform on a dense grid around the
/// atoms (EDTSurf's approach, refined near the surface; 16 bytes a node), the same mesher and
/// remeshing, then every vertex moved onto the interpolated field with the field's gradient as
/// its normal, and no chord compensation. Faster for a protein, but the grid bridges the
/// crevices thinner than a voxel, so area falls and volume grows
/// (docs/decisions.md#distance-transform-ses has the measured figures).
enum class SesMethod { exact, distance_transform };

/// The names of the methods, indexed by SesMethod (as --ses-method spells them).
inline constexpr std::array<const char*, 2> ses_method_names = {"exact", "edt"};

struct SesOptions {
  SesMethod method = SesMethod::exact;  ///< the SES only; build_sas is always exact
  double probe_radius = 1.4;            ///< A, >= 0 (water); 0 gives the van der Waals surface
  /// Target vertices per A^2 after remeshing, in [min_vertex_density, max_vertex_density]
  /// (method §1.2: ~2-3).
  double vertex_density = 2.5;
  /// Grid spacing, A; 0 = automatic: min(L, r_min / 2) with L the edge length for
  /// vertex_density (edge_length_for_density) and r_min the smallest atom radius. The grid
  /// decides only the topology (features thinner than about a voxel are lost); vertices are
  /// projected onto the exact surface. Must be at most r_min / 2.
  double voxel_size = 0.0;
  bool remesh = true;  ///< isotropic remeshing to edge length L; false keeps the grid mesh
  /// Move each vertex along its normal by the mean gap between its flat triangles and the
  /// curved surface (H (a^2 + b^2 + c^2) / 24, H the exact mean curvature), so that area and
  /// volume are unbiased (default); false leaves every vertex exactly on the surface, whose
  /// chord triangles then underestimate area and volume (docs/decisions.md#chord-compensation).
  bool compensate_chords = true;
  /// Keep the closed inward-facing components that line internal cavities (the probe fits in
  /// them but cannot reach them from outside). Default false: only outward-facing components
  /// (positive enclosed volume) are kept, as MSMS and EDTSurf do by default.
  bool keep_cavities = false;
  /// Default 0.5; in [0, 1], 0 keeps every component. Closed components of the grid mesh that
  /// enclose less than this fraction of the smallest body they could hold are dropped: for an
  /// outward component the smallest atom's van der Waals ball (4/3 pi r_min^3), for a cavity
  /// (keep_cavities) the probe's ball. Every atom's ball lies inside the SES, so a smaller
  /// outward component holds no atom and bounds no part of the molecule: it is what the grid
  /// keeps of a feature thinner than a voxel, such as a neck where the probe just fails to pass
  /// between two atoms (docs/decisions.md#small-ses-components). The fraction leaves room for
  /// the grid's volume error on a lone atom. The outward component of largest volume is always
  /// kept.
  double min_component_volume_fraction = 0.5;

  // Resource limits, checked before the memory they bound is allocated; an input over a limit
  // is refused with InputError giving the estimate, the limit and the option that raises it
  // (docs/decisions.md#resource-limits). Each must be >= 1.
  /// Default 2,000,000 atoms (CLI --max-atoms).
  std::int64_t max_atoms = 2'000'000;
  /// Default 2e8 (CLI --max-grid-cells). The grid nodes within reach (largest radius + probe +
  /// 2 voxels) of some atom, estimated before sampling as the smaller of the bounding box of
  /// those balls and the sum of their cubes, in voxels. The sampled band, and so the memory,
  /// is a fraction of it; the limit stops a huge radius or a tiny voxel. With
  /// SesMethod::distance_transform it also bounds the dense box's nodes (16 bytes each).
  double max_grid_cells = 2e8;
  /// Default 20,000,000 (CLI --max-vertices). The vertices of the result, estimated from the
  /// grid mesh before remeshing (its area times vertex_density; its vertex count without
  /// remeshing). Every later stage (ESP, LP, curvature, patches) is at least linear in it.
  std::int64_t max_vertices = 20'000'000;

  /// Reports the build's progress: called with (k, 4) as each of its four stages ends (grid
  /// sampled and meshed, components kept, remeshed, vertices placed on the exact surface), and
  /// (0, 4) once the limits are checked and the work starts. Empty: no reports.
  std::function<void(std::int64_t done, std::int64_t total)> progress;
};

/// The smallest voxel build_ses and build_sas accept, A: an automatic voxel (r_min / 2) below it
/// comes from an atom radius below 2 * min_voxel_size, refused as input.
inline constexpr double min_voxel_size = 1e-3;

/// The grid spacing build_ses and build_sas take for atoms of these radii: options.voxel_size,
/// or the automatic choice documented in SesOptions. A surface built from a subset of the atoms
/// (a binding site's neighbourhood) passes the whole structure's spacing, so that it samples the
/// same grid. Throws as build_ses for the atoms and the options.
double ses_voxel_size(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                      const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options);

/// The solvent-excluded surface (Richards 1977; Connolly 1983): the boundary of the region a
/// probe sphere of radius `probe_radius` cannot enter while rolling over the atoms.
/// Method: U is the union of spheres R_i = r_i + probe (the SAS region); a point belongs to the
/// SES region iff its distance to the boundary of U is at least `probe`. That distance is
/// computed exactly from the exposed pieces of U's boundary (sphere patches, circle arcs where
/// two spheres meet, vertices where three meet), sampled only near the surface into a sparse
/// grid (adaptive octree culling, the field being 1-Lipschitz), meshed by dual marching cubes
/// (Nielson 2004; a closed 2-manifold, quads split along the shorter diagonal), filtered by
/// component (keep_cavities, min_component_volume_fraction), remeshed isotropically (CGAL,
/// 2 rounds), and every vertex is projected onto the exact SES (convex sphere caps, toroidal
/// and spherical re-entrant patches), with the exact normal, then moved by the chord
/// compensation. Disjoint molecules give several outward components; so do parts joined only
/// by a neck thinner than a voxel that the grid loses: the mesh connects two parts only through
/// grid nodes inside the surface linked along grid edges or across the diagonals of cell faces.
/// That is options.method exact, the default; distance_transform replaces the exact field and
/// placement by a dense distance transform (SesMethod), and its normals are the field's.
/// `centers` is #A by 3 (A), `radii` #A van der Waals radii (A).
/// Returns a closed, 2-manifold, outward-oriented surface (positive volume) with exact unit
/// outward vertex normals; source() is `source`, which the messages name (default "<ses>"; a
/// molecule's file). Deterministic: the same input gives the same
/// arrays whatever the thread count.
/// Atoms with the same centre and radius as an earlier atom are skipped: they add nothing to the
/// union of spheres.
/// Throws InputError for no atoms, a size mismatch, a non-finite centre or radius, a radius
/// <= 0 or < 2 * min_voxel_size (with an automatic voxel), a centre farther than 2^30 voxels
/// from the origin, more atoms, grid cells or vertices than the limits; OptionError for a
/// probe < 0, a density <= 0, a voxel_size < 0, in (0, min_voxel_size) or > r_min / 2, a
/// min_component_volume_fraction outside [0, 1], a limit < 1;
/// TopologyError if the mesh is not a closed manifold (a bug, reported rather than returned).
mesh::Surface build_ses(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                        const Eigen::Ref<const Eigen::VectorXd>& radii,
                        const SesOptions& options = {}, const std::string& source = "<ses>");

/// A region of space as a union of balls, A: `centers` #B by 3, `radii` #B (finite, > 0).
struct SesRegion {
  Eigen::MatrixX3d centers;
  Eigen::VectorXd radii;
};

/// build_ses confined to `region`: the boundary of the SES region cut to the union of the
/// region's balls. Where a ball's sphere cuts the molecule, the surface is closed by that
/// sphere, so the result is still a closed, 2-manifold, outward-oriented surface; its vertices
/// on the SES are placed exactly as build_ses places them, those on the spheres exactly on the
/// spheres (normals outward from the ball). The grid is sampled only inside the region, which
/// is the point: a binding site's surface (build_site_surface) costs the site's region, not the
/// whole structure's margin. The SES within the region is exact when `centers` holds every atom
/// within 2 probe radii plus the largest atom radius of it (and the mesh the whole surface's
/// there, away from the cut, when it holds those within two voxels more). Pieces the cut leaves
/// smaller than the component filter's limit (min_component_volume_fraction) are dropped.
/// Throws as build_ses, and InputError for an empty region, a size mismatch, a ball that is
/// not finite with a radius > 0, or a region that holds none of the surface.
mesh::Surface build_ses(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                        const Eigen::Ref<const Eigen::VectorXd>& radii, const SesRegion& region,
                        const SesOptions& options = {}, const std::string& source = "<ses>");

/// The solvent-accessible surface (Lee & Richards 1971): the boundary of the union of spheres of
/// radius r_i + probe_radius (the surface the probe centre traces), built like build_ses from
/// the field min_i (|x - c_i| - R_i). Vertices are projected onto their nearest point of the
/// SAS (a sphere patch, a crease where two spheres meet or a vertex where three meet), and the
/// mesh is made to follow the concave creases: edges whose ends lie on no common sphere are
/// split at (or their nearer end moved to) the exact crease point, and the short edges left
/// are collapsed onto the crease vertices, so that no triangle chords across a crease. Crease
/// vertices get the mean of the spheres' normals and no chord compensation. Same arguments,
/// guarantees and exceptions; source() is "<sas>".
mesh::Surface build_sas(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                        const Eigen::Ref<const Eigen::VectorXd>& radii,
                        const SesOptions& options = {});

}  // namespace surfcomp::molsurf
