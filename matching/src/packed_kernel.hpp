// Internal to the matching module: the SIMD kernels behind packed_overlay.hpp (Highway stays in
// packed_kernel.cpp).
#pragma once

#include "surfcomp/matching/packed_overlay.hpp"

#include <cstdint>
#include <vector>

namespace surfcomp::matching::detail {

/// A rigid motion in single precision, row-major: x' = rotation x + translation.
struct FrameTransform {
  float rotation[9];
  float translation[3];
};

/// The unnormalised overlaps of overlay.hpp: S, and the ESP and LP parts of C before their
/// scaling (sum w_i w_j g f max(0, e_i e_j), and so for LP).
struct CrossSums {
  double shape = 0.0;
  double esp = 0.0;
  double lp = 0.0;
};

/// A group of packed_group reference points as the kernels read them: x, y, z, the normal
/// times the weight (x, y, z), ESP and LP, packed_group floats each.
inline constexpr std::size_t group_floats = 8 * packed_group;

/// The reference points within the cutoff of each cell of a grid, as groups.
struct CellIndex {
  float origin[3] = {0.0F, 0.0F, 0.0F};
  float inverse_cell = 1.0F;
  int dims[3] = {0, 0, 0};
  /// Cell c (x fastest) lists the groups [offsets[c], offsets[c + 1]).
  std::vector<std::uint32_t> offsets;
  std::vector<float> groups;  ///< group_floats per group
};

/// The points of `sample` as groups, in order (the padding's positions far away, its weights 0).
std::vector<float> sample_groups(const PackedSampleView& sample);

/// The sums over the pairs (i of the index's reference, j of `probe` moved by `transform`, both
/// in their stored frames) within 3 sigma whose normals face each other, summed in single
/// precision lane by lane, the lanes in double.
CrossSums cross_sums(const CellIndex& index, const PackedSampleView& probe,
                     const FrameTransform& transform, float sigma);

/// cross_sums, and for each probe point j the refinement's step (overlay.hpp): the mean of its
/// reference neighbours i weighted by pull_ij = k_ij (1 + esp_pull max(0, e_i e_j) + lp_pull
/// max(0, l_i l_j)) with k_ij = w_i g f_ij (so esp_pull = chem_weight times the pair's ESP scale),
/// as targets (3 per point, reference frame; the moved point itself where it has none), and w_j
/// times the sum of the pulls as its weight.
CrossSums cross_sums_and_targets(const CellIndex& index, const PackedSampleView& probe,
                                 const FrameTransform& transform, float sigma, float esp_pull,
                                 float lp_pull, double* targets, double* weights);

/// The same sums of a sample with itself (every pair, in the same arithmetic).
CrossSums self_sums(const PackedSampleView& sample, float sigma);

}  // namespace surfcomp::matching::detail
