// The molecule model shared by every stage: atoms with position, charge, radius and
// lipophilicity increment. Readers (core/io) fill it; surface builders consume it.
#pragma once

#include <Eigen/Core>

#include <string>
#include <string_view>
#include <vector>

namespace surfcomp {

/// One atom. Units: position in A, charge in e, radius in A, lipophilicity as a
/// dimensionless logP increment (Wildman-Crippen for ligands, a residue-atom table for proteins).
struct Atom {
  std::string element;                                 ///< capitalised symbol, "C", "Cl", "Zn"
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< A
  double charge = 0.0;                                 ///< partial charge, e
  double radius = 0.0;         ///< van der Waals radius, A (Bondi by default)
  double lipophilicity = 0.0;  ///< logP increment f_i
  std::string name;            ///< PDB atom name, "" when unknown
  std::string residue_name;    ///< PDB residue name, "" when unknown
  int residue_number = 0;      ///< PDB residue sequence number
  std::string chain;           ///< PDB chain identifier
  bool hetero = false;         ///< HETATM record in a PDB/PQR file
};

/// Where a molecule's charges came from, for the summary and for later stages.
enum class ChargeSource { none, file, gasteiger, mmff, residue_table };

/// A molecule: its atoms (hydrogens included when the file has them) and provenance.
struct Molecule {
  std::string source;  ///< file it was read from, for messages
  std::string title;   ///< title line / molecule name
  std::vector<Atom> atoms;
  ChargeSource charge_source = ChargeSource::none;
  bool lipophilicity_assigned = false;  ///< f_i were set (Crippen or the residue table)
};

/// Checks that `molecule` has at least one atom and that every coordinate, radius and charge
/// is finite and every radius positive. Throws InputError naming molecule.source and the atom.
void validate_molecule(const Molecule& molecule);

/// A residue or atom name as a comparison key: blanks removed, upper case (" oxt" -> "OXT").
std::string residue_key(std::string_view name);

/// "atom N (element name residue numberchain)" for messages; N is 1-based.
std::string describe_atom(const Molecule& molecule, std::size_t index);

/// Applies the rigid motion x -> rotation * x + translation to every atom position.
void transform_molecule(Molecule& molecule, const Eigen::Matrix3d& rotation,
                        const Eigen::Vector3d& translation);

}  // namespace surfcomp
