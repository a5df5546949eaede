// The complementarity score's terms on analytic spheres: a receptor of single atoms, ligand
// samples on spheres about them, where each term has a closed form; the pose refinement back to
// contact; and the complement of a description, an involution that mirrors images.
#include "surfcomp/docking/complementarity.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/docking/complement.hpp"
#include "surfcomp/docking/dock.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace surfcomp::docking {
namespace {

constexpr double pi = 3.14159265358979323846;

Atom atom_at(const Eigen::Vector3d& position, double radius, double charge,
             double lipophilicity = 0.0) {
  Atom a;
  a.element = "C";
  a.position = position;
  a.radius = radius;
  a.charge = charge;
  a.lipophilicity = lipophilicity;
  return a;
}

/// `n` points spread over the sphere of `radius` about `centre` (a Fibonacci lattice).
Eigen::Matrix3Xd sphere_points(const Eigen::Vector3d& centre, double radius, int n) {
  Eigen::Matrix3Xd points(3, n);
  const double golden = pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double r = std::sqrt(1.0 - z * z);
    points.col(i) =
        centre + radius * Eigen::Vector3d(r * std::cos(golden * i), r * std::sin(golden * i), z);
  }
  return points;
}

LigandSample sample_of(const Eigen::Matrix3Xd& points, double esp = 0.0, double lp = 0.0) {
  LigandSample s;
  s.points = points;
  s.esp = Eigen::VectorXd::Constant(points.cols(), esp);
  s.lp = Eigen::VectorXd::Constant(points.cols(), lp);
  s.centroid = points.rowwise().mean();
  return s;
}

Molecule one_atom(double radius, double charge) {
  Molecule m;
  m.source = "atom";
  m.atoms.push_back(atom_at(Eigen::Vector3d::Zero(), radius, charge));
  return m;
}

const std::vector<molsurf::SiteSphere> around_origin{{Eigen::Vector3d::Zero(), 4.0}};

TEST(Complementarity, SignedDistanceIsTheDistanceToTheAtomsSurface) {
  const ReceptorField field(one_atom(1.7, 0.0), around_origin);
  for (const double r : {0.5, 1.7, 2.3, 3.9}) {
    // Trilinear interpolation of |x| - R on a grid of h = 0.4 A errs by at most h^2 / 8 times
    // the Laplacian's bound 2 / |x|.
    const double distance = std::hypot(r, 0.3, 0.2);
    EXPECT_NEAR(field.signed_distance(Eigen::Vector3d(r, 0.3, -0.2)), distance - 1.7,
                0.04 / distance)
        << r;
  }
  EXPECT_DOUBLE_EQ(field.signed_distance(Eigen::Vector3d(100, 0, 0)), 4.0);  // off the grid
}

TEST(Complementarity, ASampleAtTheContactGapIsAllContactAndNoClash) {
  const ComplementarityOptions o;
  const ReceptorField field(one_atom(1.7, 0.0), around_origin);
  const LigandSample touching = sample_of(sphere_points({0, 0, 0}, 1.7 + o.contact_gap, 200));
  const ComplementarityScore s = field.score(touching, {});
  EXPECT_NEAR(s.contact, 1.0, 1e-3);
  EXPECT_DOUBLE_EQ(s.clash, 0.0);
  EXPECT_DOUBLE_EQ(s.deepest, 0.0);
  EXPECT_NEAR(s.score, s.contact, 1e-12);  // no ESP or LP anywhere
}

TEST(Complementarity, ASampleInFreeSpaceScoresTheCappedDistancesContactAlone) {
  // Points more than the 4 A cap (plus a grid cell) from the atom, inside the grid: every node
  // about them holds the cap, so each adds the Gaussian at the cap and nothing else.
  const ComplementarityOptions o;
  const ReceptorField field(one_atom(1.7, 0.5), around_origin);
  const LigandSample far = sample_of(sphere_points({0, 0, 0}, 1.7 + 4.0 + 1.0, 100), 1.0, 1.0);
  Eigen::Matrix<double, 6, 1> gradient;
  const ComplementarityScore s = field.score(far, {}, &gradient);
  const double gap = 4.0 - o.contact_gap;
  EXPECT_NEAR(s.contact, std::exp(-gap * gap / (2 * o.contact_width * o.contact_width)), 1e-15);
  EXPECT_DOUBLE_EQ(s.esp, 0.0);
  EXPECT_DOUBLE_EQ(s.lp, 0.0);
  EXPECT_DOUBLE_EQ(s.clash, 0.0);
  EXPECT_DOUBLE_EQ(gradient.norm(), 0.0);
}

TEST(Complementarity, ASampleInsideTheAtomClashesByItsDepthBeyondTheTolerance) {
  const ComplementarityOptions o;
  // A large atom, so that the grid's interpolation error (0.04 / r, see above) stays small.
  const ReceptorField field(one_atom(3.0, 0.0), {{Eigen::Vector3d::Zero(), 5.0}});
  const double depth = 1.0;  // below the surface
  const double error = 0.04 / (3.0 - depth);
  const LigandSample inside = sample_of(sphere_points({0, 0, 0}, 3.0 - depth, 200));
  const ComplementarityScore s = field.score(inside, {});
  const double beyond = depth - o.clash_tolerance;
  EXPECT_NEAR(s.clash, beyond * beyond, 2 * beyond * error + error * error);
  EXPECT_NEAR(s.deepest, depth, error);
  const double gap = -depth - o.contact_gap;
  const double slope = std::abs(gap) / (o.contact_width * o.contact_width);  // of the Gaussian
  EXPECT_NEAR(s.contact, std::exp(-gap * gap / (2 * o.contact_width * o.contact_width)),
              slope * error);
  EXPECT_NEAR(s.score, s.contact - o.clash_weight * s.clash, 1e-12);
}

TEST(Complementarity, AReceptorMetalCountsSmallerByTheAllowance) {
  // A zinc atom of 3 A (large, for the grid's interpolation): its sphere counts 3 - 1 A, and a
  // carbon atom's its whole 3 A.
  ComplementarityOptions o;
  o.metal_allowance = 1.0;
  Molecule zinc = one_atom(3.0, 0.0);
  zinc.atoms[0].element = "Zn";
  const ReceptorField shrunk(zinc, {{Eigen::Vector3d::Zero(), 5.0}}, o);
  const ReceptorField carbon(one_atom(3.0, 0.0), {{Eigen::Vector3d::Zero(), 5.0}}, o);
  const Eigen::Vector3d x(3.5, 0.3, -0.2);
  const double error = 0.04 / x.norm();  // the grid's interpolation, as above
  EXPECT_NEAR(shrunk.signed_distance(x), x.norm() - 2.0, error);
  EXPECT_NEAR(carbon.signed_distance(x), x.norm() - 3.0, error);
  o.metal_allowance = -0.1;
  EXPECT_THROW(validate(o), OptionError);
}

TEST(Complementarity, ALigandMetalPointsAreLiftedOutOfTheClash) {
  // An iron atom and a carbon beside it; each sample point belongs to the atom whose sphere it
  // lies nearest.
  const std::vector<harmonic::SurfaceAtom> atoms{{"Fe", Eigen::Vector3d::Zero()},
                                                 {"C", Eigen::Vector3d(3.0, 0, 0)}};
  LigandSample sample =
      sample_of((Eigen::Matrix3Xd(3, 3) << -2, 0, 5, 0, 2, 0, 0, 0, 0).finished());
  lift_metal_points(sample, atoms, 1.0);
  ASSERT_EQ(sample.lift.size(), 3);
  EXPECT_DOUBLE_EQ(sample.lift(0), 1.0);  // on the iron's sphere (2.00 A)
  EXPECT_DOUBLE_EQ(sample.lift(1), 1.0);
  EXPECT_DOUBLE_EQ(sample.lift(2), 0.0);  // on the carbon's
  LigandSample organic = sample;
  lift_metal_points(organic, {{"C", Eigen::Vector3d::Zero()}}, 1.0);
  EXPECT_EQ(organic.lift.size(), 0);

  // Points 1 A deep in a receptor atom: lifted by 1 A they sit on its surface, no clash.
  const ComplementarityOptions o;
  const ReceptorField field(one_atom(3.0, 0.0), {{Eigen::Vector3d::Zero(), 5.0}});
  LigandSample inside = sample_of(sphere_points({0, 0, 0}, 2.0, 200));
  EXPECT_GT(field.score(inside, {}).clash, 0.0);
  inside.lift = Eigen::VectorXd::Constant(200, 1.0);
  const ComplementarityScore lifted = field.score(inside, {});
  EXPECT_DOUBLE_EQ(lifted.clash, 0.0);
  EXPECT_NEAR(lifted.deepest, 0.0, 0.04 / 2.0);
  const double gap = o.contact_gap;
  EXPECT_NEAR(lifted.contact, std::exp(-gap * gap / (2 * o.contact_width * o.contact_width)), 0.04);
}

TEST(Complementarity, OppositeEspAcrossTheContactScoresAndLikeEspCosts) {
  // Two atoms of opposite charge 12 A apart: the receptor's ESP is positive about the first
  // and negative about the second, and its z-scores with it.
  Molecule receptor;
  receptor.source = "pair";
  receptor.atoms.push_back(atom_at({-6, 0, 0}, 1.7, +1.0));
  receptor.atoms.push_back(atom_at({+6, 0, 0}, 1.7, -1.0));
  const std::vector<molsurf::SiteSphere> site{{{-6, 0, 0}, 3.0}, {{6, 0, 0}, 3.0}};
  const ReceptorField field(receptor, site);
  const double r = 1.7 + ComplementarityOptions{}.contact_gap;
  const LigandSample negative_at_positive = sample_of(sphere_points({-6, 0, 0}, r, 100), -1.0);
  const LigandSample negative_at_negative = sample_of(sphere_points({6, 0, 0}, r, 100), -1.0);
  EXPECT_GT(field.score(negative_at_positive, {}).esp, 0.5);
  EXPECT_LT(field.score(negative_at_negative, {}).esp, -0.5);
  // The ESP term is symmetric: the two placements' terms are opposite.
  EXPECT_NEAR(field.score(negative_at_positive, {}).esp, -field.score(negative_at_negative, {}).esp,
              0.05);
}

TEST(Complementarity, RefinementBringsADisplacedSampleBackToContact) {
  const ComplementarityOptions o;
  const ReceptorField field(one_atom(1.7, 0.0), around_origin);
  const LigandSample shell = sample_of(sphere_points({0, 0, 0}, 1.7 + o.contact_gap, 200));
  matching::RigidTransform start;
  start.translation = Eigen::Vector3d(0.6, -0.4, 0.3);
  const matching::RigidTransform refined = refine_pose(field, shell, start);
  EXPECT_LT(refined.translation.norm(), 0.1);
  EXPECT_GT(field.score(shell, refined).score, field.score(shell, start).score);
}

TEST(Complementarity, OptionsOutsideTheirDomainAreRefused) {
  ComplementarityOptions o;
  o.contact_width = 0.0;
  EXPECT_THROW(validate(o), OptionError);
  o = {};
  o.spacing = 0.01;
  EXPECT_THROW(ReceptorField(one_atom(1.7, 0.0), around_origin, o), OptionError);
  EXPECT_THROW(ReceptorField(Molecule{}, around_origin), InputError);
  EXPECT_THROW(ReceptorField(one_atom(1.7, 0.0), {}), InputError);
}

TEST(Complementarity, AnOpenSiteOpensAndAnEnclosedOneDoesNot) {
  // A shell of atoms 6 A about the origin, 1.2 A apart, leaves no gap of 0.5 A.
  Molecule cage;
  cage.source = "cage";
  const Eigen::Matrix3Xd shell = sphere_points({0, 0, 0}, 6.0, 400);
  for (Eigen::Index i = 0; i < shell.cols(); ++i)
    cage.atoms.push_back(atom_at(shell.col(i), 1.7, 0.0));
  const std::vector<molsurf::SiteSphere> centre{{Eigen::Vector3d::Zero(), 2.0}};
  EXPECT_FALSE(ReceptorField(cage, centre).site_opens(centre));
  Molecule open = cage;  // the atoms of one cap taken away
  open.atoms.erase(std::remove_if(open.atoms.begin(), open.atoms.end(),
                                  [](const Atom& a) { return a.position.z() > 4.0; }),
                   open.atoms.end());
  EXPECT_TRUE(ReceptorField(open, centre).site_opens(centre));
  // The free volume inside a 2 A sphere with no atom in reach is the sphere's, as the 0.4 A
  // lattice counts it (a count that differs from the volume by up to about a tenth).
  const double sphere = 4.0 / 3.0 * pi * 8.0;
  EXPECT_NEAR(ReceptorField(cage, centre).free_volume(centre), sphere, 0.1 * sphere);
}

TEST(Complement, MirrorsImagesSectorBySectorAndIsAnInvolution) {
  harmonic::ShapeImage image;
  image.rings = 2;
  image.sectors = 6;
  image.values = Eigen::VectorXd::LinSpaced(12, 1.0, 12.0);
  image.valid.assign(12, 1);
  image.valid[3] = 0;
  image.face = Eigen::VectorXi::LinSpaced(12, 0, 11);
  image.barycentric = Eigen::MatrixX3d::Random(12, 3);
  const harmonic::ShapeImage mirrored = mirrored_image(image);
  for (int ring = 0; ring < 2; ++ring) {
    for (int s = 0; s < 6; ++s) {
      const int i = ring * 6 + s, j = ring * 6 + (6 - s) % 6;
      EXPECT_DOUBLE_EQ(mirrored.values(j), -image.values(i));
      EXPECT_EQ(mirrored.valid[static_cast<std::size_t>(j)],
                image.valid[static_cast<std::size_t>(i)]);
      EXPECT_EQ(mirrored.face(j), image.face(i));
      EXPECT_EQ(mirrored.barycentric.row(j), image.barycentric.row(i));
    }
  }
  const harmonic::ShapeImage twice = mirrored_image(mirrored);
  EXPECT_EQ(twice.values, image.values);
  EXPECT_EQ(twice.face, image.face);
}

}  // namespace
}  // namespace surfcomp::docking
