#include "surfcomp/core/elements.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/molecule.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace surfcomp {
namespace {

TEST(Elements, BondiRadiiOfTheOrganicElements) {
  EXPECT_DOUBLE_EQ(*bondi_radius("C"), 1.70);
  EXPECT_DOUBLE_EQ(*bondi_radius("N"), 1.55);
  EXPECT_DOUBLE_EQ(*bondi_radius("O"), 1.52);
  EXPECT_DOUBLE_EQ(*bondi_radius("H"), 1.20);
  EXPECT_DOUBLE_EQ(*bondi_radius("S"), 1.80);
  EXPECT_DOUBLE_EQ(*bondi_radius("CL"), 1.75);
  EXPECT_DOUBLE_EQ(*bondi_radius(" zn"), 1.39);
  EXPECT_FALSE(bondi_radius("Xx").has_value());
  EXPECT_EQ(normalize_element(" BR "), "Br");
}

Molecule one_atom() {
  Molecule m;
  m.source = "test.sdf";
  Atom a;
  a.element = "C";
  a.radius = 1.7;
  m.atoms.push_back(a);
  return m;
}

TEST(Molecule, ValidationRejectsEmptyAndNonFinite) {
  Molecule empty;
  empty.source = "empty.sdf";
  EXPECT_THROW(validate_molecule(empty), InputError);

  Molecule nan_coord = one_atom();
  nan_coord.atoms[0].position.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate_molecule(nan_coord), InputError);

  Molecule inf_charge = one_atom();
  inf_charge.atoms[0].charge = std::numeric_limits<double>::infinity();
  EXPECT_THROW(validate_molecule(inf_charge), InputError);

  Molecule no_radius = one_atom();
  no_radius.atoms[0].radius = 0.0;
  try {
    validate_molecule(no_radius);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("test.sdf"), std::string::npos);
  }
  EXPECT_NO_THROW(validate_molecule(one_atom()));
}

TEST(Molecule, TransformAppliesRotationThenTranslation) {
  Molecule m = one_atom();
  m.atoms[0].position = Eigen::Vector3d(1, 0, 0);
  const Eigen::Matrix3d rz =
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  transform_molecule(m, rz, Eigen::Vector3d(0, 0, 2));
  EXPECT_NEAR((m.atoms[0].position - Eigen::Vector3d(0, 1, 2)).norm(), 0.0, 1e-12);
}

TEST(Errors, MessagesNameFileAndLine) {
  EXPECT_STREQ(FormatError("a.pdb", 12, "bad x").what(), "a.pdb:12: bad x");
  EXPECT_STREQ(FormatError("a.ply", "truncated").what(), "a.ply: truncated");
  EXPECT_STREQ(FileError("b.sdf", "cannot open").what(), "b.sdf: cannot open");
}

}  // namespace
}  // namespace surfcomp
