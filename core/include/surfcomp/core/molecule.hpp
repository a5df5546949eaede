// The molecule model shared by every stage: atoms with position, charge, radius and
// lipophilicity increment. Readers (core/io) fill it; surface builders consume it.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <optional>
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
  int formal_charge = 0;  ///< formal charge, e, as the file gives it (SDF, MOL2, PDB via RDKit)
  double radius = 0.0;    ///< van der Waals radius, A (Bondi by default)
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
  /// The atoms of acid and base groups that the file draws neutral but that are ionised at
  /// pH 7, as the RDKit reader finds them: the acidic hydroxyl oxygen of a carboxylic,
  /// phosphonic, phosphoric, sulfonic or sulfuric acid, the N-H nitrogen of a tetrazole, the
  /// nitrogen of an aliphatic amine and the imine nitrogen of an amidine or guanidine. Indices
  /// into `atoms`, ascending; read from SDF, MOL and MOL2 files (a PDB file has no bond
  /// orders), empty from the other formats.
  std::vector<std::size_t> ionisable_atoms;
  ChargeSource charge_source = ChargeSource::none;
  bool lipophilicity_assigned = false;  ///< f_i were set (Crippen or the residue table)
};

/// Checks that `molecule` has at least one atom and that every coordinate, radius and charge
/// is finite and every radius positive. Throws InputError naming molecule.source and the atom.
void validate_molecule(const Molecule& molecule);

/// A residue or atom name as a comparison key: blanks removed, upper case (" oxt" -> "OXT").
std::string residue_key(std::string_view name);

/// True for the water residue names HOH, WAT and DOD (compared by residue_key).
bool is_water_residue(std::string_view residue_name);

/// Which copy of a ligand residue select_ligand takes.
struct LigandSelector {
  /// The HETATM residue name, compared by residue_key (blanks ignored, case-insensitive).
  std::string residue_name;
  /// Only the copies in this chain (compared as written, blanks ignored); default any chain.
  std::optional<std::string> chain;
  /// Only the copies with this residue number; default any number.
  std::optional<int> residue_number;
};

/// The selector a user writes as RESIDUE[:CHAIN[:NUMBER]] ("ATP", "ATP:B", "ATP:B:501",
/// "ATP::501"; an empty chain or number is any). Throws OptionError naming `text` when the
/// residue is empty, the number is not an integer or there are more than three fields.
LigandSelector parse_ligand_selector(std::string_view text);

/// Indices into molecule.atoms, in order, of one copy of a ligand residue: the HETATM atoms
/// named selector.residue_name, narrowed to selector.chain and selector.residue_number when
/// they are given; a copy is one (chain, residue number), and of several copies the one with
/// the lowest chain, then the lowest residue number, is taken. This is the one ligand
/// selection of the project (io::MoleculeReadOptions::ligand, molsurf::binding_site).
/// Throws InputError naming molecule.source when no HETATM residue has that name (listing up
/// to ten HETATM residue names present) or when no copy of it is in the chain and number asked
/// for (listing the copies present).
std::vector<std::size_t> select_ligand(const Molecule& molecule, const LigandSelector& selector);

/// Within this of an atom of opposite formal charge, a charged atom is taken as bonded to it
/// (nitro N-O 1.2 A, sulfonium ylide C-S 1.8 A; a salt bridge's closest approach is about
/// 2.6 A).
inline constexpr double charge_pair_bond_length = 2.0;

/// Whether `molecule` carries an ionic group at pH 7: an atom whose formal charge no bonded
/// atom of the opposite charge balances (a carboxylate, an ammonium, an amidinium; not a nitro
/// group or an N-oxide), or a group drawn neutral that ionises (Molecule::ionisable_atoms: a
/// carboxylic acid, an aliphatic amine...). Without any of them or any formal charge in the
/// file, whether its partial charges sum to a net charge of at least 0.5 e in size (a PQR
/// file's ion).
bool carries_ionic_group(const Molecule& molecule);

/// "atom N (element name residue numberchain)" for messages; N is 1-based.
std::string describe_atom(const Molecule& molecule, std::size_t index);

/// Applies the rigid motion x -> rotation * x + translation to every atom position.
void transform_molecule(Molecule& molecule, const Eigen::Matrix3d& rotation,
                        const Eigen::Vector3d& translation);

}  // namespace surfcomp
