// Harmonic shape images and their comparison (method §4; Zhang & Hebert
// 1999). A patch already embedded in the unit disk (by harmonic_disk_map) is resampled onto a
// polar grid over the disk; two images are compared by the Pearson correlation of their values,
// maximised over rotations. On a polar grid a rotation by one angular step is a cyclic shift of
// every ring's samples, so all rotations are compared at once by circular cross-correlations
// (FFTs of each ring) instead of resampling rotated grids as the seed did [choice;
// docs/decisions.md#image-comparison-on-a-polar-grid].
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace surfcomp::harmonic {

/// The polar grid of a harmonic shape image.
struct ImageOptions {
  /// Rings of the grid; ring k (0-based) lies at radius (k + 0.5) / rings. Must be >= 1.
  int rings = 16;
  /// Sectors of the grid, i.e. samples per ring; sector j of every ring lies at angle
  /// j * 360 / sectors degrees, counter-clockwise from the +u axis. The default, 180, gives
  /// 2-degree steps, so a rotation by 2 degrees is a cyclic shift by one sector (method §4.3). Must
  /// be >= 1.
  int sectors = 180;
};

/// A scalar field of a patch resampled onto the polar grid of ImageOptions. Grid point i
/// (0 <= i < rings * sectors) is ring i / sectors and sector i % sectors (ring-major order).
struct ShapeImage {
  int rings = 0;    ///< as ImageOptions::rings
  int sectors = 0;  ///< as ImageOptions::sectors
  /// The interpolated value at each grid point; 0 where the grid point is not valid.
  Eigen::VectorXd values;
  /// 1 where a triangle of the embedded patch lies under the grid point, 0 where none does
  /// (outside the mapped region, or in a hole of the patch).
  std::vector<std::uint8_t> valid;
  /// The patch face under each grid point (row of the faces array), -1 where none.
  Eigen::VectorXi face;
  /// Barycentric coordinates of the grid point in that face, in the order of the face's three
  /// vertices (they sum to 1); zero rows where the grid point is not valid.
  Eigen::MatrixX3d barycentric;
};

/// (u, v) of grid point `grid_index` of the polar grid of `options` (see ImageOptions). Throws
/// OptionError for grid sizes below 1, InputError when grid_index is outside the grid.
Eigen::Vector2d image_grid_point(const ImageOptions& options, int grid_index);

/// Resamples a per-vertex scalar (the shape index, method §0) of a patch embedded in the
/// unit disk onto the polar grid of `options`. uv: #V by 2 embedded vertex positions (normally
/// inside the closed unit disk); faces: #F by 3 vertex indices; values: #V. Each grid point is
/// located in the embedded triangles through a uniform grid of their bounding boxes, by CGAL's
/// exact orientation predicates (so a point on an edge shared by two triangles is never lost);
/// when several triangles contain it (a point on a shared edge or vertex) the lowest face index
/// is used. A grid point strictly inside the previous grid point's triangle or one of its edge
/// neighbours is taken from there without a search: the same answer for an embedding,
/// where no other triangle contains such a point (if triangles overlap, uv is no embedding and
/// that triangle wins). The value is the barycentric interpolation of the three vertex values,
/// exact for values linear in (u, v). Triangles of zero area in uv are skipped. Timing:
/// bench/shape_image_bench.cpp. Deterministic: the same input gives the same image bit for
/// bit.
/// Throws OptionError for grid sizes below 1; InputError when uv and values differ in length,
/// a face refers to a vertex outside [0, #V), or a coordinate or value is not finite.
ShapeImage harmonic_shape_image(const Eigen::Ref<const Eigen::MatrixX2d>& uv,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                const Eigen::Ref<const Eigen::VectorXd>& values,
                                const ImageOptions& options = {});

/// The 3D point of the patch under grid point `grid_index` of `image`: the barycentric
/// combination of the 3D positions (#V by 3, the patch's vertices, same indexing as the uv the
/// image was built from) of the corners of the face under it; on a planar patch mapped to the
/// disk by a similarity this is exactly the preimage of the grid point. Throws InputError when
/// grid_index is outside the grid, the grid point is not valid, or the face or its vertices are
/// outside `faces` / `positions`.
Eigen::Vector3d image_point_to_surface(const ShapeImage& image, int grid_index,
                                       const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                       const Eigen::Ref<const Eigen::MatrixX3i>& faces);

/// The best rotation between two images.
struct ImageMatch {
  /// Area-weighted Pearson correlation (see compare_images) at the best rotation, in [-1, 1];
  /// -1 when no rotation has min_overlap common valid grid points.
  double correlation = -1.0;
  /// The rotation, in degrees in [0, 360), that best carries image a onto image b: b at the
  /// point a(p) rotated counter-clockwise by angle_degrees about the disk centre matches a(p),
  /// i.e. b(R(angle) p) ~ a(p). If b was built from the patch of a with its uv rotated by
  /// +theta, angle_degrees is theta (to the nearest grid step). angle = shift * 360 / sectors.
  double angle_degrees = 0.0;
  /// The same rotation in grid steps: sector j of a ring of a is compared with sector
  /// (j + shift) mod sectors of the same ring of b.
  int shift = 0;
  /// Grid points valid in both images at that rotation.
  int overlap = 0;
};

/// The correlation of two images for every rotation (shift) of b; see compare_images.
struct RotationProfile {
  Eigen::VectorXd correlation;  ///< one value per shift (sectors); -1 where overlap < min_overlap
  Eigen::VectorXi overlap;      ///< per shift, the common valid grid points
};

/// Reused state for comparing one image with many: per ring, the discrete Fourier spectra of
/// the validity mask, of the masked values and of the masked squared values (values centred on
/// the image's area-weighted mean first, which the correlation ignores but which keeps the
/// sums well conditioned). Build it once per image and compare the prepared images; it holds
/// 3 x rings x (sectors / 2 + 1) complex numbers (70 KB for the default grid).
/// Immutable after construction, so one prepared image may be used by many threads at once.
class PreparedImage {
 public:
  /// Throws InputError when the image's arrays do not match its grid size, or a valid value is
  /// not finite.
  explicit PreparedImage(const ShapeImage& image);

  int rings() const { return rings_; }
  int sectors() const { return sectors_; }

 private:
  friend RotationProfile rotation_profile(const PreparedImage& a, const PreparedImage& b,
                                          int min_overlap);
  friend ImageMatch compare_images(const PreparedImage& a, const PreparedImage& b, int min_overlap);
  /// The correlation and overlap of this image with `b` for every shift (sectors values each),
  /// written to the two arrays. Throws as rotation_profile.
  void correlate(const PreparedImage& b, int min_overlap, double* correlation, int* overlap) const;
  int rings_;
  int sectors_;
  int bins_;                              ///< sectors / 2 + 1 (real-signal half spectrum)
  std::vector<std::uint8_t> ring_full_;   ///< 1 where every sample of the ring is valid
  std::vector<std::uint8_t> ring_empty_;  ///< 1 where no sample of the ring is valid
  double mean_square_;                    ///< weighted mean of value^2 over the valid points
  /// Half spectra (bins_ values, unscaled DFT) of three signals per ring: the mask (signal 0),
  /// mask * (value - mean) (1) and mask * (value - mean)^2 (2). Ring r, signal q starts at
  /// (3 r + q) * 2 bins_: bins_ real parts, then bins_ imaginary parts.
  std::vector<double> spectra_;
};

/// The correlation of a with b rotated by every multiple of 360 / sectors degrees (b's
/// sectors cyclically shifted, see ImageMatch::shift), over the grid points valid in both.
/// The correlation is area-weighted [choice]: every ring has the same number of samples, so a
/// sample of ring k stands for an area proportional to its radius (k + 0.5), and each sample
/// is weighted by k + 0.5 in the Pearson sums; otherwise the small inner rings would dominate.
/// A shift with fewer than min_overlap common valid points gets correlation -1; one where a or
/// b is constant over the common points (weighted standard deviation there below 1e-10 of the
/// image's weighted root mean square value, which absorbs interpolation round-off) gets 0. Throws
/// InputError when the grids differ in size.
RotationProfile rotation_profile(const PreparedImage& a, const PreparedImage& b,
                                 int min_overlap = 16);

/// The best rotation of rotation_profile(a, b, min_overlap): the largest correlation, ties
/// (within 1e-12) broken by the smallest shift. Cost: one inverse FFT of `sectors` points
/// when every ring of both images is fully valid, up to seven when rings are partial; timing in
/// bench/shape_image_bench.cpp. Allocates nothing once warm (per-thread scratch).
ImageMatch compare_images(const PreparedImage& a, const PreparedImage& b, int min_overlap = 16);

/// compare_images on images not prepared yet (prepares both: use PreparedImage when an image is
/// compared more than once). Throws InputError when the grids differ in size.
ImageMatch compare_images(const ShapeImage& a, const ShapeImage& b, int min_overlap = 16);

}  // namespace surfcomp::harmonic
