#include "surfcomp/matching/overlay.hpp"

#include "em_climb.hpp"
#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/spatial_grid.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::matching {
namespace {

constexpr double kCutoffSigmas = 3.0;
/// A sample of at most this many points is ligand-sized (the 1THL ligand's has about 180): its
/// self-overlap tests every pair's distance instead of listing it in cells
/// (docs/decisions.md#screen-stage-one).
constexpr std::size_t kLigandSizedPoints = 512;

/// A sample's weighted sums of squared ESP and LP and of weights: its share of the root mean
/// squares over two samples.
struct Squares {
  double esp = 0.0;
  double lp = 0.0;
  double weight = 0.0;
};

Squares squares(const SurfaceSample& s) {
  return {(s.esp.array().square() * s.weights.array()).sum(),
          (s.lp.array().square() * s.weights.array()).sum(), s.weights.sum()};
}

/// sqrt(sum w x^2 / sum w) from those two sums; 1 when it is zero (no such property).
double root_mean_square(double weighted_squares, double weights) {
  const double r = std::sqrt(weighted_squares / weights);
  return r > 0.0 ? r : 1.0;
}

/// g = exp(-d2 / (2 sigma^2)) for 0 <= d2 <= cutoff^2, interpolated linearly in d2 from
/// kSamples + 1 tabulated values (and one spare) (absolute error below 1e-6 at the 3 sigma
/// cutoff, overlay_test), which is cheaper than std::exp in the overlap sums
/// (docs/decisions.md#overlay-speed).
class GaussianTable {
 public:
  GaussianTable() = default;
  GaussianTable(double sigma, double cutoff) : scale_(kSamples / (cutoff * cutoff)) {
    values_.resize(kSamples + 2);
    for (std::size_t k = 0; k < values_.size(); ++k)
      values_[k] = std::exp(-static_cast<double>(k) / scale_ / (2.0 * sigma * sigma));
  }

  double operator()(double d2) const {
    const double x = d2 * scale_;
    const std::size_t k = static_cast<std::size_t>(x);
    return values_[k] + (x - static_cast<double>(k)) * (values_[k + 1] - values_[k]);
  }

 private:
  static constexpr int kSamples = 2048;
  double scale_ = 1.0;
  std::vector<double> values_;  ///< g at d2 = k / scale_, k = 0 .. kSamples + 1
};

/// Unnormalised overlaps S and C of two samples (see overlay.hpp).
struct Sums {
  double shape = 0.0;
  double chem = 0.0;
};

/// The chemical match c_ij of point i of `a` and point j of `b` (see overlay.hpp) when the
/// product of the two points' ESPs is divided by the square of the ESP's root mean square, and so
/// for LP: an overlay keeps its reference's values and divides its probe's by those squares.
double chemistry(const SurfaceSample& a, Eigen::Index i, const SurfaceSample& b, Eigen::Index j) {
  return std::max(0.0, a.esp(i) * b.esp(j)) + std::max(0.0, a.lp(i) * b.lp(j));
}

/// A sample's self-overlap S_SS and the ESP and LP parts of C_SS before the pair's scaling:
/// C_SS = esp / r_esp^2 + lp / r_lp^2 for the root mean squares r of the pair's two samples,
/// so that a reference's is summed once for all its probes.
struct SelfSums {
  /// Adds the pair (i, j) of `s` with weight w_i w_j g n_i . n_j (times its multiplicity).
  void add(const SurfaceSample& s, Eigen::Index i, Eigen::Index j, double weight) {
    shape += weight;
    esp += weight * std::max(0.0, s.esp(i) * s.esp(j));
    lp += weight * std::max(0.0, s.lp(i) * s.lp(j));
  }

  double shape = 0.0;
  double esp = 0.0;
  double lp = 0.0;
};

/// What an overlay keeps of its reference (ESP and LP as given), with the table, index and sums
/// built from it: shared by the overlays of one reference with many probes.
struct SharedReference {
  SurfaceSample sample;
  AtomSample atoms;
  GaussianTable gaussian;
  /// The reference points within 3 sigma of each cell (cells of edge sigma, sigma / 2 for many
  /// probes, coarser for a very large box): a query reads one list instead of the cells of
  /// 3 sigma around it, the same sums for fewer visits (docs/decisions.md#overlay-speed).
  mesh::SpatialGrid grid;
  SelfSums self;  ///< of `sample` over `grid`
  Squares squares;
  double atom_self = 0.0;  ///< H_AA
};

}  // namespace

/// The shared reference, the probe (ESP and LP over the squares of their root mean squares),
/// and the self-overlaps: everything score and refine read, fixed on construction.
struct SurfaceOverlay::Impl {
  /// The reference listed on cells of `reference_cell` sigmas.
  Impl(SurfaceSample reference, SurfaceSample probe, const OverlayOptions& options,
       AtomSample reference_atoms, AtomSample probe_atoms, double reference_cell);
  /// `other`'s reference (its shared part) with a new probe.
  Impl(const Impl& other, SurfaceSample probe, AtomSample probe_atoms);
  /// Checks the probe's side, sums the self-overlaps and scales the probe's ESP and LP.
  void finish();

  /// Sums over the pairs (i of a, j of b moved by `transform`) within 3 sigma (see overlay.hpp),
  /// `neighbours(q, visit)` calling visit(i) for a superset of a's points within 3 sigma of q
  /// by increasing index (so that any such superset gives the same sums: the points beyond
  /// the cutoff add nothing). With `targets`, also the refinement's step: for each j, the mean
  /// of its neighbours i weighted by w_i g max(0, n_i . R n_j) (1 + chem_weight c_ij), and that
  /// weight's sum times w_j.
  template <class Neighbours>
  Sums overlap(const SurfaceSample& a, const Neighbours& neighbours, const SurfaceSample& b,
               const RigidTransform& transform, Eigen::Matrix3Xd* targets = nullptr,
               Eigen::VectorXd* target_weights = nullptr) const;
  /// For each j of b moved by `transform` (q_j, normal m_j), in order: pair(j, i, k) for each
  /// neighbour i (as overlap takes them) within 3 sigma of q_j and facing m_j, with
  /// k = w_i g(|a_i - q_j|^2) n_i . m_j; then done(j, q_j).
  template <class Neighbours, class Pair, class Done>
  void for_each_pair(const SurfaceSample& a, const Neighbours& neighbours, const SurfaceSample& b,
                     const RigidTransform& transform, const Pair& pair, const Done& done) const;
  /// overlap(a, ..., b, ...) with `grid` listing a's points within 3 sigma of each of its cells.
  Sums overlap(const SurfaceSample& a, const mesh::SpatialGrid& grid, const SurfaceSample& b,
               const RigidTransform& transform, Eigen::Matrix3Xd* targets = nullptr,
               Eigen::VectorXd* target_weights = nullptr) const {
    return overlap(
        a, [&grid](const Eigen::Vector3d& q, const auto& visit) { grid.for_each_listed(q, visit); },
        b, transform, targets, target_weights);
  }
  /// The self-overlap of s (ESP and LP as given) over `neighbours`, as overlap takes it.
  template <class Neighbours>
  SelfSums self_sums(const SurfaceSample& s, const Neighbours& neighbours) const;
  /// self_sums of a probe: by a grid, or testing every pair once when it is ligand-sized.
  SelfSums probe_self_sums(const SurfaceSample& s) const;
  /// Unnormalised same-element heteroatom overlap H of `a` and `b` moved by `transform`. With
  /// `targets`, also the refinement's step for b's atoms: for each, the Gaussian-weighted mean
  /// of a's atoms of its element (its own moved position when there is none) and, in
  /// `totals`, the sum of those weights.
  double atom_overlap(const AtomSample& a, const AtomSample& b, const RigidTransform& transform,
                      Eigen::Matrix3Xd* targets = nullptr, Eigen::VectorXd* totals = nullptr) const;
  /// The surface scores of the sums (atoms 0, score the surface part: what refine climbs).
  OverlayScore tanimoto(const Sums& sums) const;
  /// `s` with the atom term of `transform` added, when the overlay uses atoms.
  OverlayScore with_atoms(OverlayScore s, const RigidTransform& transform) const;
  /// `s` with the atom term of the overlap `h` (atom_overlap of the two samples) added.
  OverlayScore with_atom_overlap(OverlayScore s, double h) const;
  /// The weighted mean of s's terms (the atom term only `with_atoms`).
  double combined(const OverlayScore& s, bool with_atoms) const;
  bool uses_atoms() const { return atom_self > 0.0 && options.atom_weight > 0.0; }
  OverlayScore score(const RigidTransform& transform) const;
  RefineResult refine(const RigidTransform& start, const RefineOptions& refine_options) const;

  const SurfaceSample& reference() const { return shared->sample; }
  const AtomSample& reference_atoms() const { return shared->atoms; }

  SurfaceSample probe;
  OverlayOptions options;
  AtomSample probe_atoms;
  std::shared_ptr<const SharedReference> shared;
  double chem_weight = 0.0;  ///< options.chem_weight, 0 when neither sample has ESP or LP
  Sums self;                 ///< S_AA + S_BB and C_AA + C_BB
  double atom_self = 0.0;    ///< H_AA + H_BB, 0 when a side has no heteroatoms
};

namespace {

void check_atoms(const AtomSample& atoms, const char* side) {
  if (static_cast<std::size_t>(atoms.points.cols()) != atoms.size() || !atoms.points.allFinite()) {
    throw InputError(std::string("overlay: the ") + side + " atoms have " +
                     std::to_string(atoms.points.cols()) + " positions for " +
                     std::to_string(atoms.size()) + " elements, or a position that is not finite");
  }
}

}  // namespace

SurfaceOverlay::Impl::Impl(SurfaceSample reference_sample, SurfaceSample probe_sample,
                           const OverlayOptions& overlay_options, AtomSample reference_atom_sample,
                           AtomSample probe_atom_sample, double reference_cell)
    : probe(std::move(probe_sample)),
      options(overlay_options),
      probe_atoms(std::move(probe_atom_sample)) {
  detail::check_overlay_options(options, {"overlay", ""});
  if (reference_sample.size() == 0) {
    throw InputError(
        "overlay: the reference sample has no points (an empty surface or site region)");
  }
  check_atoms(reference_atom_sample, "reference");
  const double cutoff = kCutoffSigmas * options.sigma;
  auto built = std::make_shared<SharedReference>();
  built->gaussian = GaussianTable(options.sigma, cutoff);
  built->grid = mesh::SpatialGrid(reference_sample.points, reference_cell * options.sigma, cutoff);
  built->squares = squares(reference_sample);
  built->sample = std::move(reference_sample);
  built->atoms = std::move(reference_atom_sample);
  shared = built;  // self_sums reads the table
  const mesh::SpatialGrid& grid = built->grid;
  built->self = self_sums(built->sample, [&grid](const Eigen::Vector3d& q, const auto& visit) {
    grid.for_each_listed(q, visit);
  });
  if (built->atoms.size() > 0) built->atom_self = atom_overlap(built->atoms, built->atoms, {});
  finish();
}

SurfaceOverlay::Impl::Impl(const Impl& other, SurfaceSample probe_sample,
                           AtomSample probe_atom_sample)
    : probe(std::move(probe_sample)),
      options(other.options),
      probe_atoms(std::move(probe_atom_sample)),
      shared(other.shared) {
  finish();
}

void SurfaceOverlay::Impl::finish() {
  if (probe.size() == 0) {
    throw InputError("overlay: the probe sample has no points (an empty surface or site region)");
  }
  check_atoms(probe_atoms, "probe");
  // ESP and LP over their root mean squares over both samples, so that the two properties
  // count alike whatever their units: a product of two points' values over the square.
  const Squares probe_squares = squares(probe);
  const Squares& reference_squares = shared->squares;
  const double weights = reference_squares.weight + probe_squares.weight;
  const double esp_rms = root_mean_square(reference_squares.esp + probe_squares.esp, weights);
  const double lp_rms = root_mean_square(reference_squares.lp + probe_squares.lp, weights);
  const double esp_scale = 1.0 / (esp_rms * esp_rms);
  const double lp_scale = 1.0 / (lp_rms * lp_rms);
  const SelfSums probe_self = probe_self_sums(probe);
  self.shape = shared->self.shape + probe_self.shape;
  self.chem = (shared->self.esp + probe_self.esp) * esp_scale +
              (shared->self.lp + probe_self.lp) * lp_scale;
  chem_weight = self.chem > 0.0 ? options.chem_weight : 0.0;
  probe.esp *= esp_scale;
  probe.lp *= lp_scale;
  if (shared->atom_self > 0.0 && probe_atoms.size() > 0)
    atom_self = shared->atom_self + atom_overlap(probe_atoms, probe_atoms, {});
}

SelfSums SurfaceOverlay::Impl::probe_self_sums(const SurfaceSample& s) const {
  const double cutoff = kCutoffSigmas * options.sigma;
  if (s.size() > kLigandSizedPoints) {
    const mesh::SpatialGrid grid(s.points, options.sigma, cutoff);
    return self_sums(s, [&grid](const Eigen::Vector3d& q, const auto& visit) {
      grid.for_each_listed(q, visit);
    });
  }
  // Ligand-sized: each pair tested once, as the sums are symmetric in i and j.
  const double cutoff2 = cutoff * cutoff;
  SelfSums sums;
  for (Eigen::Index j = 0; j < s.points.cols(); ++j) {
    for (Eigen::Index i = 0; i <= j; ++i) {
      const double d2 = (s.points.col(i) - s.points.col(j)).squaredNorm();
      if (!(d2 <= cutoff2)) continue;
      const double facing = s.normals.col(i).dot(s.normals.col(j));
      if (facing <= 0.0) continue;
      sums.add(s, i, j,
               (i == j ? 1.0 : 2.0) * s.weights(i) * s.weights(j) * shared->gaussian(d2) * facing);
    }
  }
  return sums;
}

template <class Neighbours>
SelfSums SurfaceOverlay::Impl::self_sums(const SurfaceSample& s,
                                         const Neighbours& neighbours) const {
  SelfSums sums;
  for_each_pair(
      s, neighbours, s, {},
      [&](Eigen::Index j, int i, double k) { sums.add(s, i, j, s.weights(j) * k); },
      [](Eigen::Index, const Eigen::Vector3d&) {});
  return sums;
}

template <class Neighbours, class Pair, class Done>
void SurfaceOverlay::Impl::for_each_pair(const SurfaceSample& a, const Neighbours& neighbours,
                                         const SurfaceSample& b, const RigidTransform& transform,
                                         const Pair& pair, const Done& done) const {
  const double cutoff2 = std::pow(kCutoffSigmas * options.sigma, 2);
  for (Eigen::Index j = 0; j < b.points.cols(); ++j) {
    const Eigen::Vector3d q = transform.rotation * b.points.col(j) + transform.translation;
    const Eigen::Vector3d m = transform.rotation * b.normals.col(j);
    neighbours(q, [&](int i) {
      const double d2 = (a.points.col(i) - q).squaredNorm();
      if (!(d2 <= cutoff2)) return;
      const double facing = a.normals.col(i).dot(m);
      if (facing <= 0.0) return;
      pair(j, i, a.weights(i) * shared->gaussian(d2) * facing);
    });
    done(j, q);
  }
}

template <class Neighbours>
Sums SurfaceOverlay::Impl::overlap(const SurfaceSample& a, const Neighbours& neighbours,
                                   const SurfaceSample& b, const RigidTransform& transform,
                                   Eigen::Matrix3Xd* targets,
                                   Eigen::VectorXd* target_weights) const {
  Sums sums;
  const auto add = [&](Eigen::Index j, int i, double k) {
    const double c = chemistry(a, i, b, j);
    sums.shape += b.weights(j) * k;
    sums.chem += b.weights(j) * k * c;
    return c;
  };
  // The sums alone (a score) skip the step's weighted means.
  if (targets == nullptr) {
    for_each_pair(a, neighbours, b, transform, add, [](Eigen::Index, const Eigen::Vector3d&) {});
    return sums;
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double total = 0.0;
  for_each_pair(
      a, neighbours, b, transform,
      [&](Eigen::Index j, int i, double k) {
        const double pull = k * (1.0 + options.chem_weight * add(j, i, k));
        mean += pull * a.points.col(i);
        total += pull;
      },
      [&](Eigen::Index j, const Eigen::Vector3d& q) {
        targets->col(j) = total > 0.0 ? Eigen::Vector3d(mean / total) : q;
        (*target_weights)(j) = b.weights(j) * total;
        mean.setZero();
        total = 0.0;
      });
  return sums;
}

double SurfaceOverlay::Impl::atom_overlap(const AtomSample& a, const AtomSample& b,
                                          const RigidTransform& transform,
                                          Eigen::Matrix3Xd* targets,
                                          Eigen::VectorXd* totals) const {
  const double inv2s2 = 1.0 / (2.0 * options.sigma * options.sigma);
  double sum = 0.0;
  for (std::size_t l = 0; l < b.size(); ++l) {
    const Eigen::Vector3d y =
        transform.rotation * b.points.col(static_cast<Eigen::Index>(l)) + transform.translation;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    double total = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      if (a.elements[k] != b.elements[l]) continue;
      const Eigen::Vector3d x = a.points.col(static_cast<Eigen::Index>(k));
      const double g = std::exp(-(x - y).squaredNorm() * inv2s2);
      sum += g;
      mean += g * x;
      total += g;
    }
    if (targets != nullptr) {
      targets->col(static_cast<Eigen::Index>(l)) = total > 0.0 ? Eigen::Vector3d(mean / total) : y;
      (*totals)(static_cast<Eigen::Index>(l)) = total;
    }
  }
  return sum;
}

double SurfaceOverlay::Impl::combined(const OverlayScore& s, bool with_atoms) const {
  const double atom_weight = with_atoms ? options.atom_weight : 0.0;
  return (s.shape + chem_weight * s.chem + atom_weight * s.atoms) /
         (1.0 + chem_weight + atom_weight);
}

OverlayScore SurfaceOverlay::Impl::tanimoto(const Sums& sums) const {
  OverlayScore s;
  s.shape = sums.shape / (self.shape - sums.shape);
  // Without ESP and LP (a mesh without a molecule) there is no chemistry to overlap: 0, and
  // its weight leaves the score (chem_weight).
  s.chem = self.chem > 0.0 ? sums.chem / (self.chem - sums.chem) : 0.0;
  s.score = combined(s, false);
  return s;
}

OverlayScore SurfaceOverlay::Impl::with_atoms(OverlayScore s,
                                              const RigidTransform& transform) const {
  return uses_atoms()
             ? with_atom_overlap(s, atom_overlap(reference_atoms(), probe_atoms, transform))
             : s;
}

OverlayScore SurfaceOverlay::Impl::with_atom_overlap(OverlayScore s, double h) const {
  s.atoms = h / (atom_self - h);
  s.score = combined(s, true);
  return s;
}

OverlayScore SurfaceOverlay::Impl::score(const RigidTransform& transform) const {
  return with_atoms(tanimoto(overlap(reference(), shared->grid, probe, transform)), transform);
}

RefineResult SurfaceOverlay::Impl::refine(const RigidTransform& start,
                                          const RefineOptions& refine_options) const {
  const bool pull_atoms = refine_options.pull_atoms && uses_atoms();
  const Eigen::Index n = probe.points.cols();
  const Eigen::Index m = pull_atoms ? probe_atoms.points.cols() : 0;
  Eigen::Matrix3Xd from(3, n + m);
  from.leftCols(n) = probe.points;
  if (m > 0) from.rightCols(m) = probe_atoms.points;
  const Eigen::Vector3d probe_centroid = probe.points * probe.weights / probe.weights.sum();
  // Each term pulls about in proportion to its weight in the score over its self-overlap: a
  // surface point by its share of S + chem_weight C (its EM weight) over S_AA + S_BB, a
  // heteroatom by its share of H times atom_weight over H_AA + H_BB, the common factor
  // 1 / (S_AA + S_BB) taken out. An approximation: a Tanimoto x / (D - x) rises by
  // (1 + T)^2 / D per unit of x, so the ratio is exact only where the shape and atom Tanimotos
  // are equal; as a step must raise the score, it can only cost steps, not correctness.
  const double atom_scale = pull_atoms ? options.atom_weight * self.shape / atom_self : 0.0;
  Eigen::Matrix3Xd atom_targets(3, m);
  Eigen::VectorXd atom_totals(m);
  // The scores at `t` (the atom term's too when pulling atoms) and the EM targets and weights
  // there, the heteroatoms' after the surface points'.
  const auto step = [&](const RigidTransform& t, Eigen::Matrix3Xd& tg, Eigen::VectorXd& w) {
    const OverlayScore score = tanimoto(overlap(reference(), shared->grid, probe, t, &tg, &w));
    if (!pull_atoms) return score;
    const double h = atom_overlap(reference_atoms(), probe_atoms, t, &atom_targets, &atom_totals);
    tg.rightCols(m) = atom_targets;
    w.tail(m) = atom_scale * atom_totals;
    return with_atom_overlap(score, h);
  };
  const detail::Climb climb = detail::em_climb(
      from, n, probe.points, probe_centroid, start, options, step,
      [&](const RigidTransform& t) { return refine_options.abandon && refine_options.abandon(t); });
  RefineResult result;
  result.transform = climb.transform;
  result.abandoned = climb.abandoned;
  result.score = pull_atoms ? climb.score : with_atoms(climb.score, climb.transform);
  return result;
}

SurfaceOverlay::SurfaceOverlay(SurfaceSample reference, SurfaceSample probe,
                               const OverlayOptions& options, AtomSample reference_atoms,
                               AtomSample probe_atoms)
    : impl_(std::make_unique<const Impl>(std::move(reference), std::move(probe), options,
                                         std::move(reference_atoms), std::move(probe_atoms), 1.0)) {
}

SurfaceOverlay::SurfaceOverlay(std::unique_ptr<const Impl> impl) : impl_(std::move(impl)) {}

SurfaceOverlay SurfaceOverlay::for_many_probes(const SurfaceSample& reference,
                                               const OverlayOptions& options,
                                               const AtomSample& reference_atoms) {
  // Cells of sigma / 2 list fewer points beyond the cutoff than cells of sigma, and eight times
  // as many lists: worth building for many probes, not for one pair
  // (docs/decisions.md#screen-stage-one).
  return SurfaceOverlay(std::make_unique<const Impl>(reference, reference, options, reference_atoms,
                                                     reference_atoms, 0.5));
}

SurfaceOverlay::SurfaceOverlay(const SurfaceOverlay& other, SurfaceSample probe,
                               AtomSample probe_atoms)
    : impl_(std::make_unique<const Impl>(*other.impl_, std::move(probe), std::move(probe_atoms))) {}

SurfaceOverlay::SurfaceOverlay(SurfaceOverlay&&) noexcept = default;
SurfaceOverlay& SurfaceOverlay::operator=(SurfaceOverlay&&) noexcept = default;
SurfaceOverlay::~SurfaceOverlay() = default;

OverlayScore SurfaceOverlay::score(const RigidTransform& transform) const {
  return impl_->score(transform);
}

RefineResult SurfaceOverlay::refine(const RigidTransform& start,
                                    const RefineOptions& options) const {
  return impl_->refine(start, options);
}

const OverlayOptions& SurfaceOverlay::options() const { return impl_->options; }

bool SurfaceOverlay::uses_atoms() const { return impl_->uses_atoms(); }

const Eigen::Matrix3Xd& SurfaceOverlay::probe_points() const { return impl_->probe.points; }

}  // namespace surfcomp::matching
