#include "surfcomp/matching/overlay.hpp"

#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>

namespace surfcomp::matching {
namespace {

constexpr double kCutoffSigmas = 3.0;

/// sqrt(sum w x^2 / sum w) over both samples' values; 1 when it is zero (no such property).
double root_mean_square(const Eigen::VectorXd& a, const Eigen::VectorXd& wa,
                        const Eigen::VectorXd& b, const Eigen::VectorXd& wb) {
  const double r = std::sqrt(
      ((a.array().square() * wa.array()).sum() + (b.array().square() * wb.array()).sum()) /
      (wa.sum() + wb.sum()));
  return r > 0.0 ? r : 1.0;
}

}  // namespace

SurfaceSample sample_surface(const mesh::Surface& surface, double spacing,
                             const std::vector<bool>* vertex_mask) {
  detail::check_overlay_spacing(spacing, {"sample_surface", ""});
  const std::size_t n = surface.n_vertices();
  if (vertex_mask != nullptr && vertex_mask->size() != n) {
    throw InputError(surface.source() + ": overlay vertex mask has " +
                     std::to_string(vertex_mask->size()) + " flags for " + std::to_string(n) +
                     " vertices");
  }
  const Eigen::MatrixX3d positions = surface.positions();
  Eigen::MatrixX3d normals;
  if (surface.has_normals()) {
    normals = surface.normals();
  } else {
    mesh::Surface copy = surface;
    copy.compute_normals();
    normals = copy.normals();
  }
  const Eigen::VectorXd area = mesh::vertex_areas(surface);
  const auto property_or_zero = [&](const char* name) {
    return surface.has_property(name)
               ? surface.property(name)
               : Eigen::VectorXd(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n)));
  };
  const Eigen::VectorXd esp = property_or_zero(mesh::property::esp);
  const Eigen::VectorXd lp = property_or_zero(mesh::property::lp);

  struct Cell {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    double esp = 0.0, lp = 0.0, weight = 0.0;
  };
  std::map<std::array<long, 3>, Cell> cells;
  for (std::size_t v = 0; v < n; ++v) {
    if (vertex_mask != nullptr && !(*vertex_mask)[v]) continue;
    const Eigen::Index i = static_cast<Eigen::Index>(v);
    const double w = area(i);
    if (!(w > 0.0)) continue;
    const Eigen::Vector3d p = positions.row(i);
    const std::array<long, 3> key{static_cast<long>(std::floor(p.x() / spacing)),
                                  static_cast<long>(std::floor(p.y() / spacing)),
                                  static_cast<long>(std::floor(p.z() / spacing))};
    Cell& cell = cells[key];
    cell.position += w * p;
    cell.normal += w * Eigen::Vector3d(normals.row(i));
    cell.esp += w * esp(i);
    cell.lp += w * lp(i);
    cell.weight += w;
  }
  SurfaceSample sample;
  const Eigen::Index m = static_cast<Eigen::Index>(cells.size());
  sample.points.resize(3, m);
  sample.normals.resize(3, m);
  sample.weights.resize(m);
  sample.esp.resize(m);
  sample.lp.resize(m);
  Eigen::Index k = 0;
  for (const auto& [key, cell] : cells) {
    sample.points.col(k) = cell.position / cell.weight;
    const double length = cell.normal.norm();
    sample.normals.col(k) =
        length > 0.0 ? Eigen::Vector3d(cell.normal / length) : Eigen::Vector3d::Zero();
    sample.esp(k) = cell.esp / cell.weight;
    sample.lp(k) = cell.lp / cell.weight;
    sample.weights(k) = cell.weight;
    ++k;
  }
  return sample;
}

AtomSample sample_atoms(const std::vector<harmonic::SurfaceAtom>& atoms) {
  std::vector<const harmonic::SurfaceAtom*> kept;
  for (const harmonic::SurfaceAtom& atom : atoms) {
    if (atom.element != "H" && atom.element != "C") kept.push_back(&atom);
  }
  AtomSample sample;
  sample.points.resize(3, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    sample.points.col(static_cast<Eigen::Index>(k)) = kept[k]->position;
    sample.elements.push_back(kept[k]->element);
  }
  return sample;
}

namespace {

/// The weighted centroid and principal axes (columns, by increasing variance, right-handed)
/// of a sample.
std::pair<Eigen::Vector3d, Eigen::Matrix3d> principal_frame(const SurfaceSample& sample) {
  const double total = sample.weights.sum();
  const Eigen::Vector3d centroid = sample.points * sample.weights / total;
  const Eigen::Matrix3Xd centred = sample.points.colwise() - centroid;
  const Eigen::Matrix3d covariance =
      centred * sample.weights.asDiagonal() * centred.transpose() / total;
  Eigen::Matrix3d axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors();
  if (axes.determinant() < 0.0) axes.col(0) = -axes.col(0);
  return {centroid, axes};
}

}  // namespace

std::vector<RigidTransform> principal_axes_starts(const SurfaceSample& reference,
                                                  const SurfaceSample& probe, bool all_orders) {
  if (reference.size() == 0 || probe.size() == 0) {
    throw InputError(std::string("principal axes: the ") +
                     (reference.size() == 0 ? "reference" : "probe") + " sample has no points");
  }
  const auto [reference_centroid, reference_axes] = principal_frame(reference);
  const auto [probe_centroid, probe_axes] = principal_frame(probe);
  // Signed permutation matrices P with det +1: probe axis j goes onto reference axis perm[j].
  std::array<int, 3> perm{0, 1, 2};
  std::vector<RigidTransform> starts;
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
      for (int j = 0; j < 3; ++j)
        p(perm[static_cast<std::size_t>(j)], j) = (signs >> j) & 1 ? -1.0 : 1.0;
      if (p.determinant() < 0.0) continue;
      RigidTransform t;
      t.rotation = reference_axes * p * probe_axes.transpose();
      t.translation = reference_centroid - t.rotation * probe_centroid;
      starts.push_back(t);
    }
  } while (all_orders && std::next_permutation(perm.begin(), perm.end()));
  return starts;
}

SurfaceOverlay::Grid SurfaceOverlay::make_grid(const SurfaceSample& sample, double cell,
                                               double cutoff) {
  constexpr double kMaxCells =
      1 << 22;  // a larger box gets larger cells (a whole protein at small sigma)
  Grid grid;
  grid.origin = sample.points.rowwise().minCoeff().array() - cutoff;
  const Eigen::Vector3d extent =
      sample.points.rowwise().maxCoeff().array() + cutoff - grid.origin.array();
  grid.cell = std::max(cell, std::cbrt(extent.prod() / kMaxCells));
  for (int d = 0; d < 3; ++d)
    grid.size(d) = static_cast<int>(std::floor(extent(d) / grid.cell)) + 1;
  // A cell lists every point within the cutoff of any of its places: within the cutoff plus
  // half the cell's diagonal of its centre. Two passes: count, then fill.
  const double reach = cutoff + 0.5 * std::sqrt(3.0) * grid.cell;
  const auto for_each_cell_near = [&](Eigen::Index i, const auto& visit) {
    const Eigen::Vector3d p = sample.points.col(i);
    const Eigen::Vector3i low =
        ((p.array() - reach - grid.origin.array()) / grid.cell).floor().cast<int>().max(0);
    const Eigen::Vector3i high = ((p.array() + reach - grid.origin.array()) / grid.cell)
                                     .floor()
                                     .cast<int>()
                                     .min(grid.size.array() - 1);
    for (int z = low.z(); z <= high.z(); ++z) {
      for (int y = low.y(); y <= high.y(); ++y) {
        for (int x = low.x(); x <= high.x(); ++x) {
          const Eigen::Vector3d centre =
              grid.origin + grid.cell * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
          if ((centre - p).squaredNorm() <= reach * reach) visit(grid.index(x, y, z));
        }
      }
    }
  };
  const std::size_t cells = grid.index(0, 0, grid.size.z());
  grid.start.assign(cells + 1, 0);
  for (Eigen::Index i = 0; i < sample.points.cols(); ++i)
    for_each_cell_near(i, [&](std::size_t c) { ++grid.start[c + 1]; });
  for (std::size_t c = 0; c < cells; ++c) grid.start[c + 1] += grid.start[c];
  grid.points.resize(grid.start[cells]);
  std::vector<std::size_t> fill(grid.start.begin(), grid.start.end() - 1);
  for (Eigen::Index i = 0; i < sample.points.cols(); ++i) {
    for_each_cell_near(i, [&](std::size_t c) { grid.points[fill[c]++] = static_cast<int>(i); });
  }
  return grid;
}

namespace {

/// Calls visit(i) for each point i listed for the cell of `p`: a superset of the points within
/// the grid's cutoff of p (none when p is outside the grid).
template <typename Grid, typename Visit>
void visit_near(const Grid& grid, const Eigen::Vector3d& p, const Visit& visit) {
  const Eigen::Vector3d local = (p - grid.origin) / grid.cell;
  // Outside the grid, or not a number (also guards the int conversion below).
  if (!((local.array() >= 0.0).all() &&
        (local.array() < grid.size.template cast<double>().array()).all()))
    return;
  const Eigen::Vector3i c = local.array().floor().cast<int>();
  const std::size_t cell = grid.index(c.x(), c.y(), c.z());
  for (std::size_t k = grid.start[cell]; k < grid.start[cell + 1]; ++k) visit(grid.points[k]);
}

}  // namespace

double SurfaceOverlay::chemistry(const SurfaceSample& a, int i, const SurfaceSample& b, int j) {
  // The samples' ESP and LP were divided by their root mean squares on construction.
  return std::max(0.0, a.esp(i) * b.esp(j)) + std::max(0.0, a.lp(i) * b.lp(j));
}

SurfaceOverlay::Sums SurfaceOverlay::overlap(const SurfaceSample& a, const Grid& grid,
                                             const SurfaceSample& b,
                                             const RigidTransform& transform,
                                             Eigen::Matrix3Xd* targets,
                                             Eigen::VectorXd* target_weights) const {
  const double cutoff2 = std::pow(kCutoffSigmas * options_.sigma, 2);
  Sums sums;
  for (Eigen::Index j = 0; j < b.points.cols(); ++j) {
    const Eigen::Vector3d q = transform.rotation * b.points.col(j) + transform.translation;
    const Eigen::Vector3d m = transform.rotation * b.normals.col(j);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    double total = 0.0;
    visit_near(grid, q, [&](int i) {
      const double d2 = (a.points.col(i) - q).squaredNorm();
      if (!(d2 <= cutoff2)) return;
      const double facing = a.normals.col(i).dot(m);
      if (facing <= 0.0) return;
      const double k = a.weights(i) * gaussian(d2) * facing;
      const double c = chemistry(a, i, b, static_cast<int>(j));
      sums.shape += b.weights(j) * k;
      sums.chem += b.weights(j) * k * c;
      const double pull = k * (1.0 + options_.chem_weight * c);
      mean += pull * a.points.col(i);
      total += pull;
    });
    if (targets != nullptr) {
      targets->col(j) = total > 0.0 ? Eigen::Vector3d(mean / total) : q;
      (*target_weights)(j) = b.weights(j) * total;
    }
  }
  return sums;
}

double SurfaceOverlay::atom_overlap(const AtomSample& a, const AtomSample& b,
                                    const RigidTransform& transform, Eigen::Matrix3Xd* targets,
                                    Eigen::VectorXd* totals) const {
  const double inv2s2 = 1.0 / (2.0 * options_.sigma * options_.sigma);
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

double SurfaceOverlay::combined(const OverlayScore& s, bool with_atoms) const {
  const double atom_weight = with_atoms ? options_.atom_weight : 0.0;
  return (s.shape + chem_weight_ * s.chem + atom_weight * s.atoms) /
         (1.0 + chem_weight_ + atom_weight);
}

OverlayScore SurfaceOverlay::tanimoto(const Sums& sums) const {
  OverlayScore s;
  s.shape = sums.shape / (self_.shape - sums.shape);
  // Without ESP and LP (a mesh without a molecule) there is no chemistry to overlap: 0, and
  // its weight leaves the score (chem_weight_).
  s.chem = self_.chem > 0.0 ? sums.chem / (self_.chem - sums.chem) : 0.0;
  s.score = combined(s, false);
  return s;
}

OverlayScore SurfaceOverlay::with_atoms(OverlayScore s, const RigidTransform& transform) const {
  return uses_atoms()
             ? with_atom_overlap(s, atom_overlap(reference_atoms_, probe_atoms_, transform))
             : s;
}

OverlayScore SurfaceOverlay::with_atom_overlap(OverlayScore s, double h) const {
  s.atoms = h / (atom_self_ - h);
  s.score = combined(s, true);
  return s;
}

SurfaceOverlay::SurfaceOverlay(SurfaceSample reference, SurfaceSample probe,
                               const OverlayOptions& options, AtomSample reference_atoms,
                               AtomSample probe_atoms)
    : reference_(std::move(reference)),
      probe_(std::move(probe)),
      options_(options),
      reference_atoms_(std::move(reference_atoms)),
      probe_atoms_(std::move(probe_atoms)) {
  detail::check_overlay_options(options_, {"overlay", ""});
  if (reference_.size() == 0 || probe_.size() == 0) {
    throw InputError(std::string("overlay: the ") +
                     (reference_.size() == 0 ? "reference" : "probe") +
                     " sample has no points (an empty surface or site region)");
  }
  for (const AtomSample* atoms : {&reference_atoms_, &probe_atoms_}) {
    if (static_cast<std::size_t>(atoms->points.cols()) != atoms->size() ||
        !atoms->points.allFinite()) {
      throw InputError(
          std::string("overlay: the ") + (atoms == &reference_atoms_ ? "reference" : "probe") +
          " atoms have " + std::to_string(atoms->points.cols()) + " positions for " +
          std::to_string(atoms->size()) + " elements, or a position that is not finite");
    }
  }
  // ESP and LP over their root mean squares over both samples, so that the two properties
  // count alike whatever their units.
  const double esp_rms =
      root_mean_square(reference_.esp, reference_.weights, probe_.esp, probe_.weights);
  const double lp_rms =
      root_mean_square(reference_.lp, reference_.weights, probe_.lp, probe_.weights);
  for (SurfaceSample* sample : {&reference_, &probe_}) {
    sample->esp /= esp_rms;
    sample->lp /= lp_rms;
  }
  const double cutoff = kCutoffSigmas * options_.sigma;
  gaussian_scale_ = kGaussianSamples / (cutoff * cutoff);
  gaussian_.resize(kGaussianSamples + 2);
  for (std::size_t k = 0; k < gaussian_.size(); ++k) {
    gaussian_[k] = std::exp(-static_cast<double>(k) / gaussian_scale_ /
                            (2.0 * options_.sigma * options_.sigma));
  }
  reference_grid_ = make_grid(reference_, options_.sigma, cutoff);
  const Grid probe_grid = make_grid(probe_, options_.sigma, cutoff);
  const RigidTransform identity;
  const Sums reference_self = overlap(reference_, reference_grid_, reference_, identity);
  const Sums probe_self = overlap(probe_, probe_grid, probe_, identity);
  self_.shape = reference_self.shape + probe_self.shape;
  self_.chem = reference_self.chem + probe_self.chem;
  chem_weight_ = self_.chem > 0.0 ? options_.chem_weight : 0.0;
  if (reference_atoms_.size() > 0 && probe_atoms_.size() > 0) {
    atom_self_ = atom_overlap(reference_atoms_, reference_atoms_, identity) +
                 atom_overlap(probe_atoms_, probe_atoms_, identity);
  }
}

OverlayScore SurfaceOverlay::score(const RigidTransform& transform) const {
  return with_atoms(tanimoto(overlap(reference_, reference_grid_, probe_, transform)), transform);
}

namespace {

/// `current` followed by `alpha` times the motion that takes `current` to `step` (rotation angle
/// and translation scaled about `centre`, a point in the moved frame); alpha 1 gives `step`.
RigidTransform extrapolate(const RigidTransform& current, const RigidTransform& step,
                           const Eigen::Vector3d& centre, double alpha) {
  const Eigen::Matrix3d relative = step.rotation * current.rotation.transpose();
  const Eigen::Vector3d shift =
      relative * centre + (step.translation - relative * current.translation) - centre;
  const Eigen::AngleAxisd angle_axis(relative);
  const Eigen::Matrix3d scaled =
      Eigen::AngleAxisd(alpha * angle_axis.angle(), angle_axis.axis()).toRotationMatrix();
  RigidTransform out;
  out.rotation = scaled * current.rotation;
  out.translation = scaled * (current.translation - centre) + centre + alpha * shift;
  return out;
}

}  // namespace

std::optional<RigidTransform> SurfaceOverlay::refine(
    const RigidTransform& start, OverlayScore* final_score,
    const std::function<bool(const RigidTransform&)>& abandon, bool pull_atoms) const {
  constexpr double kMaxAlpha = 8.0;
  pull_atoms = pull_atoms && uses_atoms();
  const Eigen::Index n = probe_.points.cols();
  const Eigen::Index m = pull_atoms ? probe_atoms_.points.cols() : 0;
  Eigen::Matrix3Xd from(3, n + m);
  from.leftCols(n) = probe_.points;
  if (m > 0) from.rightCols(m) = probe_atoms_.points;
  const Eigen::Vector3d probe_centroid = probe_.points * probe_.weights / probe_.weights.sum();
  Eigen::Matrix3Xd targets(3, n + m), next_targets(3, n + m);
  Eigen::VectorXd weights(n + m), next_weights(n + m);
  // Each term pulls about in proportion to its weight in the score over its self-overlap: a
  // surface point by its share of S + chem_weight C (its EM weight) over S_AA + S_BB, a
  // heteroatom by its share of H times atom_weight over H_AA + H_BB, the common factor
  // 1 / (S_AA + S_BB) taken out. An approximation: a Tanimoto x / (D - x) rises by
  // (1 + T)^2 / D per unit of x, so the ratio is exact only where the shape and atom Tanimotos
  // are equal; as a step must raise the score, it can only cost steps, not correctness.
  const double atom_scale = pull_atoms ? options_.atom_weight * self_.shape / atom_self_ : 0.0;
  Eigen::Matrix3Xd atom_targets(3, m);
  Eigen::VectorXd atom_totals(m);
  // The scores at `t` (the atom term's too when pulling atoms) and the EM targets and weights
  // there, the heteroatoms' after the surface points'.
  const auto step = [&](const RigidTransform& t, Eigen::Matrix3Xd& tg, Eigen::VectorXd& w) {
    const OverlayScore score = tanimoto(overlap(reference_, reference_grid_, probe_, t, &tg, &w));
    if (!pull_atoms) return score;
    const double h = atom_overlap(reference_atoms_, probe_atoms_, t, &atom_targets, &atom_totals);
    tg.rightCols(m) = atom_targets;
    w.tail(m) = atom_scale * atom_totals;
    return with_atom_overlap(score, h);
  };
  RigidTransform current = start;
  OverlayScore current_score = step(current, targets, weights);
  // Expectation-maximisation steps, over-relaxed: while they keep raising the score, the step
  // is stretched (alpha doubles up to kMaxAlpha); one that does not is retried plain.
  double alpha = 1.0;
  for (int iteration = 0; iteration < options_.iterations; ++iteration) {
    if (!(weights.head(n).sum() > 0.0)) break;  // no surface contact: nothing to climb
    const RigidTransform em = fit_rigid_weighted(from, targets, weights).transform;
    RigidTransform next = extrapolate(current, em, current.apply(probe_centroid), alpha);
    OverlayScore next_score = step(next, next_targets, next_weights);
    if (!(next_score.score > current_score.score) && alpha > 1.0) {
      alpha = 1.0;
      next = em;
      next_score = step(next, next_targets, next_weights);
    } else {
      alpha = std::min(2.0 * alpha, kMaxAlpha);
    }
    if (!(next_score.score > current_score.score)) break;
    const double moved =
        (next.apply(probe_.points) - current.apply(probe_.points)).colwise().norm().maxCoeff();
    current = next;
    current_score = next_score;
    targets.swap(next_targets);
    weights.swap(next_weights);
    if (abandon && abandon(current)) return std::nullopt;
    if (moved <= options_.tolerance) break;
  }
  if (final_score != nullptr)
    *final_score = pull_atoms ? current_score : with_atoms(current_score, current);
  return current;
}

}  // namespace surfcomp::matching
