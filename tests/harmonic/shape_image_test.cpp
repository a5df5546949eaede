// Harmonic shape images (method §4): resampling on the polar grid (exact for linear data,
// masks for points outside the patch and in holes), grid points back to the surface, and the
// comparison over rotations (angle convention, self-comparison, unrelated fields, the FFT
// comparison against a direct evaluation, the area weighting).
#include "analytic_meshes.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/harmonic/shape_image.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <random>
#include <vector>

namespace surfcomp::harmonic {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A planar disk patch embedded in the unit disk: the ring-triangulated disk of radius 1
/// (rings of vertices at radii k / rings), uv = (x, y).
struct DiskPatch {
  Eigen::MatrixX2d uv;
  Eigen::MatrixX3i faces;
};

DiskPatch unit_disk_patch(int rings) {
  const mesh::Surface disk = test::disk(1.0, rings);
  return {disk.positions().leftCols(2), disk.faces()};
}

Eigen::MatrixX2d rotated(const Eigen::MatrixX2d& uv, double degrees) {
  const Eigen::Matrix2d r = Eigen::Rotation2Dd(degrees * kPi / 180.0).toRotationMatrix();
  return uv * r.transpose();
}

/// A smooth field without rotational symmetry.
double smooth_field(double u, double v) {
  return std::sin(3.0 * u + 0.5) + std::cos(2.0 * v - 0.3 * u) + 1.5 * u * v + 0.4 * v;
}

/// A smooth random field: eight plane waves with random directions, wave numbers in [4, 10]
/// per unit length (wavelengths 0.6-1.6 across the unit disk), random phases and amplitudes,
/// from the given seed.
Eigen::VectorXd random_field(const Eigen::MatrixX2d& uv, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi), wave(4.0, 10.0),
      amplitude(0.5, 1.0);
  Eigen::VectorXd values = Eigen::VectorXd::Zero(uv.rows());
  for (int m = 0; m < 8; ++m) {
    const double direction = angle(generator), k = wave(generator), phase = angle(generator),
                 a = amplitude(generator);
    for (Eigen::Index v = 0; v < uv.rows(); ++v) {
      values(v) +=
          a *
          std::cos(k * (std::cos(direction) * uv(v, 0) + std::sin(direction) * uv(v, 1)) + phase);
    }
  }
  return values;
}

Eigen::VectorXd field_values(const Eigen::MatrixX2d& uv, double (*f)(double, double)) {
  Eigen::VectorXd values(uv.rows());
  for (Eigen::Index v = 0; v < uv.rows(); ++v) values(v) = f(uv(v, 0), uv(v, 1));
  return values;
}

int valid_count(const ShapeImage& image, int ring) {
  int count = 0;
  for (int j = 0; j < image.sectors; ++j)
    count += image.valid[static_cast<std::size_t>(ring * image.sectors + j)];
  return count;
}

/// The documented correlation evaluated directly: for every shift s, the area-weighted Pearson
/// correlation (weight k + 0.5 on ring k) of a_j and b_(j+s) over the points valid in both,
/// two-pass (means first), -1 below min_overlap points, 0 for a constant image.
RotationProfile naive_profile(const ShapeImage& a, const ShapeImage& b, int min_overlap) {
  const int rings = a.rings, n = a.sectors;
  RotationProfile profile;
  profile.correlation.resize(n);
  profile.overlap.resize(n);
  for (int s = 0; s < n; ++s) {
    double weight = 0.0, sum_a = 0.0, sum_b = 0.0;
    int count = 0;
    auto for_each_pair = [&](auto&& body) {
      for (int r = 0; r < rings; ++r) {
        for (int j = 0; j < n; ++j) {
          const int ia = r * n + j, ib = r * n + (j + s) % n;
          if (a.valid[static_cast<std::size_t>(ia)] && b.valid[static_cast<std::size_t>(ib)]) {
            body(r + 0.5, a.values(ia), b.values(ib));
          }
        }
      }
    };
    for_each_pair([&](double w, double x, double y) {
      weight += w;
      sum_a += w * x;
      sum_b += w * y;
      ++count;
    });
    profile.overlap(s) = count;
    if (count < min_overlap) {
      profile.correlation(s) = -1.0;
      continue;
    }
    const double mean_a = sum_a / weight, mean_b = sum_b / weight;
    double saa = 0.0, sbb = 0.0, sab = 0.0;
    for_each_pair([&](double w, double x, double y) {
      saa += w * (x - mean_a) * (x - mean_a);
      sbb += w * (y - mean_b) * (y - mean_b);
      sab += w * (x - mean_a) * (y - mean_b);
    });
    profile.correlation(s) = saa > 0.0 && sbb > 0.0 ? sab / std::sqrt(saa * sbb) : 0.0;
  }
  return profile;
}

/// An image with random values in [-1, 1] and random validity: each ring is full, empty or
/// has each point valid with probability `density`.
ShapeImage random_image(int rings, int n, double density, std::mt19937& generator) {
  std::uniform_real_distribution<double> value(-1.0, 1.0), unit(0.0, 1.0);
  ShapeImage image;
  image.rings = rings;
  image.sectors = n;
  image.values = Eigen::VectorXd::Zero(rings * n);
  image.valid.assign(static_cast<std::size_t>(rings * n), 0);
  image.face = Eigen::VectorXi::Constant(rings * n, -1);
  image.barycentric = Eigen::MatrixX3d::Zero(rings * n, 3);
  for (int r = 0; r < rings; ++r) {
    const double kind = unit(generator);
    const double p = kind < 0.3 ? 1.0 : kind < 0.4 ? 0.0 : density;
    for (int j = 0; j < n; ++j) {
      const int i = r * n + j;
      if (unit(generator) < p) {
        image.valid[static_cast<std::size_t>(i)] = 1;
        image.values(i) = value(generator);
      }
    }
  }
  return image;
}

// ---------------------------------------------------------------------------------------------

TEST(ShapeImage, GridPointsLieOnRingsAtTwoDegreeSteps) {
  const ImageOptions options;
  EXPECT_EQ(options.rings, 16);
  EXPECT_EQ(options.sectors, 180);
  // Grid point 5 * 180 + 45: ring 5 (radius 5.5 / 16), sector 45 (90 degrees).
  const Eigen::Vector2d p = image_grid_point(options, 5 * 180 + 45);
  EXPECT_NEAR(p.x(), 0.0, 1e-15);
  EXPECT_NEAR(p.y(), 5.5 / 16.0, 1e-15);
  const Eigen::Vector2d q = image_grid_point(options, 15 * 180 + 1);
  EXPECT_NEAR(q.norm(), 15.5 / 16.0, 1e-15);
  EXPECT_NEAR(std::atan2(q.y(), q.x()) * 180.0 / kPi, 2.0, 1e-12);
  EXPECT_THROW(image_grid_point(options, 2880), InputError);
  EXPECT_THROW(image_grid_point(options, -1), InputError);
  EXPECT_THROW(image_grid_point(ImageOptions{0, 180}, 0), OptionError);
}

TEST(ShapeImage, ReproducesLinearFunctionsExactly) {
  const DiskPatch patch = unit_disk_patch(8);
  auto linear = [](double u, double v) { return 0.3 + 1.7 * u - 2.2 * v; };
  Eigen::VectorXd values(patch.uv.rows());
  for (Eigen::Index v = 0; v < values.size(); ++v)
    values(v) = linear(patch.uv(v, 0), patch.uv(v, 1));
  const ShapeImage image = harmonic_shape_image(patch.uv, patch.faces, values);
  ASSERT_EQ(image.values.size(), 2880);
  // The disk polygon's innermost boundary point is at cos(pi / 48) = 0.9979 > 15.5 / 16.
  double worst = 0.0;
  for (int i = 0; i < 2880; ++i) {
    ASSERT_EQ(image.valid[static_cast<std::size_t>(i)], 1) << "grid point " << i;
    const Eigen::Vector2d q = image_grid_point({}, i);
    worst = std::max(worst, std::abs(image.values(i) - linear(q.x(), q.y())));
    EXPECT_NEAR(image.barycentric.row(i).sum(), 1.0, 1e-14);
    EXPECT_GE(image.barycentric.row(i).minCoeff(), -1e-12);
    // The barycentric coordinates reproduce the grid point itself from the face's corners.
    Eigen::Vector2d back = Eigen::Vector2d::Zero();
    for (int c = 0; c < 3; ++c)
      back += image.barycentric(i, c) * patch.uv.row(patch.faces(image.face(i), c)).transpose();
    EXPECT_LE((back - q).norm(), 1e-14);
  }
  EXPECT_LE(worst, 1e-12);
  std::cout << "linear data: largest resampling error " << worst << "\n";
}

TEST(ShapeImage, LocatesTheLowestIndexTriangle) {
  // Brute force over all faces: the candidates for a grid point are the faces whose barycentric
  // coordinates are all >= -1e-12. The located face must be a candidate, and where the point
  // lies exactly on a shared edge (sector 0 of the unrotated disk: y = 0 on the spoke edges
  // along +u), the lowest-index candidate. Elsewhere rounding decides which side of an edge a
  // point within 1e-16 of it is on, so only membership is asserted.
  const DiskPatch patch = unit_disk_patch(8);
  for (const double theta : {0.0, 13.0}) {
    const Eigen::MatrixX2d uv = rotated(patch.uv, theta);
    const ShapeImage image =
        harmonic_shape_image(uv, patch.faces, Eigen::VectorXd::Zero(uv.rows()));
    int not_candidate = 0, on_edge = 0, shared = 0;
    for (int i = 0; i < 2880; ++i) {
      const Eigen::Vector2d q = image_grid_point({}, i);
      std::vector<int> candidates;
      for (int f = 0; f < patch.faces.rows(); ++f) {
        const Eigen::Vector2d p0 = uv.row(patch.faces(f, 0)).transpose(),
                              p1 = uv.row(patch.faces(f, 1)).transpose(),
                              p2 = uv.row(patch.faces(f, 2)).transpose();
        auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
          return a.x() * b.y() - a.y() * b.x();
        };
        const double area = cross(p1 - p0, p2 - p0);
        const double l0 = cross(p1 - q, p2 - q) / area, l1 = cross(p2 - q, p0 - q) / area;
        if (std::min({l0, l1, 1.0 - l0 - l1}) >= -1e-12) candidates.push_back(f);
      }
      if (std::find(candidates.begin(), candidates.end(), image.face(i)) == candidates.end())
        ++not_candidate;
      shared += candidates.size() > 1 ? 1 : 0;
      if (theta == 0.0 && i % 180 == 0) {
        ++on_edge;
        EXPECT_GE(candidates.size(), 2u) << "grid point " << i;
        EXPECT_EQ(image.face(i), candidates.front()) << "grid point " << i;
      }
    }
    EXPECT_EQ(not_candidate, 0) << "rotation " << theta;
    std::cout << "rotation " << theta << ": " << shared << " grid points on shared edges, "
              << on_edge << " checked for the lowest index\n";
  }
}

TEST(ShapeImage, GridPointsOutsideThePatchAreInvalid) {
  // The disk of radius 0.5 (48 boundary vertices, inscribed polygon with apothem 0.4989):
  // rings 0-7 (radii up to 7.5 / 16 = 0.469) lie inside, rings 8-15 (from 0.531) outside.
  const DiskPatch patch = unit_disk_patch(8);
  const Eigen::MatrixX2d half = 0.5 * patch.uv;
  const ShapeImage image =
      harmonic_shape_image(half, patch.faces, Eigen::VectorXd::Ones(half.rows()));
  for (int r = 0; r < 16; ++r) {
    EXPECT_EQ(valid_count(image, r), r < 8 ? 180 : 0) << "ring " << r;
  }
  for (int i = 8 * 180; i < 2880; ++i) {
    EXPECT_EQ(image.face(i), -1);
    EXPECT_EQ(image.values(i), 0.0);
    EXPECT_EQ(image.barycentric.row(i).norm(), 0.0);
  }
}

TEST(ShapeImage, HolesAreInvalid) {
  // Remove the faces between vertex rings 3 (radius 0.375, 18 vertices, polygon apothem 0.3693)
  // and 4 (radius 0.5, 24 vertices, apothem 0.4957): grid rings 6 and 7 (radii 0.406, 0.469)
  // fall into the hole, rings 0-5 (up to 0.344) and 8-15 (from 0.531) stay on the patch.
  const DiskPatch patch = unit_disk_patch(8);
  std::vector<int> kept;
  for (int f = 0; f < patch.faces.rows(); ++f) {
    double lo = 1.0, hi = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double rho = patch.uv.row(patch.faces(f, c)).norm();
      lo = std::min(lo, rho);
      hi = std::max(hi, rho);
    }
    const bool in_gap = std::abs(lo - 0.375) < 1e-9 && std::abs(hi - 0.5) < 1e-9;
    if (!in_gap) kept.push_back(f);
  }
  ASSERT_EQ(patch.faces.rows() - static_cast<Eigen::Index>(kept.size()), 18 + 24);
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i)
    faces.row(static_cast<Eigen::Index>(i)) = patch.faces.row(kept[i]);
  const ShapeImage image =
      harmonic_shape_image(patch.uv, faces, Eigen::VectorXd::Ones(patch.uv.rows()));
  for (int r = 0; r < 16; ++r) {
    EXPECT_EQ(valid_count(image, r), r == 6 || r == 7 ? 0 : 180) << "ring " << r;
  }
}

TEST(ShapeImage, GridPointsMapBackToThePlanarPatch) {
  // A disk of radius 2.5 A, rotated and translated in space; its embedding is (x, y) / 2.5, so
  // grid point q lies at rotation * (2.5 q, 0) + translation.
  const DiskPatch patch = unit_disk_patch(6);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d translation(3.0, -1.5, 12.25);
  Eigen::MatrixX3d positions(patch.uv.rows(), 3);
  for (Eigen::Index v = 0; v < patch.uv.rows(); ++v) {
    positions.row(v) =
        (rotation * Eigen::Vector3d(2.5 * patch.uv(v, 0), 2.5 * patch.uv(v, 1), 0.0) + translation)
            .transpose();
  }
  const ShapeImage image =
      harmonic_shape_image(patch.uv, patch.faces, Eigen::VectorXd::Zero(patch.uv.rows()));
  double worst = 0.0;
  for (int i = 0; i < 2880; ++i) {
    ASSERT_TRUE(image.valid[static_cast<std::size_t>(i)]);
    const Eigen::Vector2d q = image_grid_point({}, i);
    const Eigen::Vector3d expected =
        rotation * Eigen::Vector3d(2.5 * q.x(), 2.5 * q.y(), 0.0) + translation;
    worst = std::max(worst,
                     (image_point_to_surface(image, i, positions, patch.faces) - expected).norm());
  }
  EXPECT_LE(worst, 1e-12);

  // An invalid grid point and a grid index outside the grid are errors.
  const ShapeImage small =
      harmonic_shape_image(0.5 * patch.uv, patch.faces, Eigen::VectorXd::Zero(patch.uv.rows()));
  EXPECT_THROW(image_point_to_surface(small, 15 * 180, positions, patch.faces), InputError);
  EXPECT_THROW(image_point_to_surface(small, 2880, positions, patch.faces), InputError);
}

TEST(ShapeImage, RotationAngleIsRecovered) {
  // b is a's patch with its uv rotated by +theta (b(p) = f(R(-theta) p)): compare_images(a, b)
  // reports angle theta, exactly for multiples of 2 degrees, to the nearest 2-degree step
  // otherwise.
  const DiskPatch patch = unit_disk_patch(24);
  const Eigen::VectorXd values = field_values(patch.uv, smooth_field);
  const PreparedImage a(harmonic_shape_image(patch.uv, patch.faces, values));
  for (const double theta : {0.0, 2.0, 10.0, 90.0, 200.0, 358.0}) {
    const ShapeImage b = harmonic_shape_image(rotated(patch.uv, theta), patch.faces, values);
    const ImageMatch match = compare_images(a, PreparedImage(b));
    EXPECT_EQ(match.shift, static_cast<int>(theta / 2.0)) << "theta " << theta;
    EXPECT_DOUBLE_EQ(match.angle_degrees, theta);
    EXPECT_GE(match.correlation, 0.99);
    EXPECT_EQ(match.overlap, 2880);
    std::cout << "theta " << theta << ": angle " << match.angle_degrees
              << ", R = " << match.correlation << "\n";
  }
  double lowest = 1.0;
  for (const double theta : {1.0, 7.3, 45.9, 123.4, 271.0, 359.5}) {
    const ShapeImage b = harmonic_shape_image(rotated(patch.uv, theta), patch.faces, values);
    const ImageMatch match = compare_images(a, PreparedImage(b));
    const double error = std::abs(std::remainder(match.angle_degrees - theta, 360.0));
    EXPECT_LE(error, 1.0 + 1e-9) << "theta " << theta << " found " << match.angle_degrees;
    EXPECT_GE(match.correlation, 0.98);
    lowest = std::min(lowest, match.correlation);
    std::cout << "theta " << theta << ": angle " << match.angle_degrees
              << ", R = " << match.correlation << "\n";
  }
  std::cout << "lowest R at angles off the grid: " << lowest << "\n";
}

TEST(ShapeImage, SelfComparisonIsTheIdentity) {
  const DiskPatch patch = unit_disk_patch(12);
  const ShapeImage image = harmonic_shape_image(patch.uv, patch.faces, random_field(patch.uv, 7));
  const ImageMatch match = compare_images(image, image);
  EXPECT_NEAR(match.correlation, 1.0, 1e-12);
  EXPECT_EQ(match.shift, 0);
  EXPECT_EQ(match.angle_degrees, 0.0);
  EXPECT_EQ(match.overlap, 2880);
}

TEST(ShapeImage, UnrelatedFieldsCorrelateLess) {
  // Pairs of smooth random fields (seeds 101..110 against 201..210) on the same patch. Without
  // rotation they are uncorrelated on average; the maximum over 180 rotations is biased upwards
  // (measured: mean 0.37, max 0.50 for these seeds), yet stays far below a field against itself
  // or its rotated copy (R > 0.999 in RotationAngleIsRecovered).
  const DiskPatch patch = unit_disk_patch(12);
  double highest = -1.0, total = 0.0, total_unrotated = 0.0;
  for (unsigned seed = 101; seed <= 110; ++seed) {
    const PreparedImage a(
        harmonic_shape_image(patch.uv, patch.faces, random_field(patch.uv, seed)));
    const PreparedImage b(
        harmonic_shape_image(patch.uv, patch.faces, random_field(patch.uv, seed + 100)));
    const double r = compare_images(a, b).correlation;
    highest = std::max(highest, r);
    total += r;
    total_unrotated += rotation_profile(a, b).correlation(0);
  }
  std::cout << "unrelated smooth fields: best-rotation R mean " << total / 10 << ", max " << highest
            << "; unrotated R mean " << total_unrotated / 10 << "\n";
  EXPECT_LT(highest, 0.6);
  EXPECT_LT(total / 10, 0.45);
  EXPECT_LT(std::abs(total_unrotated / 10), 0.2);
}

TEST(ShapeImage, FastComparisonEqualsDirectEvaluation) {
  std::mt19937 generator(20240611);
  struct Case {
    int rings, n;
    double density;
    int min_overlap;
  };
  // Full grids, odd and small ring lengths, sparse masks where some shifts fall below min_overlap.
  for (const Case& c : {Case{16, 180, 0.8, 16}, Case{16, 180, 0.3, 16}, Case{4, 45, 0.7, 8},
                        Case{3, 36, 0.5, 4}, Case{2, 7, 0.6, 2}, Case{16, 180, 0.01, 16}}) {
    for (int trial = 0; trial < 4; ++trial) {
      const ShapeImage a = random_image(c.rings, c.n, c.density, generator);
      const ShapeImage b = random_image(c.rings, c.n, c.density, generator);
      const RotationProfile fast =
          rotation_profile(PreparedImage(a), PreparedImage(b), c.min_overlap);
      const RotationProfile direct = naive_profile(a, b, c.min_overlap);
      ASSERT_EQ(fast.correlation.size(), c.n);
      for (int s = 0; s < c.n; ++s) {
        EXPECT_EQ(fast.overlap(s), direct.overlap(s)) << c.rings << "x" << c.n << " shift " << s;
        EXPECT_NEAR(fast.correlation(s), direct.correlation(s), 1e-12)
            << c.rings << "x" << c.n << " shift " << s;
      }
      Eigen::Index best = 0;
      direct.correlation.maxCoeff(&best);
      const ImageMatch match = compare_images(a, b, c.min_overlap);
      EXPECT_EQ(match.shift, static_cast<int>(best));
      EXPECT_NEAR(match.correlation, direct.correlation(best), 1e-12);
      EXPECT_EQ(match.overlap, direct.overlap(best));
    }
  }
}

TEST(ShapeImage, CorrelationIsAreaWeighted) {
  // Two rings of four samples, weights 0.5 and 1.5 (1 : 3). a alternates +1, -1 on both rings;
  // b is a on ring 1 and -a on ring 0. At shift 0 the weighted covariance is -4 + 12 = 8 and
  // both weighted variances are 16: R = 0.5 (unweighted it would be 0). Shift 1 flips both
  // rings: R = -0.5. Shift 2 ties with shift 0; the smallest shift wins.
  ShapeImage a;
  a.rings = 2;
  a.sectors = 4;
  a.values.resize(8);
  a.values << 1, -1, 1, -1, 1, -1, 1, -1;
  a.valid.assign(8, 1);
  a.face = Eigen::VectorXi::Constant(8, -1);
  a.barycentric = Eigen::MatrixX3d::Zero(8, 3);
  ShapeImage b = a;
  b.values << -1, 1, -1, 1, 1, -1, 1, -1;
  const RotationProfile profile = rotation_profile(PreparedImage(a), PreparedImage(b), 1);
  EXPECT_NEAR(profile.correlation(0), 0.5, 1e-14);
  EXPECT_NEAR(profile.correlation(1), -0.5, 1e-14);
  EXPECT_NEAR(profile.correlation(2), 0.5, 1e-14);
  EXPECT_NEAR(profile.correlation(3), -0.5, 1e-14);
  const ImageMatch match = compare_images(a, b, 1);
  EXPECT_EQ(match.shift, 0);
  EXPECT_NEAR(match.correlation, 0.5, 1e-14);
  EXPECT_EQ(match.overlap, 8);
}

TEST(ShapeImage, TiesAndDegenerateImages) {
  const DiskPatch patch = unit_disk_patch(8);
  // An image constant on each ring (value ring^2) matches itself at every rotation: the sums
  // are equal for all shifts up to FFT round-off, and shift 0 wins the tie.
  ShapeImage by_ring;
  by_ring.rings = 16;
  by_ring.sectors = 180;
  by_ring.values.resize(2880);
  for (int i = 0; i < 2880; ++i) by_ring.values(i) = (i / 180) * (i / 180);
  by_ring.valid.assign(2880, 1);
  by_ring.face = Eigen::VectorXi::Constant(2880, -1);
  by_ring.barycentric = Eigen::MatrixX3d::Zero(2880, 3);
  const ImageMatch tie = compare_images(by_ring, by_ring);
  EXPECT_EQ(tie.shift, 0);
  EXPECT_NEAR(tie.correlation, 1.0, 1e-12);
  Eigen::VectorXd radial(patch.uv.rows());
  for (Eigen::Index v = 0; v < radial.size(); ++v) radial(v) = patch.uv.row(v).squaredNorm();
  const ShapeImage symmetric = harmonic_shape_image(patch.uv, patch.faces, radial);
  // A constant image has no variance: correlation 0 at every rotation.
  const ShapeImage constant =
      harmonic_shape_image(patch.uv, patch.faces, Eigen::VectorXd::Constant(patch.uv.rows(), 0.3));
  const RotationProfile flat = rotation_profile(PreparedImage(constant), PreparedImage(symmetric));
  EXPECT_EQ(flat.correlation.cwiseAbs().maxCoeff(), 0.0);
  // Images that never overlap in min_overlap points: correlation -1, shift 0.
  const ShapeImage inner =
      harmonic_shape_image(0.2 * patch.uv, patch.faces, radial);  // rings 0-2 valid
  const ShapeImage outer = harmonic_shape_image(patch.uv, patch.faces, radial);
  const ImageMatch none = compare_images(inner, outer, 3 * 180 + 1);
  EXPECT_EQ(none.correlation, -1.0);
  EXPECT_EQ(none.shift, 0);
  EXPECT_EQ(none.overlap, 3 * 180);
}

TEST(ShapeImage, IsDeterministic) {
  const DiskPatch patch = unit_disk_patch(12);
  const Eigen::VectorXd values = random_field(patch.uv, 3);
  const Eigen::MatrixX2d uv = rotated(patch.uv, 13.0);
  const ShapeImage first = harmonic_shape_image(uv, patch.faces, values);
  const ShapeImage second = harmonic_shape_image(uv, patch.faces, values);
  EXPECT_EQ(std::memcmp(first.values.data(), second.values.data(), sizeof(double) * 2880), 0);
  EXPECT_EQ(
      std::memcmp(first.barycentric.data(), second.barycentric.data(), sizeof(double) * 3 * 2880),
      0);
  EXPECT_EQ(first.face, second.face);
  EXPECT_EQ(first.valid, second.valid);
}

TEST(ShapeImage, RejectsBadInput) {
  const DiskPatch patch = unit_disk_patch(2);
  const Eigen::VectorXd values = Eigen::VectorXd::Zero(patch.uv.rows());
  EXPECT_THROW(harmonic_shape_image(patch.uv, patch.faces, values.head(3)), InputError);
  Eigen::MatrixX3i bad_faces = patch.faces;
  bad_faces(2, 1) = static_cast<int>(patch.uv.rows());
  EXPECT_THROW(harmonic_shape_image(patch.uv, bad_faces, values), InputError);
  Eigen::VectorXd nan_values = values;
  nan_values(4) = std::nan("");
  EXPECT_THROW(harmonic_shape_image(patch.uv, patch.faces, nan_values), InputError);
  EXPECT_THROW(harmonic_shape_image(patch.uv, patch.faces, values, ImageOptions{16, 0}),
               OptionError);
  const ShapeImage a = harmonic_shape_image(patch.uv, patch.faces, values);
  const ShapeImage b = harmonic_shape_image(patch.uv, patch.faces, values, ImageOptions{16, 90});
  EXPECT_THROW(compare_images(a, b), InputError);
  EXPECT_THROW(compare_images(a, a, 0), OptionError);
  ShapeImage truncated = a;
  truncated.valid.pop_back();
  EXPECT_THROW(PreparedImage{truncated}, InputError);
}

}  // namespace
}  // namespace surfcomp::harmonic
