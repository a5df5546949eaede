#include "analytic_meshes.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/curvature.hpp"
#include "surfcomp/mesh/patch.hpp"

#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <cmath>
#include <iostream>
#include <numeric>
#include <random>
#include <string>

namespace surfcomp::mesh {
namespace {

/// Fraction of values within relative tolerance `relative` of `expected`.
double fraction_within(const Eigen::VectorXd& values, double expected, double relative) {
  Eigen::Index n = 0;
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    if (std::abs(values(i) - expected) <= relative * std::abs(expected)) ++n;
  }
  return static_cast<double>(n) / static_cast<double>(values.size());
}

/// Fraction of values within absolute tolerance `tolerance` of `expected`.
double fraction_near(const Eigen::VectorXd& values, double expected, double tolerance) {
  return static_cast<double>(((values.array() - expected).abs() <= tolerance).count()) /
         static_cast<double>(values.size());
}

/// The sphere centred at the origin with every vertex moved radially by uniform noise in
/// [-amplitude, amplitude] (A).
Surface radially_perturbed(const Surface& sphere, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-amplitude, amplitude);
  Eigen::MatrixX3d p = sphere.positions();
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    const Eigen::RowVector3d direction = p.row(i).normalized();
    p.row(i) += noise(rng) * direction;
  }
  return test::with_positions(sphere, p);
}

/// Index of the vertex nearest to `point`.
Eigen::Index nearest_vertex(const Surface& surface, const Eigen::Vector3d& point) {
  Eigen::Index best = 0;
  (surface.positions().rowwise() - point.transpose()).rowwise().squaredNorm().minCoeff(&best);
  return best;
}

TEST(PrincipalCurvatures, SphereHasMinusOneOverRadiusAtEveryScale) {
  const int frequency = 8;  // 642 vertices
  Eigen::VectorXd reference;
  for (const double r : {0.5, 1.7, 5.0, 50.0}) {
    const PrincipalCurvatures c = principal_curvatures(test::icosphere(r, frequency));
    const double cc1 = fraction_within(c.cc1, -1.0 / r, 0.05);
    const double cc2 = fraction_within(c.cc2, -1.0 / r, 0.05);
    const double s = fraction_near(c.shape_index, 1.0, 0.02);
    std::cout << "sphere r " << r << " (" << c.cc1.size() << " vertices): cc1 within 5% " << cc1
              << ", cc2 " << cc2 << ", shape index within 0.02 of +1 " << s << "; mean cc1*r "
              << c.cc1.mean() * r << "\n";
    EXPECT_GE(cc1, 0.95) << "r " << r;
    EXPECT_GE(cc2, 0.95) << "r " << r;
    EXPECT_GE(s, 0.95) << "r " << r;
    EXPECT_GE(fraction_within(c.curvedness, 1.0 / r, 0.05), 0.95) << "r " << r;
    EXPECT_TRUE((c.cc1.cwiseAbs().array() >= c.cc2.cwiseAbs().array()).all());
    // Scale invariance (CGAL's curvature test): r * cc is the same at every scale.
    if (reference.size() == 0) {
      reference = c.cc1 * r;
    } else {
      EXPECT_LT((c.cc1 * r - reference).cwiseAbs().maxCoeff(), 1e-6) << "r " << r;
    }
  }
}

TEST(PrincipalCurvatures, SphereAtMolecularSurfaceDensity) {
  for (const double r : {1.7, 5.0}) {
    const int frequency = test::icosphere_frequency_for_density(r, 2.5);
    const Surface sphere = test::icosphere(r, frequency);
    const PrincipalCurvatures c = principal_curvatures(sphere);
    const double cc1 = fraction_within(c.cc1, -1.0 / r, 0.05);
    const double cc2 = fraction_within(c.cc2, -1.0 / r, 0.05);
    std::cout << "sphere r " << r << " at " << sphere.n_vertices() / (4 * M_PI * r * r)
              << " vertices/A^2 (" << sphere.n_vertices() << "): cc1 within 5% " << cc1 << ", cc2 "
              << cc2 << "\n";
    EXPECT_GE(cc1, 0.95);
    EXPECT_GE(cc2, 0.95);
    EXPECT_GE(fraction_near(c.shape_index, 1.0, 0.02), 0.95);
  }
}

TEST(PrincipalCurvatures, CgalJetAgreesOnAFineSphere) {
  // The reference estimator: CGAL's degree-2 jet, whose bias on a fine mesh is small.
  CurvatureOptions jet;
  jet.method = CurvatureMethod::jet;
  const double r = 2.0;
  const PrincipalCurvatures c = principal_curvatures(test::icosphere(r, 8), jet);
  EXPECT_GE(fraction_within(c.cc1, -1.0 / r, 0.05), 0.95);
  EXPECT_GE(fraction_within(c.cc2, -1.0 / r, 0.05), 0.95);
  EXPECT_GE(fraction_near(c.shape_index, 1.0, 0.02), 0.95);
}

TEST(PrincipalCurvatures, InsideOutSphereIsACup) {
  const double r = 1.7;
  for (auto method : {CurvatureMethod::quadric, CurvatureMethod::jet}) {
    CurvatureOptions options;
    options.method = method;
    const PrincipalCurvatures c =
        principal_curvatures(test::with_flipped_faces(test::icosphere(r, 8)), options);
    EXPECT_GE(fraction_near(c.shape_index, -1.0, 0.02), 0.95);
    EXPECT_GE(fraction_within(c.cc1, 1.0 / r, 0.05), 0.95);
    EXPECT_GE(fraction_within(c.cc2, 1.0 / r, 0.05), 0.95);
  }
}

TEST(PrincipalCurvatures, NoisySphereStaysWithinTenPercent) {
  const double r = 1.7;
  const int frequency = test::icosphere_frequency_for_density(r, 2.5);  // 3: 92 vertices
  const Surface sphere = test::icosphere(r, frequency);
  for (const unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    const PrincipalCurvatures c = principal_curvatures(radially_perturbed(sphere, 0.02, seed));
    const double cc1 = fraction_within(c.cc1, -1.0 / r, 0.10);
    const double cc2 = fraction_within(c.cc2, -1.0 / r, 0.10);
    std::cout << "noisy sphere r " << r << ", " << sphere.n_vertices()
              << " vertices, noise +-0.02 A, seed " << seed << ": cc1 within 10% " << cc1
              << ", cc2 " << cc2 << ", shape index within 0.1 of +1 "
              << fraction_near(c.shape_index, 1.0, 0.1) << "\n";
    EXPECT_GE(cc1, 0.95) << "seed " << seed;
    EXPECT_GE(cc2, 0.95) << "seed " << seed;
  }
}

TEST(PrincipalCurvatures, EllipsoidMatchesTheClosedForm) {
  const double a = 3.0, b = 2.0, c = 1.5;
  const Surface ellipsoid = test::ellipsoid(a, b, c, 16);  // 2562 vertices
  const PrincipalCurvatures k = principal_curvatures(ellipsoid);
  const Eigen::MatrixX3d positions = ellipsoid.positions();
  Eigen::Index good = 0;
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const auto [k_max, k_min] =
        test::ellipsoid_principal_curvatures(a, b, c, positions.row(v).transpose());
    if (std::abs(-k.cc1(v) - k_max) <= 0.05 * k_max &&
        std::abs(-k.cc2(v) - k_min) <= 0.05 * k_max) {
      ++good;
    }
  }
  const double fraction = static_cast<double>(good) / static_cast<double>(positions.rows());
  std::cout << "ellipsoid (3, 2, 1.5): both curvatures within 5% of k_max at " << fraction << " of "
            << positions.rows() << " vertices\n";
  EXPECT_GE(fraction, 0.95);
  // At the ends of the long axis: a / c^2 and a / b^2 (convex positive).
  for (const double side : {1.0, -1.0}) {
    const Eigen::Index tip = nearest_vertex(ellipsoid, Eigen::Vector3d(side * a, 0, 0));
    const auto [k_max, k_min] =
        test::ellipsoid_principal_curvatures(a, b, c, positions.row(tip).transpose());
    EXPECT_NEAR(k_max, a / (c * c), 0.02 * a / (c * c));  // the vertex is near the tip
    EXPECT_NEAR(k_min, a / (b * b), 0.02 * a / (b * b));
    EXPECT_NEAR(-k.cc1(tip), k_max, 0.05 * k_max);
    EXPECT_NEAR(-k.cc2(tip), k_min, 0.05 * k_min);
    std::cout << "ellipsoid tip " << side * a << ": cc1 " << k.cc1(tip) << " (analytic " << -k_max
              << "), cc2 " << k.cc2(tip) << " (" << -k_min << ")\n";
  }
}

TEST(PrincipalCurvatures, TorusEquators) {
  struct Case {
    double major, minor;
  };
  for (const Case t : {Case{3.0, 1.0}, Case{2.0, 1.2}}) {
    const int n_major = 160, n_minor = 64;
    const Surface torus = test::torus(t.major, t.minor, n_major, n_minor);
    const PrincipalCurvatures k = principal_curvatures(torus);
    for (int i = 0; i < n_major; i += 20) {
      // Outer equator (phi = 0): convex, k = 1/r and 1/(R + r).
      const int outer = i * n_minor;
      EXPECT_NEAR(k.cc1(outer), -1.0 / t.minor, 0.05 / t.minor);
      EXPECT_NEAR(k.cc2(outer), -1.0 / (t.major + t.minor), 0.05 / (t.major + t.minor));
      // Inner equator (phi = pi): a saddle, k = 1/r and -1/(R - r).
      const int inner = i * n_minor + n_minor / 2;
      const double k_tube = 1.0 / t.minor, k_ring = -1.0 / (t.major - t.minor);
      const double larger = std::max(std::abs(k_tube), std::abs(k_ring));
      const double smaller = std::min(std::abs(k_tube), std::abs(k_ring));
      EXPECT_NEAR(std::abs(k.cc1(inner)), larger, 0.05 * larger);
      EXPECT_NEAR(std::abs(k.cc2(inner)), smaller, 0.05 * larger);
      EXPECT_LT(k.cc1(inner) * k.cc2(inner), 0.0);  // negative Gaussian curvature
      const double s = 2.0 / M_PI * std::atan((k_tube + k_ring) / (k_tube - k_ring));
      EXPECT_NEAR(k.shape_index(inner), s, 0.03) << "R " << t.major << " r " << t.minor;
      if (i == 0) {
        std::cout << "torus R " << t.major << " r " << t.minor << ": outer cc1 " << k.cc1(outer)
                  << " cc2 " << k.cc2(outer) << "; inner cc1 " << k.cc1(inner) << " cc2 "
                  << k.cc2(inner) << " S " << k.shape_index(inner) << " (analytic " << s << ")\n";
      }
    }
  }
  // S < 0 at the inner equator needs |k_ring| > k_tube, i.e. R < 2r: R 2, r 1.2 has S -0.13.
  const PrincipalCurvatures k = principal_curvatures(test::torus(2.0, 1.2, 160, 64));
  EXPECT_LT(k.shape_index(32), -0.1);
}

TEST(PrincipalCurvatures, PlaneIsFlat) {
  // Without the ridge, the quadric's z^2, xz, yz columns vanish on a plane: the least-squares
  // system is rank-deficient and its basic solution leaves them at 0.
  for (const double ridge : {0.01, 0.0}) {
    CurvatureOptions options;
    options.quadric_ridge = ridge;
    const PrincipalCurvatures k = principal_curvatures(test::disk(5.0, 10), options);
    EXPECT_LT(k.cc1.cwiseAbs().maxCoeff(), 1e-9) << "ridge " << ridge;
    EXPECT_LT(k.curvedness.maxCoeff(), 1e-9) << "ridge " << ridge;
  }
}

TEST(PrincipalCurvatures, ResultDoesNotDependOnThreadCount) {
  const Surface sphere = radially_perturbed(test::icosphere(3.0, 12), 0.05, 11);
  const PrincipalCurvatures parallel = principal_curvatures(sphere);
  PrincipalCurvatures serial;
  tbb::task_arena one_thread(1);
  one_thread.execute([&] { serial = principal_curvatures(sphere); });
  EXPECT_TRUE((parallel.cc1.array() == serial.cc1.array()).all());
  EXPECT_TRUE((parallel.cc2.array() == serial.cc2.array()).all());
  EXPECT_TRUE((parallel.shape_index.array() == serial.shape_index.array()).all());
}

TEST(PrincipalCurvatures, UsesTheSurfaceNormalsWhenItHasThem) {
  Surface sphere = test::icosphere(2.0, 6);
  sphere.set_normals(-(sphere.positions().rowwise().normalized()));  // inward normals
  const PrincipalCurvatures k = principal_curvatures(sphere);
  EXPECT_GE(fraction_near(k.shape_index, -1.0, 0.02), 0.95);  // seen from inside: a cup
}

TEST(PrincipalCurvatures, ComponentSmallerThanMinPointsGetsItsCircumsphere) {
  // 4 and 6 vertices, fewer than min_points (12): each neighbourhood is the whole closed
  // component, and the fitted sphere is its circumsphere, at every scale and wherever it lies.
  const Eigen::Vector3d centre(3.0, -1.0, 2.0);
  for (auto method : {CurvatureMethod::quadric, CurvatureMethod::jet}) {
    CurvatureOptions options;
    options.method = method;
    for (const double r : {1e-3, 0.02, 1.7, 1e3}) {
      for (const Surface& shape : {test::tetrahedron(r, centre), test::octahedron(r, centre)}) {
        const PrincipalCurvatures k = principal_curvatures(shape, options);
        const std::string what = shape.source() + " r " + std::to_string(r);
        EXPECT_LT((k.cc1.array() * r + 1.0).abs().maxCoeff(), 1e-9) << what;
        EXPECT_LT((k.cc2.array() * r + 1.0).abs().maxCoeff(), 1e-9) << what;
        EXPECT_LT((k.shape_index.array() - 1.0).abs().maxCoeff(), 1e-9) << what;
        EXPECT_LT((k.curvedness.array() * r - 1.0).abs().maxCoeff(), 1e-9) << what;
        // Inside out, the same sphere is a cup.
        const PrincipalCurvatures cup =
            principal_curvatures(test::with_flipped_faces(shape), options);
        EXPECT_LT((cup.cc1.array() * r - 1.0).abs().maxCoeff(), 1e-9) << what;
        EXPECT_LT((cup.shape_index.array() + 1.0).abs().maxCoeff(), 1e-9) << what;
      }
    }
  }
}

TEST(PrincipalCurvatures, TinyComponentLeavesTheRestOfTheSurfaceAlone) {
  // A sphere with a 4-vertex fragment 0.02 A across beside it, as the SES grid can leave where
  // it loses a sub-voxel neck: each vertex is fitted within its own component.
  const double r = 2.0, fragment = 0.02;
  const Surface sphere = test::icosphere(r, 6);
  const Surface both =
      test::merged(sphere, test::tetrahedron(fragment, Eigen::Vector3d(4.0, 0.0, 0.0)));
  const PrincipalCurvatures alone = principal_curvatures(sphere);
  const PrincipalCurvatures k = principal_curvatures(both);
  const Eigen::Index n = alone.cc1.size();
  EXPECT_TRUE((k.cc1.head(n).array() == alone.cc1.array()).all());
  EXPECT_TRUE((k.cc2.head(n).array() == alone.cc2.array()).all());
  EXPECT_TRUE((k.shape_index.head(n).array() == alone.shape_index.array()).all());
  EXPECT_LT((k.cc1.tail(4).array() * fragment + 1.0).abs().maxCoeff(), 1e-9);
  EXPECT_LT((k.cc2.tail(4).array() * fragment + 1.0).abs().maxCoeff(), 1e-9);
}

TEST(PrincipalCurvatures, RejectsBadInput) {
  Eigen::MatrixX3d points(3, 3);
  points << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  const Surface no_faces = Surface::from_arrays(points, Eigen::MatrixX3i(0, 3), "no_faces");
  EXPECT_THROW(principal_curvatures(no_faces), TopologyError);
  EXPECT_THROW(angle_defects(no_faces), TopologyError);

  Eigen::MatrixX3i one_face(1, 3);
  one_face << 0, 1, 2;
  // Three vertices: fewer than even the sphere's 4 coefficients.
  EXPECT_THROW(principal_curvatures(Surface::from_arrays(points, one_face)), TopologyError);

  const Surface sphere = test::icosphere(1.0, 2);
  CurvatureOptions bad;
  bad.rings = 0;
  EXPECT_THROW(principal_curvatures(sphere, bad), OptionError);
  bad = {};
  bad.min_points = 5;
  EXPECT_THROW(principal_curvatures(sphere, bad), OptionError);
  bad = {};
  bad.method = CurvatureMethod::jet;
  bad.jet_degree = 5;
  EXPECT_THROW(principal_curvatures(sphere, bad), OptionError);
  bad = {};
  bad.radius = -1.0;
  EXPECT_THROW(principal_curvatures(sphere, bad), OptionError);
}

TEST(PrincipalCurvatures, RadiusNeighbourhood) {
  CurvatureOptions options;
  options.radius = 1.0;  // A
  const double r = 3.0;
  const PrincipalCurvatures k = principal_curvatures(test::icosphere(r, 12), options);
  EXPECT_GE(fraction_within(k.cc1, -1.0 / r, 0.05), 0.95);
  EXPECT_GE(fraction_within(k.cc2, -1.0 / r, 0.05), 0.95);
}

// Spheres at the surface builder's density (2.5 vertices per A^2), a ligand's size and a
// protein's (the sizes bench/curvature_bench.cpp times).
TEST(PrincipalCurvatures, SpheresAtTheSurfaceBuildersDensity) {
  for (const int frequency : {11, 55}) {  // 1,212 and 30,252 vertices
    const double r = std::sqrt(10.0 * frequency * frequency / (4 * M_PI * 2.5));
    const PrincipalCurvatures k = principal_curvatures(test::icosphere(r, frequency));
    EXPECT_GE(fraction_within(k.cc1, -1.0 / r, 0.05), 0.95) << "frequency " << frequency;
  }
}

TEST(AngleDefects, GaussBonnet) {
  const Eigen::VectorXd sphere = angle_defects(test::icosphere(1.7, 7));
  EXPECT_NEAR(sphere.sum(), 4 * M_PI, 1e-9);
  EXPECT_TRUE((sphere.array() > 0).all());  // convex everywhere
  const Eigen::VectorXd torus = angle_defects(test::torus(3.0, 1.0, 60, 24));
  EXPECT_NEAR(torus.sum(), 0.0, 1e-9);
  EXPECT_LT(torus(12), 0.0);  // inner equator: a saddle
  EXPECT_GT(torus(0), 0.0);   // outer equator: convex
  // A flat disk: no defect inside; the boundary terms pi - angle sum to the turning, 2 pi.
  const Surface disk = test::disk(2.0, 6);
  const Eigen::VectorXd flat = angle_defects(disk);
  std::vector<int> all_faces(disk.n_faces());
  std::iota(all_faces.begin(), all_faces.end(), 0);
  const BoundaryLoops border = boundary_loops(disk, all_faces);
  ASSERT_EQ(border.outer.size(), 36u);  // the outermost ring, 6 * 6 vertices
  ASSERT_TRUE(border.holes.empty());
  std::vector<bool> on_border(disk.n_vertices(), false);
  double boundary = 0.0;
  for (const int v : border.outer) {
    on_border[static_cast<std::size_t>(v)] = true;
    boundary += flat(v);
  }
  for (Eigen::Index v = 0; v < flat.size(); ++v) {
    if (!on_border[static_cast<std::size_t>(v)]) {
      EXPECT_NEAR(flat(v), 0.0, 1e-12);
    }
  }
  EXPECT_NEAR(boundary, 2 * M_PI, 1e-9);
}

}  // namespace
}  // namespace surfcomp::mesh
