// Harmonic shape images: resampling on a polar grid (triangles found through a grid of their
// bounding boxes, CGAL's exact orientation tests), and comparison over all rotations by
// per-ring circular cross-correlations computed with FFTs (Eigen's kissfft).
#include "surfcomp/harmonic/shape_image.hpp"

#include "embedded_triangles.hpp"
#include "surfcomp/core/error.hpp"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <utility>

namespace surfcomp::harmonic {
namespace {

using detail::EmbeddedTriangles;
using detail::Kernel;

constexpr double kPi = 3.14159265358979323846;
/// A weighted variance below this times the image's mean square value counts as zero: a
/// standard deviation below 1e-10 of the root mean square (see rotation_profile).
constexpr double kConstantVariance = 1e-20;
/// Correlations within this of the best count as ties (see compare_images).
constexpr double kTie = 1e-12;

std::string grid_name(int rings, int sectors) {
  return std::to_string(rings) + " rings x " + std::to_string(sectors) + " sectors";
}

void check_grid(int rings, int sectors) {
  if (rings < 1 || sectors < 1) {
    throw OptionError(
        "shape image: the polar grid must have at least one ring "
        "and one sector, got " +
        grid_name(rings, sectors));
  }
}

/// Ring k's weight in the correlation sums: proportional to the area a sample of it stands for.
double ring_weight(int ring) { return ring + 0.5; }

/// One FFT object per thread: kissfft caches its twiddle factors per length in the object.
Eigen::FFT<double>& thread_fft() {
  thread_local Eigen::FFT<double> fft = [] {
    Eigen::FFT<double> f;
    f.SetFlag(Eigen::FFT<double>::HalfSpectrum);
    f.SetFlag(Eigen::FFT<double>::Unscaled);
    return f;
  }();
  return fft;
}

/// Throws InputError unless `values` has one finite value per embedded vertex, the embedding's
/// coordinates are finite and every face names an embedded vertex.
void check_embedding(const Eigen::Ref<const Eigen::MatrixX2d>& uv,
                     const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                     const Eigen::Ref<const Eigen::VectorXd>& values) {
  const Eigen::Index vertex_count = uv.rows();
  if (values.size() != vertex_count) {
    throw InputError("shape image: " + std::to_string(values.size()) + " values for " +
                     std::to_string(vertex_count) +
                     " embedded vertices; expected one value per vertex");
  }
  for (Eigen::Index v = 0; v < vertex_count; ++v) {
    if (!std::isfinite(uv(v, 0)) || !std::isfinite(uv(v, 1))) {
      throw InputError("shape image: embedded vertex " + std::to_string(v) +
                       " has a non-finite coordinate");
    }
    if (!std::isfinite(values(v))) {
      throw InputError("shape image: vertex " + std::to_string(v) + " has a non-finite value");
    }
  }
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      if (faces(f, c) < 0 || faces(f, c) >= vertex_count) {
        throw InputError("shape image: face " + std::to_string(f) + " refers to vertex " +
                         std::to_string(faces(f, c)) + "; expected an index in [0, " +
                         std::to_string(vertex_count) + ")");
      }
    }
  }
}

}  // namespace

Eigen::Vector2d image_grid_point(const ImageOptions& options, int grid_index) {
  check_grid(options.rings, options.sectors);
  const long long size = static_cast<long long>(options.rings) * options.sectors;
  if (grid_index < 0 || grid_index >= size) {
    throw InputError("shape image: grid point " + std::to_string(grid_index) +
                     " is outside the grid of " + std::to_string(size) + " points");
  }
  const int ring = grid_index / options.sectors;
  const int sector = grid_index % options.sectors;
  const double radius = (ring + 0.5) / options.rings;
  const double angle = 2.0 * kPi * sector / options.sectors;
  return {radius * std::cos(angle), radius * std::sin(angle)};
}

ShapeImage harmonic_shape_image(const Eigen::Ref<const Eigen::MatrixX2d>& uv,
                                const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                const Eigen::Ref<const Eigen::VectorXd>& values,
                                const ImageOptions& options) {
  check_grid(options.rings, options.sectors);
  check_embedding(uv, faces, values);
  const EmbeddedTriangles triangles(uv, faces);
  const int size = options.rings * options.sectors;
  ShapeImage image;
  image.rings = options.rings;
  image.sectors = options.sectors;
  image.values = Eigen::VectorXd::Zero(size);
  image.valid.assign(static_cast<std::size_t>(size), 0);
  image.face = Eigen::VectorXi::Constant(size, -1);
  image.barycentric = Eigen::MatrixX3d::Zero(size, 3);
  if (triangles.size() == 0) return image;

  // Neighbouring grid points mostly fall into the same triangle or one next to it: try the
  // previous point's triangle and its edge neighbours first, and accept one only when the point
  // is strictly inside it, where no other triangle of an embedding can contain it; otherwise
  // search the grid.
  // The grid's directions, computed as in image_grid_point (so the points are bit-identical).
  std::vector<Eigen::Vector2d> direction(static_cast<std::size_t>(options.sectors));
  for (int j = 0; j < options.sectors; ++j) {
    const double angle = 2.0 * kPi * j / options.sectors;
    direction[static_cast<std::size_t>(j)] = {std::cos(angle), std::sin(angle)};
  }
  const std::size_t none = triangles.size();
  std::size_t previous = none;
  for (int i = 0; i < size; ++i) {
    const int ring = i / options.sectors;
    const double radius = (ring + 0.5) / options.rings;
    const Eigen::Vector2d& d = direction[static_cast<std::size_t>(i % options.sectors)];
    const Eigen::Vector2d q(radius * d.x(), radius * d.y());
    const Kernel::Point_2 q2(q.x(), q.y());
    std::size_t found = previous < none ? triangles.strictly_inside_or_beside(previous, q2) : none;
    if (found == none) found = triangles.locate(q2);
    if (found == none) continue;
    previous = found;
    const int face = triangles.face(found);
    const Eigen::Vector2d p0 = uv.row(faces(face, 0)).transpose();
    const Eigen::Vector2d p1 = uv.row(faces(face, 1)).transpose();
    const Eigen::Vector2d p2 = uv.row(faces(face, 2)).transpose();
    auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      return a.x() * b.y() - a.y() * b.x();
    };
    const double area = cross(p1 - p0, p2 - p0);
    const double l0 = cross(p1 - q, p2 - q) / area;
    const double l1 = cross(p2 - q, p0 - q) / area;
    const double l2 = 1.0 - l0 - l1;
    image.valid[static_cast<std::size_t>(i)] = 1;
    image.face(i) = face;
    image.barycentric.row(i) << l0, l1, l2;
    image.values(i) =
        l0 * values(faces(face, 0)) + l1 * values(faces(face, 1)) + l2 * values(faces(face, 2));
  }
  return image;
}

Eigen::Vector3d image_point_to_surface(const ShapeImage& image, int grid_index,
                                       const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                       const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  const long long size = static_cast<long long>(image.rings) * image.sectors;
  if (grid_index < 0 || grid_index >= size || image.face.size() != size ||
      image.barycentric.rows() != size) {
    throw InputError("shape image: grid point " + std::to_string(grid_index) +
                     " is outside the image's grid of " + std::to_string(size) + " points");
  }
  const int face = image.face(grid_index);
  if (face < 0) {
    throw InputError("shape image: grid point " + std::to_string(grid_index) +
                     " is not valid (no triangle under it)");
  }
  if (face >= faces.rows()) {
    throw InputError("shape image: grid point " + std::to_string(grid_index) + " lies on face " +
                     std::to_string(face) + " but the patch has " + std::to_string(faces.rows()) +
                     " faces");
  }
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c) {
    const int v = faces(face, c);
    if (v < 0 || v >= positions.rows()) {
      throw InputError("shape image: face " + std::to_string(face) + " refers to vertex " +
                       std::to_string(v) + " but there are " + std::to_string(positions.rows()) +
                       " positions");
    }
    point += image.barycentric(grid_index, c) * positions.row(v).transpose();
  }
  return point;
}

PreparedImage::PreparedImage(const ShapeImage& image)
    : rings_(image.rings), sectors_(image.sectors) {
  check_grid(rings_, sectors_);
  const int n = sectors_;
  const int size = rings_ * n;
  if (image.values.size() != size || image.valid.size() != static_cast<std::size_t>(size)) {
    throw InputError("shape image: " + std::to_string(image.values.size()) + " values and " +
                     std::to_string(image.valid.size()) + " validity flags for a grid of " +
                     grid_name(rings_, sectors_));
  }
  bins_ = n / 2 + 1;
  ring_full_.assign(static_cast<std::size_t>(rings_), 0);
  ring_empty_.assign(static_cast<std::size_t>(rings_), 0);
  spectra_.assign(static_cast<std::size_t>(rings_) * 6 * static_cast<std::size_t>(bins_), 0.0);

  // Area-weighted mean over the valid points: subtracting it changes no correlation but keeps
  // the sums of squares small.
  double weight_sum = 0.0, value_sum = 0.0, square_sum = 0.0;
  for (int i = 0; i < size; ++i) {
    if (!image.valid[static_cast<std::size_t>(i)]) continue;
    if (!std::isfinite(image.values(i))) {
      throw InputError("shape image: grid point " + std::to_string(i) +
                       " is valid but has a non-finite value");
    }
    weight_sum += ring_weight(i / n);
    value_sum += ring_weight(i / n) * image.values(i);
    square_sum += ring_weight(i / n) * image.values(i) * image.values(i);
  }
  const double mean = weight_sum > 0.0 ? value_sum / weight_sum : 0.0;
  mean_square_ = weight_sum > 0.0 ? square_sum / weight_sum : 0.0;

  Eigen::FFT<double>& fft = thread_fft();
  std::array<std::vector<double>, 3> signal;
  for (auto& s : signal) s.resize(static_cast<std::size_t>(n));
  std::vector<std::complex<double>> spectrum(static_cast<std::size_t>(bins_));
  for (int r = 0; r < rings_; ++r) {
    int valid_count = 0;
    for (int j = 0; j < n; ++j) {
      const int i = r * n + j;
      const bool valid = image.valid[static_cast<std::size_t>(i)] != 0;
      const double x = valid ? image.values(i) - mean : 0.0;
      signal[0][static_cast<std::size_t>(j)] = valid ? 1.0 : 0.0;
      signal[1][static_cast<std::size_t>(j)] = x;
      signal[2][static_cast<std::size_t>(j)] = x * x;
      valid_count += valid ? 1 : 0;
    }
    ring_full_[static_cast<std::size_t>(r)] = valid_count == n ? 1 : 0;
    ring_empty_[static_cast<std::size_t>(r)] = valid_count == 0 ? 1 : 0;
    for (int q = 0; q < 3; ++q) {
      double* out = spectra_.data() + static_cast<std::size_t>((3 * r + q) * 2 * bins_);
      if (q == 0 && (valid_count == n || valid_count == 0)) {
        // The exact spectrum of a constant mask: n (or 0) at frequency 0, nothing elsewhere.
        out[0] = valid_count;
        continue;
      }
      fft.fwd(spectrum.data(), signal[static_cast<std::size_t>(q)].data(), n);
      for (int k = 0; k < bins_; ++k) {
        out[k] = spectrum[static_cast<std::size_t>(k)].real();
        out[bins_ + k] = spectrum[static_cast<std::size_t>(k)].imag();
      }
    }
  }
}

void PreparedImage::correlate(const PreparedImage& b, int min_overlap, double* correlation,
                              int* overlap) const {
  const PreparedImage& a = *this;
  if (a.rings_ != b.rings_ || a.sectors_ != b.sectors_) {
    throw InputError("compare shape images: grids of " + grid_name(a.rings_, a.sectors_) + " and " +
                     grid_name(b.rings_, b.sectors_) + "; expected equal grids");
  }
  if (min_overlap < 1) {
    throw OptionError("compare shape images: min_overlap is " + std::to_string(min_overlap) +
                      "; expected at least 1");
  }
  const int n = a.sectors_;
  const int bins = a.bins_;
  // Sums over the common valid points, for every shift s at once: sum_j x_j y_(j+s) over a
  // ring is the inverse DFT of conj(X_k) Y_k. With ma, mb the masks and a, b the masked centred
  // values: weight (0), a (1), a^2 (2), b (3), b^2 (4), a b (5), all weighted by ring, and the
  // unweighted point count (6).
  enum Sum { kWeight, kA, kAA, kB, kBB, kAB, kCount, kSums };
  // Per-thread scratch, so that a comparison allocates nothing once warm: the real and
  // imaginary parts of each sum's spectrum (2 bins per sum), then each sum for every shift (n).
  thread_local std::vector<double> scratch;
  thread_local std::vector<std::complex<double>> spectrum;
  const std::size_t spectra_size =
      static_cast<std::size_t>(kSums) * 2 * static_cast<std::size_t>(bins);
  scratch.resize(spectra_size + static_cast<std::size_t>(kSums * n));
  std::fill(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(spectra_size), 0.0);
  spectrum.resize(static_cast<std::size_t>(bins));
  auto spectrum_re = [&](int t) { return scratch.data() + static_cast<std::size_t>(2 * t * bins); };
  auto spectrum_im = [&](int t) { return spectrum_re(t) + bins; };
  auto sums = [&](int t) {
    return scratch.data() + spectra_size + static_cast<std::size_t>(t * n);
  };
  // A sum whose spectrum stayed zero beyond frequency 0 is the same for every shift.
  std::array<bool, kSums> varies{};

  // Spectrum of sum t, bins k in [0, end): += w * conj(X_k) Y_k.
  auto accumulate = [&](Sum t, const double* x, const double* y, double w, int end) {
    double* out_re = spectrum_re(t);
    double* out_im = spectrum_im(t);
    const double* x_im = x + bins;
    const double* y_im = y + bins;
    for (int k = 0; k < end; ++k) {
      out_re[k] += w * (x[k] * y[k] + x_im[k] * y_im[k]);
      out_im[k] += w * (x[k] * y_im[k] - x_im[k] * y[k]);
    }
    if (end > 1) varies[t] = true;
  };

  const std::ptrdiff_t part = 2 * static_cast<std::ptrdiff_t>(bins);  // one spectrum, re and im
  for (int r = 0; r < a.rings_; ++r) {
    const auto ru = static_cast<std::size_t>(r);
    if (a.ring_empty_[ru] || b.ring_empty_[ru]) continue;
    const double w = ring_weight(r);
    const double* ma = a.spectra_.data() + static_cast<std::size_t>(6 * r * bins);
    const double* xa = ma + part;
    const double* sa = xa + part;
    const double* mb = b.spectra_.data() + static_cast<std::size_t>(6 * r * bins);
    const double* xb = mb + part;
    const double* sb = xb + part;
    // A full ring's mask spectrum is zero beyond frequency 0, so its products need only k = 0.
    const int a_mask_end = a.ring_full_[ru] ? 1 : bins;
    const int b_mask_end = b.ring_full_[ru] ? 1 : bins;
    const int both_mask_end = std::min(a_mask_end, b_mask_end);
    accumulate(kWeight, ma, mb, w, both_mask_end);
    accumulate(kA, xa, mb, w, b_mask_end);
    accumulate(kAA, sa, mb, w, b_mask_end);
    accumulate(kB, ma, xb, w, a_mask_end);
    accumulate(kBB, ma, sb, w, a_mask_end);
    accumulate(kAB, xa, xb, w, bins);
    accumulate(kCount, ma, mb, 1.0, both_mask_end);
  }

  // Back to shifts: sums[t][s] = (1/n) sum_k conj(X_k) Y_k exp(2 pi i k s / n).
  Eigen::FFT<double>& fft = thread_fft();
  const double inv_n = 1.0 / n;
  for (int t = 0; t < kSums; ++t) {
    double* out = sums(t);
    if (!varies[static_cast<std::size_t>(t)]) {
      std::fill(out, out + n, spectrum_re(t)[0] * inv_n);
      continue;
    }
    for (int k = 0; k < bins; ++k)
      spectrum[static_cast<std::size_t>(k)] = {spectrum_re(t)[k], spectrum_im(t)[k]};
    fft.inv(out, spectrum.data(), n);
    for (int s = 0; s < n; ++s) out[s] *= inv_n;
  }

  const double* count_sum = sums(kCount);
  const double *weight_sum = sums(kWeight), *a_sum = sums(kA), *aa_sum = sums(kAA),
               *b_sum = sums(kB), *bb_sum = sums(kBB), *ab_sum = sums(kAB);
  for (int s = 0; s < n; ++s) {
    // Counts are integers; the FFT returns them to within far less than 0.5.
    const int count = static_cast<int>(std::lround(count_sum[s]));
    overlap[s] = count;
    if (count < min_overlap) {
      correlation[s] = -1.0;
      continue;
    }
    const double weight = weight_sum[s], inv_weight = 1.0 / weight;
    const double sa = a_sum[s], sb = b_sum[s];
    const double var_a = aa_sum[s] - sa * sa * inv_weight;
    const double var_b = bb_sum[s] - sb * sb * inv_weight;
    if (var_a <= kConstantVariance * weight * a.mean_square_ ||
        var_b <= kConstantVariance * weight * b.mean_square_) {
      correlation[s] = 0.0;
      continue;
    }
    const double covariance = ab_sum[s] - sa * sb * inv_weight;
    correlation[s] = std::clamp(covariance / std::sqrt(var_a * var_b), -1.0, 1.0);
  }
}

RotationProfile rotation_profile(const PreparedImage& a, const PreparedImage& b, int min_overlap) {
  RotationProfile profile;
  profile.correlation.resize(b.sectors_);
  profile.overlap.resize(b.sectors_);
  a.correlate(b, min_overlap, profile.correlation.data(), profile.overlap.data());
  return profile;
}

ImageMatch compare_images(const PreparedImage& a, const PreparedImage& b, int min_overlap) {
  thread_local std::vector<double> correlation;
  thread_local std::vector<int> overlap;
  const int n = b.sectors_;
  correlation.resize(static_cast<std::size_t>(n));
  overlap.resize(static_cast<std::size_t>(n));
  a.correlate(b, min_overlap, correlation.data(), overlap.data());
  const double best = *std::max_element(correlation.begin(), correlation.end());
  ImageMatch match;
  for (int s = 0; s < n; ++s) {
    if (correlation[static_cast<std::size_t>(s)] >= best - kTie) {
      match.correlation = correlation[static_cast<std::size_t>(s)];
      match.shift = s;
      match.angle_degrees = 360.0 * s / n;
      match.overlap = overlap[static_cast<std::size_t>(s)];
      break;
    }
  }
  return match;
}

ImageMatch compare_images(const ShapeImage& a, const ShapeImage& b, int min_overlap) {
  return compare_images(PreparedImage(a), PreparedImage(b), min_overlap);
}

}  // namespace surfcomp::harmonic
