// The SIMD kernels of packed_overlay.hpp, compiled for each x86 instruction set Highway targets
// and dispatched at run time.
#include "packed_kernel.hpp"

#include "surfcomp/core/detail/simd_dispatch.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "packed_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <utility>

HWY_BEFORE_NAMESPACE();
namespace surfcomp::matching::detail::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// exp(x) for x in [-80, 0], to a relative error of about 1e-7: 2^(x log2 e) as 2^n times a
/// degree-5 polynomial of the fraction (fitted for relative error on [0, 1)), about half the
/// operations of Highway's Exp, which covers the whole range.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V ExpNegative(D d, V x) {
  const hn::RebindToSigned<D> di;
  const V y = hn::Mul(x, hn::Set(d, 1.44269504088896341F));
  const V n = hn::Floor(y);
  const V f = hn::Sub(y, n);
  V p = hn::Set(d, 0.00187623429F);
  p = hn::MulAdd(p, f, hn::Set(d, 0.00899259431F));
  p = hn::MulAdd(p, f, hn::Set(d, 0.0558235814F));
  p = hn::MulAdd(p, f, hn::Set(d, 0.240154545F));
  p = hn::MulAdd(p, f, hn::Set(d, 0.693152965F));
  p = hn::MulAdd(p, f, hn::Set(d, 0.999999927F));
  const auto exponent = hn::ShiftLeft<23>(hn::ConvertTo(di, n));
  return hn::BitCast(d, hn::Add(hn::BitCast(di, p), exponent));
}

/// The refinement's step of one probe point: its pull-weighted sums of reference positions and of
/// pulls, pull = k (1 + esp_weight max(0, e_i e) + lp_weight max(0, l_i l)) with k as AddPoint's
/// without the probe point's weight.
template <class V>
struct Pull {
  V esp_weight, lp_weight;
  V x, y, z, total;
};

/// Adds one probe point's terms with the reference groups [first, last) to the accumulators:
/// for each pair within the cutoff, k = g(d^2) max(0, w_i n_i . m) (the reference weight is in
/// its normal), then shape += w k, esp += w k max(0, e_i e), lp += w k max(0, l_i l), w the probe
/// point's weight; with kPull also the step's sums (Pull).
template <bool kPull, class D, class V = hn::Vec<D>>
HWY_INLINE void AddPoint(D d, const float* first, const float* last, const float q[3],
                         const float m[3], float w, float e, float l, V cut2, V scale, V& shape,
                         V& esp, V& lp, Pull<V>* pull) {
  const std::size_t lanes = hn::Lanes(d);
  const V zero = hn::Zero(d);
  const V qx = hn::Set(d, q[0]), qy = hn::Set(d, q[1]), qz = hn::Set(d, q[2]);
  const V mx = hn::Set(d, m[0]), my = hn::Set(d, m[1]), mz = hn::Set(d, m[2]);
  const V ve = hn::Set(d, e), vl = hn::Set(d, l), vw = hn::Set(d, w);
  for (const float* g = first; g != last; g += group_floats) {
    for (std::size_t o = 0; o < packed_group; o += lanes) {
      const V ax = hn::LoadU(d, g + o), ay = hn::LoadU(d, g + packed_group + o),
              az = hn::LoadU(d, g + 2 * packed_group + o);
      const V dx = hn::Sub(ax, qx), dy = hn::Sub(ay, qy), dz = hn::Sub(az, qz);
      const V d2 = hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz));
      const V facing = hn::Add(hn::Add(hn::Mul(hn::LoadU(d, g + 3 * packed_group + o), mx),
                                       hn::Mul(hn::LoadU(d, g + 4 * packed_group + o), my)),
                               hn::Mul(hn::LoadU(d, g + 5 * packed_group + o), mz));
      const auto pairs = hn::And(hn::Le(d2, cut2), hn::Gt(facing, zero));
      if (hn::AllFalse(d, pairs)) continue;
      // Lanes beyond the cutoff are masked out; clamping them keeps them in ExpNegative's range.
      const V gauss = ExpNegative(d, hn::Mul(hn::Min(d2, cut2), scale));
      const V k = hn::IfThenElseZero(pairs, hn::Mul(gauss, facing));
      const V ke = hn::Mul(k, hn::Max(zero, hn::Mul(hn::LoadU(d, g + 6 * packed_group + o), ve)));
      const V kl = hn::Mul(k, hn::Max(zero, hn::Mul(hn::LoadU(d, g + 7 * packed_group + o), vl)));
      shape = hn::Add(shape, hn::Mul(k, vw));
      esp = hn::Add(esp, hn::Mul(ke, vw));
      lp = hn::Add(lp, hn::Mul(kl, vw));
      if constexpr (kPull) {
        const V p =
            hn::Add(hn::Add(k, hn::Mul(ke, pull->esp_weight)), hn::Mul(kl, pull->lp_weight));
        pull->x = hn::Add(pull->x, hn::Mul(p, ax));
        pull->y = hn::Add(pull->y, hn::Mul(p, ay));
        pull->z = hn::Add(pull->z, hn::Mul(p, az));
        pull->total = hn::Add(pull->total, p);
      }
    }
  }
}

/// The sum of a vector's lanes, in double, lane by lane.
template <class D, class V = hn::Vec<D>>
HWY_INLINE double LaneSum(D d, V v) {
  HWY_ALIGN float lane[packed_group];
  hn::Store(v, d, lane);
  double s = 0.0;
  for (std::size_t i = 0; i < hn::Lanes(d); ++i) s += static_cast<double>(lane[i]);
  return s;
}

/// The groups [first, last) of the index's cell holding q; none outside the grid (or for a
/// coordinate that is not a number): no reference point lies within the cutoff there.
HWY_INLINE std::pair<std::uint32_t, std::uint32_t> CellGroups(const CellIndex& index,
                                                              const float q[3]) {
  std::size_t cell[3];
  for (int c = 0; c < 3; ++c) {
    const float local = (q[c] - index.origin[c]) * index.inverse_cell;
    if (!(local >= 0.0F && local < static_cast<float>(index.dims[c]))) return {0, 0};
    cell[c] = static_cast<std::size_t>(local);
  }
  const std::size_t c = (cell[2] * static_cast<std::size_t>(index.dims[1]) + cell[1]) *
                            static_cast<std::size_t>(index.dims[0]) +
                        cell[0];
  return {index.offsets[c], index.offsets[c + 1]};
}

/// Runs `point(j, q, m)` for each real probe point, q and m its position and normal moved.
template <class Point>
HWY_INLINE void ForEachMovedPoint(const PackedSampleView& probe, const FrameTransform& t,
                                  const Point& point) {
  const float* r = t.rotation;
  for (std::size_t j = 0; j < probe.header.points; ++j) {
    const float p[3] = {probe.array(0)[j], probe.array(1)[j], probe.array(2)[j]};
    const float n[3] = {probe.array(3)[j], probe.array(4)[j], probe.array(5)[j]};
    const float q[3] = {r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + t.translation[0],
                        r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + t.translation[1],
                        r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + t.translation[2]};
    const float m[3] = {r[0] * n[0] + r[1] * n[1] + r[2] * n[2],
                        r[3] * n[0] + r[4] * n[1] + r[5] * n[2],
                        r[6] * n[0] + r[7] * n[1] + r[8] * n[2]};
    point(j, q, m);
  }
}

CrossSums CrossSumsImpl(const CellIndex& index, const PackedSampleView& probe,
                        const FrameTransform& transform, float sigma) {
  const hn::CappedTag<float, packed_group> d;
  using V = hn::Vec<decltype(d)>;
  const float cutoff = 3.0F * sigma;
  const V cut2 = hn::Set(d, cutoff * cutoff);
  const V scale = hn::Set(d, -1.0F / (2.0F * sigma * sigma));
  V shape = hn::Zero(d), esp = hn::Zero(d), lp = hn::Zero(d);
  const float* groups = index.groups.data();
  ForEachMovedPoint(probe, transform, [&](std::size_t j, const float q[3], const float m[3]) {
    const auto [first, last] = CellGroups(index, q);
    if (first == last) return;
    AddPoint<false>(d, groups + first * group_floats, groups + last * group_floats, q, m,
                    probe.array(6)[j], probe.array(7)[j], probe.array(8)[j], cut2, scale, shape,
                    esp, lp, static_cast<Pull<V>*>(nullptr));
  });
  return {LaneSum(d, shape), LaneSum(d, esp), LaneSum(d, lp)};
}

CrossSums CrossSumsAndTargetsImpl(const CellIndex& index, const PackedSampleView& probe,
                                  const FrameTransform& transform, float sigma, float esp_pull,
                                  float lp_pull, double* targets, double* weights) {
  const hn::CappedTag<float, packed_group> d;
  using V = hn::Vec<decltype(d)>;
  const float cutoff = 3.0F * sigma;
  const V cut2 = hn::Set(d, cutoff * cutoff);
  const V scale = hn::Set(d, -1.0F / (2.0F * sigma * sigma));
  const V vesp_pull = hn::Set(d, esp_pull), vlp_pull = hn::Set(d, lp_pull);
  V shape = hn::Zero(d), esp = hn::Zero(d), lp = hn::Zero(d);
  const float* groups = index.groups.data();
  ForEachMovedPoint(probe, transform, [&](std::size_t j, const float q[3], const float m[3]) {
    for (int c = 0; c < 3; ++c) targets[3 * j + static_cast<std::size_t>(c)] = q[c];
    weights[j] = 0.0;
    const auto [first, last] = CellGroups(index, q);
    if (first == last) return;
    Pull<V> pull{vesp_pull, vlp_pull, hn::Zero(d), hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    const float w = probe.array(6)[j];
    AddPoint<true>(d, groups + first * group_floats, groups + last * group_floats, q, m, w,
                   probe.array(7)[j], probe.array(8)[j], cut2, scale, shape, esp, lp, &pull);
    const double total = LaneSum(d, pull.total);
    if (!(total > 0.0)) return;
    targets[3 * j] = LaneSum(d, pull.x) / total;
    targets[3 * j + 1] = LaneSum(d, pull.y) / total;
    targets[3 * j + 2] = LaneSum(d, pull.z) / total;
    weights[j] = static_cast<double>(w) * total;
  });
  return {LaneSum(d, shape), LaneSum(d, esp), LaneSum(d, lp)};
}

CrossSums SelfSumsImpl(const PackedSampleView& sample, float sigma) {
  const hn::CappedTag<float, packed_group> d;
  using V = hn::Vec<decltype(d)>;
  const float cutoff = 3.0F * sigma;
  const V cut2 = hn::Set(d, cutoff * cutoff);
  const V scale = hn::Set(d, -1.0F / (2.0F * sigma * sigma));
  const std::vector<float> groups = sample_groups(sample);
  FrameTransform identity{{1.0F, 0.0F, 0.0F, 0.0F, 1.0F, 0.0F, 0.0F, 0.0F, 1.0F},
                          {0.0F, 0.0F, 0.0F}};
  V shape = hn::Zero(d), esp = hn::Zero(d), lp = hn::Zero(d);
  ForEachMovedPoint(sample, identity, [&](std::size_t j, const float q[3], const float m[3]) {
    AddPoint<false>(d, groups.data(), groups.data() + groups.size(), q, m, sample.array(6)[j],
                    sample.array(7)[j], sample.array(8)[j], cut2, scale, shape, esp, lp,
                    static_cast<Pull<V>*>(nullptr));
  });
  return {LaneSum(d, shape), LaneSum(d, esp), LaneSum(d, lp)};
}

}  // namespace surfcomp::matching::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace surfcomp::matching::detail {

CrossSums cross_sums_and_targets(const CellIndex& index, const PackedSampleView& probe,
                                 const FrameTransform& transform, float sigma, float esp_pull,
                                 float lp_pull, double* targets, double* weights) {
  return SURFCOMP_SIMD_CALL(CrossSumsAndTargetsImpl, index, probe, transform, sigma, esp_pull,
                            lp_pull, targets, weights);
}

std::vector<float> sample_groups(const PackedSampleView& sample) {
  const std::size_t padded = sample.padded_points();
  std::vector<float> groups(padded / packed_group * group_floats, 0.0F);
  for (std::size_t i = 0; i < padded; ++i) {
    float* g = groups.data() + i / packed_group * group_floats + i % packed_group;
    const bool real = i < sample.header.points;
    const float w = real ? sample.array(6)[i] : 0.0F;
    for (int c = 0; c < 3; ++c)
      g[c * packed_group] = real ? sample.array(c)[i] : 1e30F;  // padding: beyond any cutoff
    for (int c = 0; c < 3; ++c) g[(3 + c) * packed_group] = w * sample.array(3 + c)[i];
    g[6 * packed_group] = real ? sample.array(7)[i] : 0.0F;
    g[7 * packed_group] = real ? sample.array(8)[i] : 0.0F;
  }
  return groups;
}

CrossSums cross_sums(const CellIndex& index, const PackedSampleView& probe,
                     const FrameTransform& transform, float sigma) {
  return SURFCOMP_SIMD_CALL(CrossSumsImpl, index, probe, transform, sigma);
}

CrossSums self_sums(const PackedSampleView& sample, float sigma) {
  return SURFCOMP_SIMD_CALL(SelfSumsImpl, sample, sigma);
}

}  // namespace surfcomp::matching::detail
#endif
