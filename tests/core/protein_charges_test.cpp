// Residue charges for proteins read from PDB files: formal charges of ionisable groups at pH 7.
#include "surfcomp/core/protein_charges.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <tuple>

namespace surfcomp {
namespace {

TEST(ProteinCharges, IonisableGroupsCarryTheirFormalCharge) {
  EXPECT_DOUBLE_EQ(
      *protein_atom_formal_charge("ASP", "OD1") + *protein_atom_formal_charge("ASP", "OD2"), -1.0);
  EXPECT_DOUBLE_EQ(
      *protein_atom_formal_charge("GLU", " OE1") + *protein_atom_formal_charge("GLU", "OE2"), -1.0);
  EXPECT_DOUBLE_EQ(*protein_atom_formal_charge("LYS", "NZ"), 1.0);
  EXPECT_NEAR(*protein_atom_formal_charge("ARG", "NE") + *protein_atom_formal_charge("ARG", "NH1") +
                  *protein_atom_formal_charge("ARG", "NH2"),
              1.0, 1e-15);
  EXPECT_DOUBLE_EQ(*protein_atom_formal_charge("HIS", "NE2"), 0.0);
  EXPECT_DOUBLE_EQ(
      *protein_atom_formal_charge("HIP", "ND1") + *protein_atom_formal_charge("HIP", "NE2"), 1.0);
  EXPECT_DOUBLE_EQ(*protein_atom_formal_charge("ALA", "CB"), 0.0);
  EXPECT_FALSE(protein_atom_formal_charge("0DB", "C1").has_value());
  EXPECT_EQ(*usual_ionic_charge("ZN"), 2);
  EXPECT_EQ(*usual_ionic_charge("Cl"), -1);
  EXPECT_FALSE(usual_ionic_charge("C").has_value());
}

/// Net charge of a PDB protein counted from its text: +1 per LYS and ARG, -1 per ASP and GLU,
/// +1 per chain (N-terminus), -1 per OXT, the usual charge of each metal ion; water excluded.
double net_charge_from_text(const std::filesystem::path& pdb) {
  std::ifstream in(pdb);
  std::set<std::tuple<char, std::string, std::string>> residues;
  std::set<char> chains;
  double charge = 0.0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("ENDMDL", 0) == 0) break;
    const bool atom = line.rfind("ATOM  ", 0) == 0;
    const bool hetatm = line.rfind("HETATM", 0) == 0;
    if ((!atom && !hetatm) || line.size() < 54) continue;
    if (line[16] != ' ' && line[16] != 'A') continue;  // first alternate location only
    const std::string name = line.substr(17, 3);
    const std::string number = line.substr(22, 5);
    if (atom) {
      chains.insert(line[21]);
      if (residues.emplace(line[21], number, name).second) {
        if (name == "LYS" || name == "ARG") charge += 1;
        if (name == "ASP" || name == "GLU") charge -= 1;
      }
      if (line.substr(12, 4) == " OXT") charge -= 1;
    } else if (name == " ZN" || name == " CA" || name == " MG") {
      charge += 2;
    }
  }
  return charge + static_cast<double>(chains.size());
}

void expect_net_charge(const std::filesystem::path& pdb) {
  const Molecule protein = io::read_molecule(pdb);
  EXPECT_EQ(protein.charge_source, ChargeSource::residue_table);
  double total = 0.0;
  for (const Atom& atom : protein.atoms) total += atom.charge;
  const double expected = net_charge_from_text(pdb);
  std::printf("[ charge   ] %s: %zu atoms, net charge %.3f (counted from the text: %.0f)\n",
              pdb.filename().c_str(), protein.atoms.size(), total, expected);
  EXPECT_NEAR(total, expected, 1e-9);
}

TEST(ProteinCharges, NetChargeOfThermolysinMatchesItsResidues) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/1THL.pdb");
  expect_net_charge(pdb);
}

TEST(ProteinCharges, ProteinWithExplicitHydrogensReads) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "surfaces/masif/1EWY_A.pdb");
  expect_net_charge(pdb);
}

TEST(ProteinCharges, GasteigerOnAProteinPdbIsAnOptionError) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/1THL.pdb");
  io::MoleculeReadOptions options;
  options.charges = io::ChargeModel::gasteiger;
  EXPECT_THROW(io::read_molecule(pdb, options), OptionError);
}

}  // namespace
}  // namespace surfcomp
