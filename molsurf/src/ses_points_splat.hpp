// Internal to the molsurf module: the distance splat of ses_points (ses_points.cpp), a SIMD kernel
// (Highway stays in ses_points_splat.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace surfcomp::molsurf::detail {

/// A dense grid of nodes origin + spacing * (i, j, k), i fastest, as the splat sees it.
struct SplatGrid {
  double origin[3] = {0.0, 0.0, 0.0};
  double spacing = 1.0;
  int nx = 0, ny = 0, nz = 0;
};

/// For each probe centre p (3 floats each) and each node x of the grid within `reach` of it:
/// distance2[x] = min(distance2[x], |x - p|^2), owner[x] the probe that gave the minimum (the
/// earlier probe on a tie), and for each row (j + ny k) the first and last node reached widened
/// to cover x. distance2 and owner hold nx ny nz values and `row_padding` more (written but
/// not read as nodes), first and last ny nz.
inline constexpr std::size_t row_padding = 16;
void splat_probes(const SplatGrid& grid, const std::vector<float>& probes, double reach,
                  float* distance2, std::int32_t* owner, int* first, int* last);

}  // namespace surfcomp::molsurf::detail
