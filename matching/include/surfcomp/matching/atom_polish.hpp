// The last step of a molecule match: its best poses polished on the heavy atoms themselves. The
// surface overlay (overlay.hpp) finds where two molecules correspond, but its Gaussians, 1 A wide
// on points pooled 1.5 A apart, place a pose only to a few tenths of an angstrom. The atom
// overlap of two molecules A and B under a transform T of B is the Gaussian overlap of their
// heavy atoms, each atom against the atoms of its own element, at a narrow width sigma:
//   H(A, T B) = sum over pairs (k, l) of like elements of exp(-|x_k - T y_l|^2 / (2 sigma^2)),
// as a Tanimoto, fit = H_AB / (H_AA + H_BB - H_AB): 1 for a molecule on itself, near 0 when no
// atom lies on a like atom. The polish climbs overlay score + weight fit from a pose by
// expectation-maximisation steps on the atoms (each the weighted least-squares rigid fit of every
// probe atom onto the Gaussian-weighted mean of its like reference atoms, as
// SurfaceOverlay::refine steps on surface points), a step taken only when it raises that sum.
// The atoms two molecules share come to lie on each other, as Open3DAlign lays its matched atoms
// on each other, as far as the surfaces agree; a molecule on a moved copy of itself ends at the
// identity (both terms are highest there; the atom sum has no cutoff, so that its Gaussian
// kernel stays positive definite and the fit at most 1). Why this width and weight:
// docs/decisions.md#atom-polish.
#pragma once

#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/rigid_fit.hpp"

#include <Eigen/Core>

#include <vector>

namespace surfcomp::matching {

/// The narrowest atom Gaussian accepted, A: narrower ones underflow in the overlap sums.
inline constexpr double min_atom_polish_sigma = 0.05;

struct AtomPolishOptions {
  /// Default 0.5 A. Width of the atom Gaussians. 0 turns the polish off (match_surfaces);
  /// otherwise finite and >= min_atom_polish_sigma (0.05 A).
  double sigma = 0.5;
  /// Default 1. Weight of the atom fit beside the overlay score, in the polish and in the order
  /// of the scored poses (match_surfaces). Finite, >= 0.
  double weight = 1.0;
  /// Default 1000. Most steps per pose (the climb stops at `tolerance` first). >= 0.
  int iterations = 1000;
  /// Default 1e-5 A. The polish stops when a step moves no probe atom by more than this. >= 0.
  double tolerance = 1e-5;
};

/// The atom fit of one probe molecule on one reference molecule (see the file comment), built
/// once per pair: it keeps both molecules' heavy atoms with their element types and their
/// self-overlaps. fit and polish are const and may run from any number of threads.
class AtomOverlap {
 public:
  /// `reference` and `probe` are heavy atoms (SurfaceDescriptors::atoms). Throws OptionError
  /// unless sigma is finite and >= min_atom_polish_sigma; InputError when either side has no atoms
  /// or an atom's position is not finite.
  AtomOverlap(const std::vector<harmonic::SurfaceAtom>& reference,
              const std::vector<harmonic::SurfaceAtom>& probe, double sigma);

  /// The atom fit of `transform` (moving probe coordinates into the reference frame), [0, 1].
  double fit(const RigidTransform& transform) const;

  /// A transform near `start` with a higher overlay.score(T).score + options.weight fit(T) (see
  /// the file comment); `start` itself when no step raises that sum. `overlay` must be the
  /// overlay of the same two molecules' surfaces. The width is the constructor's: options.sigma
  /// is not read. Throws OptionError for a weight, iterations or tolerance outside its domain.
  RigidTransform polish(const SurfaceOverlay& overlay, const RigidTransform& start,
                        const AtomPolishOptions& options) const;

 private:
  double overlap(const RigidTransform& transform, Eigen::Matrix3Xd* targets,
                 Eigen::VectorXd* weights) const;
  /// The fit of an overlap h: h / (H_AA + H_BB - h).
  double tanimoto(double h) const { return h / (self_ - h); }

  Eigen::Matrix3Xd reference_;
  std::vector<int> reference_types_;
  Eigen::Matrix3Xd probe_;
  std::vector<int> probe_types_;
  double sigma_ = 0.5;
  double self_ = 0.0;  ///< H_AA + H_BB
};

}  // namespace surfcomp::matching
