// The distance splat of ses_points, compiled for each x86 instruction set Highway targets and
// dispatched at run time: a row of nodes within a probe's reach is one or two vectors.
#include "ses_points_splat.hpp"

#include "surfcomp/core/detail/simd_dispatch.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "ses_points_splat.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <algorithm>
#include <cmath>

HWY_BEFORE_NAMESPACE();
namespace surfcomp::molsurf::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void SplatProbesImpl(const SplatGrid& grid, const std::vector<float>& probes, double reach,
                     float* distance2, std::int32_t* owner, int* first, int* last) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const int lanes = static_cast<int>(hn::Lanes(df));
  const double h = grid.spacing;
  const double r = reach / h;  // in spacings
  const auto h2 = hn::Set(df, static_cast<float>(h * h));
  const auto iota = hn::Iota(df, 0.0F);
  const std::size_t count = probes.size() / 3;
  for (std::size_t p = 0; p < count; ++p) {
    const double local[3] = {(probes[3 * p] - grid.origin[0]) / h,
                             (probes[3 * p + 1] - grid.origin[1]) / h,
                             (probes[3 * p + 2] - grid.origin[2]) / h};
    const auto id = hn::Set(di, static_cast<std::int32_t>(p));
    const int k0 = std::max(0, static_cast<int>(std::ceil(local[2] - r)));
    const int k1 = std::min(grid.nz - 1, static_cast<int>(std::floor(local[2] + r)));
    for (int k = k0; k <= k1; ++k) {
      const double dz = k - local[2];
      const double disk = std::sqrt(std::max(0.0, r * r - dz * dz));
      const int j0 = std::max(0, static_cast<int>(std::ceil(local[1] - disk)));
      const int j1 = std::min(grid.ny - 1, static_cast<int>(std::floor(local[1] + disk)));
      for (int j = j0; j <= j1; ++j) {
        const double dy = j - local[1];
        const double rest = r * r - dy * dy - dz * dz;
        if (rest < 0.0) continue;
        const double chord = std::sqrt(rest);
        const int i0 = std::max(0, static_cast<int>(std::ceil(local[0] - chord)));
        const int i1 = std::min(grid.nx - 1, static_cast<int>(std::floor(local[0] + chord)));
        if (i1 < i0) continue;
        const std::size_t row = static_cast<std::size_t>(k) * static_cast<std::size_t>(grid.ny) +
                                static_cast<std::size_t>(j);
        first[row] = std::min(first[row], i0);
        last[row] = std::max(last[row], i1);
        const std::size_t at =
            row * static_cast<std::size_t>(grid.nx) + static_cast<std::size_t>(i0);
        const auto base = hn::Set(df, static_cast<float>((dy * dy + dz * dz) * h * h));
        const auto x0 = hn::Set(df, static_cast<float>(i0 - local[0]));
        const int n = i1 - i0 + 1;
        // Whole vectors: lanes beyond the row are masked out (their values written back as
        // they were; the arrays are padded beyond the last row).
        for (int o = 0; o < n; o += lanes) {
          const auto dx = hn::Add(x0, hn::Add(iota, hn::Set(df, static_cast<float>(o))));
          const auto d2 = hn::MulAdd(hn::Mul(dx, dx), h2, base);
          const auto in_row = hn::FirstN(df, static_cast<std::size_t>(n - o));
          const auto old = hn::LoadU(df, distance2 + at + o);
          const auto closer = hn::And(in_row, hn::Lt(d2, old));
          hn::StoreU(hn::IfThenElse(closer, d2, old), df, distance2 + at + o);
          const auto previous = hn::LoadU(di, owner + at + o);
          hn::StoreU(hn::IfThenElse(hn::RebindMask(di, closer), id, previous), di, owner + at + o);
        }
      }
    }
  }
}

}  // namespace surfcomp::molsurf::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace surfcomp::molsurf::detail {

void splat_probes(const SplatGrid& grid, const std::vector<float>& probes, double reach,
                  float* distance2, std::int32_t* owner, int* first, int* last) {
  SURFCOMP_SIMD_CALL(SplatProbesImpl, grid, probes, reach, distance2, owner, first, last);
}

}  // namespace surfcomp::molsurf::detail
#endif
