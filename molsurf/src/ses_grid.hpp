// Internal to the molsurf module (not installed): the first stage of build_ses and build_sas, the
// surface's distance field sampled near its zero level set into a sparse grid (sparse_grid.hpp)
// and meshed (dual_marching_cubes.hpp).
#pragma once

#include "dual_marching_cubes.hpp"
#include "sas_geometry.hpp"
#include "ses_region.hpp"

#include <Eigen/Core>

namespace surfcomp::molsurf::detail {

/// Grid values are exact within this many voxels of the surface and clamped beyond. Dual
/// marching cubes reads values only on grid edges whose ends differ in sign, which the field's
/// Lipschitz bound puts within a voxel of the surface; the extra hundredth keeps the float band
/// above the voxel.
inline constexpr double band_voxels = 1.01;

/// Which surface of a SasGeometry a field describes.
enum class SurfaceKind { excluded, accessible };

/// The grid mesh of `sas`'s SES (excluded) or SAS (accessible): the field (exact within a band
/// of a voxel of the surface, 1-Lipschitz) sampled on the nodes ijk * voxel of the root
/// boxes within `reach` A of an atom of `centers` (#A by 3, A), refined adaptively, and its
/// zero isosurface meshed by dual marching cubes (a closed, 2-manifold mesh; each quad split
/// along its shorter diagonal). Vertices are sorted by coordinates and faces by indices, so the
/// arrays do not depend on the thread count. With a `region`, the field is cut to it
/// (max(field, region value)) and only nodes inside it are sampled: the mesh is the surface's
/// region intersected with the union of balls.
TriangleSoup grid_mesh(const SasGeometry& sas, SurfaceKind kind,
                       const Eigen::Ref<const Eigen::MatrixX3d>& centers, double reach,
                       double voxel, const BallUnion* region = nullptr);

}  // namespace surfcomp::molsurf::detail
