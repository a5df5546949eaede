// Dense point correspondences of matched critical points (method §6):
// two patches whose harmonic shape images match at a rotation are paired point by point through
// their images: the same disk position after the rotation, mapped back to each patch in 3D.
#pragma once

#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace surfcomp::matching {

/// One critical-point pair of a clique: a indexes a.critical_points (the reference surface), b
/// indexes b.critical_points (the probe), image_shift is the best image rotation in grid steps
/// as harmonic::compare_images(image of a, image of b) returns it: sector j of a ring of a's
/// image matches sector (j + image_shift) mod sectors of the same ring of b's image.
struct MatchedPair {
  int a = -1;
  int b = -1;
  int image_shift = 0;
};

/// Pairs compare by (a, b) only: one CP pair has one best rotation.
inline bool operator<(const MatchedPair& x, const MatchedPair& y) {
  return x.a != y.a ? x.a < y.a : x.b < y.b;
}
inline bool operator==(const MatchedPair& x, const MatchedPair& y) {
  return x.a == y.a && x.b == y.b;
}

struct CorrespondenceOptions {
  /// Default 1 (every ring). Only rings r with r % ring_step == 0 are used. Must be >= 1.
  int ring_step = 1;
  /// Default 3. Only sectors s with s % sector_step == 0 of a's image are used: on the default
  /// 16 x 180 grid that is every 6 degrees, at most 960 correspondences per pair, which bounds
  /// the cost of the fits and of the clustering's distances while the points stay closer than
  /// the mesh spacing (the outer ring's 6-degree arc at radius ~5 A is ~0.5 A). Must be >= 1.
  int sector_step = 3;
  /// Default "esp". The vertex property interpolated at the corresponding points (R_chem, seed
  /// 3.10); both surfaces must have it. Empty: none (a shape-only match), every value 0 and
  /// so R_chem 0.
  std::string property = mesh::property::esp;
};

/// Corresponding points: column i of a_points (on surface A) corresponds to column i of
/// b_points (on surface B). 3 by N, A; the properties are options.property at those points.
struct Correspondences {
  Eigen::Matrix3Xd a_points;
  Eigen::Matrix3Xd b_points;
  Eigen::VectorXd a_property;
  Eigen::VectorXd b_property;

  std::size_t size() const { return static_cast<std::size_t>(a_points.cols()); }
};

/// The correspondences of one CP pair: for each subsampled grid point i = ring * angular + s of
/// a's image that is valid, the grid point j = ring * angular + (s + image_shift) mod angular
/// of b's image, if valid; p = image_point_to_surface(a's image, i, a's patch) and q = the same
/// for j on b's patch, and the property interpolated with the same barycentric coordinates
/// from the surface vertices of the face's corners. Ordered by i.
/// Throws InputError when an index is outside its critical_points, a point has no image
/// (status not ok), the two images' grids differ, or a surface lacks options.property;
/// OptionError for a step below 1.
Correspondences pair_correspondences(const harmonic::SurfaceDescriptors& a,
                                     const harmonic::SurfaceDescriptors& b, const MatchedPair& pair,
                                     const CorrespondenceOptions& options = {});

/// The columns of all `parts`, in order (the union of the correspondences of several pairs).
Correspondences concatenate(const std::vector<const Correspondences*>& parts);

/// Pearson correlation of a_property and b_property (R_chem, method §6.5); 0 when
/// there are fewer than 2 points or either side is constant (standard deviation below 1e-12
/// times its root mean square value, or exactly 0). Throws InputError when a value is not
/// finite or the two vectors differ in length.
double property_correlation(const Correspondences& correspondences);

}  // namespace surfcomp::matching
