// Dense correspondences through harmonic shape images (method §6) on the 1THL ligand surface and
// a rigidly moved copy: the points paired through the images of the same critical point must be
// images of each other under the motion, and their fit must recover it.
#include "surfcomp/matching/correspondences.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/clustering.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include "test_data.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

namespace surfcomp::matching {
namespace {

const char* k1thl = "thermolysin/ligands-common-frame/1THL_ligand.sdf";

struct Motion {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d translation;
};

Motion random_motion(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss;
  return {Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng))
              .normalized()
              .toRotationMatrix(),
          Eigen::Vector3d(12.0, -3.0, 40.0)};
}

double percentile(std::vector<double> v, double fraction) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(fraction * static_cast<double>(v.size() - 1))];
}

/// Residuals |q - (R p + t)| of correspondences, A.
std::vector<double> residuals(const Correspondences& c, const Motion& m) {
  std::vector<double> out;
  for (Eigen::Index i = 0; i < c.a_points.cols(); ++i) {
    out.push_back((c.b_points.col(i) - (m.rotation * c.a_points.col(i) + m.translation)).norm());
  }
  return out;
}

// The same mesh moved: every patch, map and image is the same, the best shift is 0, and the
// correspondences are exact images of each other (to round-off); so are the properties.
TEST(Correspondences, AMovedCopyOfTheSameMeshCorrespondsExactly) {
  SURFCOMP_SHARED_OR_SKIP(file, k1thl);
  const mesh::Surface surface = molsurf::build_molecular_surface(io::read_molecule(file));
  const Motion m = random_motion(7u);
  mesh::Surface moved = surface;
  mesh::transform_surface(moved, m.rotation, m.translation);
  molsurf::assign_surface_properties(moved, nullptr);  // curvature refitted on the moved mesh
  const auto a = harmonic::describe_surface(surface);
  const auto b = harmonic::describe_surface(moved);
  ASSERT_EQ(a.critical_points.size(), b.critical_points.size());
  double worst = 0.0, worst_property = 0.0;
  std::size_t total = 0;
  std::vector<MatchedPair> pairs;
  for (std::size_t i = 0; i < a.critical_points.size(); ++i) {
    if (a.critical_points[i].status != harmonic::PatchStatus::ok) continue;
    const auto match =
        harmonic::compare_images(a.critical_points[i].image, b.critical_points[i].image);
    EXPECT_EQ(match.shift, 0) << "critical point " << i;
    const MatchedPair pair{static_cast<int>(i), static_cast<int>(i), match.shift};
    pairs.push_back(pair);
    const Correspondences c = pair_correspondences(a, b, pair);
    total += c.size();
    for (double r : residuals(c, m)) worst = std::max(worst, r);
    worst_property = std::max(worst_property, (c.a_property - c.b_property).cwiseAbs().maxCoeff());
    EXPECT_GT(c.size(), 300u);
    EXPECT_LE(c.size(), 16u * 60u);
  }
  std::printf(
      "[ same mesh] %zu correspondences, worst |q - (Rp + t)| %.2e A, worst esp difference %.2e\n",
      total, worst, worst_property);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_property, 1e-9);
  // One clique of all pairs: its fit moves B onto A, the inverse motion, with R_chem 1.
  const auto clusters = cluster_alignments({pairs}, a, b);
  ASSERT_EQ(clusters.size(), 1u);
  EXPECT_LT(rotation_angle_degrees(clusters[0].fit.transform.rotation * m.rotation), 1e-6);
  EXPECT_LT((clusters[0].fit.transform.translation + m.rotation.transpose() * m.translation).norm(),
            1e-9);
  EXPECT_LT(clusters[0].fit.rmsd, 1e-9);
  EXPECT_NEAR(clusters[0].r_chem, 1.0, 1e-12);
}

// The molecule moved and its surface built anew: another triangulation (SES edges ~0.7 A at
// 2.5 vertices/A^2), other critical-point centres (up to 0.75 A apart after the motion), other
// patch borders and harmonic maps. Critical points are paired when of one type and within
// 0.75 A after the motion; the best image rotation pairs their points. Measured (motions of
// seeds 11-20): per-pair median residual 0.18-1.02 A, all points median 0.36-0.39 A and 90th
// percentile 0.72-0.82 A (seeds 11-13); the union fit is off by 0.7-2.0 degrees and 0.03-0.15 A at
// the molecule's centroid. The rotation error comes from the jitter of the critical points
// themselves: a fit of the paired critical points' positions alone is off by 2.2 degrees.
// Tolerances: each pair's median residual < its CP offset + 0.7 A (one mesh edge; the centres
// map onto each other, so the offset shifts the whole pair), all points' median < 0.5 A and 90th
// percentile < 1 A; union fit rotation < 2.5 degrees, centroid < 0.5 A.
TEST(Correspondences, ARebuiltMovedSurfaceCorrespondsToWithinTheMeshResolution) {
  SURFCOMP_SHARED_OR_SKIP(file, k1thl);
  const Molecule molecule = io::read_molecule(file);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& atom : molecule.atoms)
    centroid += atom.position / static_cast<double>(molecule.atoms.size());
  const auto a = harmonic::describe_surface(molsurf::build_molecular_surface(molecule));
  for (unsigned seed : {11u, 12u, 13u}) {
    Molecule moved_molecule = molecule;
    const Motion m = random_motion(seed);
    transform_molecule(moved_molecule, m.rotation, m.translation);
    const auto b = harmonic::describe_surface(molsurf::build_molecular_surface(moved_molecule));

    std::vector<MatchedPair> pairs;
    std::vector<double> all;
    double worst_pair = 0.0;
    for (std::size_t i = 0; i < a.critical_points.size(); ++i) {
      const auto& ca = a.critical_points[i];
      if (ca.status != harmonic::PatchStatus::ok) continue;
      for (std::size_t j = 0; j < b.critical_points.size(); ++j) {
        const auto& cb = b.critical_points[j];
        if (cb.status != harmonic::PatchStatus::ok || cb.point.type != ca.point.type) continue;
        const double offset =
            (m.rotation * ca.point.position + m.translation - cb.point.position).norm();
        if (offset > 0.75) continue;
        const auto match = harmonic::compare_images(ca.image, cb.image);
        const MatchedPair pair{static_cast<int>(i), static_cast<int>(j), match.shift};
        const std::vector<double> r = residuals(pair_correspondences(a, b, pair), m);
        all.insert(all.end(), r.begin(), r.end());
        worst_pair = std::max(worst_pair, percentile(r, 0.5) - offset);
        pairs.push_back(pair);
      }
    }
    ASSERT_GE(pairs.size(), 10u);
    std::printf(
        "[ rebuilt  ] seed %u: %zu pairs, %zu correspondences: median %.3f A, 90th percentile "
        "%.3f A; worst pair median minus its CP offset %.3f A\n",
        seed, pairs.size(), all.size(), percentile(all, 0.5), percentile(all, 0.9), worst_pair);
    EXPECT_LT(worst_pair, 0.7);
    EXPECT_LT(percentile(all, 0.5), 0.5);
    EXPECT_LT(percentile(all, 0.9), 1.0);

    // One clique of all pairs: its fit (moving B onto A) is the inverse motion.
    const auto clusters = cluster_alignments({pairs}, a, b);
    ASSERT_EQ(clusters.size(), 1u);
    const RigidFit& fit = clusters[0].fit;
    const double rotation_error = rotation_angle_degrees(fit.transform.rotation * m.rotation);
    const double centroid_error =
        (fit.transform.rotation * (m.rotation * centroid + m.translation) +
         fit.transform.translation - centroid)
            .norm();
    std::printf(
        "[ rebuilt  ] seed %u: union fit %zu points, RMSD %.3f A, rotation error %.3f deg, "
        "centroid error %.3f A, R_chem %.3f\n",
        seed, fit.n_points, fit.rmsd, rotation_error, centroid_error, clusters[0].r_chem);
    EXPECT_LT(rotation_error, 2.5);
    EXPECT_LT(centroid_error, 0.5);
    EXPECT_GT(clusters[0].r_chem, 0.9);
  }
}

TEST(Correspondences, BadPairsAreRejected) {
  SURFCOMP_SHARED_OR_SKIP(file, k1thl);
  const auto a =
      harmonic::describe_surface(molsurf::build_molecular_surface(io::read_molecule(file)));
  const int n = static_cast<int>(a.critical_points.size());
  int k = 0;
  while (k < n &&
         a.critical_points[static_cast<std::size_t>(k)].status != harmonic::PatchStatus::ok)
    ++k;
  ASSERT_LT(k, n);
  EXPECT_THROW(pair_correspondences(a, a, {n, k, 0}), InputError);
  EXPECT_THROW(pair_correspondences(a, a, {k, -1, 0}), InputError);
  CorrespondenceOptions options;
  options.sector_step = 0;
  EXPECT_THROW(pair_correspondences(a, a, {k, k, 0}, options), OptionError);
  options = {};
  options.property = "no_such_property";
  EXPECT_THROW(pair_correspondences(a, a, {k, k, 0}, options), InputError);
  // A self-pair with every grid point: each valid grid point once, p == q.
  options = {};
  options.sector_step = 1;
  const Correspondences self = pair_correspondences(a, a, {k, k, 0}, options);
  const auto& valid = a.critical_points[static_cast<std::size_t>(k)].image.valid;
  EXPECT_EQ(self.size(), static_cast<std::size_t>(std::count(valid.begin(), valid.end(), 1)));
  EXPECT_EQ((self.a_points - self.b_points).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_DOUBLE_EQ(property_correlation(self), 1.0);
}

}  // namespace
}  // namespace surfcomp::matching
