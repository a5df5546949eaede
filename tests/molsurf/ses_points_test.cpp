// The SES as points straight from the atoms (molsurf::ses_points) and the screening sample built on
// it (matching::sample_molecule): points on the analytic surfaces of one and two atoms, areas
// against the analytic SES and the union of balls, rigid motions, cavities, bad input; and the
// sample against the sample of the full surface on a real ligand.
#include "surfcomp/molsurf/ses_points.hpp"
#include "atom_balls.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "test_data.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace surfcomp {
namespace {

using molsurf::SesPointOptions;
using molsurf::SurfacePoints;
using test::Atoms;
using test::make_atoms;

TEST(SesPoints, OneAtomIsItsSphereWithRadialNormals) {
  const double r = 1.7;
  const Eigen::Vector3d c(0.3, -0.2, 0.1);
  const Atoms atom = make_atoms({c}, {r});
  const SurfacePoints s = molsurf::ses_points(atom.centers, atom.radii);
  ASSERT_GT(s.size(), 100u);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Eigen::Vector3d p = s.points.col(static_cast<Eigen::Index>(i));
    EXPECT_NEAR((p - c).norm(), r, 1e-9);
    EXPECT_NEAR(s.normals.col(static_cast<Eigen::Index>(i)).dot((p - c) / r), 1.0, 1e-9);
  }
  // Each point stands for spacing^2 / |n|_1: on average over the sphere the area, within the
  // statistical error of about a thousand crossings.
  EXPECT_NEAR(s.areas.sum(), 4.0 * M_PI * r * r, 0.01 * 4.0 * M_PI * r * r);
}

TEST(SesPoints, TwoAtomsMatchCapsPlusTorus) {
  const double r1 = 1.7, r2 = 1.5, d = 2.5, p = 1.4;
  const test::TwoAtomSes exact = test::two_atom_ses(r1, r2, d, p);
  ASSERT_GT(exact.h, p);
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 0.4, -0.7).normalized();
  const Eigen::Vector3d c1(0.1, 0.2, 0.3);
  const Atoms atoms = make_atoms({c1, c1 + d * axis}, {r1, r2});
  const SurfacePoints s = molsurf::ses_points(atoms.centers, atoms.radii);
  EXPECT_NEAR(s.areas.sum(), exact.area, 0.015 * exact.area);
  // Every point lies on the SES: at least the probe's radius from every probe position that
  // touches both atoms (the torus's centre circle), and on an atom's sphere or on the torus.
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Eigen::Vector3d q = s.points.col(static_cast<Eigen::Index>(i));
    const double t = (q - c1).dot(axis);
    const double y = (q - c1 - t * axis).norm();
    const double on1 = std::abs((q - c1).norm() - r1);
    const double on2 = std::abs((q - c1 - d * axis).norm() - r2);
    const double x0 = (d * d + (r1 + p) * (r1 + p) - (r2 + p) * (r2 + p)) / (2.0 * d);
    const double on_torus = std::abs(std::hypot(t - x0, y - exact.h) - p);
    EXPECT_LT(std::min({on1, on2, on_torus}), 0.05) << "point " << i;
  }
}

TEST(SesPoints, ZeroProbeGivesTheUnionOfBalls) {
  const Atoms atoms = make_atoms({{0, 0, 0}, {1.4, 0.3, 0}, {2.1, 1.5, 0.4}}, {1.7, 1.5, 1.52});
  SesPointOptions options;
  options.probe_radius = 0.0;
  const SurfacePoints s = molsurf::ses_points(atoms.centers, atoms.radii, options);
  const double union_area = test::union_area(atoms, 0.0, 20000);
  EXPECT_NEAR(s.areas.sum(), union_area, 0.02 * union_area);
}

TEST(SesPoints, RigidMotionsKeepTheArea) {
  // para-cresol's heavy atoms and three hydrogens.
  const Atoms atoms = make_atoms({{0, 0, 0},
                                  {1.39, 0, 0},
                                  {2.085, 1.204, 0},
                                  {1.39, 2.408, 0},
                                  {0, 2.408, 0},
                                  {-0.695, 1.204, 0},
                                  {-0.75, -1.3, 0},
                                  {2.1, 3.6, 0.1},
                                  {-0.6, -1.0, 0.0},
                                  {3.1, 1.2, 0.0}},
                                 {1.7, 1.7, 1.7, 1.7, 1.7, 1.7, 1.52, 1.7, 1.2, 1.2});
  const double reference = molsurf::ses_points(atoms.centers, atoms.radii).areas.sum();
  std::mt19937 random(20261127);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Quaterniond q =
        Eigen::Quaterniond(normal(random), normal(random), normal(random), normal(random))
            .normalized();
    const Eigen::Vector3d shift(normal(random) * 10, normal(random) * 10, normal(random) * 10);
    const Eigen::MatrixX3d moved =
        ((q.toRotationMatrix() * atoms.centers.transpose()).colwise() + shift).transpose();
    const double area = molsurf::ses_points(moved, atoms.radii).areas.sum();
    EXPECT_NEAR(area, reference, 0.02 * reference) << "trial " << trial;
  }
}

TEST(SesPoints, AnInternalCavityIsLeftOut) {
  // Atoms on a sphere of radius 7 A, 1.4 A apart: a closed shell around a cavity of radius
  // about 5 A that the probe fits in but cannot reach.
  std::vector<Eigen::Vector3d> centers;
  const int n = 300;
  for (int k = 0; k < n; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / n;
    const double ring = std::sqrt(1.0 - z * z);
    const double phi = k * M_PI * (3.0 - std::sqrt(5.0));
    centers.push_back(7.0 * Eigen::Vector3d(ring * std::cos(phi), ring * std::sin(phi), z));
  }
  const Atoms shell = make_atoms(centers, std::vector<double>(centers.size(), 1.8));
  const SurfacePoints s = molsurf::ses_points(shell.centers, shell.radii);
  ASSERT_GT(s.size(), 0u);
  EXPECT_GT(s.points.colwise().norm().minCoeff(), 8.0);  // only the outside (7 + 1.8 A)
}

TEST(SesPoints, BadInputIsRefused) {
  const Atoms none = make_atoms({}, {});
  EXPECT_THROW(molsurf::ses_points(none.centers, none.radii), InputError);
  const Atoms one = make_atoms({{0, 0, 0}}, {1.5});
  SesPointOptions options;
  options.probe_radius = -1.0;
  EXPECT_THROW(molsurf::ses_points(one.centers, one.radii, options), OptionError);
  options = {};
  options.grid_spacing = 0.0;
  EXPECT_THROW(molsurf::ses_points(one.centers, one.radii, options), OptionError);
  const Atoms far =
      make_atoms({{0, 0, 0}, {1e3, 0, 0}, {0, 1e3, 0}, {0, 0, 1e3}}, {1.5, 1.5, 1.5, 1.5});
  try {
    molsurf::ses_points(far.centers, far.radii);
    ADD_FAILURE() << "no error for a grid over the limit";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("raise it with max_grid_cells"), std::string::npos)
        << e.what();
  }
  const Atoms nan = make_atoms({{0, 0, std::nan("")}}, {1.5});
  EXPECT_THROW(molsurf::ses_points(nan.centers, nan.radii), InputError);
}

TEST(ScreeningSample, StandsInForTheFullSurfacesSample) {
  const auto path = test::shared_dataset("thermolysin/ligands-common-frame/1THL_ligand.sdf");
  if (!path) SURFCOMP_DATA_ABSENT(test::shared_absent_message("thermolysin"));
  const Molecule ligand = io::read_molecule(*path);
  const matching::OverlayOptions options;
  const matching::SurfaceSample full =
      matching::sample_surface(molsurf::build_molecular_surface(ligand), options.spacing);
  const matching::SurfaceSample fast = matching::sample_molecule(ligand, options.spacing);
  // About the same area (the re-entrant surface a little low: over the therm set's 76 molecules
  // the ratio is 0.965-0.987, median 0.976), about as many points, and the two samples overlay
  // each other in place nearly as each does itself (shape Tanimoto 0.97-0.99 over the therm and
  // bzr sets; screening_sample_bench).
  EXPECT_NEAR(fast.weights.sum(), full.weights.sum(), 0.04 * full.weights.sum());
  EXPECT_NEAR(static_cast<double>(fast.size()), static_cast<double>(full.size()),
              0.15 * static_cast<double>(full.size()));
  const matching::SurfaceOverlay overlay(full, fast, options);
  const matching::OverlayScore s = overlay.score({});
  EXPECT_GT(s.shape, 0.97);
  EXPECT_GT(s.chem, 0.97);
  // ESP and LP at the pooled points are the molecule's potentials there.
  const Eigen::VectorXd esp = molsurf::electrostatic_potential(fast.points.transpose(), ligand);
  EXPECT_TRUE(esp.isApprox(fast.esp, 1e-12));
}

}  // namespace
}  // namespace surfcomp
