#include "surfcomp/matching/packed_overlay.hpp"

#include "em_climb.hpp"
#include "option_checks.hpp"
#include "packed_kernel.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/matching/principal_axes.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>

namespace surfcomp::matching {
namespace {

/// The arrays of a packed sample, in PackedSampleView::array order.
enum Array { kX, kY, kZ, kNx, kNy, kNz, kWeight, kEsp, kLp, kArrays };

/// Orders `order[first, last)` (indices of columns of `points`) into compact runs of
/// packed_group: each range is split across its longest extent into a part of a multiple of
/// packed_group points and the rest, recursively, so that consecutive runs of the order are small
/// clusters of the surface. Ties are broken by index (deterministic).
void order_in_blocks(const Eigen::Matrix3Xd& points, std::vector<std::uint32_t>& order,
                     std::size_t first, std::size_t last) {
  const std::size_t count = last - first;
  if (count <= packed_group) return;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (std::size_t k = first; k < last; ++k) {
    low = low.cwiseMin(points.col(order[k]));
    high = high.cwiseMax(points.col(order[k]));
  }
  Eigen::Index axis = 0;
  (high - low).maxCoeff(&axis);
  const std::size_t blocks = (count + packed_group - 1) / packed_group;
  const std::size_t middle = first + (blocks / 2) * packed_group;
  const auto begin = order.begin() + static_cast<std::ptrdiff_t>(first);
  std::nth_element(begin, order.begin() + static_cast<std::ptrdiff_t>(middle),
                   order.begin() + static_cast<std::ptrdiff_t>(last),
                   [&](std::uint32_t a, std::uint32_t b) {
                     const double pa = points(axis, a), pb = points(axis, b);
                     return pa != pb ? pa < pb : a < b;
                   });
  order_in_blocks(points, order, first, middle);
  order_in_blocks(points, order, middle, last);
}

detail::FrameTransform frame_transform(const Eigen::Matrix3d& rotation,
                                       const Eigen::Vector3d& translation) {
  detail::FrameTransform t{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) t.rotation[3 * r + c] = static_cast<float>(rotation(r, c));
    t.translation[r] = static_cast<float>(translation(r));
  }
  return t;
}

/// H: same-element heteroatom pairs, Gaussians of width sigma, probe atoms moved by `transform`
/// (frame coordinates).
double atom_overlap(const PackedSampleView& a, const PackedSampleView& b,
                    const detail::FrameTransform& transform, float sigma) {
  const float scale = -1.0F / (2.0F * sigma * sigma);
  const float* r = transform.rotation;
  const float* t = transform.translation;
  double sum = 0.0;
  for (std::uint32_t l = 0; l < b.header.atoms; ++l) {
    const float* p = b.atom_points + std::size_t{3} * l;
    const float y[3] = {r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + t[0],
                        r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + t[1],
                        r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + t[2]};
    for (std::uint32_t k = 0; k < a.header.atoms; ++k) {
      if (a.atom_elements[k] != b.atom_elements[l]) continue;
      const float* x = a.atom_points + std::size_t{3} * k;
      const float d2 = (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                       (x[2] - y[2]) * (x[2] - y[2]);
      sum += static_cast<double>(std::exp(d2 * scale));
    }
  }
  return sum;
}

/// What the scores of one pair need besides its cross sums.
struct PairConstants {
  double self_shape = 0.0, self_chem = 0.0, atom_self = 0.0;
  double esp_scale = 1.0, lp_scale = 1.0;
  double chem_weight = 0.0, atom_weight = 0.0;
};

PairConstants pair_constants(const PackedHeader& a, const PackedHeader& b,
                             const OverlayOptions& options) {
  const auto rms = [](double squares, double weights) {
    const double r = std::sqrt(squares / weights);
    return r > 0.0 ? r : 1.0;
  };
  PairConstants c;
  const double weights = a.squares_weight + b.squares_weight;
  const double esp_rms = rms(a.squares_esp + b.squares_esp, weights);
  const double lp_rms = rms(a.squares_lp + b.squares_lp, weights);
  c.esp_scale = 1.0 / (esp_rms * esp_rms);
  c.lp_scale = 1.0 / (lp_rms * lp_rms);
  c.self_shape = a.self_shape + b.self_shape;
  c.self_chem = (a.self_esp + b.self_esp) * c.esp_scale + (a.self_lp + b.self_lp) * c.lp_scale;
  c.chem_weight = c.self_chem > 0.0 ? options.chem_weight : 0.0;
  if (a.atom_self > 0.0 && b.atom_self > 0.0 && options.atom_weight > 0.0) {
    c.atom_self = a.atom_self + b.atom_self;
    c.atom_weight = options.atom_weight;
  }
  return c;
}

OverlayScore scores(const PairConstants& c, const detail::CrossSums& sums, double h) {
  OverlayScore s;
  s.shape = sums.shape / (c.self_shape - sums.shape);
  const double chem = sums.esp * c.esp_scale + sums.lp * c.lp_scale;
  s.chem = c.self_chem > 0.0 ? chem / (c.self_chem - chem) : 0.0;
  if (c.atom_weight > 0.0) s.atoms = h / (c.atom_self - h);
  s.score = (s.shape + c.chem_weight * s.chem + c.atom_weight * s.atoms) /
            (1.0 + c.chem_weight + c.atom_weight);
  return s;
}

/// The cell edge of a query's index, in sigmas: a probe point reads one list of the reference
/// points within the cutoff of its cell (docs/decisions.md#screen-stage-one).
constexpr double kIndexCellSigmas = 1.0;
constexpr double kMaxIndexCells = 67108864.0;  // 2^26

detail::CellIndex build_index(const PackedSampleView& sample, double sigma) {
  const double cutoff = 3.0 * sigma;
  const double cell = kIndexCellSigmas * sigma;
  const std::size_t n = sample.header.points;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p(sample.array(kX)[i], sample.array(kY)[i], sample.array(kZ)[i]);
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  low.array() -= cutoff;
  high.array() += cutoff;
  const Eigen::Array3d extent = ((high - low) / cell).array().ceil().max(1.0);
  if (!(extent.prod() <= kMaxIndexCells)) {
    throw InputError("packed overlay: the query's index would have " +
                     std::to_string(extent.prod()) + " cells; it is far too large for a screen");
  }
  detail::CellIndex index;
  for (int c = 0; c < 3; ++c) {
    index.origin[c] = static_cast<float>(low(c));
    index.dims[c] = static_cast<int>(extent(c));
  }
  index.inverse_cell = static_cast<float>(1.0 / cell);
  const std::size_t cells = static_cast<std::size_t>(index.dims[0]) *
                            static_cast<std::size_t>(index.dims[1]) *
                            static_cast<std::size_t>(index.dims[2]);
  // The cells within the cutoff of each point (by the distance from the point to the cell's
  // box), listed twice: counted, then filled in point order.
  std::vector<std::uint32_t> count(cells, 0);
  const auto for_each_cell_near = [&](std::size_t i, const auto& visit) {
    const Eigen::Vector3d p(sample.array(kX)[i], sample.array(kY)[i], sample.array(kZ)[i]);
    int lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::max(0, static_cast<int>(std::floor((p(c) - cutoff - low(c)) / cell)));
      hi[c] = std::min(index.dims[c] - 1,
                       static_cast<int>(std::floor((p(c) + cutoff - low(c)) / cell)));
    }
    for (int z = lo[2]; z <= hi[2]; ++z) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const int at[3] = {x, y, z};
          double gap2 = 0.0;
          for (int c = 0; c < 3; ++c) {
            const double from = low(c) + at[c] * cell;
            const double gap = std::max({from - p(c), 0.0, p(c) - (from + cell)});
            gap2 += gap * gap;
          }
          if (gap2 > cutoff * cutoff) continue;
          visit((static_cast<std::size_t>(z) * static_cast<std::size_t>(index.dims[1]) +
                 static_cast<std::size_t>(y)) *
                    static_cast<std::size_t>(index.dims[0]) +
                static_cast<std::size_t>(x));
        }
      }
    }
  };
  for (std::size_t i = 0; i < n; ++i) for_each_cell_near(i, [&](std::size_t c) { ++count[c]; });
  index.offsets.assign(cells + 1, 0);
  for (std::size_t c = 0; c < cells; ++c)
    index.offsets[c + 1] = index.offsets[c] + (count[c] + packed_group - 1) / packed_group;
  const std::vector<float> groups = detail::sample_groups(sample);
  index.groups.assign(static_cast<std::size_t>(index.offsets[cells]) * detail::group_floats, 0.0F);
  // Empty lanes lie beyond any cutoff, with weight 0.
  for (std::size_t g = 0; g < index.offsets[cells]; ++g) {
    for (std::size_t k = 0; k < 3 * packed_group; ++k)
      index.groups[g * detail::group_floats + k] = 1e30F;
  }
  std::fill(count.begin(), count.end(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const float* from = groups.data() + i / packed_group * detail::group_floats + i % packed_group;
    for_each_cell_near(i, [&](std::size_t c) {
      const std::size_t slot = count[c]++;
      float* to = index.groups.data() +
                  (index.offsets[c] + slot / packed_group) * detail::group_floats +
                  slot % packed_group;
      for (std::size_t a = 0; a < 8; ++a) to[a * packed_group] = from[a * packed_group];
    });
  }
  return index;
}

/// The signed permutation matrices (det +1) of principal_axes_starts, in its order.
std::vector<Eigen::Matrix3d> axes_permutations(bool all_orders) {
  std::array<int, 3> perm{0, 1, 2};
  std::vector<Eigen::Matrix3d> out;
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
      for (int j = 0; j < 3; ++j)
        p(perm[static_cast<std::size_t>(j)], j) = (signs >> j) & 1 ? -1.0 : 1.0;
      if (p.determinant() > 0.0) out.push_back(p);
    }
  } while (all_orders && std::next_permutation(perm.begin(), perm.end()));
  return out;
}

/// A transform of the two samples' own coordinates in their principal frames, and back.
RigidTransform to_frames(const RigidTransform& t, const PackedHeader& reference,
                         const PackedHeader& probe) {
  RigidTransform f;
  f.rotation = reference.axes.transpose() * t.rotation * probe.axes;
  f.translation = reference.axes.transpose() *
                  (t.rotation * probe.centroid + t.translation - reference.centroid);
  return f;
}
RigidTransform from_frames(const RigidTransform& f, const PackedHeader& reference,
                           const PackedHeader& probe) {
  RigidTransform t;
  t.rotation = reference.axes * f.rotation * probe.axes.transpose();
  t.translation = reference.axes * f.translation + reference.centroid - t.rotation * probe.centroid;
  return t;
}

void check_probe(const PackedHeader& reference, const PackedSampleView& probe,
                 const OverlayOptions& options) {
  detail::check_overlay_options(options, {"packed overlay", ""});
  if (probe.header.points == 0) throw InputError("packed overlay: the probe sample has no points");
  if (reference.sigma != options.sigma || probe.header.sigma != options.sigma) {
    throw InputError("packed overlay: the samples were packed for a Gaussian width of " +
                     std::to_string(reference.sigma) + " and " +
                     std::to_string(probe.header.sigma) + " A, the overlay asks for " +
                     std::to_string(options.sigma) + " A");
  }
}

}  // namespace

std::uint32_t element_code(const std::string& element) {
  std::uint32_t code = 0;
  for (std::size_t i = 0; i < element.size() && i < 4; ++i)
    code |= static_cast<std::uint32_t>(static_cast<unsigned char>(element[i])) << (8 * i);
  return code;
}

PackedSample::PackedSample(const SurfaceSample& sample, const AtomSample& atoms, double sigma,
                           SampleKind kind) {
  if (!(sigma > 0.0) || !std::isfinite(sigma))
    throw OptionError("packed sample: sigma must be finite and > 0");
  const std::size_t n = sample.size();
  if (n == 0) throw InputError("packed sample: the sample has no points");
  if (static_cast<std::size_t>(atoms.points.cols()) != atoms.size())
    throw InputError("packed sample: the atoms' positions and elements differ in number");
  if (!sample.points.allFinite() || !sample.normals.allFinite() || !sample.weights.allFinite() ||
      !sample.esp.allFinite() || !sample.lp.allFinite() || !atoms.points.allFinite())
    throw InputError("packed sample: a value is not finite");
  const PrincipalFrame frame = principal_frame(sample);
  header_.points = static_cast<std::uint32_t>(n);
  header_.atoms = static_cast<std::uint32_t>(atoms.size());
  header_.kind = kind;
  header_.centroid = frame.centroid;
  header_.axes = frame.axes;
  header_.sigma = sigma;
  const Eigen::Matrix3Xd local =
      frame.axes.transpose() * (sample.points.colwise() - frame.centroid);
  const Eigen::Matrix3Xd normals = frame.axes.transpose() * sample.normals;
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0U);
  order_in_blocks(local, order, 0, n);
  const std::size_t padded = PackedSampleView{header_}.padded_points();
  arrays_.assign(kArrays * padded, 0.0F);
  const auto at = [&](int array, std::size_t i) -> float& {
    return arrays_[static_cast<std::size_t>(array) * padded + i];
  };
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<Eigen::Index>(order[k]);
    for (int c = 0; c < 3; ++c) {
      at(kX + c, k) = static_cast<float>(local(c, i));
      at(kNx + c, k) = static_cast<float>(normals(c, i));
    }
    at(kWeight, k) = static_cast<float>(sample.weights(i));
    at(kEsp, k) = static_cast<float>(sample.esp(i));
    at(kLp, k) = static_cast<float>(sample.lp(i));
  }
  for (std::size_t a = 0; a < atoms.size(); ++a) {
    const Eigen::Vector3d p =
        frame.axes.transpose() * (atoms.points.col(static_cast<Eigen::Index>(a)) - frame.centroid);
    for (int c = 0; c < 3; ++c) atom_points_.push_back(static_cast<float>(p(c)));
    atom_elements_.push_back(element_code(atoms.elements[a]));
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double w = at(kWeight, k);
    header_.squares_esp += w * at(kEsp, k) * at(kEsp, k);
    header_.squares_lp += w * at(kLp, k) * at(kLp, k);
    header_.squares_weight += w;
  }
  const PackedSampleView self = view();
  const detail::CrossSums sums = detail::self_sums(self, static_cast<float>(sigma));
  header_.self_shape = sums.shape;
  header_.self_esp = sums.esp;
  header_.self_lp = sums.lp;
  if (header_.atoms > 0) {
    const detail::FrameTransform identity =
        frame_transform(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    header_.atom_self = atom_overlap(self, self, identity, static_cast<float>(sigma));
  }
}

PackedSample::PackedSample(const PackedSampleView& view)
    : header_(view.header),
      arrays_(view.arrays, view.arrays + kArrays * view.padded_points()),
      atom_points_(view.atom_points, view.atom_points + std::size_t{3} * view.header.atoms),
      atom_elements_(view.atom_elements, view.atom_elements + view.header.atoms) {}

PackedSampleView PackedSample::view() const {
  PackedSampleView v;
  v.header = header_;
  v.arrays = arrays_.data();
  v.atom_points = atom_points_.data();
  v.atom_elements = atom_elements_.data();
  return v;
}

SurfaceSample PackedSample::sample() const {
  const PackedSampleView v = view();
  const auto n = static_cast<Eigen::Index>(header_.points);
  SurfaceSample s;
  s.points.resize(3, n);
  s.normals.resize(3, n);
  s.weights.resize(n);
  s.esp.resize(n);
  s.lp.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const Eigen::Vector3d p(v.array(kX)[i], v.array(kY)[i], v.array(kZ)[i]);
    const Eigen::Vector3d m(v.array(kNx)[i], v.array(kNy)[i], v.array(kNz)[i]);
    s.points.col(k) = header_.axes * p + header_.centroid;
    s.normals.col(k) = header_.axes * m;
    s.weights(k) = v.array(kWeight)[i];
    s.esp(k) = v.array(kEsp)[i];
    s.lp(k) = v.array(kLp)[i];
  }
  return s;
}

AtomSample PackedSample::atoms() const {
  AtomSample a;
  a.points.resize(3, static_cast<Eigen::Index>(header_.atoms));
  for (std::size_t k = 0; k < header_.atoms; ++k) {
    const Eigen::Vector3d p(atom_points_[3 * k], atom_points_[3 * k + 1], atom_points_[3 * k + 2]);
    a.points.col(static_cast<Eigen::Index>(k)) = header_.axes * p + header_.centroid;
    std::string element;
    for (int b = 0; b < 4; ++b) {
      const char c = static_cast<char>((atom_elements_[k] >> (8 * b)) & 0xFFU);
      if (c != '\0') element += c;
    }
    a.elements.push_back(element);
  }
  return a;
}

struct PackedQuery::Impl {
  PackedSample sample;
  detail::CellIndex index;

  OverlayScore score_in_frames(const PackedSampleView& probe, const PairConstants& c,
                               const detail::FrameTransform& t) const {
    const auto sigma = static_cast<float>(sample.header().sigma);
    const detail::CrossSums sums = detail::cross_sums(index, probe, t, sigma);
    const double h = c.atom_weight > 0.0 ? atom_overlap(sample.view(), probe, t, sigma) : 0.0;
    return scores(c, sums, h);
  }
};

PackedQuery::PackedQuery(PackedSample sample) : impl_(std::make_unique<Impl>()) {
  impl_->index = build_index(sample.view(), sample.header().sigma);
  impl_->sample = std::move(sample);
}

PackedQuery::PackedQuery(PackedQuery&&) noexcept = default;
PackedQuery& PackedQuery::operator=(PackedQuery&&) noexcept = default;
PackedQuery::~PackedQuery() = default;

const PackedSample& PackedQuery::sample() const { return impl_->sample; }

std::vector<PackedQuery::Score> PackedQuery::start_scores(const PackedSampleView& probe,
                                                          const OverlayOptions& options,
                                                          bool all_orders) const {
  const PackedHeader& reference = impl_->sample.header();
  check_probe(reference, probe, options);
  const PairConstants c = pair_constants(reference, probe.header, options);
  // In the two principal frames each start is its signed permutation itself.
  std::vector<Score> out;
  for (const Eigen::Matrix3d& p : axes_permutations(all_orders)) {
    Score s;
    s.score = impl_->score_in_frames(probe, c, frame_transform(p, Eigen::Vector3d::Zero()));
    RigidTransform f;
    f.rotation = p;
    s.transform = from_frames(f, reference, probe.header);
    out.push_back(s);
  }
  return out;
}

PackedQuery::Score PackedQuery::fast_score(const PackedSampleView& probe,
                                           const OverlayOptions& options, bool all_orders) const {
  const std::vector<Score> starts = start_scores(probe, options, all_orders);
  std::size_t best = 0;
  for (std::size_t k = 1; k < starts.size(); ++k) {
    if (starts[k].score.score > starts[best].score.score) best = k;
  }
  return starts[best];
}

OverlayScore PackedQuery::score(const PackedSampleView& probe, const RigidTransform& transform,
                                const OverlayOptions& options) const {
  const PackedHeader& reference = impl_->sample.header();
  check_probe(reference, probe, options);
  const PairConstants c = pair_constants(reference, probe.header, options);
  const RigidTransform f = to_frames(transform, reference, probe.header);
  return impl_->score_in_frames(probe, c, frame_transform(f.rotation, f.translation));
}

RefineResult PackedQuery::refine(const PackedSampleView& probe, const RigidTransform& start,
                                 const OverlayOptions& options) const {
  const PackedHeader& reference = impl_->sample.header();
  check_probe(reference, probe, options);
  const PairConstants c = pair_constants(reference, probe.header, options);
  const auto sigma = static_cast<float>(options.sigma);
  const auto esp_pull = static_cast<float>(c.chem_weight * c.esp_scale);
  const auto lp_pull = static_cast<float>(c.chem_weight * c.lp_scale);
  const auto n = static_cast<Eigen::Index>(probe.header.points);
  Eigen::Matrix3Xd from(3, n);
  Eigen::VectorXd probe_weights(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (int k = 0; k < 3; ++k) from(k, j) = probe.array(k)[static_cast<std::size_t>(j)];
    probe_weights(j) = probe.array(6)[static_cast<std::size_t>(j)];
  }
  const Eigen::Vector3d probe_centroid = from * probe_weights / probe_weights.sum();
  // The surface part of the score at `t` (frames) and the EM targets and weights there.
  const auto step = [&](const RigidTransform& t, Eigen::Matrix3Xd& tg, Eigen::VectorXd& w) {
    OverlayScore s = scores(c,
                            detail::cross_sums_and_targets(
                                impl_->index, probe, frame_transform(t.rotation, t.translation),
                                sigma, esp_pull, lp_pull, tg.data(), w.data()),
                            0.0);
    s.atoms = 0.0;
    s.score = (s.shape + c.chem_weight * s.chem) / (1.0 + c.chem_weight);
    return s;
  };
  const detail::Climb climb =
      detail::em_climb(from, n, from, probe_centroid, to_frames(start, reference, probe.header),
                       options, step, [](const RigidTransform&) { return false; });
  RefineResult result;
  result.transform = from_frames(climb.transform, reference, probe.header);
  result.score = impl_->score_in_frames(
      probe, c, frame_transform(climb.transform.rotation, climb.transform.translation));
  return result;
}

}  // namespace surfcomp::matching
