// Whole-surface overlay: a score of how well two surfaces coincide under a rigid transform, in
// shape and in chemistry, and a refinement of a transform that raises it. The critical-point
// level (cliques of CP pairs, their fits) finds where two surfaces may correspond; this level
// judges each candidate on every part of both surfaces, as Gaussian-overlay tools (ROCS,
// Shape-it) judge theirs, and polishes it. This stage is beyond the seed; why it exists and
// how its defaults were chosen: docs/decisions.md#overlay-stage.
//
// A surface is sampled as area-weighted points: the vertices are pooled in cubic cells of edge
// `spacing`, each cell giving one point (the area-weighted mean position, unit normal, ESP and
// LP of its vertices) whose weight is the cells' vertex area (A^2). Two samples A and B under a
// transform T of B overlap by
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
// and the best few are then polished on the whole score (refine with pull_atoms;
// MatchOptions::polish_top). Why heteroatoms: docs/decisions.md#heteroatom-term.
#pragma once

#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/rigid_fit.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <string>
#include <vector>

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
  /// (refine with pull_atoms; MatchOptions::polish_top). See docs/decisions.md#heteroatom-term.
  /// Must be >= 0.
  double atom_weight = 14.0;
  /// Default 40. Most refinement steps per transform. Must be >= 0.
  int iterations = 40;
  /// Default 0.1 A. Refinement stops when a step moves no sampled probe point by more than this
  /// (docs/decisions.md#refinement-tolerance). Must be >= 0.
  double tolerance = 0.1;
};

/// Area-weighted points of a surface (see the file comment). Columns of the matrices and
/// entries of the vectors belong to one point.
struct SurfaceSample {
  Eigen::Matrix3Xd points;   ///< A
  Eigen::Matrix3Xd normals;  ///< unit, outward
  Eigen::VectorXd weights;   ///< A^2; they sum to the area of the sampled vertices
  Eigen::VectorXd esp;       ///< the surface's "esp" property, 0 where it has none
  Eigen::VectorXd lp;        ///< the surface's "lp" property, 0 where it has none

  std::size_t size() const { return static_cast<std::size_t>(points.cols()); }
};

/// The heteroatoms (heavy atoms other than carbon) of a molecule, for the atom term.
struct AtomSample {
  Eigen::Matrix3Xd points;            ///< A
  std::vector<std::string> elements;  ///< one per column of points

  std::size_t size() const { return elements.size(); }
};

/// The heteroatoms among `atoms` (hydrogens and carbons dropped), in their order.
AtomSample sample_atoms(const std::vector<harmonic::SurfaceAtom>& atoms);

/// The sample of `surface`'s vertices whose flag in `vertex_mask` is set (all when null), pooled
/// in cells of `spacing` A; cells are ordered by their integer coordinates (deterministic).
/// Vertex normals are the surface's, or are computed when it has none. Throws InputError when
/// the mask has the wrong size; OptionError when spacing <= 0 or is not finite.
SurfaceSample sample_surface(const mesh::Surface& surface, double spacing,
                             const std::vector<bool>* vertex_mask = nullptr);

/// The proper rotations that superpose the probe sample's area-weighted principal axes on the
/// reference sample's, with the weighted centroids coincident: the starts Gaussian-overlay
/// tools (Shape-it, ROCS) refine, independent of any critical point. With `all_orders` false,
/// the four that pair the axes in order of their variance (signs taken in the four ways that
/// keep a right-handed frame); with it true, the 24 that pair them in any order (for samples
/// whose variances are too close for the order to mean much, as pockets' often are). Throws
/// InputError when a sample is empty.
std::vector<RigidTransform> principal_axes_starts(const SurfaceSample& reference,
                                                  const SurfaceSample& probe,
                                                  bool all_orders = false);

/// Whether `n` is a number of principal-axes starts there are: 0 (none), 4 or 24.
inline bool is_axes_start_count(int n) { return n == 0 || n == 4 || n == 24; }

/// The Tanimoto scores of one transform (see the file comment).
struct OverlayScore {
  double shape = 0.0;  ///< about [0, 1]
  double chem = 0.0;   ///< about [0, 1]
  double atoms = 0.0;  ///< [0, 1]; 0 when a side has no heteroatoms
  /// (shape + chem_weight chem + atom_weight atoms) / (1 + chem_weight + atom_weight), the atom
  /// term left out (weight 0) when the overlay has no atoms on a side.
  double score = 0.0;
};

/// Scores and refines transforms of one probe sample onto one reference sample.
class SurfaceOverlay {
 public:
  /// Throws OptionError for options outside their domain, InputError when a sample is empty.
  /// The atom samples may be empty (no molecule, or none of its atoms a heteroatom); the atom
  /// term then takes no part.
  SurfaceOverlay(SurfaceSample reference, SurfaceSample probe, const OverlayOptions& options = {},
                 AtomSample reference_atoms = {}, AtomSample probe_atoms = {});

  /// The scores of `transform` (moving probe coordinates into the reference frame).
  OverlayScore score(const RigidTransform& transform) const;

  /// A transform near `start` with a higher overlap: each step pairs every moved probe point
  /// with the Gaussian- and chemistry-weighted mean of its reference neighbours (within 3 sigma)
  /// and takes the weighted least-squares rigid fit of the probe points onto those means (an
  /// expectation-maximisation step of the Gaussian overlay), until options.iterations or
  /// options.tolerance. A step must raise the surface part of the score, (shape + chem_weight
  /// chem) / (1 + chem_weight), or the refinement stops. Returns `start` unchanged when no probe
  /// point has a neighbour. With `final_score`, also the returned transform's
  /// scores (as score() gives them). With `abandon`, the refinement stops as soon as it returns
  /// true for the current transform (say, one that has come to a pose already found), and
  /// refine returns nullopt. With `pull_atoms` (and uses_atoms()), the refinement climbs the
  /// whole score instead: each step also pulls every probe heteroatom toward the Gaussian-
  /// weighted mean of the reference heteroatoms of its element, weighted about as the atom
  /// term weighs in the score, and must raise the score, atom term included.
  std::optional<RigidTransform> refine(const RigidTransform& start, OverlayScore* final_score,
                                       const std::function<bool(const RigidTransform&)>& abandon,
                                       bool pull_atoms = false) const;
  RigidTransform refine(const RigidTransform& start, OverlayScore* final_score = nullptr) const {
    return *refine(start, final_score, {});
  }

  const OverlayOptions& options() const { return options_; }
  /// Whether the atom term takes part (both atom samples have heteroatoms and atom_weight > 0).
  bool uses_atoms() const { return atom_self_ > 0.0 && options_.atom_weight > 0.0; }
  /// The probe sample's points (probe frame, A).
  const Eigen::Matrix3Xd& probe_points() const { return probe_.points; }

 private:
  /// Neighbour lists of a sample on a grid of cubic cells of edge sigma (larger where the box
  /// would need more than about 2^22 cells) over its bounding box grown by the cutoff: cell c lists
  /// the points within the cutoff of some place in c, so a query looks at one list instead of
  /// 27 cells of 3 sigma: the same sums, fewer visits (docs/decisions.md#overlay-speed).
  struct Grid {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    double cell = 1.0;
    Eigen::Vector3i size = Eigen::Vector3i::Zero();
    std::vector<std::size_t> start;  ///< points listed for cell c: points[start[c] .. start[c + 1])
    std::vector<int> points;

    /// The index c of the cell (x, y, z).
    std::size_t index(int x, int y, int z) const {
      return (static_cast<std::size_t>(z) * static_cast<std::size_t>(size.y()) +
              static_cast<std::size_t>(y)) *
                 static_cast<std::size_t>(size.x()) +
             static_cast<std::size_t>(x);
    }
  };
  static Grid make_grid(const SurfaceSample& sample, double cell, double cutoff);
  /// Unnormalised overlaps S and C of `a` (bucketed by `grid`) and `b` moved by `transform`.
  struct Sums {
    double shape = 0.0;
    double chem = 0.0;
  };
  /// Sums over the pairs (i of a, j of b) within 3 sigma (see the file comment). With
  /// `targets`, also the refinement's step: for each j, the mean of its neighbours i weighted
  /// by w_i g max(0, n_i . R n_j) (1 + chem_weight c_ij), and that weight's sum times w_j.
  Sums overlap(const SurfaceSample& a, const Grid& grid, const SurfaceSample& b,
               const RigidTransform& transform, Eigen::Matrix3Xd* targets = nullptr,
               Eigen::VectorXd* target_weights = nullptr) const;
  /// The surface scores of the sums (atoms 0, score the surface part: what refine climbs).
  OverlayScore tanimoto(const Sums& sums) const;
  /// `s` with the atom term of `transform` added, when the overlay uses atoms.
  OverlayScore with_atoms(OverlayScore s, const RigidTransform& transform) const;
  /// `s` with the atom term of the overlap `h` (atom_overlap of the two samples) added.
  OverlayScore with_atom_overlap(OverlayScore s, double h) const;
  /// The weighted mean of s's terms (the atom term only `with_atoms`).
  double combined(const OverlayScore& s, bool with_atoms) const;
  /// Unnormalised same-element heteroatom overlap H of `a` and `b` moved by `transform`. With
  /// `targets`, also the refinement's step for b's atoms: for each, the Gaussian-weighted mean
  /// of a's atoms of its element (its own moved position when there is none) and, in
  /// `totals`, the sum of those weights.
  double atom_overlap(const AtomSample& a, const AtomSample& b, const RigidTransform& transform,
                      Eigen::Matrix3Xd* targets = nullptr, Eigen::VectorXd* totals = nullptr) const;
  static double chemistry(const SurfaceSample& a, int i, const SurfaceSample& b, int j);
  /// g = exp(-d2 / (2 sigma^2)) for 0 <= d2 <= (3 sigma)^2, interpolated linearly in d2 from
  /// kGaussianSamples + 1 tabulated values (and one spare) (absolute error below 1e-6,
  /// overlay_test), which is cheaper than std::exp in the overlap sums
  /// (docs/decisions.md#overlay-speed).
  double gaussian(double d2) const {
    const double x = d2 * gaussian_scale_;
    const std::size_t k = static_cast<std::size_t>(x);
    return gaussian_[k] + (x - static_cast<double>(k)) * (gaussian_[k + 1] - gaussian_[k]);
  }
  static constexpr int kGaussianSamples = 2048;

  SurfaceSample reference_;
  SurfaceSample probe_;
  OverlayOptions options_;
  Grid reference_grid_;
  double chem_weight_ = 0.0;      ///< options_.chem_weight, 0 when neither sample has ESP or LP
  Sums self_;                     ///< S_AA + S_BB and C_AA + C_BB
  std::vector<double> gaussian_;  ///< g at d2 = k / gaussian_scale_, k = 0 .. kGaussianSamples + 1
  double gaussian_scale_ = 1.0;
  AtomSample reference_atoms_;
  AtomSample probe_atoms_;
  double atom_self_ = 0.0;  ///< H_AA + H_BB, 0 when a side has no heteroatoms
};

}  // namespace surfcomp::matching
