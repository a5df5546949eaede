// How closely two surfaces lie on each other under a rigid transform, measured point to
// surface: the coverage score (how much of each surface lies on the other) and a point-to-plane
// ICP polish of a pose. The overlay (overlay.hpp) judges a pose by a Gaussian Tanimoto of the
// whole surfaces, which a true partial match cannot raise much: a 30 % crop of a mesh on the
// mesh scores far below 1 however exact the pose. The coverage asks instead what fraction of
// each surface lies within a distance of the other; its score is the larger fraction, that of
// the part (the smaller surface of a partial match), near 1 for a crop wherever it came from.
// Why both, and the defaults: docs/decisions.md#coverage-and-icp.
//
// Each surface is measured at up to max_points of its vertices (an even stride through them),
// weighted by their barycentric areas; distances are to the other surface's triangles (CGAL's
// AABB tree), so they do not depend on how finely the other surface is meshed.
#pragma once

#include "surfcomp/matching/rigid_fit.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <cstddef>
#include <memory>
#include <vector>

namespace surfcomp::matching {

/// How much of each surface lies on the other under one transform.
struct CoverageScore {
  double reference = 0.0;  ///< fraction of REF's area within the distance of the moved PROBE
  double probe = 0.0;      ///< fraction of PROBE's area within the distance of REF, once moved
  /// The larger of the two: the fraction of the part that lies on the whole in a partial match,
  /// 1 when it lies wholly on it, whatever the whole holds beyond it. Not chosen by area: noise
  /// inflates a scan's area, so that a noisy part can have more area than the whole.
  double score = 0.0;
};

/// The point-to-plane ICP polish (SurfaceFit::icp).
struct IcpOptions {
  /// Default 1.5 (A, or units of a general mesh). Point pairs farther apart are left out of a
  /// step: the polish corrects a pose that is nearly right, it does not search. > 0.
  double max_distance = 1.5;
  /// Default 30. Most steps. >= 1.
  int iterations = 30;
  /// Default 1e-4 (A or units). The polish stops when a step moves no sampled point farther. >= 0.
  double tolerance = 1e-4;
};

/// Measures and polishes transforms of one probe surface onto one reference surface. Built once
/// per pair (it indexes both surfaces' triangles); coverage and icp are const and may run from
/// any number of threads.
class SurfaceFit {
 public:
  /// Default 2000: the vertices each surface is measured at (an even stride through them).
  static constexpr std::size_t default_max_points = 2000;

  /// Indexes the two surfaces, or the parts their masks flag (one flag per vertex; null for
  /// all): the flagged vertices, and the triangles whose three corners are flagged. Throws
  /// InputError when a mask has the wrong size or a side keeps no triangle.
  SurfaceFit(const mesh::Surface& reference, const mesh::Surface& probe,
             const std::vector<bool>* reference_mask = nullptr,
             const std::vector<bool>* probe_mask = nullptr,
             std::size_t max_points = default_max_points);
  SurfaceFit(SurfaceFit&&) noexcept;
  SurfaceFit& operator=(SurfaceFit&&) noexcept;
  ~SurfaceFit();

  /// The coverage of `transform` (moving probe coordinates into the reference frame): a point
  /// lies on the other surface when its distance to the nearest of that surface's triangles is
  /// at most `distance`. Throws OptionError unless distance is finite and > 0.
  CoverageScore coverage(const RigidTransform& transform, double distance) const;

  /// `start` polished by point-to-plane ICP (Chen and Medioni 1992): each step pairs every
  /// sampled probe vertex, moved, with the nearest point of the reference's triangles, keeps the
  /// pairs within options.max_distance whose normals agree (the moved vertex normal and the
  /// reference's normal there, its corners' vertex normals interpolated, point the same way),
  /// and takes the area-weighted least-squares rigid motion that brings each vertex onto the
  /// plane through its pair with that normal (linearised about the pairs' centroid).
  /// Gives `start` when fewer than six pairs are kept. Throws OptionError for options outside
  /// their domain.
  RigidTransform icp(const RigidTransform& start, const IcpOptions& options = {}) const;

  double reference_area() const;  ///< of the indexed triangles, A^2 (or units^2)
  double probe_area() const;      ///< of the indexed triangles

 private:
  struct Impl;
  std::unique_ptr<const Impl> impl_;
};

}  // namespace surfcomp::matching
