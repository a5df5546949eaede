#include "surfcomp/matching/atom_polish.hpp"

#include "em_climb.hpp"
#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"

#include <cmath>
#include <map>
#include <string>

namespace surfcomp::matching {
namespace {

/// The Gaussians exp(-d^2 / (2 sigma^2)) of the like pairs of `points`, summed: the
/// self-overlap of one molecule.
double self_overlap(const Eigen::Matrix3Xd& points, const std::vector<int>& types, double sigma) {
  double sum = 0.0;
  for (Eigen::Index l = 0; l < points.cols(); ++l) {
    for (Eigen::Index k = 0; k < points.cols(); ++k) {
      if (types[static_cast<std::size_t>(l)] == types[static_cast<std::size_t>(k)])
        sum += std::exp(-(points.col(l) - points.col(k)).squaredNorm() / (2.0 * sigma * sigma));
    }
  }
  return sum;
}

/// `atoms` as the columns of `points`, each with the index of its element in `type_of` (shared by
/// both molecules of a pair). Throws InputError for no atoms or a position that is not finite.
void typed_atoms(const std::vector<harmonic::SurfaceAtom>& atoms, const char* side,
                 std::map<std::string, int>& type_of, Eigen::Matrix3Xd& points,
                 std::vector<int>& types) {
  if (atoms.empty()) throw InputError(std::string("atom polish: the ") + side + " has no atoms");
  points.resize(3, static_cast<Eigen::Index>(atoms.size()));
  types.clear();
  for (std::size_t k = 0; k < atoms.size(); ++k) {
    if (!atoms[k].position.allFinite()) {
      throw InputError(std::string("atom polish: the ") + side + "'s atom " +
                       std::to_string(k + 1) + " has a position that is not finite");
    }
    points.col(static_cast<Eigen::Index>(k)) = atoms[k].position;
    types.push_back(
        type_of.emplace(atoms[k].element, static_cast<int>(type_of.size())).first->second);
  }
}

}  // namespace

AtomOverlap::AtomOverlap(const std::vector<harmonic::SurfaceAtom>& reference,
                         const std::vector<harmonic::SurfaceAtom>& probe, double sigma)
    : sigma_(sigma) {
  detail::OptionCheck{"atom polish", ""}.require(
      std::isfinite(sigma) && sigma >= min_atom_polish_sigma, "sigma", sigma,
      "a finite value >= 0.05 A");
  std::map<std::string, int> type_of;
  typed_atoms(reference, "reference", type_of, reference_, reference_types_);
  typed_atoms(probe, "probe", type_of, probe_, probe_types_);
  self_ =
      self_overlap(reference_, reference_types_, sigma) + self_overlap(probe_, probe_types_, sigma);
}

double AtomOverlap::overlap(const RigidTransform& transform, Eigen::Matrix3Xd* targets,
                            Eigen::VectorXd* weights) const {
  const double inv2s2 = 1.0 / (2.0 * sigma_ * sigma_);
  double sum = 0.0;
  for (Eigen::Index l = 0; l < probe_.cols(); ++l) {
    const Eigen::Vector3d y = transform.rotation * probe_.col(l) + transform.translation;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    double total = 0.0;
    for (Eigen::Index k = 0; k < reference_.cols(); ++k) {
      if (reference_types_[static_cast<std::size_t>(k)] !=
          probe_types_[static_cast<std::size_t>(l)])
        continue;
      const double g = std::exp(-(reference_.col(k) - y).squaredNorm() * inv2s2);
      mean += g * reference_.col(k);
      total += g;
    }
    if (targets != nullptr) {
      targets->col(l) = total > 0.0 ? Eigen::Vector3d(mean / total) : y;
      (*weights)(l) = total;
    }
    sum += total;
  }
  return sum;
}

double AtomOverlap::fit(const RigidTransform& transform) const {
  return tanimoto(overlap(transform, nullptr, nullptr));
}

RigidTransform AtomOverlap::polish(const SurfaceOverlay& overlay, const RigidTransform& start,
                                   const AtomPolishOptions& options) const {
  detail::check_atom_polish_options(options, {"atom polish", ""});
  // The sum climbed at `t`, and each probe atom's EM target and weight there.
  const auto step = [&](const RigidTransform& t, Eigen::Matrix3Xd& targets,
                        Eigen::VectorXd& weights) {
    const double h = overlap(t, &targets, &weights);
    OverlayScore climbed;
    climbed.score = overlay.score(t).score + options.weight * tanimoto(h);
    return climbed;
  };
  OverlayOptions climb;
  climb.iterations = options.iterations;
  climb.tolerance = options.tolerance;
  const Eigen::Vector3d centroid = probe_.rowwise().mean();
  return detail::em_climb(probe_, probe_.cols(), probe_, centroid, start, climb, step,
                          [](const RigidTransform&) { return false; })
      .transform;
}

}  // namespace surfcomp::matching
