// Harmonic shape images: resampling on a polar grid (triangles found through a
// grid of their bounding boxes, CGAL's exact orientation tests), and comparison
// over all rotations by per-ring circular cross-correlations computed with FFTs
// (Eigen's kissfft).
#include "surfcomp/harmonic/shape_image.hpp"

#include "surfcomp/core/error.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
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

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

constexpr double kPi = 3.14159265358979323846;
/// A weighted variance below this times the image's mean square value counts as
/// zero: a standard deviation below 1e-10 of the root mean square (see
/// rotation_profile).
constexpr double kConstantVariance = 1e-20;
/// Correlations within this of the best count as ties (see compare_images).
constexpr double kTie = 1e-12;

std::string grid_name(int rings, int sectors) {
  return std::to_string(rings) + " rings x " + std::to_string(sectors) +
         " sectors";
}

void check_grid(int rings, int sectors) {
  if (rings < 1 || sectors < 1) {
    throw OptionError("shape image: the polar grid must have at least one ring "
                      "and one sector, got " +
                      grid_name(rings, sectors));
  }
}

/// Ring k's weight in the correlation sums: proportional to the area a sample
/// of it stands for.
double ring_weight(int ring) { return ring + 0.5; }

/// One FFT object per thread: kissfft caches its twiddle factors per length in
/// the object.
Eigen::FFT<double> &thread_fft() {
  thread_local Eigen::FFT<double> fft = [] {
    Eigen::FFT<double> f;
    f.SetFlag(Eigen::FFT<double>::HalfSpectrum);
    f.SetFlag(Eigen::FFT<double>::Unscaled);
    return f;
  }();
  return fft;
}

/// Plane triangles listed in the cells of a uniform grid over their common
/// bounding box, each in every cell its own bounding box overlaps: a cell lists
/// every triangle that may contain a point of it, by increasing index.
class TriangleBins {
public:
  /// `boxes`: per triangle its x min, x max, y min, y max.
  explicit TriangleBins(const std::vector<std::array<double, 4>> &boxes) {
    lo_ = {boxes[0][0], boxes[0][2]};
    hi_ = {boxes[0][1], boxes[0][3]};
    for (const auto &b : boxes) {
      lo_ = {std::min(lo_[0], b[0]), std::min(lo_[1], b[2])};
      hi_ = {std::max(hi_[0], b[1]), std::max(hi_[1], b[3])};
    }
    // About two triangles per cell.
    side_ = std::max(1, static_cast<int>(std::ceil(std::sqrt(
                            0.5 * static_cast<double>(boxes.size())))));
    for (int axis = 0; axis < 2; ++axis) {
      inverse_[axis] =
          hi_[axis] > lo_[axis] ? side_ / (hi_[axis] - lo_[axis]) : 0.0;
    }
    offsets_.assign(static_cast<std::size_t>(side_) * side_ + 1, 0);
    std::vector<std::array<int, 4>> ranges(
        boxes.size()); // first and last cell along x, y
    for (std::size_t t = 0; t < boxes.size(); ++t) {
      const auto &b = boxes[t];
      ranges[t] = {cell(b[0], 0), cell(b[1], 0), cell(b[2], 1), cell(b[3], 1)};
      for (int i = ranges[t][0]; i <= ranges[t][1]; ++i) {
        for (int j = ranges[t][2]; j <= ranges[t][3]; ++j)
          ++offsets_[i * side_ + j + 1];
      }
    }
    for (std::size_t c = 1; c < offsets_.size(); ++c)
      offsets_[c] += offsets_[c - 1];
    listed_.resize(static_cast<std::size_t>(offsets_.back()));
    std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
    for (std::size_t t = 0; t < boxes.size(); ++t) {
      for (int i = ranges[t][0]; i <= ranges[t][1]; ++i) {
        for (int j = ranges[t][2]; j <= ranges[t][3]; ++j) {
          listed_[static_cast<std::size_t>(fill[i * side_ + j]++)] =
              static_cast<int>(t);
        }
      }
    }
  }

  /// Calls visit(t) for the triangles listed in the cell of q, by increasing
  /// index, until visit returns true; nothing when q lies outside the bounding
  /// box.
  template <class Visit>
  void for_each_candidate(double x, double y, Visit &&visit) const {
    if (!(x >= lo_[0] && x <= hi_[0] && y >= lo_[1] && y <= hi_[1]))
      return;
    const int c = cell(x, 0) * side_ + cell(y, 1);
    for (int k = offsets_[c]; k < offsets_[c + 1]; ++k) {
      if (visit(listed_[static_cast<std::size_t>(k)]))
        return;
    }
  }

private:
  /// The cell along `axis` holding coordinate v, clamped to the grid;
  /// non-decreasing in v, so a point inside a box falls between the cells of
  /// the box's ends.
  int cell(double v, int axis) const {
    const double c = std::floor((v - lo_[axis]) * inverse_[axis]);
    return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(side_ - 1)));
  }

  std::array<double, 2> lo_{}, hi_{}, inverse_{};
  int side_ = 1;
  std::vector<int>
      offsets_; ///< cell c lists listed_[offsets_[c] .. offsets_[c + 1])
  std::vector<int> listed_;
};

/// Throws InputError unless `values` has one finite value per embedded vertex,
/// the embedding's coordinates are finite and every face names an embedded
/// vertex.
void check_embedding(const Eigen::Ref<const Eigen::MatrixX2d> &uv,
                     const Eigen::Ref<const Eigen::MatrixX3i> &faces,
                     const Eigen::Ref<const Eigen::VectorXd> &values) {
  const Eigen::Index vertex_count = uv.rows();
  if (values.size() != vertex_count) {
    throw InputError("shape image: " + std::to_string(values.size()) +
                     " values for " + std::to_string(vertex_count) +
                     " embedded vertices; expected one value per vertex");
  }
  for (Eigen::Index v = 0; v < vertex_count; ++v) {
    if (!std::isfinite(uv(v, 0)) || !std::isfinite(uv(v, 1))) {
      throw InputError("shape image: embedded vertex " + std::to_string(v) +
                       " has a non-finite coordinate");
    }
    if (!std::isfinite(values(v))) {
      throw InputError("shape image: vertex " + std::to_string(v) +
                       " has a non-finite value");
    }
  }
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      if (faces(f, c) < 0 || faces(f, c) >= vertex_count) {
        throw InputError("shape image: face " + std::to_string(f) +
                         " refers to vertex " + std::to_string(faces(f, c)) +
                         "; expected an index in [0, " +
                         std::to_string(vertex_count) + ")");
      }
    }
  }
}

/// The triangles of an embedding in the plane that have non-zero area, in face
/// order, and where a point falls among them, by CGAL's exact orientation
/// predicates.
class EmbeddedTriangles {
public:
  EmbeddedTriangles(const Eigen::Ref<const Eigen::MatrixX2d> &uv,
                    const Eigen::Ref<const Eigen::MatrixX3i> &faces) {
    corners_.reserve(static_cast<std::size_t>(faces.rows()));
    face_.reserve(static_cast<std::size_t>(faces.rows()));
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      std::array<Kernel::Point_2, 3> c;
      for (std::size_t k = 0; k < 3; ++k) {
        const Eigen::Index v = faces(f, static_cast<Eigen::Index>(k));
        c[k] = Kernel::Point_2(uv(v, 0), uv(v, 1));
      }
      if (CGAL::collinear(c[0], c[1], c[2]))
        continue;
      corners_.push_back(c);
      face_.push_back(static_cast<int>(f));
    }
    if (corners_.empty())
      return;
    turn_.resize(size());
    box_.resize(size()); // x min, x max, y min, y max
    for (std::size_t t = 0; t < size(); ++t) {
      const auto &c = corners_[t];
      turn_[t] = CGAL::orientation(c[0], c[1], c[2]);
      box_[t] = {std::min({c[0].x(), c[1].x(), c[2].x()}),
                 std::max({c[0].x(), c[1].x(), c[2].x()}),
                 std::min({c[0].y(), c[1].y(), c[2].y()}),
                 std::max({c[0].y(), c[1].y(), c[2].y()})};
    }
    bins_.emplace(box_);
    link_neighbours(faces, uv.rows());
  }

  std::size_t size() const { return corners_.size(); }
  /// The face of triangle t.
  int face(std::size_t t) const { return face_[t]; }

  /// Triangle t, or the first of its edge neighbours, that holds q strictly
  /// inside (not on its edges), where no other triangle of an embedding can
  /// hold it; size() when none does.
  std::size_t strictly_inside_or_beside(std::size_t t,
                                        const Kernel::Point_2 &q) const {
    if (strictly_inside(t, q))
      return t;
    for (const int n : neighbour_[t]) {
      if (n >= 0 && strictly_inside(static_cast<std::size_t>(n), q))
        return static_cast<std::size_t>(n);
    }
    return size();
  }

  /// The lowest triangle containing q, or size() when none does: the bins'
  /// candidates by increasing index, screened by their bounding boxes before
  /// the exact tests.
  std::size_t locate(const Kernel::Point_2 &q) const {
    std::size_t found = size();
    bins_->for_each_candidate(q.x(), q.y(), [&](int index) {
      const auto t = static_cast<std::size_t>(index);
      const auto &b = box_[t];
      if (q.x() >= b[0] && q.x() <= b[1] && q.y() >= b[2] && q.y() <= b[3] &&
          contains(t, q)) {
        found = t;
        return true;
      }
      return false;
    });
    return found;
  }

private:
  /// The orientations of q against triangle t's three edges.
  std::array<CGAL::Orientation, 3> sides(std::size_t t,
                                         const Kernel::Point_2 &q) const {
    const auto &c = corners_[t];
    return {CGAL::orientation(c[0], c[1], q), CGAL::orientation(c[1], c[2], q),
            CGAL::orientation(c[2], c[0], q)};
  }
  /// True when q lies strictly inside triangle t (not on its edges).
  bool strictly_inside(std::size_t t, const Kernel::Point_2 &q) const {
    const auto s = sides(t, q);
    return s[0] == turn_[t] && s[1] == turn_[t] && s[2] == turn_[t];
  }
  /// True when q lies in the closed triangle t: no edge has q on the other
  /// side.
  bool contains(std::size_t t, const Kernel::Point_2 &q) const {
    const auto s = sides(t, q);
    const CGAL::Orientation other = CGAL::opposite(turn_[t]);
    return s[0] != other && s[1] != other && s[2] != other;
  }

  /// Triangles sharing an edge (as vertex pairs): up to three neighbours per
  /// triangle, -1 where none. An edge's first triangle (in triangle and side
  /// order) is linked with each later one.
  void link_neighbours(const Eigen::Ref<const Eigen::MatrixX3i> &faces,
                       Eigen::Index vertex_count) {
    neighbour_.assign(size(), {-1, -1, -1});
    // The triangle sides grouped by their lower vertex, in triangle and side
    // order.
    std::vector<int> first(static_cast<std::size_t>(vertex_count) + 1, 0);
    for (std::size_t t = 0; t < size(); ++t) {
      for (int side = 0; side < 3; ++side) {
        const Eigen::Index f = face_[t];
        ++first[static_cast<std::size_t>(
                    std::min(faces(f, side), faces(f, (side + 1) % 3))) +
                1];
      }
    }
    for (std::size_t v = 1; v < first.size(); ++v)
      first[v] += first[v - 1];
    struct Side {
      int high, triangle, side;
    };
    std::vector<Side> sides_of(static_cast<std::size_t>(first.back()));
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t < size(); ++t) {
      const Eigen::Index f = face_[t];
      for (int side = 0; side < 3; ++side) {
        const int a = faces(f, side), b = faces(f, (side + 1) % 3);
        const int low = std::min(a, b), high = std::max(a, b);
        const int begin = first[static_cast<std::size_t>(low)];
        int &end = fill[static_cast<std::size_t>(low)];
        for (int k = begin; k < end; ++k) {
          const Side &owner = sides_of[static_cast<std::size_t>(k)];
          if (owner.high != high)
            continue;
          neighbour_[t][static_cast<std::size_t>(side)] = owner.triangle;
          neighbour_[static_cast<std::size_t>(owner.triangle)]
                    [static_cast<std::size_t>(owner.side)] =
                        static_cast<int>(t);
          break;
        }
        sides_of[static_cast<std::size_t>(end++)] =
            Side{high, static_cast<int>(t), side};
      }
    }
  }

  std::vector<std::array<Kernel::Point_2, 3>> corners_;
  std::vector<int> face_; ///< the face of each triangle
  std::vector<CGAL::Orientation> turn_;
  std::vector<std::array<double, 4>> box_;
  std::optional<TriangleBins> bins_;
  std::vector<std::array<int, 3>> neighbour_;
};

} // namespace

Eigen::Vector2d image_grid_point(const ImageOptions &options, int grid_index) {
  check_grid(options.rings, options.sectors);
  const long long size =
      static_cast<long long>(options.rings) * options.sectors;
  if (grid_index < 0 || grid_index >= size) {
    throw InputError("shape image: grid point " + std::to_string(grid_index) +
                     " is outside the grid of " + std::to_string(size) +
                     " points");
  }
  const int ring = grid_index / options.sectors;
  const int sector = grid_index % options.sectors;
  const double radius = (ring + 0.5) / options.rings;
  const double angle = 2.0 * kPi * sector / options.sectors;
  return {radius * std::cos(angle), radius * std::sin(angle)};
}

ShapeImage harmonic_shape_image(const Eigen::Ref<const Eigen::MatrixX2d> &uv,
                                const Eigen::Ref<const Eigen::MatrixX3i> &faces,
                                const Eigen::Ref<const Eigen::VectorXd> &values,
                                const ImageOptions &options) {
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
  if (triangles.size() == 0)
    return image;

  // Neighbouring grid points mostly fall into the same triangle or one next to
  // it: try the previous point's triangle and its edge neighbours first, and
  // accept one only when the point is strictly inside it, where no other
  // triangle of an embedding can contain it; otherwise search the grid. The
  // grid's directions, computed as in image_grid_point (so the points are
  // bit-identical).
  std::vector<Eigen::Vector2d> direction(
      static_cast<std::size_t>(options.sectors));
  for (int j = 0; j < options.sectors; ++j) {
    const double angle = 2.0 * kPi * j / options.sectors;
    direction[static_cast<std::size_t>(j)] = {std::cos(angle), std::sin(angle)};
  }
  const std::size_t none = triangles.size();
  std::size_t previous = none;
  for (int i = 0; i < size; ++i) {
    const int ring = i / options.sectors;
    const double radius = (ring + 0.5) / options.rings;
    const Eigen::Vector2d &d =
        direction[static_cast<std::size_t>(i % options.sectors)];
    const Eigen::Vector2d q(radius * d.x(), radius * d.y());
    const Kernel::Point_2 q2(q.x(), q.y());
    std::size_t found = previous < none
                            ? triangles.strictly_inside_or_beside(previous, q2)
                            : none;
    if (found == none)
      found = triangles.locate(q2);
    if (found == none)
      continue;
    previous = found;
    const int face = triangles.face(found);
    const Eigen::Vector2d p0 = uv.row(faces(face, 0)).transpose();
    const Eigen::Vector2d p1 = uv.row(faces(face, 1)).transpose();
    const Eigen::Vector2d p2 = uv.row(faces(face, 2)).transpose();
    auto cross = [](const Eigen::Vector2d &a, const Eigen::Vector2d &b) {
      return a.x() * b.y() - a.y() * b.x();
    };
    const double area = cross(p1 - p0, p2 - p0);
    const double l0 = cross(p1 - q, p2 - q) / area;
    const double l1 = cross(p2 - q, p0 - q) / area;
    const double l2 = 1.0 - l0 - l1;
    image.valid[static_cast<std::size_t>(i)] = 1;
    image.face(i) = face;
    image.barycentric.row(i) << l0, l1, l2;
    image.values(i) = l0 * values(faces(face, 0)) +
                      l1 * values(faces(face, 1)) + l2 * values(faces(face, 2));
  }
  return image;
}

Eigen::Vector3d
image_point_to_surface(const ShapeImage &image, int grid_index,
                       const Eigen::Ref<const Eigen::MatrixX3d> &positions,
                       const Eigen::Ref<const Eigen::MatrixX3i> &faces) {
  const long long size = static_cast<long long>(image.rings) * image.sectors;
  if (grid_index < 0 || grid_index >= size || image.face.size() != size ||
      image.barycentric.rows() != size) {
    throw InputError("shape image: grid point " + std::to_string(grid_index) +
                     " is outside the image's grid of " + std::to_string(size) +
                     " points");
  }
  const int face = image.face(grid_index);
  if (face < 0) {
    throw InputError("shape image: grid point " + std::to_string(grid_index) +
                     " is not valid (no triangle under it)");
  }
  if (face >= faces.rows()) {
    throw InputError("shape image: grid point " + std::to_string(grid_index) +
                     " lies on face " + std::to_string(face) +
                     " but the patch has " + std::to_string(faces.rows()) +
                     " faces");
  }
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c) {
    const int v = faces(face, c);
    if (v < 0 || v >= positions.rows()) {
      throw InputError("shape image: face " + std::to_string(face) +
                       " refers to vertex " + std::to_string(v) +
                       " but there are " + std::to_string(positions.rows()) +
                       " positions");
    }
    point += image.barycentric(grid_index, c) * positions.row(v).transpose();
  }
  return point;
}

PreparedImage::PreparedImage(const ShapeImage &image)
    : rings_(image.rings), sectors_(image.sectors) {
  check_grid(rings_, sectors_);
  const int n = sectors_;
  const int size = rings_ * n;
  if (image.values.size() != size ||
      image.valid.size() != static_cast<std::size_t>(size)) {
    throw InputError("shape image: " + std::to_string(image.values.size()) +
                     " values and " + std::to_string(image.valid.size()) +
                     " validity flags for a grid of " +
                     grid_name(rings_, sectors_));
  }
  bins_ = n / 2 + 1;
  ring_full_.assign(static_cast<std::size_t>(rings_), 0);
  ring_empty_.assign(static_cast<std::size_t>(rings_), 0);
  spectra_.assign(static_cast<std::size_t>(rings_) * 6 *
                      static_cast<std::size_t>(bins_),
                  0.0);

  // Area-weighted mean over the valid points: subtracting it changes no
  // correlation but keeps the sums of squares small.
  double weight_sum = 0.0, value_sum = 0.0, square_sum = 0.0;
  for (int i = 0; i < size; ++i) {
    if (!image.valid[static_cast<std::size_t>(i)])
      continue;
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

  Eigen::FFT<double> &fft = thread_fft();
  std::array<std::vector<double>, 3> signal;
  for (auto &s : signal)
    s.resize(static_cast<std::size_t>(n));
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
      double *out =
          spectra_.data() + static_cast<std::size_t>((3 * r + q) * 2 * bins_);
      if (q == 0 && (valid_count == n || valid_count == 0)) {
        // The exact spectrum of a constant mask: n (or 0) at frequency 0,
        // nothing elsewhere.
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

void PreparedImage::correlate(const PreparedImage &b, int min_overlap,
                              double *correlation, int *overlap) const {
  const PreparedImage &a = *this;
  if (a.rings_ != b.rings_ || a.sectors_ != b.sectors_) {
    throw InputError(
        "compare shape images: grids of " + grid_name(a.rings_, a.sectors_) +
        " and " + grid_name(b.rings_, b.sectors_) + "; expected equal grids");
  }
  if (min_overlap < 1) {
    throw OptionError("compare shape images: min_overlap is " +
                      std::to_string(min_overlap) + "; expected at least 1");
  }
  const int n = a.sectors_;
  const int bins = a.bins_;
  // Sums over the common valid points, for every shift s at once: sum_j x_j
  // y_(j+s) over a ring is the inverse DFT of conj(X_k) Y_k. With ma, mb the
  // masks and a, b the masked centred values: weight (0), a (1), a^2 (2), b
  // (3), b^2 (4), a b (5), all weighted by ring, and the unweighted point count
  // (6).
  enum Sum { kWeight, kA, kAA, kB, kBB, kAB, kCount, kSums };
  // Per-thread scratch, so that a comparison allocates nothing once warm: the
  // real and imaginary parts of each sum's spectrum (2 bins per sum), then each
  // sum for every shift (n).
  thread_local std::vector<double> scratch;
  thread_local std::vector<std::complex<double>> spectrum;
  const std::size_t spectra_size =
      static_cast<std::size_t>(kSums) * 2 * static_cast<std::size_t>(bins);
  scratch.resize(spectra_size + static_cast<std::size_t>(kSums * n));
  std::fill(scratch.begin(),
            scratch.begin() + static_cast<std::ptrdiff_t>(spectra_size), 0.0);
  spectrum.resize(static_cast<std::size_t>(bins));
  auto spectrum_re = [&](int t) {
    return scratch.data() + static_cast<std::size_t>(2 * t * bins);
  };
  auto spectrum_im = [&](int t) { return spectrum_re(t) + bins; };
  auto sums = [&](int t) {
    return scratch.data() + spectra_size + static_cast<std::size_t>(t * n);
  };
  // A sum whose spectrum stayed zero beyond frequency 0 is the same for every
  // shift.
  std::array<bool, kSums> varies{};

  // Spectrum of sum t, bins k in [0, end): += w * conj(X_k) Y_k.
  auto accumulate = [&](Sum t, const double *x, const double *y, double w,
                        int end) {
    double *out_re = spectrum_re(t);
    double *out_im = spectrum_im(t);
    const double *x_im = x + bins;
    const double *y_im = y + bins;
    for (int k = 0; k < end; ++k) {
      out_re[k] += w * (x[k] * y[k] + x_im[k] * y_im[k]);
      out_im[k] += w * (x[k] * y_im[k] - x_im[k] * y[k]);
    }
    if (end > 1)
      varies[t] = true;
  };

  const std::ptrdiff_t part =
      2 * static_cast<std::ptrdiff_t>(bins); // one spectrum, re and im
  for (int r = 0; r < a.rings_; ++r) {
    const auto ru = static_cast<std::size_t>(r);
    if (a.ring_empty_[ru] || b.ring_empty_[ru])
      continue;
    const double w = ring_weight(r);
    const double *ma =
        a.spectra_.data() + static_cast<std::size_t>(6 * r * bins);
    const double *xa = ma + part;
    const double *sa = xa + part;
    const double *mb =
        b.spectra_.data() + static_cast<std::size_t>(6 * r * bins);
    const double *xb = mb + part;
    const double *sb = xb + part;
    // A full ring's mask spectrum is zero beyond frequency 0, so its products
    // need only k = 0.
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
  Eigen::FFT<double> &fft = thread_fft();
  const double inv_n = 1.0 / n;
  for (int t = 0; t < kSums; ++t) {
    double *out = sums(t);
    if (!varies[static_cast<std::size_t>(t)]) {
      std::fill(out, out + n, spectrum_re(t)[0] * inv_n);
      continue;
    }
    for (int k = 0; k < bins; ++k)
      spectrum[static_cast<std::size_t>(k)] = {spectrum_re(t)[k],
                                               spectrum_im(t)[k]};
    fft.inv(out, spectrum.data(), n);
    for (int s = 0; s < n; ++s)
      out[s] *= inv_n;
  }

  const double *count_sum = sums(kCount);
  const double *weight_sum = sums(kWeight), *a_sum = sums(kA),
               *aa_sum = sums(kAA), *b_sum = sums(kB), *bb_sum = sums(kBB),
               *ab_sum = sums(kAB);
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
    correlation[s] =
        std::clamp(covariance / std::sqrt(var_a * var_b), -1.0, 1.0);
  }
}

RotationProfile rotation_profile(const PreparedImage &a, const PreparedImage &b,
                                 int min_overlap) {
  RotationProfile profile;
  profile.correlation.resize(b.sectors_);
  profile.overlap.resize(b.sectors_);
  a.correlate(b, min_overlap, profile.correlation.data(),
              profile.overlap.data());
  return profile;
}

ImageMatch compare_images(const PreparedImage &a, const PreparedImage &b,
                          int min_overlap) {
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

ImageMatch compare_images(const ShapeImage &a, const ShapeImage &b,
                          int min_overlap) {
  return compare_images(PreparedImage(a), PreparedImage(b), min_overlap);
}

} // namespace surfcomp::harmonic
