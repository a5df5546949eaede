// The packed single-precision overlay of a screen's first two stages (matching::PackedQuery)
// against the double-precision SurfaceOverlay it stands in for: the same scores at any transform,
// a sample on itself scoring 1, the best principal-axes start, rigid motions of the probe, the
// refinement, and the checks.
#include "surfcomp/matching/packed_overlay.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/matching/principal_axes.hpp"
#include "test_data.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <random>
#include <string>

namespace surfcomp {
namespace {

using matching::AtomSample;
using matching::OverlayOptions;
using matching::PackedQuery;
using matching::PackedSample;
using matching::RigidTransform;
using matching::SampleKind;
using matching::SurfaceSample;

struct Ligand {
  SurfaceSample sample;
  AtomSample atoms;
};

/// The screening sample and heteroatoms of a thermolysin crystal ligand (common frame).
std::optional<Ligand> ligand(const std::string& id) {
  const auto path = test::shared_dataset("thermolysin/ligands-common-frame/" + id + "_ligand.sdf");
  if (!path) return std::nullopt;
  const Molecule molecule = io::read_molecule(*path);
  return Ligand{matching::sample_molecule(molecule, OverlayOptions{}.spacing),
                matching::sample_atoms(harmonic::surface_atoms(molecule))};
}

/// A rotation by `angle` about `axis` through `centre`.
RigidTransform turn_about(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis,
                          double angle) {
  RigidTransform t;
  t.rotation = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  t.translation = centre - t.rotation * centre;
  return t;
}

/// The sample's area-weighted centroid.
Eigen::Vector3d centroid(const SurfaceSample& s) { return s.points * s.weights / s.weights.sum(); }

RigidTransform random_motion(std::mt19937& random, double shift) {
  std::normal_distribution<double> normal(0.0, 1.0);
  RigidTransform t;
  t.rotation = Eigen::Quaterniond(normal(random), normal(random), normal(random), normal(random))
                   .normalized()
                   .toRotationMatrix();
  t.translation = shift * Eigen::Vector3d(normal(random), normal(random), normal(random));
  return t;
}

/// `sample` and `atoms` moved by `t`.
Ligand moved(const Ligand& l, const RigidTransform& t) {
  Ligand out = l;
  out.sample.points = t.apply(l.sample.points);
  out.sample.normals = t.rotation * l.sample.normals;
  out.atoms.points = t.apply(l.atoms.points);
  return out;
}

class PackedOverlayTest : public ::testing::Test {
 protected:
  void SetUp() override {
    reference_ = ligand("1THL");
    probe_ = ligand("4TMN");
    if (!reference_ || !probe_) SURFCOMP_DATA_ABSENT(test::shared_absent_message("thermolysin"));
  }
  std::optional<Ligand> reference_, probe_;
  const OverlayOptions options_;
};

TEST_F(PackedOverlayTest, ScoresMatchTheDoubleOverlayAtAnyTransform) {
  const PackedQuery query(
      PackedSample(reference_->sample, reference_->atoms, options_.sigma, SampleKind::atoms));
  const PackedSample probe(probe_->sample, probe_->atoms, options_.sigma, SampleKind::atoms);
  const matching::SurfaceOverlay overlay(reference_->sample, probe_->sample, options_,
                                         reference_->atoms, probe_->atoms);
  std::mt19937 random(20261127);
  std::normal_distribution<double> normal(0.0, 1.0);
  double largest = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    // Motions about the crystal pose (turns about the probe's centre, shifts), where the two
    // surfaces overlap more or less.
    RigidTransform t = turn_about(centroid(probe_->sample),
                                  Eigen::Vector3d(normal(random), normal(random), normal(random)),
                                  0.5 * trial / 20.0);
    t.translation += 0.5 * Eigen::Vector3d(normal(random), normal(random), normal(random));
    const matching::OverlayScore exact = overlay.score(t);
    largest = std::max(largest, exact.score);
    const matching::OverlayScore packed = query.score(probe.view(), t, options_);
    EXPECT_NEAR(packed.shape, exact.shape, 2e-6) << "trial " << trial;
    EXPECT_NEAR(packed.chem, exact.chem, 2e-6) << "trial " << trial;
    EXPECT_NEAR(packed.atoms, exact.atoms, 2e-6) << "trial " << trial;
    EXPECT_NEAR(packed.score, exact.score, 2e-6) << "trial " << trial;
  }
  EXPECT_GT(largest, 0.3);  // the trials include overlapping poses (the crystal pair: 0.41)
}

TEST_F(PackedOverlayTest, ASampleOnItselfScoresOneAtTheIdentity) {
  const PackedSample packed(reference_->sample, reference_->atoms, options_.sigma,
                            SampleKind::atoms);
  const PackedQuery query(packed);
  const PackedQuery::Score best = query.fast_score(packed.view(), options_);
  EXPECT_NEAR(best.score.score, 1.0, 1e-6);
  EXPECT_LT(matching::rotation_angle_degrees(best.transform.rotation), 1e-6);
  EXPECT_LT(best.transform.translation.norm(), 1e-9);
}

TEST_F(PackedOverlayTest, FastScoreIsTheBestPrincipalAxesStartAndIgnoresRigidMotions) {
  const PackedQuery query(
      PackedSample(reference_->sample, reference_->atoms, options_.sigma, SampleKind::atoms));
  const matching::SurfaceOverlay overlay(reference_->sample, probe_->sample, options_,
                                         reference_->atoms, probe_->atoms);
  double best = 0.0;
  for (const RigidTransform& start :
       matching::principal_axes_starts(reference_->sample, probe_->sample))
    best = std::max(best, overlay.score(start).score);
  const PackedSample probe(probe_->sample, probe_->atoms, options_.sigma, SampleKind::atoms);
  const PackedQuery::Score fast = query.fast_score(probe.view(), options_);
  EXPECT_NEAR(fast.score.score, best, 2e-6);
  EXPECT_NEAR(overlay.score(fast.transform).score, best, 2e-6);  // the transform is that start's
  // The probe anywhere else: its principal frame moves with it.
  std::mt19937 random(7);
  for (int trial = 0; trial < 3; ++trial) {
    const Ligand far = moved(*probe_, random_motion(random, 20.0));
    const PackedSample packed_far(far.sample, far.atoms, options_.sigma, SampleKind::atoms);
    EXPECT_NEAR(query.fast_score(packed_far.view(), options_).score.score, best, 1e-5);
  }
}

TEST_F(PackedOverlayTest, RefinementFindsTheSelfOverlayFromAPerturbedPose) {
  const PackedSample packed(reference_->sample, reference_->atoms, options_.sigma,
                            SampleKind::atoms);
  const PackedQuery query(packed);
  const matching::SurfaceOverlay overlay(reference_->sample, reference_->sample, options_,
                                         reference_->atoms, reference_->atoms);
  const Eigen::Vector3d centre = centroid(reference_->sample);
  RigidTransform start = turn_about(centre, Eigen::Vector3d(0.3, -1.0, 0.5), 0.25);
  start.translation += Eigen::Vector3d(0.6, -0.4, 0.5);
  const matching::RefineResult packed_result = query.refine(packed.view(), start, options_);
  const matching::RefineResult exact = overlay.refine(start);
  EXPECT_GT(packed_result.score.score, query.score(packed.view(), start, options_).score + 0.2);
  EXPECT_GT(packed_result.score.score, 0.97);
  EXPECT_LT(matching::rotation_angle_degrees(packed_result.transform.rotation), 2.0);
  EXPECT_LT((packed_result.transform.apply(centre) - centre).norm(), 0.2);
  EXPECT_NEAR(packed_result.score.score, exact.score.score, 0.01);
}

TEST_F(PackedOverlayTest, PackingRoundTripsAndRefusesOtherWidths) {
  const PackedSample packed(probe_->sample, probe_->atoms, options_.sigma, SampleKind::atoms);
  const SurfaceSample back = packed.sample();
  ASSERT_EQ(back.size(), probe_->sample.size());
  // The points in another order (compact clusters), each within single precision.
  EXPECT_NEAR(back.weights.sum(), probe_->sample.weights.sum(), 1e-4);
  const AtomSample atoms = packed.atoms();
  EXPECT_EQ(atoms.size(), probe_->atoms.size());
  EXPECT_LT((atoms.points - probe_->atoms.points).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_EQ(atoms.elements, probe_->atoms.elements);
  const PackedSample view_copy(packed.view());
  EXPECT_EQ(view_copy.header().self_shape, packed.header().self_shape);
  const PackedQuery query(packed);
  OverlayOptions wider = options_;
  wider.sigma = 1.5;
  EXPECT_THROW(query.fast_score(packed.view(), wider), InputError);
  EXPECT_THROW(PackedSample(SurfaceSample{}, AtomSample{}, 1.0, SampleKind::atoms), InputError);
  EXPECT_THROW(PackedSample(probe_->sample, probe_->atoms, 0.0, SampleKind::atoms), OptionError);
}

}  // namespace
}  // namespace surfcomp
