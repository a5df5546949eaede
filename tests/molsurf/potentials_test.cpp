#include "analytic_meshes.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/molsurf/potentials.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace surfcomp::molsurf {
namespace {

Atom atom_at(const Eigen::Vector3d& position, double charge, double lipophilicity = 0.0) {
  Atom a;
  a.element = "C";
  a.radius = 1.7;
  a.position = position;
  a.charge = charge;
  a.lipophilicity = lipophilicity;
  return a;
}

Molecule molecule_of(std::initializer_list<Atom> atoms) {
  Molecule m;
  m.source = "potentials_test";
  m.atoms = atoms;
  return m;
}

TEST(ElectrostaticPotential, UnitChargeAtTheCentreOfASphere) {
  for (const double r : {1.0, 2.5, 7.0}) {
    const Eigen::Vector3d centre(0.3, -1.2, 2.0);
    const Eigen::MatrixX3d points = test::icosphere(r, 4, centre).positions();
    const Molecule m = molecule_of({atom_at(centre, 1.0)});
    const Eigen::VectorXd esp = electrostatic_potential(points, m);
    ASSERT_EQ(esp.size(), points.rows());
    for (Eigen::Index i = 0; i < esp.size(); ++i) {
      EXPECT_NEAR(esp(i), 332.06 / r, 1e-9 * 332.06 / r) << "r " << r << " vertex " << i;
    }
    EspOptions ddd;
    ddd.dielectric = 4.0;
    ddd.distance_dependent = true;
    const Eigen::VectorXd esp4d = electrostatic_potential(points, m, ddd);
    for (Eigen::Index i = 0; i < esp4d.size(); ++i) {
      EXPECT_NEAR(esp4d(i), 332.06 / (4 * r * r), 1e-9 * 332.06 / (4 * r * r));
    }
    EspOptions constant4;
    constant4.dielectric = 4.0;
    EXPECT_NEAR(electrostatic_potential(points, m, constant4)(0), 332.06 / (4 * r), 1e-9);
  }
}

TEST(ElectrostaticPotential, TwoChargesSuperpose) {
  const Eigen::Vector3d a(0, 0, 0), b(3, 1, -1);
  const Eigen::MatrixX3d points = test::icosphere(4.0, 3, Eigen::Vector3d(1, 0, 0)).positions();
  const Eigen::VectorXd both =
      electrostatic_potential(points, molecule_of({atom_at(a, 0.4), atom_at(b, -0.7)}));
  const Eigen::VectorXd only_a = electrostatic_potential(points, molecule_of({atom_at(a, 0.4)}));
  const Eigen::VectorXd only_b = electrostatic_potential(points, molecule_of({atom_at(b, -0.7)}));
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double expected = 332.06 * (0.4 / (points.row(i) - a.transpose()).norm() -
                                      0.7 / (points.row(i) - b.transpose()).norm());
    EXPECT_NEAR(both(i), expected, 1e-9 * std::abs(expected) + 1e-12);
    EXPECT_NEAR(both(i), only_a(i) + only_b(i), 1e-9 * std::abs(expected) + 1e-12);
  }
}

TEST(ElectrostaticPotential, DistancesBelowTheMinimumAreClamped) {
  const Molecule m = molecule_of({atom_at(Eigen::Vector3d::Zero(), 1.0)});
  Eigen::MatrixX3d points(3, 3);
  points << 0, 0, 0, 0.2, 0, 0, 0, 0, 2.0;
  const Eigen::VectorXd esp = electrostatic_potential(points, m);
  EXPECT_DOUBLE_EQ(esp(0), 332.06 / 0.5);
  EXPECT_DOUBLE_EQ(esp(1), 332.06 / 0.5);
  EXPECT_DOUBLE_EQ(esp(2), 332.06 / 2.0);
}

TEST(LipophilicPotential, KernelsAtKnownDistances) {
  const Molecule m = molecule_of({atom_at(Eigen::Vector3d(1, 2, 3), 0.0, 1.0)});
  Eigen::MatrixX3d points(4, 3);
  points << 1, 2, 3.5, 1, 0, 3, 4, 2, 3, 1, 2, 9;  // d = 0.5, 2, 3, 6
  const double d[] = {0.5, 2.0, 3.0, 6.0};
  const Eigen::VectorXd fauchere = lipophilic_potential(points, m);
  LpOptions dubost_options;
  dubost_options.kernel = LipophilicKernel::dubost;
  const Eigen::VectorXd dubost = lipophilic_potential(points, m, dubost_options);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(fauchere(i), std::exp(-d[i]), 1e-15) << "d " << d[i];
    EXPECT_NEAR(dubost(i), 1.0 / (1.0 + d[i]), 1e-15) << "d " << d[i];
  }
  LpOptions cut;
  cut.cutoff = 2.5;
  const Eigen::VectorXd within = lipophilic_potential(points, m, cut);
  EXPECT_NEAR(within(0), std::exp(-0.5), 1e-15);
  EXPECT_NEAR(within(1), std::exp(-2.0), 1e-15);
  EXPECT_EQ(within(2), 0.0);
  EXPECT_EQ(within(3), 0.0);
}

TEST(LipophilicPotential, IncrementsWeighTheKernel) {
  const Molecule m = molecule_of(
      {atom_at(Eigen::Vector3d(0, 0, 0), 0.0, 0.6), atom_at(Eigen::Vector3d(2, 0, 0), 0.0, -0.3)});
  Eigen::MatrixX3d points(1, 3);
  points << 0, 1, 0;
  EXPECT_NEAR(lipophilic_potential(points, m)(0),
              0.6 * std::exp(-1.0) - 0.3 * std::exp(-std::sqrt(5.0)), 1e-15);
}

TEST(Potentials, RigidMotionLeavesValuesUnchanged) {
  Molecule m = molecule_of({atom_at(Eigen::Vector3d(0, 0, 0), 0.5, 0.4),
                            atom_at(Eigen::Vector3d(1.5, 0.2, 0), -0.3, -0.8),
                            atom_at(Eigen::Vector3d(0.3, 1.4, 0.5), -0.2, 0.1)});
  const Eigen::MatrixX3d points =
      test::icosphere(3.5, 5, Eigen::Vector3d(0.5, 0.5, 0.2)).positions();
  const Eigen::VectorXd esp = electrostatic_potential(points, m);
  const Eigen::VectorXd lp = lipophilic_potential(points, m);

  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d translation(12.0, -7.5, 3.25);
  transform_molecule(m, rotation, translation);
  const Eigen::MatrixX3d moved =
      (points * rotation.transpose()).rowwise() + translation.transpose();
  const Eigen::VectorXd esp_moved = electrostatic_potential(moved, m);
  const Eigen::VectorXd lp_moved = lipophilic_potential(moved, m);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    EXPECT_NEAR(esp_moved(i), esp(i), 1e-9 * std::max(1.0, std::abs(esp(i))));
    EXPECT_NEAR(lp_moved(i), lp(i), 1e-9);
  }
}

TEST(Potentials, RejectInvalidInput) {
  const Molecule good = molecule_of({atom_at(Eigen::Vector3d::Zero(), 1.0, 1.0)});
  Eigen::MatrixX3d points(2, 3);
  points << 1, 0, 0, 0, 2, 0;
  EXPECT_THROW(electrostatic_potential(points, molecule_of({})), InputError);
  EXPECT_THROW(lipophilic_potential(points, molecule_of({})), InputError);

  Eigen::MatrixX3d bad_points = points;
  bad_points(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(electrostatic_potential(bad_points, good), InputError);
  EXPECT_THROW(lipophilic_potential(bad_points, good), InputError);

  Molecule bad_charge = good;
  bad_charge.atoms[0].charge = std::numeric_limits<double>::infinity();
  EXPECT_THROW(electrostatic_potential(points, bad_charge), InputError);
  EXPECT_NO_THROW(lipophilic_potential(points, bad_charge));  // LP does not use charges

  Molecule bad_position = good;
  bad_position.atoms[0].position.y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(electrostatic_potential(points, bad_position), InputError);
  EXPECT_THROW(lipophilic_potential(points, bad_position), InputError);

  EspOptions zero_dielectric;
  zero_dielectric.dielectric = 0.0;
  EXPECT_THROW(electrostatic_potential(points, good, zero_dielectric), OptionError);
  LpOptions negative_cutoff;
  negative_cutoff.cutoff = -1.0;
  EXPECT_THROW(lipophilic_potential(points, good, negative_cutoff), OptionError);

  EXPECT_EQ(electrostatic_potential(Eigen::MatrixX3d(0, 3), good).size(), 0);
}

// A protein-sized case, 30,252 surface points and 2,000 atoms on a grid inside them (the size
// bench/potentials_bench.cpp times): the parallel sum agrees with a serial one.
TEST(LipophilicPotential, CutoffSumsExactlyTheNearAtomsWithinItsBound) {
  // Points on spheres of radius 5 to 25 A around a 20 x 10 x 10 grid of 2,000 atoms 1 A apart:
  // some points inside the grid's cutoff, some with every atom beyond it.
  Molecule m;
  m.source = "grid";
  double sum_abs_f = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const double f = 0.1 * (i % 7) - 0.3;
    m.atoms.push_back(
        atom_at(Eigen::Vector3d(i % 20 - 9.5, (i / 20) % 10 - 4.5, i / 200 - 4.5), 0.0, f));
    sum_abs_f += std::abs(f);
  }
  std::vector<Eigen::MatrixX3d> shells;
  Eigen::Index n = 0;
  for (const double radius : {5.0, 9.0, 14.0, 25.0}) {
    shells.push_back(test::icosphere(radius, 6).positions());
    n += shells.back().rows();
  }
  Eigen::MatrixX3d points(n, 3);
  Eigen::Index row = 0;
  for (const Eigen::MatrixX3d& shell : shells) {
    points.middleRows(row, shell.rows()) = shell;
    row += shell.rows();
  }
  LpOptions every_atom;
  every_atom.cutoff = 0.0;
  const Eigen::VectorXd exact = lipophilic_potential(points, m, every_atom);
  for (const LipophilicKernel kernel : {LipophilicKernel::fauchere, LipophilicKernel::dubost}) {
    for (const double cutoff : {3.0, 6.0, 10.0}) {
      LpOptions options;
      options.kernel = kernel;
      options.cutoff = cutoff;
      const Eigen::VectorXd cut = lipophilic_potential(points, m, options);
      for (Eigen::Index p = 0; p < n; ++p) {
        double expected = 0.0;  // the atoms within the cutoff, summed in index order
        for (const Atom& a : m.atoms) {
          const double d = (points.row(p) - a.position.transpose()).norm();
          if (d > cutoff) continue;
          expected += a.lipophilicity *
                      (kernel == LipophilicKernel::dubost ? 1.0 / (1.0 + d) : std::exp(-d));
        }
        ASSERT_NEAR(cut(p), expected, 1e-12) << "cutoff " << cutoff << ", point " << p;
        // What the cutoff leaves out: at most exp(-cutoff) per unit |f| (Fauchere's kernel).
        if (kernel == LipophilicKernel::fauchere) {
          ASSERT_LE(std::abs(cut(p) - exact(p)), std::exp(-cutoff) * sum_abs_f) << "point " << p;
        }
      }
    }
  }
  // Unset, the cutoff is default_fauchere_cutoff for Fauchere's kernel and none for Dubost's.
  LpOptions twelve;
  twelve.cutoff = default_fauchere_cutoff;
  EXPECT_TRUE(lipophilic_potential(points, m) == lipophilic_potential(points, m, twelve));
  LpOptions dubost;
  dubost.kernel = LipophilicKernel::dubost;
  LpOptions dubost_every_atom = dubost;
  dubost_every_atom.cutoff = 0.0;
  EXPECT_TRUE(lipophilic_potential(points, m, dubost) ==
              lipophilic_potential(points, m, dubost_every_atom));
}

TEST(ElectrostaticPotential, TreecodeStaysNearItsToleranceAndLigandsStayExact) {
  // 2,000 atoms 1 A apart with varied charges (more than treecode_min_atoms), and points on
  // spheres of radius 6 to 25 A around them, some among the outer atoms' boxes.
  Molecule m;
  m.source = "grid";
  for (int i = 0; i < 2000; ++i) {
    m.atoms.push_back(atom_at(Eigen::Vector3d(i % 20 - 9.5, (i / 20) % 10 - 4.5, i / 200 - 4.5),
                              0.05 * (i % 11) - 0.25, 0.0));
  }
  ASSERT_GT(m.atoms.size(), treecode_min_atoms);
  std::vector<Eigen::MatrixX3d> shells;
  Eigen::Index n = 0;
  for (const double radius : {6.0, 9.0, 14.0, 25.0}) {
    shells.push_back(test::icosphere(radius, 8).positions());
    n += shells.back().rows();
  }
  Eigen::MatrixX3d points(n, 3);
  Eigen::Index row = 0;
  for (const Eigen::MatrixX3d& shell : shells) {
    points.middleRows(row, shell.rows()) = shell;
    row += shell.rows();
  }
  EspOptions exact_options;
  exact_options.treecode_tolerance = 0.0;
  const Eigen::VectorXd exact = electrostatic_potential(points, m, exact_options);
  double previous = HUGE_VAL;
  for (const double tolerance : {1e-1, 1e-2, 1e-3, 1e-4}) {
    EspOptions options;
    options.treecode_tolerance = tolerance;
    const double error =
        (electrostatic_potential(points, m, options) - exact).cwiseAbs().maxCoeff();
    // Measured on 4we2: 1.3 to 1.9 times the tolerance per box.
    EXPECT_LT(error, 20.0 * tolerance) << "tolerance " << tolerance;
    EXPECT_LT(error, previous) << "tolerance " << tolerance;
    previous = error;
  }
  // The default is the treecode at default_treecode_tolerance; a ligand-sized molecule (at most
  // treecode_min_atoms atoms) gets the exact sum bit for bit.
  EspOptions by_default;
  by_default.treecode_tolerance = default_treecode_tolerance;
  EXPECT_TRUE(electrostatic_potential(points, m) == electrostatic_potential(points, m, by_default));
  m.atoms.resize(treecode_min_atoms);
  EXPECT_TRUE(electrostatic_potential(points, m) ==
              electrostatic_potential(points, m, exact_options));
}

TEST(Potentials, ProteinSizedCaseAgreesWithASerialSum) {
  const Eigen::MatrixX3d points = test::icosphere(30.0, 55).positions();
  Molecule m;
  m.source = "grid";
  for (int i = 0; i < 2000; ++i) {
    m.atoms.push_back(atom_at(Eigen::Vector3d(i % 20 - 9.5, (i / 20) % 10 - 4.5, i / 200 - 4.5),
                              i % 2 ? 0.1 : -0.1, 0.01 * (i % 7)));
  }
  EspOptions exact;  // the treecode has its own test
  exact.treecode_tolerance = 0.0;
  const Eigen::VectorXd esp = electrostatic_potential(points, m, exact);
  const Eigen::VectorXd lp = lipophilic_potential(points, m);
  ASSERT_EQ(esp.size(), points.rows());
  EXPECT_EQ(lp.size(), points.rows());
  for (const Eigen::Index i :
       {Eigen::Index{0}, Eigen::Index{7}, points.rows() / 2, points.rows() - 1}) {
    double expected = 0.0;
    for (const Atom& a : m.atoms)
      expected += 332.06 * a.charge / (points.row(i) - a.position.transpose()).norm();
    EXPECT_NEAR(esp(i), expected, 1e-9 * std::abs(expected) + 1e-12) << "point " << i;
  }
}

}  // namespace
}  // namespace surfcomp::molsurf
