// The harmonic disk map computed by CGAL's Surface_mesh_parameterization package, the
// reference that harmonic_disk_map is tested and benchmarked against (method §4).
// CGAL's headers stay in cgal_reference.cpp.
#pragma once

#include "surfcomp/harmonic/disk_map.hpp"
#include "surfcomp/harmonic/map_distortion.hpp"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace surfcomp::harmonic {

/// The map of harmonic_disk_map (same arguments, same result up to rounding), computed by
/// CGAL 5.5's fixed-border parameterizers on a CGAL::Surface_mesh of the patch:
/// Circular_border_arc_length_parameterizer_3 for the border, and for the interior
/// Barycentric_mapping_parameterizer_3 (uniform), Discrete_conformal_map_parameterizer_3
/// (cotangent), Mean_value_coordinates_parameterizer_3 (mean_value), or a
/// Fixed_border_parameterizer_3 whose compute_w_ij is 1 / |p_i - p_j| (inverse_length).
/// The linear systems are solved with Eigen::SparseLU (CGAL's default BiCGSTAB stops at a
/// residual it does not report), one factorisation per coordinate as CGAL does.
///
/// CGAL walks the border halfedge loop, which runs opposite to the faces (clockwise seen from
/// outside): starting at the border halfedge outer_boundary[0] -> outer_boundary[#B - 1], it
/// puts the vertex at CGAL arc length s at (0.5 + 0.5 cos(-2 pi s / L), 0.5 + 0.5 sin(-2 pi s
/// / L)). Our vertex k at counter-clockwise arc length L_k has s = L - L_k (s = 0 for k = 0),
/// so its CGAL angle -2 pi (L - L_k) / L equals our theta_k = 2 pi L_k / L modulo 2 pi: no
/// reflection and no rotation, and uv_ours = 2 (uv_cgal - (0.5, 0.5)) for every vertex.
///
/// Throws what check_disk_map_input throws, NumericError when CGAL reports a failure
/// (its message is included).
DiskMap cgal_disk_map(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                      const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                      const std::vector<int>& outer_boundary, const DiskMapOptions& options = {});

/// harmonic_disk_map against cgal_disk_map on one patch, for people comparing
/// parameterizations (surfcomp patch-map --compare-cgal).
struct DiskMapComparison {
  DiskMap ours, cgal;
  double max_distance = 0.0;   ///< largest |uv_ours - uv_cgal| over the vertices (unit disk)
  double mean_distance = 0.0;  ///< its mean over the vertices
  MapDistortion ours_distortion, cgal_distortion;
  /// Wall-clock time of one map, ms: the median of as many runs as fit in about 20 ms (at
  /// least 3), each map alone on this thread.
  double ours_ms = 0.0;
  double cgal_ms = 0.0;
};

/// Both maps of the patch (harmonic_disk_map's arguments), their distance, distortion and time.
/// Throws what either map throws.
DiskMapComparison compare_with_cgal(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                    const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                    const std::vector<int>& outer_boundary,
                                    const DiskMapOptions& options = {});

/// The parameterizations of a disk-like patch that patch-map --methods compares: ours
/// (harmonic_disk_map) and those of CGAL 5.5's Surface_mesh_parameterization that map a disk
/// with one border.
enum class Parameterization {
  harmonic,            ///< harmonic_disk_map with the description's spring weights
  tutte,               ///< Barycentric_mapping (uniform weights), circular border
  mean_value,          ///< Mean_value_coordinates, circular border
  discrete_conformal,  ///< Discrete_conformal_map (cotangent weights), circular border
  discrete_authalic,   ///< Discrete_authalic, circular border
  lscm,                ///< LSCM, free border (two vertices pinned)
  arap,                ///< ARAP (lambda 1000, 50 iterations), free border
};

/// The names of Parameterization's values, as patch-map --methods takes them.
inline constexpr std::array<const char*, 7> parameterization_names = {
    "harmonic", "tutte", "mean-value", "discrete-conformal", "discrete-authalic", "lscm", "arap"};

/// The method of that name (parameterization_names); nullopt for any other.
std::optional<Parameterization> parameterization_from_name(const std::string& name);

/// Whether `method` leaves the patch's border free (lscm, arap): its map has the scale and
/// position CGAL gives it, not the unit disk's.
constexpr bool has_free_border(Parameterization method) {
  return method == Parameterization::lscm || method == Parameterization::arap;
}

/// The map of the patch (harmonic_disk_map's arguments) by `method`: #V by 2. Fixed-border
/// methods put the border on the unit circle by arc length as cgal_disk_map does; free-border
/// methods (lscm, arap) give CGAL's uv, mirrored when CGAL's orientation is the mirror image of
/// the patch's (the distortion does not change). `options` applies to harmonic only.
/// Throws what check_disk_map_input throws, NumericError when CGAL reports a failure.
Eigen::MatrixX2d parameterize_patch(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                    const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                    const std::vector<int>& outer_boundary, Parameterization method,
                                    const DiskMapOptions& options = {});

/// One method's map of a patch, judged.
struct ParameterizationResult {
  Parameterization method = Parameterization::harmonic;
  MapDistortion distortion;
  double ms = 0.0;  ///< wall-clock time of one map, as DiskMapComparison's
  /// The map (parameterize_patch), #V by 2; 0 by 2 when the method failed.
  Eigen::MatrixX2d uv;
  /// Why the method gave no map (its NumericError or TopologyError), or empty; the distortion
  /// and time are then NaN.
  std::string failure;
};

/// Each of `methods` on the same patch (parameterize_patch), in their order; a method that
/// fails on the patch is reported in its result (ParameterizationResult::failure).
std::vector<ParameterizationResult> compare_parameterizations(
    const Eigen::Ref<const Eigen::MatrixX3d>& positions,
    const Eigen::Ref<const Eigen::MatrixX3i>& faces, const std::vector<int>& outer_boundary,
    const std::vector<Parameterization>& methods, const DiskMapOptions& options = {});

}  // namespace surfcomp::harmonic
