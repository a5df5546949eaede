// Harmonic disk maps (harmonic/disk_map.hpp) on analytic patches: exact reproduction of a
// planar disk, agreement with CGAL's Surface_mesh_parameterization for every weight kind,
// the border on the unit circle by arc length, no folds, invariance under similarity
// transforms, and the errors of bad input.
#include "surfcomp/harmonic/disk_map.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/harmonic/cgal_reference.hpp"
#include "surfcomp/harmonic/map_distortion.hpp"

#include "analytic_meshes.hpp"
#include "disk_map_patches.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace surfcomp::harmonic {
namespace {

using test::analytic_patches;
using test::arrays_of;
using test::ellipsoid_patch;
using test::MeshArrays;
using test::sphere_cap_patch;
using test::TestPatch;
using test::torus_patch_with_hole;

constexpr SpringWeights all_weights[] = {SpringWeights::inverse_length, SpringWeights::uniform,
                                         SpringWeights::cotangent, SpringWeights::mean_value};

/// Cumulative border length (A) from outer_boundary[0] to outer_boundary[k], k = 0..#B (the
/// last is the perimeter).
std::vector<double> border_arc_lengths(const TestPatch& patch) {
  const std::vector<int>& border = patch.outer_boundary;
  std::vector<double> arc = {0.0};
  for (std::size_t k = 0; k < border.size(); ++k) {
    const Eigen::RowVector3d step =
        patch.positions.row(border[(k + 1) % border.size()]) - patch.positions.row(border[k]);
    arc.push_back(arc.back() + step.norm());
  }
  return arc;
}

double max_distance(const Eigen::MatrixX2d& a, const Eigen::MatrixX2d& b) {
  return (a - b).rowwise().norm().maxCoeff();
}

TEST(SpringWeights, EachNameReadsBackAsItsWeights) {
  for (const SpringWeights weights : {SpringWeights::inverse_length, SpringWeights::uniform,
                                      SpringWeights::cotangent, SpringWeights::mean_value}) {
    EXPECT_EQ(spring_weights_from_name(to_string(weights)), weights) << to_string(weights);
  }
  EXPECT_STREQ(to_string(SpringWeights::inverse_length), "inverse-length");
  EXPECT_STREQ(to_string(SpringWeights::mean_value), "mean-value");
  EXPECT_EQ(spring_weights_from_name("inverse_length"), std::nullopt);
}

TEST(DiskMapTest, TestPatchesHaveTheIntendedTopology) {
  for (const TestPatch& patch : analytic_patches()) {
    SCOPED_TRACE(patch.name);
    // V - E + F = 1 - #holes for a disk with holes; E from the face count and border length.
    std::map<std::pair<int, int>, int> edges;
    for (Eigen::Index f = 0; f < patch.faces.rows(); ++f) {
      for (int c = 0; c < 3; ++c) {
        const int a = patch.faces(f, c), b = patch.faces(f, (c + 1) % 3);
        edges[{std::min(a, b), std::max(a, b)}] = 1;
      }
    }
    const long long euler =
        patch.positions.rows() - static_cast<long long>(edges.size()) + patch.faces.rows();
    EXPECT_EQ(euler, 1 - static_cast<long long>(patch.n_holes));
    std::cout << patch.name << ": " << patch.positions.rows() << " vertices, " << patch.faces.rows()
              << " faces, " << patch.outer_boundary.size() << " outer border vertices, "
              << patch.n_holes << " holes\n";
  }
  EXPECT_EQ(sphere_cap_patch().n_holes, 0u);
  EXPECT_EQ(ellipsoid_patch().n_holes, 0u);
  EXPECT_EQ(torus_patch_with_hole().n_holes, 1u);
  EXPECT_NEAR(static_cast<double>(sphere_cap_patch().positions.rows()), 170.0, 20.0);
  EXPECT_NEAR(static_cast<double>(ellipsoid_patch().positions.rows()), 170.0, 40.0);
}

/// A planar disk of radius 2 A (8 rings, regular 48-gon border) whose interior vertices are
/// moved at random (seed 7) by up to 30 % of the ring spacing, without folding it.
TestPatch perturbed_planar_disk() {
  const double radius = 2.0;
  const int rings = 8;
  MeshArrays disk = arrays_of(test::disk(radius, rings));
  std::mt19937 generator(7);
  std::uniform_real_distribution<double> offset(-0.3 * radius / rings, 0.3 * radius / rings);
  const Eigen::Index first_border = 1 + 3 * rings * (rings - 1);  // 1 + sum_{k<rings} 6k
  for (Eigen::Index v = 0; v < first_border; ++v) {
    disk.positions(v, 0) += offset(generator);
    disk.positions(v, 1) += offset(generator);
  }
  TestPatch patch;
  patch.name = "perturbed planar disk";
  patch.positions = disk.positions;
  patch.faces = disk.faces;
  for (Eigen::Index v = first_border; v < disk.positions.rows(); ++v) {
    patch.outer_boundary.push_back(
        static_cast<int>(v));  // ring 8, angle 0 first, counter-clockwise
  }
  return patch;
}

TEST(DiskMapTest, CotangentAndMeanValueWeightsReproduceAPlanarDisk) {
  const TestPatch disk = perturbed_planar_disk();
  ASSERT_EQ(count_flipped_triangles(disk.positions.leftCols(2), disk.faces), 0);
  ASSERT_EQ(disk.outer_boundary.size(), 48u);
  const Eigen::MatrixX2d expected = disk.positions.leftCols(2) / 2.0;
  for (const SpringWeights weights : {SpringWeights::cotangent, SpringWeights::mean_value}) {
    SCOPED_TRACE(to_string(weights));
    const DiskMap map =
        harmonic_disk_map(disk.positions, disk.faces, disk.outer_boundary, {weights});
    const double error = max_distance(map.uv, expected);
    std::cout << to_string(weights) << ": max |uv - p / R| = " << error << "\n";
    EXPECT_LE(error, 1e-6);
  }
  // Uniform and 1/length springs have no linear precision: the same test fails for them.
  for (const SpringWeights weights : {SpringWeights::uniform, SpringWeights::inverse_length}) {
    const DiskMap map =
        harmonic_disk_map(disk.positions, disk.faces, disk.outer_boundary, {weights});
    const double error = max_distance(map.uv, expected);
    std::cout << to_string(weights) << ": max |uv - p / R| = " << error << "\n";
    EXPECT_GT(error, 1e-3) << to_string(weights);
  }
}

TEST(DiskMapTest, AgreesWithCgalForEveryWeightKind) {
  for (const TestPatch& patch : analytic_patches()) {
    for (const SpringWeights weights : all_weights) {
      SCOPED_TRACE(patch.name + ", " + to_string(weights));
      const DiskMap ours =
          harmonic_disk_map(patch.positions, patch.faces, patch.outer_boundary, {weights});
      const DiskMap cgal =
          cgal_disk_map(patch.positions, patch.faces, patch.outer_boundary, {weights});
      ASSERT_EQ(ours.uv.rows(), patch.positions.rows());
      ASSERT_EQ(cgal.uv.rows(), patch.positions.rows());
      const double distance = max_distance(ours.uv, cgal.uv);
      const int flipped = count_flipped_triangles(ours.uv, patch.faces);
      std::cout << patch.name << ", " << to_string(weights) << ": max |ours - CGAL| = " << distance
                << ", flipped triangles " << flipped << " (CGAL "
                << count_flipped_triangles(cgal.uv, patch.faces) << ")\n";
      EXPECT_LE(distance, 1e-6);
      if (weights != SpringWeights::cotangent) {
        EXPECT_EQ(flipped, 0);
      }
    }
  }
}

TEST(DiskMapTest, BorderLiesOnTheUnitCircleByArcLengthAndInteriorInside) {
  for (const TestPatch& patch : analytic_patches()) {
    SCOPED_TRACE(patch.name);
    const DiskMap map = harmonic_disk_map(patch.positions, patch.faces, patch.outer_boundary);
    const std::vector<int>& border = patch.outer_boundary;
    const std::vector<double> arc = border_arc_lengths(patch);
    const double perimeter = arc.back();
    double previous_angle = -1.0;
    std::vector<char> on_border(static_cast<std::size_t>(patch.positions.rows()), 0);
    for (std::size_t k = 0; k < border.size(); ++k) {
      const Eigen::Vector2d uv = map.uv.row(border[k]).transpose();
      EXPECT_NEAR(uv.norm(), 1.0, 1e-12);
      double angle = std::atan2(uv.y(), uv.x());
      if (angle < -1e-12) angle += 2.0 * M_PI;
      EXPECT_NEAR(angle, 2.0 * M_PI * arc[k] / perimeter, 1e-12) << "border vertex " << k;
      EXPECT_GT(angle, previous_angle) << "border vertex " << k;
      previous_angle = angle;
      on_border[static_cast<std::size_t>(border[k])] = 1;
    }
    EXPECT_NEAR(map.uv(border[0], 0), 1.0, 1e-15);
    EXPECT_NEAR(map.uv(border[0], 1), 0.0, 1e-15);
    // Positive springs: every other vertex is a strict convex combination of its neighbours.
    for (Eigen::Index v = 0; v < patch.positions.rows(); ++v) {
      if (!on_border[static_cast<std::size_t>(v)]) {
        EXPECT_LT(map.uv.row(v).norm(), 1.0 - 1e-6) << v;
      }
    }
  }
}

TEST(DiskMapTest, SimilarityTransformOfThePatchLeavesTheMapUnchanged) {
  const TestPatch patch = ellipsoid_patch();
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  for (const double scale : {1e-3, 1e3}) {
    Eigen::MatrixX3d moved = scale * patch.positions * rotation.transpose();
    moved.rowwise() += Eigen::RowVector3d(10.0, -4.0, 3.0);
    for (const SpringWeights weights : all_weights) {
      SCOPED_TRACE(std::string(to_string(weights)) + ", scale " + std::to_string(scale));
      const DiskMap original =
          harmonic_disk_map(patch.positions, patch.faces, patch.outer_boundary, {weights});
      const DiskMap transformed =
          harmonic_disk_map(moved, patch.faces, patch.outer_boundary, {weights});
      EXPECT_LE(max_distance(original.uv, transformed.uv), 1e-9);
    }
  }
}

TEST(DiskMapTest, StartingTheBorderElsewhereRotatesTheMap) {
  const TestPatch patch = sphere_cap_patch();
  std::vector<int> shifted = patch.outer_boundary;
  const int shift = 5;
  std::rotate(shifted.begin(), shifted.begin() + shift, shifted.end());
  const std::vector<double> arc = border_arc_lengths(patch);
  const double angle = 2.0 * M_PI * arc[shift] / arc.back();
  const DiskMap original = harmonic_disk_map(patch.positions, patch.faces, patch.outer_boundary);
  const DiskMap rotated = harmonic_disk_map(patch.positions, patch.faces, shifted);
  const Eigen::Matrix2d back = Eigen::Rotation2Dd(angle).toRotationMatrix();
  EXPECT_LE(max_distance((rotated.uv * back.transpose()).eval(), original.uv), 1e-12);
}

TEST(DiskMapTest, CountFlippedTrianglesCountsReflectedAndDegenerateTriangles) {
  const TestPatch disk = perturbed_planar_disk();
  const DiskMap map = harmonic_disk_map(disk.positions, disk.faces, disk.outer_boundary);
  EXPECT_EQ(count_flipped_triangles(map.uv, disk.faces), 0);
  Eigen::MatrixX2d mirrored = map.uv;
  mirrored.col(1) *= -1.0;
  EXPECT_EQ(count_flipped_triangles(mirrored, disk.faces), static_cast<int>(disk.faces.rows()));
  Eigen::MatrixX2d collapsed = map.uv;
  collapsed.row(0) =
      collapsed.row(1);  // the centre onto a ring-1 vertex: its 2 triangles degenerate
  EXPECT_EQ(count_flipped_triangles(collapsed, disk.faces), 2);
  Eigen::MatrixX3i bad = disk.faces;
  bad(3, 1) = static_cast<int>(map.uv.rows());
  EXPECT_THROW(count_flipped_triangles(map.uv, bad), InputError);
}

TEST(DiskMapTest, BadInputThrowsTheRightError) {
  const TestPatch disk = perturbed_planar_disk();
  const Eigen::MatrixX3d& p = disk.positions;
  const Eigen::MatrixX3i& f = disk.faces;
  const std::vector<int>& b = disk.outer_boundary;
  for (const bool cgal : {false, true}) {
    SCOPED_TRACE(cgal ? "cgal_disk_map" : "harmonic_disk_map");
    auto map = [cgal](const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& faces,
                      const std::vector<int>& boundary,
                      SpringWeights weights = SpringWeights::inverse_length) {
      return cgal ? cgal_disk_map(positions, faces, boundary, {weights})
                  : harmonic_disk_map(positions, faces, boundary, {weights});
    };
    Eigen::MatrixX3i out_of_range = f;
    out_of_range(10, 2) = static_cast<int>(p.rows());
    EXPECT_THROW(map(p, out_of_range, b), InputError);
    Eigen::MatrixX3i negative = f;
    negative(0, 0) = -1;
    EXPECT_THROW(map(p, negative, b), InputError);
    Eigen::MatrixX3i repeated = f;
    repeated(4, 1) = repeated(4, 0);
    EXPECT_THROW(map(p, repeated, b), InputError);
    Eigen::MatrixX3d not_finite = p;
    not_finite(3, 1) = std::nan("");
    EXPECT_THROW(map(not_finite, f, b), InputError);
    EXPECT_THROW(map(Eigen::MatrixX3d(0, 3), Eigen::MatrixX3i(0, 3), b), InputError);
    EXPECT_THROW(map(p, f, {b[0], b[1]}), TopologyError);
    EXPECT_THROW(map(p, f, {}), TopologyError);
    std::vector<int> outside = b;
    outside[2] = static_cast<int>(p.rows()) + 4;
    EXPECT_THROW(map(p, f, outside), InputError);
    std::vector<int> twice = b;
    twice[2] = twice[5];
    EXPECT_THROW(map(p, f, twice), InputError);
    const std::vector<int> clockwise(b.rbegin(), b.rend());
    EXPECT_THROW(map(p, f, clockwise), TopologyError);
    std::vector<int> skipping = b;
    skipping.erase(skipping.begin() + 3);
    EXPECT_THROW(map(p, f, skipping), TopologyError);
    // An interior ring of the disk is not its border.
    EXPECT_THROW(map(p, f, {1, 2, 3, 4, 5, 6}), TopologyError);
    // A vertex in no face, and a separate triangle: not joined to the outer boundary.
    Eigen::MatrixX3d extra(p.rows() + 3, 3);
    extra << p, Eigen::RowVector3d(5, 5, 0), Eigen::RowVector3d(6, 5, 0),
        Eigen::RowVector3d(5, 6, 0);
    EXPECT_THROW(map(extra, f, b), TopologyError);
    Eigen::MatrixX3i with_island(f.rows() + 1, 3);
    const int n = static_cast<int>(p.rows());
    with_island << f, Eigen::RowVector3i(n, n + 1, n + 2);
    EXPECT_THROW(map(extra, with_island, b), TopologyError);
    // The same triangle twice: an edge traversed twice in one direction.
    Eigen::MatrixX3i doubled(f.rows() + 1, 3);
    doubled << f, f.row(0);
    EXPECT_THROW(map(p, doubled, b), TopologyError);
    // Two coincident vertices: the 1/length spring of their edge is infinite.
    Eigen::MatrixX3d coincident = p;
    coincident.row(0) = coincident.row(1);
    EXPECT_THROW(map(coincident, f, b), NumericError);
  }
}

TEST(DiskMapTest, BowTieVertexIsATopologyError) {
  // Two triangles of a fan around vertex 0 sharing only that vertex, inside a disk.
  const TestPatch disk = perturbed_planar_disk();
  // Remove two non-adjacent triangles around the centre: vertex 0 gets two border loops.
  std::vector<Eigen::Vector3i> kept;
  for (Eigen::Index f = 0; f < disk.faces.rows(); ++f) {
    if (f == 0 || f == 3) continue;  // the fan (0, 1, 2) and (0, 4, 5)
    kept.emplace_back(disk.faces.row(f).transpose());
  }
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t k = 0; k < kept.size(); ++k)
    faces.row(static_cast<Eigen::Index>(k)) = kept[k].transpose();
  ASSERT_EQ(disk.faces.row(0), Eigen::RowVector3i(0, 1, 2));
  ASSERT_EQ(disk.faces.row(3), Eigen::RowVector3i(0, 4, 5));
  EXPECT_THROW(harmonic_disk_map(disk.positions, faces, disk.outer_boundary), TopologyError);
  EXPECT_THROW(cgal_disk_map(disk.positions, faces, disk.outer_boundary), TopologyError);
}

// The distortion measures on maps with known answers: a similarity keeps angles and area ratios,
// a stretch keeps area ratios but not angles, a mirror flips every triangle.
TEST(MapDistortionTest, SimilaritiesStretchesAndMirrorsHaveTheirKnownDistortion) {
  const mesh::Surface plane = test::disk(2.0, 6);
  const Eigen::MatrixX3d positions = plane.positions();
  const Eigen::MatrixX3i faces = plane.faces();
  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(0.7).toRotationMatrix();
  const Eigen::MatrixX2d similar = positions.leftCols<2>() * rotation.transpose() / 2.0;
  const MapDistortion none = map_distortion(positions, faces, similar);
  EXPECT_LT(none.angle_max_degrees, 1e-9);
  EXPECT_LT(none.area_max_log, 1e-12);
  EXPECT_EQ(none.flipped, 0);

  Eigen::MatrixX2d stretched = positions.leftCols<2>();
  stretched.col(0) *= 2.0;
  const MapDistortion stretch = map_distortion(positions, faces, stretched);
  EXPECT_GT(stretch.angle_mean_degrees, 5.0);
  EXPECT_LT(stretch.area_max_log, 1e-12);  // every area doubles: the ratios stay
  EXPECT_EQ(stretch.flipped, 0);

  Eigen::MatrixX2d mirrored = positions.leftCols<2>();
  mirrored.col(0) *= -1.0;
  const MapDistortion mirror = map_distortion(positions, faces, mirrored);
  EXPECT_EQ(mirror.flipped, faces.rows());
  EXPECT_LT(mirror.angle_max_degrees, 1e-9);  // a mirror keeps unsigned angles
  EXPECT_TRUE(std::isnan(mirror.area_mean_log));
  EXPECT_THROW(map_distortion(positions, faces, Eigen::MatrixX2d::Zero(3, 2)), InputError);
}

// The per-corner terms are those map_distortion sums: a stretch by 2 along u turns a right angle
// between the axes into a right angle, and the corners of a triangle together lose nothing.
TEST(MapDistortionTest, CornerTermsAreTheDistortionsTerms) {
  const mesh::Surface plane = test::disk(2.0, 6);
  const Eigen::MatrixX3d positions = plane.positions();
  const Eigen::MatrixX3i faces = plane.faces();
  Eigen::MatrixX2d stretched = positions.leftCols<2>();
  stretched.col(0) *= 2.0;
  const Eigen::MatrixX3d corners = corner_angle_distortion(positions, faces, stretched);
  ASSERT_EQ(corners.rows(), faces.rows());
  const MapDistortion d = map_distortion(positions, faces, stretched);
  EXPECT_NEAR(corners.mean(), d.angle_mean_degrees, 1e-12);
  EXPECT_EQ(corners.maxCoeff(), d.angle_max_degrees);
  EXPECT_GE(corners.minCoeff(), 0.0);
  // A triangle's angles sum to 180 degrees before and after: its signed changes cancel, so its
  // largest change is at most the sum of the other two.
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    EXPECT_LE(2.0 * corners.row(f).maxCoeff(), corners.row(f).sum() + 1e-9) << f;
  EXPECT_THROW(corner_angle_distortion(positions, faces, Eigen::MatrixX2d::Zero(3, 2)), InputError);
}

// compare_with_cgal on a sphere cap: the two maps agree, and both are measured.
TEST(MapDistortionTest, TheCgalComparisonAgreesOnASphereCap) {
  const test::TestPatch patch = test::sphere_cap_patch();
  const DiskMapComparison c = compare_with_cgal(patch.positions, patch.faces, patch.outer_boundary);
  EXPECT_LT(c.max_distance, 1e-9);
  EXPECT_LE(c.mean_distance, c.max_distance);
  EXPECT_NEAR(c.ours_distortion.angle_mean_degrees, c.cgal_distortion.angle_mean_degrees, 1e-6);
  EXPECT_GT(c.ours_distortion.angle_mean_degrees, 0.0);  // a cap cannot be mapped conformally
  EXPECT_EQ(c.ours_distortion.flipped, 0);
}

TEST(Parameterizations, EachMethodHasItsKnownAnswerOnAPlanarDisk) {
  const TestPatch disk = perturbed_planar_disk();
  const Eigen::MatrixX2d expected = disk.positions.leftCols(2) / 2.0;
  for (std::size_t m = 0; m < parameterization_names.size(); ++m) {
    const auto method = static_cast<Parameterization>(m);
    SCOPED_TRACE(parameterization_names[m]);
    const Eigen::MatrixX2d uv = parameterize_patch(disk.positions, disk.faces, disk.outer_boundary,
                                                   method, {SpringWeights::cotangent});
    const MapDistortion d = map_distortion(disk.positions, disk.faces, uv);
    std::cout << parameterization_names[m] << ": angle max " << d.angle_max_degrees
              << " deg, area max " << d.area_max_log << ", flipped " << d.flipped << "\n";
    EXPECT_EQ(d.flipped, 0);
    switch (method) {
      case Parameterization::harmonic:  // cotangent springs: linear precision
      case Parameterization::mean_value:
      case Parameterization::discrete_conformal:
      case Parameterization::discrete_authalic:
        EXPECT_LE(max_distance(uv, expected), 1e-9);
        break;
      case Parameterization::lscm:  // a planar patch is its own conformal / rigid map
      case Parameterization::arap:
        EXPECT_LE(d.angle_max_degrees, 1e-8);
        EXPECT_LE(d.area_max_log, 1e-10);
        break;
      case Parameterization::tutte:  // uniform weights: no linear precision
        EXPECT_GT(max_distance(uv, expected), 1e-3);
        break;
    }
  }
}

TEST(Parameterizations, FixedBorderMethodsAreCgalsOwnMaps) {
  // parameterize_patch runs CGAL's parameterizers; where one of them is also a spring kind of
  // cgal_disk_map (the harmonic map's reference), both give the same map, and ours with those
  // springs agrees with it.
  const std::vector<std::pair<Parameterization, SpringWeights>> same = {
      {Parameterization::tutte, SpringWeights::uniform},
      {Parameterization::mean_value, SpringWeights::mean_value},
      {Parameterization::discrete_conformal, SpringWeights::cotangent}};
  for (const TestPatch& patch : analytic_patches()) {
    for (const auto& [method, weights] : same) {
      SCOPED_TRACE(patch.name + ", " + parameterization_names[static_cast<std::size_t>(method)]);
      const Eigen::MatrixX2d uv =
          parameterize_patch(patch.positions, patch.faces, patch.outer_boundary, method);
      const DiskMap cgal =
          cgal_disk_map(patch.positions, patch.faces, patch.outer_boundary, {weights});
      const DiskMap ours =
          harmonic_disk_map(patch.positions, patch.faces, patch.outer_boundary, {weights});
      EXPECT_LE(max_distance(uv, cgal.uv), 1e-12);
      EXPECT_LE(max_distance(uv, ours.uv), 1e-6);
    }
    // The free-border maps are CGAL's up to a mirror: on a curved patch they distort angles
    // less than any fixed-border map, and never flip a triangle here.
    const std::vector<ParameterizationResult> results = compare_parameterizations(
        patch.positions, patch.faces, patch.outer_boundary,
        {Parameterization::discrete_conformal, Parameterization::lscm, Parameterization::arap});
    EXPECT_LT(results[1].distortion.angle_mean_degrees, results[0].distortion.angle_mean_degrees);
    EXPECT_EQ(results[1].distortion.flipped, 0);
    EXPECT_EQ(results[2].distortion.flipped, 0);
  }
}

}  // namespace
}  // namespace surfcomp::harmonic
