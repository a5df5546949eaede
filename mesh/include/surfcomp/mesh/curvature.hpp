// Per-vertex curvature of a triangle surface: principal curvatures by local jet fitting
// (Cazals & Pouget 2005, CGAL's Monge_via_jet_fitting), the Koenderink shape index and
// curvedness, and the discrete Gaussian curvature as the angle defect.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <functional>

namespace surfcomp::mesh {

/// The local surface model fitted at each vertex.
enum class CurvatureMethod {
  /// Quadric z = a x^2 + b xy + c y^2 + d x + e y + f + g z^2 + h xz + i yz in the tangent
  /// frame of the vertex normal (9 coefficients, linear least squares), with z in the last
  /// three terms taken from the previous pass's prediction (`quadric_passes` fixed-point passes
  /// after a paraboloid) and a ridge (`quadric_ridge`) towards a sphere's g, h, i. Without
  /// noise it recovers a sphere's curvature exactly, whatever the neighbourhood size.
  quadric,
  /// Height jet of degree `jet_degree` over the neighbourhood's PCA plane, CGAL
  /// Monge_via_jet_fitting (Cazals & Pouget 2005). A degree-2 jet overestimates |k| when the
  /// neighbourhood is not small against the radius of curvature, as on atom-sized spheres
  /// (docs/decisions.md#curvature-estimator).
  jet,
};

/// Which vertices each local fit uses and the surface model fitted to them.
struct CurvatureOptions {
  /// Default quadric.
  CurvatureMethod method = CurvatureMethod::quadric;
  /// Default 2. The fit at a vertex uses its `rings`-ring (vertices at most `rings` edges
  /// away) when `radius` is 0. Must be >= 1.
  int rings = 2;
  /// Default 0 A (use `rings`). When > 0, the fit uses the vertices within this Euclidean
  /// distance (A) of the vertex that are connected to it through such vertices (the
  /// neighbourhood grows over mesh edges and stops at the sphere). Must be >= 0.
  double radius = 0.0;
  /// Default 3 (method quadric only). Fixed-point passes of the quadric fit after the initial
  /// paraboloid (0 = paraboloid only); each pass shrinks the remaining bias on a sphere by
  /// about the factor (neighbourhood radius / sphere radius)^2 / 2. 0..20.
  int quadric_passes = 3;
  /// Default 0.01 (method quadric only). Weight of the ridge term that pulls the quadric's
  /// z^2, xz, yz coefficients towards a sphere's (g = (a + c) / 2, h = i = 0) in units of the
  /// neighbourhood size; it keeps flat, noisy and boundary fits stable. >= 0.
  double quadric_ridge = 0.01;
  /// Default 2 (method jet only). Degree of the fitted height function, 2..4; a degree-d jet
  /// has (d+1)(d+2)/2 coefficients. Degree 2 is the most robust to noise.
  int jet_degree = 2;
  /// Default 12. When a neighbourhood holds fewer vertices, further rings are added until it
  /// holds this many (or the vertex's connected component is exhausted). Must be at least the
  /// number of fitted coefficients: 9 for quadric, (jet_degree+1)(jet_degree+2)/2 for jet. A
  /// component with fewer vertices is fitted by a sphere (see principal_curvatures).
  int min_points = 12;
  /// Default 1024. The most points a fit uses, which bounds its cost whatever the radius and the
  /// mesh's resolution: a neighbourhood grows by whole rings until it has visited 4 times this
  /// many vertices (so a radius far larger than the mesh's detail stops there), and one holding
  /// more is sampled evenly, ring by ring, down to this many, its extent kept. min_points to
  /// 100000.
  int max_points = 1024;
  /// Default none. Called as vertices are fitted (done, total), from the worker threads (it
  /// must be thread-safe), and once with done == total at the end.
  std::function<void(std::int64_t done, std::int64_t total)> progress;
};

/// Principal curvatures and derived descriptors, one value per vertex (#V each).
struct PrincipalCurvatures {
  /// Canonical curvatures in the seed's (MOLCAD) sign: convex is negative, so a sphere of
  /// radius r has cc1 = cc2 = -1/r; |cc1| >= |cc2|; 1/A.
  Eigen::VectorXd cc1, cc2;
  /// Koenderink shape index S = (2/pi) atan((k_max + k_min) / (k_max - k_min)) with k in the
  /// "convex positive" sign (k = -cc): +1 cap (convex umbilic), -1 cup (concave umbilic), 0
  /// symmetric saddle; a plane (k_max = k_min = 0) gives 0. In [-1, 1].
  Eigen::VectorXd shape_index;
  /// Koenderink curvedness sqrt((k_max^2 + k_min^2) / 2), 1/A.
  Eigen::VectorXd curvedness;
};

/// Principal curvatures at every vertex by fitting a local surface model to the vertex's
/// neighbourhood (options.method: the tangent-frame quadric by default, or CGAL's
/// Monge_via_jet_fitting, Cazals & Pouget, "Estimating differential quantities using
/// polynomial fitting of osculating jets", 2005). The fit's normal is turned to agree with the
/// vertex normal (surface.normals() when has_normals(), else area-weighted face normals), so
/// the sign follows the surface's orientation: an inside-out sphere gives cc = +1/r and shape
/// index -1. A vertex whose connected component has fewer than `min_points` vertices (a
/// closed fragment of a few vertices, which its neighbourhood then covers whole: a height fit
/// would mix its near and far sides) is given the curvature of the sphere fitted to all of the
/// component's vertices (algebraic least squares, 4 coefficients): cc1 = cc2 = -1/r when the
/// vertex normal points away from the centre, +1/r when towards it, 0 when the vertices are
/// coplanar. A tetrahedron or octahedron inscribed in a sphere of radius r thus gets exactly
/// -1/r. Each vertex is fitted independently (in parallel), so the result does not depend on
/// the thread count.
/// Throws TopologyError when the surface has no faces or a vertex's connected component has
/// fewer than 4 vertices (a lone triangle), OptionError for options outside their domain,
/// NumericError when a fit is degenerate (e.g. collinear neighbours).
PrincipalCurvatures principal_curvatures(const Surface& surface,
                                         const CurvatureOptions& options = {});

/// Discrete Gaussian curvature per vertex as the angle defect: 2*pi minus the sum of the
/// triangle angles at the vertex (pi minus the sum at a boundary vertex; 2*pi at a vertex in
/// no triangle), in radians (#V values). Their sum over a closed surface is 2*pi times its
/// Euler characteristic (Gauss-Bonnet). Throws TopologyError when the surface has no faces.
Eigen::VectorXd angle_defects(const Surface& surface);

}  // namespace surfcomp::mesh
