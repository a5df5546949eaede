// Harmonic maps of surface patches onto the unit disk (method §4.1-4.2; Zhang & Hebert
// 1999): the outer border is fixed on the unit circle by
// arc length, every other vertex is the weighted average of its neighbours (a spring system),
// which is one sparse linear system with two right-hand sides (u and v).
#pragma once

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace surfcomp::harmonic {

/// The spring constants k_ij of the system sum_j k_ij (u_i - u_j) = 0 at a free vertex i.
/// For the cotangent and mean-value weights, an edge i-j on the border of a hole has a
/// triangle on one side only; the other side uses the wedge that closes the one-ring of i
/// across the hole (the triangle i, next, previous hole neighbour of i), as CGAL's
/// Fixed_border_parameterizer_3 does by circulating the one-ring cyclically.
enum class SpringWeights {
  /// k_ij = 1 / |p_i - p_j| (method §4.2; Zhang & Hebert). Symmetric, positive.
  inverse_length,
  /// k_ij = 1: Tutte's barycentric map (CGAL Barycentric_mapping_parameterizer_3).
  uniform,
  /// k_ij = cot(alpha_ij) + cot(beta_ij), the angles opposite edge i-j in its two triangles
  /// (CGAL Discrete_conformal_map_parameterizer_3). Symmetric; negative on obtuse meshes, so
  /// the map may fold there. Reproduces linear functions on planar meshes.
  cotangent,
  /// k_ij = (tan(gamma_ij / 2) + tan(delta_ij / 2)) / |p_i - p_j|, the angles at i between
  /// edge i-j and its neighbouring edges (Floater's mean value coordinates; CGAL
  /// Mean_value_coordinates_parameterizer_3). Positive, not symmetric: row i uses the angles
  /// at i. Reproduces linear functions on planar meshes.
  mean_value,
};

/// The weights' names as options and outputs spell them, in the enum's order.
inline constexpr std::array<const char*, 4> spring_weights_names = {"inverse-length", "uniform",
                                                                    "cotangent", "mean-value"};

/// The name of `weights` (spring_weights_names).
const char* to_string(SpringWeights weights);

/// The weights of that name (spring_weights_names); nullopt for any other.
std::optional<SpringWeights> spring_weights_from_name(const std::string& name);

struct DiskMapOptions {
  /// Default inverse_length (method §4.2: k_ij = 1 / |p_i - p_j|).
  SpringWeights weights = SpringWeights::inverse_length;
};

/// A patch embedded in the unit disk.
struct DiskMap {
  /// #V by 2, dimensionless: the outer border on the unit circle, every other vertex strictly
  /// inside it when the weights are positive (all kinds but cotangent on obtuse triangles).
  Eigen::MatrixX2d uv;
};

/// Checks the input of harmonic_disk_map (and of cgal_disk_map) and returns nothing; it throws
/// exactly what harmonic_disk_map would throw for these arrays before any solving:
/// InputError when positions is empty or not finite, a face index is outside [0, #V), a face
/// repeats a vertex, or an outer_boundary index is outside [0, #V) or repeated;
/// TopologyError when outer_boundary has fewer than 3 vertices, an edge is used twice in the
/// same direction or by more than two faces, a vertex lies on more than one border loop
/// (bow-tie), a step outer_boundary[k] -> outer_boundary[k+1] (cyclically) is not a border
/// edge some face traverses in that direction, or a vertex is not joined to the outer
/// boundary by edges (including vertices in no face).
void check_disk_map_input(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                          const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                          const std::vector<int>& outer_boundary);

/// The harmonic map of a patch onto the unit disk (Zhang & Hebert 1999; method §4).
///
/// `positions` (#V by 3, A) and `faces` (#F by 3, patch-local vertex indices, counter-clockwise
/// seen from outside) form a connected triangulated disk, possibly with holes.
/// `outer_boundary` is its outer border loop, walked counter-clockwise seen from outside (the
/// patch on the left: every step a -> b is an edge some face traverses as a -> b), each vertex
/// once, not closed (the last vertex joins the first). Border vertex k goes to the unit circle
/// at angle theta_k = 2 pi L_k / L, where L_k is the border length from outer_boundary[0] to
/// outer_boundary[k] along the walk and L the border's perimeter (so outer_boundary[0] is at
/// (1, 0) and angles increase counter-clockwise). Every other vertex, interior or on a hole
/// (holes are free, not pinned), solves sum_j k_ij (u_i - u_j) = 0 over its neighbours j with
/// the spring constants of options.weights: one sparse matrix, one factorisation, two
/// right-hand sides. The inverse_length and uniform weights give a symmetric positive-definite
/// matrix, factorised by Eigen::SimplicialLDLT (sparse Cholesky, AMD ordering); cotangent and
/// mean_value by Eigen::SparseLU. With positive weights and no hole, the result is an
/// embedding (Tutte, Floater); see count_flipped_triangles.
///
/// Throws what check_disk_map_input throws; NumericError when a weight is not finite
/// (coincident vertices, degenerate triangles) or the factorisation fails (a singular system,
/// e.g. cotangent weights summing to zero). Deterministic, thread-safe.
DiskMap harmonic_disk_map(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                          const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                          const std::vector<int>& outer_boundary,
                          const DiskMapOptions& options = {});

/// The number of triangles of `faces` (#F by 3) whose signed area in `uv` (#V by 2) is <= 0,
/// i.e. flipped or degenerate in a map whose outer border runs counter-clockwise. 0 for an
/// embedding. Throws InputError for a face index outside [0, #V).
int count_flipped_triangles(const Eigen::Ref<const Eigen::MatrixX2d>& uv,
                            const Eigen::Ref<const Eigen::MatrixX3i>& faces);

}  // namespace surfcomp::harmonic
