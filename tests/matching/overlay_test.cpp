// The whole-surface overlay: sampling keeps the area, the Tanimoto scores are 1 exactly for a
// surface on itself (also moved) and symmetric in the two surfaces, two points overlap by the
// Gaussian of their distance, same-element heteroatoms tell apart poses the surface cannot,
// refinement climbs back to a known motion, the weighted rigid fit ignores what has no weight,
// and overlays sharing one indexed reference give the pair's numbers. The atom fit of the atom
// polish is 1 for a molecule on itself and the Gaussian of a distance for two atoms, pairs like
// elements only, and its polish takes a moved copy back to the identity.
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/matching/atom_polish.hpp"
#include "surfcomp/matching/match.hpp"
#include "surfcomp/mesh/surface.hpp"

#include "analytic_meshes.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace surfcomp {
namespace {

using matching::RigidTransform;

/// An ellipsoid with distinct axes and an ESP that varies along x and an LP along y, so that
/// neither its shape's symmetries nor its chemistry's leave another pose as good as the true one.
mesh::Surface labelled_ellipsoid() {
  mesh::Surface surface = test::ellipsoid(4.0, 2.5, 1.5, 24);
  const Eigen::MatrixX3d p = surface.positions();
  surface.set_property(mesh::property::esp, Eigen::VectorXd(p.col(0) * 3.0 + p.col(2)));
  surface.set_property(mesh::property::lp, Eigen::VectorXd(p.col(1) * 0.2));
  surface.compute_normals();
  return surface;
}

RigidTransform motion(double degrees, const Eigen::Vector3d& axis, const Eigen::Vector3d& shift) {
  RigidTransform t;
  t.rotation = Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  t.translation = shift;
  return t;
}

mesh::Surface moved(const mesh::Surface& surface, const RigidTransform& t) {
  mesh::Surface copy = surface;
  mesh::transform_surface(copy, t.rotation, t.translation);
  return copy;
}

RigidTransform inverse(const RigidTransform& t) {
  RigidTransform i;
  i.rotation = t.rotation.transpose();
  i.translation = -(i.rotation * t.translation);
  return i;
}

double surface_area(const mesh::Surface& surface) { return mesh::measure_surface(surface).area; }

TEST(Overlay, SampleWeightsAddUpToTheArea) {
  const mesh::Surface surface = labelled_ellipsoid();
  const matching::SurfaceSample sample = matching::sample_surface(surface, 1.0);
  EXPECT_NEAR(sample.weights.sum(), surface_area(surface), 1e-9 * surface_area(surface));
  EXPECT_LT(sample.size(), surface.n_vertices());
  for (std::size_t i = 0; i < sample.size(); ++i)
    EXPECT_NEAR(sample.normals.col(static_cast<Eigen::Index>(i)).norm(), 1.0, 1e-12);
  // A mask keeping the half x > 0 keeps about half the area, and only points there.
  const Eigen::MatrixX3d p = surface.positions();
  std::vector<bool> half(surface.n_vertices());
  for (std::size_t v = 0; v < half.size(); ++v) half[v] = p(static_cast<Eigen::Index>(v), 0) > 0.0;
  const matching::SurfaceSample part = matching::sample_surface(surface, 1.0, &half);
  EXPECT_NEAR(part.weights.sum() / sample.weights.sum(), 0.5, 0.05);
  EXPECT_GT(part.points.row(0).minCoeff(), 0.0);
}

TEST(Overlay, ASurfaceOnItselfScoresOneAndLessWhenMoved) {
  const mesh::Surface surface = labelled_ellipsoid();
  const matching::SurfaceSample sample = matching::sample_surface(surface, 1.0);
  const matching::SurfaceOverlay overlay(sample, sample);
  const matching::OverlayScore at_identity = overlay.score(RigidTransform{});
  EXPECT_NEAR(at_identity.shape, 1.0, 1e-12);
  EXPECT_NEAR(at_identity.chem, 1.0, 1e-12);
  EXPECT_NEAR(at_identity.score, 1.0, 1e-12);
  double last = 1.0;
  for (double shift : {0.5, 1.0, 2.0, 4.0}) {
    const double s =
        overlay.score(motion(0.0, Eigen::Vector3d::UnitX(), Eigen::Vector3d(shift, 0.0, 0.0)))
            .score;
    EXPECT_LT(s, last) << "shift " << shift;
    EXPECT_GE(s, 0.0);
    last = s;
  }
  // Turned by 180 degrees about z the shape nearly coincides but the ESP (along x) is reversed.
  const matching::OverlayScore turned =
      overlay.score(motion(180.0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()));
  EXPECT_GT(turned.shape, 0.9);
  EXPECT_LT(turned.chem, 0.5 * turned.shape);
}

TEST(Overlay, ScoresAreSymmetricInTheTwoSurfaces) {
  const mesh::Surface a = labelled_ellipsoid();
  const mesh::Surface b = test::icosphere(2.5, 12);
  const matching::SurfaceSample sa = matching::sample_surface(a, 1.0);
  const matching::SurfaceSample sb = matching::sample_surface(b, 1.0);
  const RigidTransform t =
      motion(37.0, Eigen::Vector3d(1.0, 2.0, 3.0), Eigen::Vector3d(0.7, -0.4, 0.2));
  const matching::OverlayScore ab = matching::SurfaceOverlay(sa, sb).score(t);
  const matching::OverlayScore ba = matching::SurfaceOverlay(sb, sa).score(inverse(t));
  EXPECT_GT(ab.shape, 0.05);
  EXPECT_LT(ab.shape, 1.0);
  EXPECT_NEAR(ab.shape, ba.shape, 1e-12);
  EXPECT_NEAR(ab.chem, ba.chem, 1e-12);
}

TEST(Overlay, RefinementRecoversAKnownMotion) {
  const mesh::Surface reference = labelled_ellipsoid();
  // The probe is the reference moved by `truth`; the answer is its inverse.
  const RigidTransform truth =
      motion(70.0, Eigen::Vector3d(1.0, -1.0, 2.0), Eigen::Vector3d(5.0, -3.0, 8.0));
  const mesh::Surface probe = moved(reference, truth);
  const matching::SurfaceOverlay overlay(matching::sample_surface(reference, 1.0),
                                         matching::sample_surface(probe, 1.0));
  const RigidTransform answer = inverse(truth);
  const Eigen::Vector3d centre = probe.positions().colwise().mean();
  for (const RigidTransform& error :
       {motion(12.0, Eigen::Vector3d(0.0, 1.0, 1.0), Eigen::Vector3d(0.8, 0.3, -0.5)),
        motion(-8.0, Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector3d(-1.0, 0.5, 0.5))}) {
    RigidTransform start;  // the answer, then off by `error`
    start.rotation = error.rotation * answer.rotation;
    start.translation = error.rotation * answer.translation + error.translation;
    const RigidTransform refined = overlay.refine(start).transform;
    const double angle =
        matching::rotation_angle_degrees(refined.rotation * answer.rotation.transpose());
    const double shift = ((refined.rotation * centre + refined.translation) -
                          (answer.rotation * centre + answer.translation))
                             .norm();
    const double start_angle =
        matching::rotation_angle_degrees(start.rotation * answer.rotation.transpose());
    std::printf("[ refine   ] start %.1f deg off -> %.3f deg, %.3f A; score %.3f -> %.3f\n",
                start_angle, angle, shift, overlay.score(start).score,
                overlay.score(refined).score);
    EXPECT_LT(angle, 1.0);
    EXPECT_LT(shift, 0.2);
    EXPECT_GT(overlay.score(refined).score, overlay.score(start).score);
  }
}

// refine's score is score() of its transform; `abandon` stops it after the first step taken,
// which already raises the score, and marks the result.
TEST(Overlay, RefinementReportsItsScoreAndStopsWhenAbandoned) {
  const mesh::Surface reference = labelled_ellipsoid();
  const matching::SurfaceSample sample = matching::sample_surface(reference, 1.0);
  const matching::SurfaceOverlay overlay(sample, sample);
  const RigidTransform start =
      motion(10.0, Eigen::Vector3d(0.0, 1.0, 1.0), Eigen::Vector3d(0.5, 0.2, -0.3));
  const matching::RefineResult full = overlay.refine(start);
  EXPECT_FALSE(full.abandoned);
  EXPECT_EQ(full.score.score, overlay.score(full.transform).score);
  EXPECT_EQ(full.score.shape, overlay.score(full.transform).shape);

  int calls = 0;
  matching::RefineOptions stop_at_once;
  stop_at_once.abandon = [&](const RigidTransform&) { return ++calls > 0; };
  const matching::RefineResult stopped = overlay.refine(start, stop_at_once);
  EXPECT_TRUE(stopped.abandoned);
  EXPECT_EQ(calls, 1);
  EXPECT_GT(stopped.score.score, overlay.score(start).score);
  EXPECT_EQ(stopped.score.score, overlay.score(stopped.transform).score);
  EXPECT_LE(stopped.score.score, full.score.score);
}

TEST(Overlay, PrincipalAxesStartsHoldTheMotionAndAreProperRotations) {
  const mesh::Surface reference = labelled_ellipsoid();  // axes 4, 2.5, 1.5 A: variances far apart
  const RigidTransform truth =
      motion(150.0, Eigen::Vector3d(1.0, 2.0, -1.0), Eigen::Vector3d(-6.0, 4.0, 9.0));
  const mesh::Surface probe = moved(reference, truth);
  const matching::SurfaceSample a = matching::sample_surface(reference, 1.0);
  const matching::SurfaceSample b = matching::sample_surface(probe, 1.0);
  const RigidTransform answer = inverse(truth);
  const Eigen::Vector3d centre = probe.positions().colwise().mean();
  const auto error = [&](const RigidTransform& t) {
    return std::pair<double, double>{
        matching::rotation_angle_degrees(t.rotation * answer.rotation.transpose()),
        (t.apply(centre) - answer.apply(centre)).norm()};
  };
  const auto four = matching::principal_axes_starts(a, b);
  const auto all = matching::principal_axes_starts(a, b, true);
  ASSERT_EQ(four.size(), 4u);
  ASSERT_EQ(all.size(), 24u);
  // Every start is a proper rotation; the 24 are distinct (the rotation group of the cube
  // carried by the two frames) and include the four.
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_NEAR(all[i].rotation.determinant(), 1.0, 1e-12);
    EXPECT_LT((all[i].rotation.transpose() * all[i].rotation - Eigen::Matrix3d::Identity()).norm(),
              1e-12);
    for (std::size_t j = 0; j < i; ++j) EXPECT_GT((all[i].rotation - all[j].rotation).norm(), 0.5);
  }
  for (const RigidTransform& t : four) {
    EXPECT_TRUE(std::any_of(all.begin(), all.end(), [&](const RigidTransform& u) {
      return (t.rotation - u.rotation).norm() < 1e-12 &&
             (t.translation - u.translation).norm() < 1e-12;
    }));
  }
  // One of the four is the motion, up to the two samplings' cells; the others are 180 degrees off.
  double best_angle = 180.0, best_shift = 0.0;
  for (const RigidTransform& t : four) {
    const auto [angle, shift] = error(t);
    if (angle < best_angle) std::tie(best_angle, best_shift) = std::tie(angle, shift);
  }
  std::printf("[ axes     ] best of 4 starts: %.3f deg, %.3f A from the motion\n", best_angle,
              best_shift);
  EXPECT_LT(best_angle, 3.0);
  EXPECT_LT(best_shift, 0.3);
  EXPECT_THROW(matching::principal_axes_starts(a, matching::SurfaceSample{}), InputError);
}

TEST(Overlay, WeightedFitIgnoresPointsWithoutWeight) {
  const RigidTransform truth =
      motion(50.0, Eigen::Vector3d(0.3, 1.0, -0.2), Eigen::Vector3d(1.0, 2.0, 3.0));
  Eigen::Matrix3Xd from(3, 6);
  from << 0, 1, 0, 0, 2, -1,  //
      0, 0, 1, 0, 1, 3,       //
      0, 0, 0, 1, -1, 2;
  Eigen::Matrix3Xd to = truth.apply(from);
  to.col(5) += Eigen::Vector3d(10.0, -7.0, 4.0);  // an outlier with weight 0
  Eigen::VectorXd weights(6);
  weights << 1.0, 2.0, 0.5, 1.0, 3.0, 0.0;
  const matching::RigidFit fit = matching::fit_rigid_weighted(from, to, weights);
  EXPECT_LT((fit.transform.rotation - truth.rotation).norm(), 1e-12);
  EXPECT_LT((fit.transform.translation - truth.translation).norm(), 1e-12);
  EXPECT_LT(fit.rmsd, 1e-12);
  // Equal weights: the unweighted fit.
  const matching::RigidFit plain = matching::fit_rigid(from, to);
  const matching::RigidFit equal =
      matching::fit_rigid_weighted(from, to, Eigen::VectorXd::Constant(6, 2.0));
  EXPECT_LT((plain.transform.matrix() - equal.transform.matrix()).norm(), 1e-12);
  EXPECT_NEAR(plain.rmsd, equal.rmsd, 1e-12);
  EXPECT_THROW(matching::fit_rigid_weighted(from, to, Eigen::VectorXd::Zero(6)), InputError);
}

/// One point of weight 1 at `position`, facing +z, with the given ESP and LP.
matching::SurfaceSample one_point(const Eigen::Vector3d& position, double esp = 0.0,
                                  double lp = 0.0) {
  matching::SurfaceSample s;
  s.points = position;
  s.normals = Eigen::Vector3d::UnitZ();
  s.weights = Eigen::VectorXd::Ones(1);
  s.esp = Eigen::VectorXd::Constant(1, esp);
  s.lp = Eigen::VectorXd::Constant(1, lp);
  return s;
}

// Two facing points d apart overlap by g = exp(-d^2 / (2 sigma^2)) (cut at 3 sigma) against
// self-overlaps of 1: shape = g / (2 - g). The overlay tabulates g; it must stay within 1e-6
// (linear interpolation in d^2 over 2048 steps of (3 sigma)^2: at most 6e-7).
// Without ESP or LP on either side the chemistry Tanimoto is 0, not 0 / 0, and the score is the
// shape's. A position that is not a number overlaps nothing.
TEST(Overlay, TwoPointsOverlapByTheGaussianOfTheirDistance) {
  for (double sigma : {1.0, 0.7}) {
    matching::OverlayOptions options;
    options.sigma = sigma;
    const matching::SurfaceOverlay overlay(one_point(Eigen::Vector3d::Zero()),
                                           one_point(Eigen::Vector3d::Zero()), options);
    for (double d : {0.0, 0.05, 0.3, 0.77, 1.0, 1.9, 2.5, 2.99, 3.0 * sigma * (1.0 - 1e-12)}) {
      const double g = d < 3.0 * sigma ? std::exp(-d * d / (2.0 * sigma * sigma)) : 0.0;
      const matching::OverlayScore s =
          overlay.score(motion(0.0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(d, 0.0, 0.0)));
      EXPECT_NEAR(s.shape, g / (2.0 - g), 1e-5) << "sigma " << sigma << ", d " << d;
      EXPECT_NEAR(2.0 * s.shape / (1.0 + s.shape), g, 1e-6)
          << "sigma " << sigma << ", d " << d;  // g itself
      EXPECT_EQ(s.chem, 0.0);
      EXPECT_EQ(s.atoms, 0.0);
      EXPECT_EQ(s.score, s.shape);  // no chemistry: its weight leaves the score
    }
    EXPECT_EQ(
        overlay
            .score(motion(0.0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(3.01 * sigma, 0.0, 0.0)))
            .shape,
        0.0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(
        overlay.score(motion(0.0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(nan, 0.0, 0.0))).shape,
        0.0);
  }
}

/// An atom sample from (element, x, y, z) rows.
matching::AtomSample atoms(const std::vector<std::pair<std::string, Eigen::Vector3d>>& rows) {
  std::vector<harmonic::SurfaceAtom> list;
  for (const auto& [element, position] : rows) list.push_back({element, position});
  return matching::sample_atoms(list);
}

// A surface symmetric under a half turn about z (an ellipsoid with uniform chemistry) cannot tell
// the turn from the identity; its molecule's heteroatoms can. Only same-element heteroatoms
// count: carbons and hydrogens are not sampled, and an O does not pair with an N.
TEST(Overlay, SameElementHeteroatomsTellApartPosesTheSurfaceCannot) {
  matching::SurfaceSample shape = matching::sample_surface(test::ellipsoid(4.0, 2.5, 1.5, 24), 1.0);
  shape.esp.setOnes();  // chemistry that a half turn about z leaves as it is
  shape.lp.setConstant(-0.5);
  const auto molecule = atoms({{"O", {3.0, 0.0, 0.0}},
                               {"N", {0.0, 1.5, 0.0}},
                               {"C", {0.0, 0.0, 0.0}},
                               {"H", {1.0, 0.0, 0.0}}});
  ASSERT_EQ(molecule.size(), 2u);
  EXPECT_EQ(molecule.elements, (std::vector<std::string>{"O", "N"}));
  const matching::OverlayOptions options;  // chem weight 6, atom weight 14
  const matching::SurfaceOverlay overlay(shape, shape, options, molecule, molecule);
  ASSERT_TRUE(overlay.uses_atoms());
  const RigidTransform turn = motion(180.0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero());
  const matching::OverlayScore at_identity = overlay.score(RigidTransform{});
  const matching::OverlayScore turned = overlay.score(turn);
  EXPECT_NEAR(at_identity.atoms, 1.0, 1e-12);
  EXPECT_LT(turned.atoms, 0.01);  // only the N's tails meet, 3 A apart: 0.011 / 4
  EXPECT_NEAR(turned.shape, at_identity.shape, 0.05);  // the two cell samplings differ slightly
  const double weights = 1.0 + options.chem_weight + options.atom_weight;
  EXPECT_NEAR(
      at_identity.score,
      (at_identity.shape + options.chem_weight * at_identity.chem + options.atom_weight) / weights,
      1e-12);
  EXPECT_GT(at_identity.score - turned.score, 0.5);
  // The refinement's final score carries the atom term too.
  const matching::OverlayScore refined =
      overlay.refine(motion(3.0, Eigen::Vector3d::UnitX(), Eigen::Vector3d(0.2, 0.0, 0.0))).score;
  EXPECT_GT(refined.atoms, 0.9);
  EXPECT_NEAR(
      refined.score,
      (refined.shape + options.chem_weight * refined.chem + options.atom_weight * refined.atoms) /
          weights,
      1e-12);

  // Polishing the surfaces' refinement of a pose 8 degrees and 0.6 A off on the whole score
  // (heteroatoms pulled too), as the match does, ends at least as high, its heteroatoms on the
  // reference's.
  const RigidTransform off =
      motion(8.0, Eigen::Vector3d(1.0, 1.0, 0.0), Eigen::Vector3d(0.6, -0.3, 0.0));
  matching::RefineOptions pull;
  pull.pull_atoms = true;
  const matching::RefineResult surfaces_result = overlay.refine(off);
  const matching::RefineResult polished = overlay.refine(surfaces_result.transform, pull);
  const RigidTransform& surfaces_only = surfaces_result.transform;
  const RigidTransform& pulled = polished.transform;
  const matching::OverlayScore& plain_score = surfaces_result.score;
  const matching::OverlayScore& pulled_score = polished.score;
  std::printf(
      "[ polish   ] from 8 deg off: surfaces alone %.3f deg (score %.4f), atoms pulled too %.3f "
      "deg (score %.4f)\n",
      matching::rotation_angle_degrees(surfaces_only.rotation), plain_score.score,
      matching::rotation_angle_degrees(pulled.rotation), pulled_score.score);
  EXPECT_GE(pulled_score.score, plain_score.score - 1e-12);
  EXPECT_GT(pulled_score.atoms, 0.99);
  EXPECT_LT(matching::rotation_angle_degrees(pulled.rotation), 1.0);
  // Heteroatoms without a same-element partner pull nothing: the surfaces' refinement.
  const matching::SurfaceOverlay unpaired(shape, shape, options, atoms({{"O", {3.0, 0.0, 0.0}}}),
                                          atoms({{"N", {0.0, 1.5, 0.0}}}));
  ASSERT_TRUE(unpaired.uses_atoms());
  const matching::RefineResult by_surfaces_result = unpaired.refine(off);
  const matching::RefineResult with_pull_result = unpaired.refine(off, pull);
  const RigidTransform& by_surfaces = by_surfaces_result.transform;
  const RigidTransform& with_pull = with_pull_result.transform;
  const matching::OverlayScore& a = by_surfaces_result.score;
  const matching::OverlayScore& b = with_pull_result.score;
  EXPECT_LT((by_surfaces.matrix() - with_pull.matrix()).norm(), 1e-9);
  EXPECT_NEAR(a.score, b.score, 1e-12);
  EXPECT_EQ(b.atoms, 0.0);

  // The O and N swapped: no same-element pair at the identity.
  const auto swapped = atoms({{"N", {3.0, 0.0, 0.0}}, {"O", {0.0, 1.5, 0.0}}});
  EXPECT_LT(matching::SurfaceOverlay(shape, shape, options, molecule, swapped)
                .score(RigidTransform{})
                .atoms,
            0.01);
  // No atoms on one side, or weight 0: the surface score alone.
  for (const auto& [probe_atoms, weight] :
       {std::pair<matching::AtomSample, double>{{}, 14.0}, {molecule, 0.0}}) {
    matching::OverlayOptions o = options;
    o.atom_weight = weight;
    const matching::SurfaceOverlay plain(shape, shape, o, molecule, probe_atoms);
    EXPECT_FALSE(plain.uses_atoms());
    const matching::OverlayScore s = plain.score(turn);
    EXPECT_EQ(s.atoms, 0.0);
    EXPECT_NEAR(s.score, (s.shape + o.chem_weight * s.chem) / (1.0 + o.chem_weight), 1e-15);
  }
  matching::OverlayOptions negative = options;
  negative.atom_weight = -1.0;
  EXPECT_THROW(matching::SurfaceOverlay(shape, shape, negative, molecule, molecule), OptionError);
  matching::AtomSample short_of_points = molecule;
  short_of_points.points.conservativeResize(3, 1);
  EXPECT_THROW(matching::SurfaceOverlay(shape, shape, options, molecule, short_of_points),
               InputError);
}

// A screen indexes its query once (for_many_probes, on finer cells) and overlays every library
// entry on it; that must give the pair's numbers exactly, for a ligand-sized probe (its
// self-overlap by all pairs) and a larger one (by a grid), scores and refinements alike.
TEST(Overlay, OverlaysOfOneReferenceWithManyProbesGiveThePairsNumbers) {
  const matching::SurfaceSample reference = matching::sample_surface(labelled_ellipsoid(), 1.0);
  const matching::AtomSample reference_atoms =
      atoms({{"O", {3.0, 0.0, 0.0}}, {"N", {-2.0, 1.0, 0.0}}});
  const matching::AtomSample probe_atoms = atoms({{"O", {2.5, 0.5, 0.0}}});
  mesh::Surface large = test::icosphere(2.5, 24);
  large.set_property(mesh::property::esp, Eigen::VectorXd(large.positions().col(1)));
  large.set_property(mesh::property::lp, Eigen::VectorXd(-large.positions().col(0)));
  const std::vector<matching::SurfaceSample> probes = {
      matching::sample_surface(
          moved(labelled_ellipsoid(),
                motion(20.0, Eigen::Vector3d(1.0, -1.0, 2.0), Eigen::Vector3d(0.4, 0.3, -0.2))),
          1.0),
      matching::sample_surface(large, 0.25)};
  ASSERT_LE(probes[0].size(), 512U);  // the two paths of the probe's self-overlap
  ASSERT_GT(probes[1].size(), 512U);
  const matching::SurfaceOverlay base =
      matching::SurfaceOverlay::for_many_probes(reference, {}, reference_atoms);
  const matching::OverlayScore self = base.score(RigidTransform{});
  EXPECT_EQ(self.score,
            matching::SurfaceOverlay(reference, reference, {}, reference_atoms, reference_atoms)
                .score(RigidTransform{})
                .score);
  EXPECT_NEAR(self.score, 1.0, 1e-12);
  const RigidTransform t =
      motion(-15.0, Eigen::Vector3d(0.0, 1.0, 1.0), Eigen::Vector3d(0.3, -0.2, 0.1));
  for (std::size_t k = 0; k < probes.size(); ++k) {
    const matching::SurfaceOverlay pair(reference, probes[k], {}, reference_atoms, probe_atoms);
    const matching::SurfaceOverlay shared(base, probes[k], probe_atoms);
    const matching::OverlayScore a = pair.score(t);
    const matching::OverlayScore b = shared.score(t);
    EXPECT_GT(a.shape, 0.05) << "probe " << k;
    EXPECT_EQ(a.shape, b.shape) << "probe " << k;
    EXPECT_EQ(a.chem, b.chem) << "probe " << k;
    EXPECT_EQ(a.atoms, b.atoms) << "probe " << k;
    EXPECT_EQ(a.score, b.score) << "probe " << k;
    const matching::RefineResult ra = pair.refine(t);
    const matching::RefineResult rb = shared.refine(t);
    EXPECT_GT((ra.transform.translation - t.translation).norm(), 0.01) << "probe " << k;
    EXPECT_EQ(ra.score.score, rb.score.score) << "probe " << k;
    EXPECT_EQ(ra.transform.matrix(), rb.transform.matrix()) << "probe " << k;
  }
}

TEST(Overlay, RejectsBadOptionsAndEmptySamples) {
  const mesh::Surface surface = labelled_ellipsoid();
  const matching::SurfaceSample sample = matching::sample_surface(surface, 1.0);
  matching::OverlayOptions options;
  options.sigma = 0.0;
  EXPECT_THROW(matching::SurfaceOverlay(sample, sample, options), OptionError);
  EXPECT_THROW(matching::sample_surface(surface, -1.0), OptionError);
  const std::vector<bool> none(surface.n_vertices(), false);
  EXPECT_THROW(matching::SurfaceOverlay(sample, matching::sample_surface(surface, 1.0, &none)),
               InputError);
  const std::vector<bool> wrong_size(3, true);
  EXPECT_THROW(matching::sample_surface(surface, 1.0, &wrong_size), InputError);
}

}  // namespace
}  // namespace surfcomp

namespace surfcomp {
namespace {

/// Heavy atoms from (element, x, y, z) rows.
std::vector<harmonic::SurfaceAtom> heavy_atoms(
    const std::vector<std::pair<std::string, Eigen::Vector3d>>& rows) {
  std::vector<harmonic::SurfaceAtom> list;
  for (const auto& [element, position] : rows) list.push_back({element, position});
  return list;
}

/// A small rigid molecule with no symmetry: a bent chain of carbons with an O, an N and a Cl.
std::vector<harmonic::SurfaceAtom> chiral_molecule() {
  return heavy_atoms({{"C", {0.0, 0.0, 0.0}},
                      {"C", {1.52, 0.0, 0.0}},
                      {"C", {2.03, 1.43, 0.0}},
                      {"O", {3.45, 1.50, 0.21}},
                      {"N", {-0.52, -1.37, 0.35}},
                      {"C", {1.45, 2.31, 1.10}},
                      {"Cl", {-0.70, 0.91, -1.42}}});
}

std::vector<harmonic::SurfaceAtom> moved_atoms(std::vector<harmonic::SurfaceAtom> atoms,
                                               const RigidTransform& t) {
  for (harmonic::SurfaceAtom& atom : atoms)
    atom.position = t.rotation * atom.position + t.translation;
  return atoms;
}

// Two lone atoms of one element at distance d fit by g / (2 - g), g = exp(-d^2 / (2 sigma^2)),
// at any distance (no cutoff); atoms of two elements never pair. A molecule on itself fits 1 at
// the identity and less anywhere else.
TEST(AtomPolish, TheFitIsTheTanimotoOfLikeAtomGaussians) {
  for (double sigma : {0.5, 0.35}) {
    const matching::AtomOverlap two(heavy_atoms({{"N", Eigen::Vector3d::Zero()}}),
                                    heavy_atoms({{"N", Eigen::Vector3d::Zero()}}), sigma);
    for (double d : {0.0, 0.1, 0.4, 0.9, 1.4, 2.0}) {
      const double g = std::exp(-d * d / (2.0 * sigma * sigma));
      EXPECT_NEAR(two.fit(motion(0.0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0.0, d, 0.0))),
                  g / (2.0 - g), 1e-12)
          << "sigma " << sigma << ", d " << d;
    }
    const matching::AtomOverlap unlike(heavy_atoms({{"N", Eigen::Vector3d::Zero()}}),
                                       heavy_atoms({{"O", Eigen::Vector3d::Zero()}}), sigma);
    EXPECT_EQ(unlike.fit(RigidTransform{}), 0.0);
  }
  const matching::AtomOverlap self(chiral_molecule(), chiral_molecule(), 0.5);
  EXPECT_NEAR(self.fit(RigidTransform{}), 1.0, 1e-12);
  EXPECT_LT(self.fit(motion(5.0, Eigen::Vector3d(1.0, 2.0, 0.5), Eigen::Vector3d::Zero())), 0.99);
}

// A molecule against a moved copy of itself: from poses up to 0.6 A and 15 degrees off, the
// polish ends at the motion to 1e-4 A. The surface overlay beside it, of two lone points more
// than its 3 A cutoff apart at every pose tried, scores 0: the atoms alone decide.
TEST(AtomPolish, APolishTakesAMovedCopyBackToTheMotion) {
  const std::vector<harmonic::SurfaceAtom> reference = chiral_molecule();
  const RigidTransform truth =
      motion(80.0, Eigen::Vector3d(0.3, -1.0, 0.7), Eigen::Vector3d(4.0, 1.0, -6.0));
  const std::vector<harmonic::SurfaceAtom> probe = moved_atoms(reference, truth);
  const RigidTransform answer = inverse(truth);
  const matching::AtomOverlap atoms(reference, probe, 0.5);
  const matching::SurfaceOverlay overlay(one_point(Eigen::Vector3d::Zero()),
                                         one_point(Eigen::Vector3d::Zero()));
  for (const RigidTransform& error :
       {motion(15.0, Eigen::Vector3d(0.0, 1.0, 1.0), Eigen::Vector3d(0.3, 0.2, -0.1)),
        motion(-6.0, Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector3d(-0.4, 0.4, 0.2))}) {
    RigidTransform start;
    start.rotation = error.rotation * answer.rotation;
    start.translation = error.rotation * answer.translation + error.translation;
    const RigidTransform polished = atoms.polish(overlay, start, {});
    double worst = 0.0;
    for (const harmonic::SurfaceAtom& atom : probe) {
      worst = std::max(worst, ((polished.rotation * atom.position + polished.translation) -
                               (answer.rotation * atom.position + answer.translation))
                                  .norm());
    }
    std::printf("[ polish   ] fit %.4f -> %.6f, farthest atom from the answer %.2e A\n",
                atoms.fit(start), atoms.fit(polished), worst);
    EXPECT_EQ(overlay.score(polished).score, 0.0);
    EXPECT_LT(worst, 1e-4);
    EXPECT_NEAR(atoms.fit(polished), 1.0, 1e-8);
  }
}

TEST(AtomPolish, RejectsBadWidthsWeightsAndAtoms) {
  const auto molecule = chiral_molecule();
  EXPECT_THROW(matching::AtomOverlap(molecule, molecule, 0.0), OptionError);
  EXPECT_THROW(matching::AtomOverlap(molecule, molecule, std::nan("")), OptionError);
  EXPECT_THROW(matching::AtomOverlap(molecule, {}, 0.5), InputError);
  auto broken = molecule;
  broken[3].position.x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(matching::AtomOverlap(molecule, broken, 0.5), InputError);
  const matching::AtomOverlap atoms(molecule, molecule, 0.5);
  const matching::SurfaceOverlay overlay(one_point(Eigen::Vector3d::Zero()),
                                         one_point(Eigen::Vector3d::Zero()));
  matching::AtomPolishOptions negative;
  negative.weight = -1.0;
  EXPECT_THROW(atoms.polish(overlay, RigidTransform{}, negative), OptionError);
  negative = {};
  negative.iterations = -1;
  EXPECT_THROW(atoms.polish(overlay, RigidTransform{}, negative), OptionError);
  negative = {};
  negative.tolerance = std::nan("");
  EXPECT_THROW(atoms.polish(overlay, RigidTransform{}, negative), OptionError);
  negative = {};
  negative.sigma = 0.01;
  EXPECT_THROW(atoms.polish(overlay, RigidTransform{}, negative), OptionError);
}

TEST(AtomPolish, MatchOptionsNameTheBadPolishField) {
  matching::MatchOptions options;
  options.atom_polish.iterations = -2;
  try {
    matching::validate(options);
    ADD_FAILURE() << "atom_polish.iterations -2 was accepted";
  } catch (const OptionError& error) {
    EXPECT_NE(std::string(error.what()).find("match options: atom_polish.iterations = -2"),
              std::string::npos)
        << error.what();
  }
  options = {};
  options.atom_polish.weight = std::numeric_limits<double>::infinity();
  EXPECT_THROW(matching::validate(options), OptionError);
}

}  // namespace
}  // namespace surfcomp
