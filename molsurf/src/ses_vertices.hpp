// Internal to the molsurf module (not installed): the last stage of build_ses and build_sas, which
// puts the (remeshed) grid mesh's vertices onto the exact surface.
#pragma once

#include "sas_geometry.hpp"
#include "ses_region.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

namespace surfcomp::molsurf::detail {

/// Projects every vertex (within `reach` A of the SES) onto the exact SES of `sas` and sets the
/// exact outward normals; a vertex with no surface point within reach keeps its place and the
/// mesh normal. With `compensate`, then moves each vertex along its normal by the mean gap
/// between its flat triangles and the curved surface (compensate_chord_gaps), so that area and
/// volume are unbiased instead of those of an inscribed polyhedron. With a `region`, the
/// surface is the SES region cut to it (place_in_region). Parallel, deterministic.
void place_ses_vertices(mesh::Surface& surface, const SasGeometry& sas, double reach,
                        bool compensate, const BallUnion* region = nullptr);

/// The placement of one vertex of an SES cut to `region`: `start` is where the mesh put it, and
/// (x, normal, mean_curvature) its projection onto the SES (normal zero when none was found
/// within `reach`). Keeps the SES point when it lies in the region and no sphere point of the
/// region inside the SES region is nearer; otherwise takes that sphere point, its outward
/// normal and curvature 1 / radius; where neither exists (on the seam where they meet), the
/// vertex stays at `start` with a zero normal (the mesh normal, finish_placement).
void place_in_region(const Vec3& start, const SasGeometry& sas, double reach,
                     const BallUnion& region, Vec3& x, Vec3& normal, double& mean_curvature);

/// Projects every vertex onto its nearest point of the SAS and makes the mesh follow the
/// creases, the concave circle arcs where two spheres meet, which chord triangles would
/// otherwise cut across (losing area): every edge whose ends lie on no common sphere is split
/// at the exact crease point nearest its midpoint, or its nearer end is moved there when that
/// is close; short edges left by the splits are then collapsed onto the crease vertices.
/// Lengths are relative to the target `edge_length` (A). Sets the exact normals (the mean of
/// the spheres' at a crease) and, with `compensate`, moves the vertices on one sphere by the
/// chord gap (crease vertices stay on their crease). Sequential after the parallel projection:
/// deterministic.
void place_sas_vertices(mesh::Surface& surface, const SasGeometry& sas, double reach,
                        double edge_length, bool compensate);

/// The step both placements end with: a vertex whose exact normal is unknown (a zero row of
/// `normals`, #V by 3) takes the mesh normal; the normals are set on `surface` and, with
/// `compensate`, the vertices move by the chord gap (compensate_chord_gaps).
void finish_placement(mesh::Surface& surface, Eigen::MatrixX3d& normals,
                      const Eigen::VectorXd& curvature, bool compensate);

/// Moves each vertex along its unit normal (#V by 3) by the mean gap between its flat triangles
/// and the curved surface of mean curvature curvature(v) (1/A), H * (a^2 + b^2 + c^2) / 24
/// averaged over its triangles: the mean height of a sphere of mean curvature H over a chord
/// triangle with sides a, b, c (the circumcentre-centred cap height (rho^2 - t^2) / (2 / H)
/// averaged over the triangle).
void compensate_chord_gaps(mesh::Surface& surface, const Eigen::MatrixX3d& normals,
                           const Eigen::VectorXd& curvature);

}  // namespace surfcomp::molsurf::detail
