// Whole-surface overlay: a score of how well two surfaces coincide under a rigid transform, in
// shape and in chemistry, and a refinement of a transform that raises it. The critical-point
// level (cliques of CP pairs, their fits) finds where two surfaces may correspond; this level
// judges each candidate on every part of both surfaces, as Gaussian-overlay tools (ROCS,
// Shape-it) judge theirs, and polishes it. This stage is beyond the seed; why it exists and
// how its defaults were chosen: docs/decisions.md#overlay-stage.
//
// Each surface is sampled as area-weighted points (overlay_sample.hpp). Two samples A and B
// under a transform T of B overlap by
//   S(A, T B) = sum_ij w_i w_j g(|a_i - T b_j|) max(0, n_i . R n_j)           (shape)
//   C(A, T B) = sum_ij w_i w_j g(|a_i - T b_j|) max(0, n_i . R n_j) c_ij      (chemistry)
// with g(d) = exp(-d^2 / (2 sigma^2)), cut at 3 sigma, and the chemical match
//   c_ij = max(0, e_i e_j) + max(0, l_i l_j),   e = ESP / rms(ESP), l = LP / rms(LP)
// (root mean squares over both samples, so the two properties count alike whatever their
// units): like-signed ESP and like-signed LP add in proportion to their strength, as the colour
// features of ROCS do, while neutral regions and opposite signs add nothing
// (docs/decisions.md#overlay-chemistry).
// The scores are Tanimoto ratios against each surface's overlap with itself: shape = S_AB /
// (S_AA + S_BB - S_AB) and chem = C_AB / (C_AA + C_BB - C_AB), 1 for a sample on itself and
// near 0 without contact (two samplings of one surface can give slightly more than 1, as the
// normal factor and the cutoff make the kernel only nearly positive definite); the combined
// score is (shape + chem_weight chem) / (1 + chem_weight) (shape alone when neither surface has
// ESP or LP).
//
// Where both surfaces were built from molecules (SurfaceDescriptors::atoms), the score also
// judges the pose on their heteroatoms (heavy atoms other than carbon): with P the pairs of a
// reference and a moved probe heteroatom of the same element,
//   H(A, T B) = sum_(k,l in P) exp(-|x_k - T y_l|^2 / (2 sigma^2)),
// its Tanimoto atoms = H_AB / (H_AA + H_BB - H_AB), and the score becomes
// (shape + chem_weight chem + atom_weight atoms) / (1 + chem_weight + atom_weight). The
// refinement climbs the surface part alone; the atom term decides between the refined poses,
// and the best few are then polished on the whole score (RefineOptions::pull_atoms;
// MatchOptions::polish_top). Why heteroatoms: docs/decisions.md#heteroatom-term.
#pragma once

#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/matching/principal_axes.hpp"
#include "surfcomp/matching/rigid_fit.hpp"

#include <Eigen/Core>

#include <functional>
#include <memory>

namespace surfcomp::matching {

struct OverlayOptions {
  /// Default 1.0 A. Width of the Gaussian that pairs points of the two surfaces. Must be > 0.
  double sigma = 1.0;
  /// Default 1.5 A. Edge of the cells the vertices are pooled in (the 1THL ligand's surface,
  /// 433 A^2, gives ~180 points; docs/decisions.md#overlay-sampling-and-width). Must be > 0.
  double spacing = 1.5;
  /// Default 6. Weight of the chemistry Tanimoto against the shape Tanimoto in the score and in
  /// the refinement's pull (docs/decisions.md#overlay-chemistry). Must be >= 0.
  double chem_weight = 6.0;
  /// Default 14. Weight of the heteroatom Tanimoto (same-element heteroatoms, Gaussians of
  /// width sigma) in the score, where both sides have heteroatoms; it pulls only in the polish
  /// (RefineOptions::pull_atoms; MatchOptions::polish_top). See
  /// docs/decisions.md#heteroatom-term. Must be >= 0.
  double atom_weight = 14.0;
  /// Default 40. Most refinement steps per transform. Must be >= 0.
  int iterations = 40;
  /// Default 0.1 A. Refinement stops when a step moves no sampled probe point by more than this
  /// (docs/decisions.md#refinement-tolerance). Must be >= 0.
  double tolerance = 0.1;
};

/// The Tanimoto scores of one transform (see the file comment).
struct OverlayScore {
  double shape = 0.0;  ///< about [0, 1]
  double chem = 0.0;   ///< about [0, 1]
  double atoms = 0.0;  ///< [0, 1]; 0 when a side has no heteroatoms
  /// (shape + chem_weight chem + atom_weight atoms) / (1 + chem_weight + atom_weight), the atom
  /// term left out (weight 0) when the overlay has no atoms on a side.
  double score = 0.0;
};

/// How SurfaceOverlay::refine climbs.
struct RefineOptions {
  /// Default false. Climb the whole score, atom term included (where the overlay uses_atoms()):
  /// each step also pulls every probe heteroatom toward the Gaussian-weighted mean of the
  /// reference heteroatoms of its element, weighted about as the atom term weighs in the score,
  /// and must raise the score. False: climb the surface part, (shape + chem_weight chem) /
  /// (1 + chem_weight).
  bool pull_atoms = false;
  /// Default none. Called with the transform after every step taken; when it returns true
  /// (say, for a transform that has come to a pose already found) the refinement stops there
  /// and the result is marked abandoned. Called from the refining thread.
  std::function<bool(const RigidTransform&)> abandon;
};

/// A refined transform and its scores.
struct RefineResult {
  RigidTransform transform;  ///< moves probe coordinates into the reference frame
  OverlayScore score;        ///< transform's scores, as SurfaceOverlay::score gives them
  /// Whether RefineOptions::abandon stopped the refinement (transform is where it stopped).
  bool abandoned = false;
};

/// Scores and refines transforms of one probe sample onto one reference sample. Built once per
/// pair of samples (it indexes the reference sample); score and refine are const and may run
/// from any number of threads.
class SurfaceOverlay {
 public:
  /// Throws OptionError for options outside their domain, InputError when a sample is empty.
  /// The atom samples may be empty (no molecule, or none of its atoms a heteroatom); the atom
  /// term then takes no part.
  SurfaceOverlay(SurfaceSample reference, SurfaceSample probe, const OverlayOptions& options = {},
                 AtomSample reference_atoms = {}, AtomSample probe_atoms = {});
  /// The overlay of `probe` on the reference of `other`: the same numbers as
  /// SurfaceOverlay(reference, probe, other.options(), reference_atoms, probe_atoms) with
  /// `other`'s reference and reference atoms, without indexing the reference again; for one
  /// reference against many probes (a screen's first stage). Throws InputError when the probe
  /// sample is empty or its atoms are malformed.
  SurfaceOverlay(const SurfaceOverlay& other, SurfaceSample probe, AtomSample probe_atoms = {});
  /// The overlay of `reference` on itself (the numbers of SurfaceOverlay(reference, reference,
  /// options, reference_atoms, reference_atoms)) with the reference indexed for many probes:
  /// on finer cells, which cost more to build once and less in each score of the overlays made
  /// from it by SurfaceOverlay(other, probe, ...). Throws as the first constructor.
  static SurfaceOverlay for_many_probes(const SurfaceSample& reference,
                                        const OverlayOptions& options = {},
                                        const AtomSample& reference_atoms = {});
  SurfaceOverlay(SurfaceOverlay&&) noexcept;
  SurfaceOverlay& operator=(SurfaceOverlay&&) noexcept;
  ~SurfaceOverlay();

  /// The scores of `transform` (moving probe coordinates into the reference frame).
  OverlayScore score(const RigidTransform& transform) const;

  /// A transform near `start` with a higher overlap: each step pairs every moved probe point
  /// with the Gaussian- and chemistry-weighted mean of its reference neighbours (within 3 sigma)
  /// and takes the weighted least-squares rigid fit of the probe points onto those means (an
  /// expectation-maximisation step of the Gaussian overlay), until OverlayOptions::iterations
  /// or OverlayOptions::tolerance. A step must raise the score climbed (see RefineOptions) or
  /// the refinement stops. Gives `start` unchanged when no probe point has a neighbour.
  RefineResult refine(const RigidTransform& start, const RefineOptions& options = {}) const;

  const OverlayOptions& options() const;
  /// Whether the atom term takes part (both atom samples have heteroatoms and atom_weight > 0).
  bool uses_atoms() const;
  /// The probe sample's points (probe frame, A).
  const Eigen::Matrix3Xd& probe_points() const;

 private:
  struct Impl;
  explicit SurfaceOverlay(std::unique_ptr<const Impl> impl);
  std::unique_ptr<const Impl> impl_;
};

}  // namespace surfcomp::matching
