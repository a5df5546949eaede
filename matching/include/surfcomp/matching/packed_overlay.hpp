// The whole-surface overlay of overlay.hpp in single precision, for a screen's first stage: one
// query against millions of stored samples. A sample is packed once, when its library entry is
// built: in its principal frame, float32 arrays, its self-overlaps summed. The query is indexed
// once per screen: every cell of a grid lists, as contiguous groups of eight points, the query
// points within the Gaussian's cutoff of the cell, so that a probe point reads one list and a
// SIMD kernel (Highway, dispatched at run time to the machine's best instruction set) takes it
// eight pairs at a time. A score then sums only the pair's cross terms. The scores are
// overlay.hpp's Tanimoto ratios of the same sums, to single-precision rounding (about 1e-6).
// Why: docs/decisions.md#screen-stage-one.
#pragma once

#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/matching/rigid_fit.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace surfcomp::matching {

/// A packed sample's arrays are padded to a multiple of this many points (weight 0).
inline constexpr std::size_t packed_group = 8;

/// How a packed sample's points were made.
enum class SampleKind : std::uint8_t {
  surface = 0,  ///< sample_surface of a full surface (a .hsi file, a site's pocket lining)
  atoms = 1,    ///< sample_molecule: the screening surface straight from the atoms
};

/// What a packed sample holds besides its arrays: its frame and its self-overlaps.
struct PackedHeader {
  std::uint32_t points = 0;  ///< the sample's points (the arrays hold them padded)
  std::uint32_t atoms = 0;   ///< heteroatoms
  SampleKind kind = SampleKind::surface;
  /// The principal frame: a point x of the sample is stored as axes^T (x - centroid).
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  /// The sample's overlap with itself (overlay.hpp's S, and the ESP and LP parts of C before
  /// their scaling), its weighted sums of squared ESP and LP and of weights, H of its
  /// heteroatoms, and the Gaussian width (A) they were summed with.
  double self_shape = 0.0, self_esp = 0.0, self_lp = 0.0;
  double squares_esp = 0.0, squares_lp = 0.0, squares_weight = 0.0;
  double atom_self = 0.0;
  double sigma = 0.0;
};

/// Read-only view of a packed sample (in memory or in a mapped library): nine arrays of
/// padded_points() floats, one after the other (x, y, z, normal x, y, z, weight, ESP, LP, in the
/// principal frame; padding points have weight 0), then per heteroatom three floats (principal
/// frame) and an element code (element_code).
struct PackedSampleView {
  PackedHeader header;
  const float* arrays = nullptr;
  const float* atom_points = nullptr;
  const std::uint32_t* atom_elements = nullptr;

  std::size_t padded_points() const {
    return (header.points + packed_group - 1) / packed_group * packed_group;
  }
  const float* array(int which) const {
    return arrays + static_cast<std::size_t>(which) * padded_points();
  }
};

/// The four-byte code of an element symbol (its first four characters, little-endian), as
/// packed samples store heteroatoms.
std::uint32_t element_code(const std::string& element);

/// A packed sample that owns its arrays.
class PackedSample {
 public:
  PackedSample() = default;
  /// Packs `sample` and `atoms` with the self-overlaps at Gaussian width `sigma` (A). The points
  /// are ordered in compact clusters (a probe's neighbouring points read neighbouring cells).
  /// Throws InputError for an empty sample, a non-finite value or malformed atoms, OptionError
  /// for a sigma that is not finite and > 0.
  PackedSample(const SurfaceSample& sample, const AtomSample& atoms, double sigma, SampleKind kind);
  /// A copy of a view's arrays (a library entry read once and kept).
  explicit PackedSample(const PackedSampleView& view);

  PackedSampleView view() const;
  const PackedHeader& header() const { return header_; }
  /// The sample and its heteroatoms back in their own frame, in double precision (the
  /// single-precision values, moved by the frame).
  SurfaceSample sample() const;
  AtomSample atoms() const;

 private:
  PackedHeader header_;
  std::vector<float> arrays_, atom_points_;
  std::vector<std::uint32_t> atom_elements_;
};

/// A packed sample indexed as the reference of many probes (see the file comment). Built once;
/// const and safe to use from any number of threads.
class PackedQuery {
 public:
  /// Indexes `sample` for overlays of Gaussian width sample.header().sigma. Throws InputError
  /// for a sample whose index would exceed 2^26 cells (a query far too large).
  explicit PackedQuery(PackedSample sample);
  PackedQuery(PackedQuery&&) noexcept;
  PackedQuery& operator=(PackedQuery&&) noexcept;
  ~PackedQuery();

  const PackedSample& sample() const;

  /// The first stage's score of `probe` on this reference: overlay.hpp's score (options'
  /// chem_weight and atom_weight) at each principal-axes superposition of the probe onto the
  /// reference (principal_axes_starts: 4, or 24 with `all_orders`), the best kept; ties go to the
  /// earlier start. `transform` moves the probe's own coordinates into the reference's. Throws
  /// InputError when the probe is empty or was packed with another sigma than options.sigma.
  struct Score {
    OverlayScore score;
    RigidTransform transform;
  };
  Score fast_score(const PackedSampleView& probe, const OverlayOptions& options,
                   bool all_orders = false) const;
  /// The score at each principal-axes superposition, in principal_axes_starts' order, as
  /// fast_score takes them.
  std::vector<Score> start_scores(const PackedSampleView& probe, const OverlayOptions& options,
                                  bool all_orders = false) const;
  /// The scores of one transform (moving the probe's own coordinates into the reference's), as
  /// SurfaceOverlay::score gives them, in single precision.
  OverlayScore score(const PackedSampleView& probe, const RigidTransform& transform,
                     const OverlayOptions& options) const;
  /// SurfaceOverlay::refine of `start` (the surface part climbed, no atom pull), its steps
  /// taken in single precision by the kernel and fitted in double.
  RefineResult refine(const PackedSampleView& probe, const RigidTransform& start,
                      const OverlayOptions& options) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace surfcomp::matching
