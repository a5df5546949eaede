// The search's parts on a receptor of a few charged atoms, where the score is known: its
// gradient is the derivative of the score, the local optimiser climbs it, and the Monte Carlo
// search is the same whatever the threads.
#include "surfcomp/docking/search.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/thread_limit.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace surfcomp::docking {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// A cleft: four charged, lipophilic and polar atoms around the origin, open along +z.
Molecule cleft() {
  Molecule m;
  m.source = "cleft";
  const std::vector<std::pair<Eigen::Vector3d, double>> places{{{3.2, 0, 0}, 0.5},
                                                               {{-3.2, 0, 0}, -0.5},
                                                               {{0, 3.2, 0}, 0.2},
                                                               {{0, -3.2, 0}, -0.2},
                                                               {{0, 0, -3.4}, 0.0}};
  for (const auto& [position, charge] : places) {
    Atom a;
    a.element = "C";
    a.position = position;
    a.radius = 1.8;
    a.charge = charge;
    a.lipophilicity = charge == 0.0 ? 0.5 : -0.3;
    m.atoms.push_back(a);
  }
  return m;
}

/// A small, uneven ligand sample: points on two spheres, with varying ESP and LP.
LigandSample ligand() {
  LigandSample s;
  const int n = 60;
  s.points.resize(3, n);
  s.esp.resize(n);
  s.lp.resize(n);
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), a = 2.4 * i;
    const Eigen::Vector3d centre(i % 2 ? 0.9 : -0.6, 0.0, 0.2);
    s.points.col(i) = centre + 1.4 * Eigen::Vector3d(r * std::cos(a), r * std::sin(a), z);
    s.esp(i) = std::sin(0.7 * i);
    s.lp(i) = std::cos(0.4 * i);
  }
  s.centroid = s.points.rowwise().mean();
  return s;
}

const std::vector<molsurf::SiteSphere> site{{Eigen::Vector3d(0, 0, 0.5), 2.0}};

TEST(Search, TheGradientIsTheScoresDerivative) {
  // Central differences of a step of 1e-6 stay within one trilinear cell for nearly every
  // point; the gradient must match them to a part in 10^4 of its size. The second sample lifts
  // half its points, as a metal's are (lift_metal_points).
  ComplementarityOptions o;
  o.clash_weight = 5.0;  // a pose with some clash, so that every term has a slope
  o.clash_tolerance = 0.1;
  const ReceptorField field(cleft(), site, o);
  LigandSample lifted = ligand();
  lifted.lift = Eigen::VectorXd::Zero(lifted.points.cols());
  for (Eigen::Index k = 0; k < lifted.points.cols(); k += 2) lifted.lift(k) = 0.3;
  for (const LigandSample& sample : {ligand(), lifted}) {
    matching::RigidTransform pose;
    pose.rotation =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
    pose.translation = Eigen::Vector3d(0.31, -0.27, 0.93) - pose.rotation * sample.centroid;
    Vector6d gradient;
    const ComplementarityScore at = field.score(sample, pose, &gradient);
    ASSERT_GT(at.contact, 0.1);
    ASSERT_GT(at.clash, 0.0) << at.deepest << " " << at.contact;
    const Eigen::Vector3d centre = pose.rotation * sample.centroid + pose.translation;
    const double h = 1e-6;
    for (int axis = 0; axis < 6; ++axis) {
      const auto moved = [&](double sign) {
        matching::RigidTransform t = pose;
        if (axis < 3) {
          t.translation(axis) += sign * h;
        } else {
          const Eigen::Matrix3d q =
              Eigen::AngleAxisd(sign * h, Eigen::Vector3d::Unit(axis - 3)).toRotationMatrix();
          t.rotation = q * pose.rotation;
          t.translation = q * (pose.translation - centre) + centre;
        }
        return field.score(sample, t).score;
      };
      const double numeric = (moved(1.0) - moved(-1.0)) / (2 * h);
      EXPECT_NEAR(gradient(axis), numeric, 1e-4 * gradient.norm() + 1e-7)
          << axis << (sample.lift.size() > 0 ? " lifted" : "");
    }
  }
  LigandSample wrong = ligand();
  wrong.lift = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(field.score(wrong, {}), InputError);
}

TEST(Search, RefinementClimbsToALocalMaximum) {
  const ReceptorField field(cleft(), site);
  const LigandSample sample = ligand();
  matching::RigidTransform start;
  start.translation = Eigen::Vector3d(0.8, 0.6, 2.5) - sample.centroid;
  const matching::RigidTransform refined = refine_pose(field, sample, start);
  Vector6d gradient;
  const double top = field.score(sample, refined, &gradient).score;
  EXPECT_GT(top, field.score(sample, start).score);
  // At the maximum no small move along an axis gains more than the line search's tolerance.
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      matching::RigidTransform t = refined;
      t.translation(axis) += sign * 0.02;
      EXPECT_LE(field.score(sample, t).score, top + 1e-4) << axis << " " << sign;
    }
  }
}

TEST(Search, TheSearchIsTheSameWhateverTheThreads) {
  const ReceptorField field(cleft(), site);
  const LigandSample sample = ligand();
  SearchOptions options;
  options.chains = 4;
  options.steps = 5;
  std::vector<SearchedPose> one, two;
  {
    const ThreadLimit limit(1);
    one = search_site(field, sample, site, options);
  }
  {
    const ThreadLimit limit(2);
    two = search_site(field, sample, site, options);
  }
  ASSERT_EQ(one.size(), 4u * 6u);
  ASSERT_EQ(two.size(), one.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    EXPECT_EQ(one[k].pose.matrix(), two[k].pose.matrix()) << k;
    EXPECT_EQ(one[k].score.score, two[k].score.score) << k;
  }
  options.seed = 2;
  const std::vector<SearchedPose> other = search_site(field, sample, site, options);
  EXPECT_NE(other[0].pose.matrix(), one[0].pose.matrix());  // the seed draws other starts
  for (const SearchedPose& p : one) EXPECT_LT(p.score.outside, 1.0);
}

TEST(Search, OptionsOutsideTheirDomainAreRefused) {
  SearchOptions o;
  o.chains = -1;
  EXPECT_THROW(validate(o), OptionError);
  o = {};
  o.temperature = 0.0;
  EXPECT_THROW(validate(o), OptionError);
  o = {};
  o.steps = -3;
  EXPECT_THROW(validate(o), OptionError);
  o = {};
  o.sample_spacing = 0.0;
  EXPECT_THROW(validate(o), OptionError);
  // Within each range, but too many optima to keep: refused before any memory is taken.
  o = {};
  o.chains = 100000;
  o.steps = 100000;
  EXPECT_THROW(validate(o), OptionError);
  o.chains = 2000;
  o.steps = 999;
  EXPECT_NO_THROW(validate(o));  // exactly the bound
}

}  // namespace
}  // namespace surfcomp::docking
