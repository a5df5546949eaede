// Reading a molecule file (SDF/MOL, MOL2, PDB, PQR) into the surfcomp molecule model, with
// radii, partial charges and lipophilicity increments assigned.
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_table.hpp"

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace surfcomp::io {

/// Where the partial charges come from.
enum class ChargeModel {
  /// the file's charges if it has some (MOL2 with a charge type, PQR); else, for a protein read
  /// whole from a PDB file, the residue formal charges of assign_protein_formal_charges()
  /// (protein_charges.hpp; RDKit cannot type residues without bond orders), else Gasteiger
  file,
  gasteiger,  ///< Gasteiger-Marsili charges computed by RDKit (12 iterations)
  mmff,       ///< MMFF94 charges computed by RDKit
};

/// The names of the charge models, indexed by ChargeModel (as the --charges option spells them).
inline constexpr std::array<const char*, 3> charge_model_names = {"file", "gasteiger", "mmff"};

/// How read_molecule interprets a file.
struct MoleculeReadOptions {
  /// Charge model; default ChargeModel::file. PQR files accept only ChargeModel::file.
  ChargeModel charges = ChargeModel::file;
  /// PDB/PQR: read only one copy of a HETATM residue, written RES[:CHAIN[:NUMBER]]
  /// (parse_ligand_selector), the one select_ligand takes (by default the lowest chain, then
  /// residue number); default "" = the whole structure. Refused (OptionError) for SDF/MOL/MOL2,
  /// whose molecule is the ligand itself.
  std::string ligand;
  /// SDF/MOL/MOL2: which molecule of the file to read, 1-based; default 0 = the file's only
  /// molecule, and a file holding several is refused (InputError naming their count). PDB/PQR
  /// files hold one structure: a record above 1 is refused.
  std::size_t record = 0;
  /// Whole-structure PDB/PQR: drop water residues (HOH, WAT, DOD); default true.
  bool remove_water = true;
  /// Whole-structure PDB/PQR: also drop the residues with these names (case-insensitive), e.g.
  /// a bound ligand when the binding site's surface is wanted; default none.
  std::vector<std::string> exclude_residues;
  /// Assign lipophilicity increments f_i; default true. Ligands (SDF/MOL/MOL2 and `ligand`
  /// selections) get Wildman-Crippen atom contributions from RDKit, whole structures the
  /// residue-atom table of protein_atom_lipophilicity().
  bool assign_lipophilicity = true;
  /// Default 0: every residue. Whole-structure PDB/mmCIF: drop the residues (of any kind) whose
  /// atoms' mean B-factor is below this, before anything else is read; for an AlphaFold model the
  /// B-factor column holds pLDDT (0-100), so 70 keeps the residues modelled with confidence.
  /// Refused (OptionError) for SDF/MOL/MOL2 and PQR, whose columns hold no B-factor. In [0, 100].
  double min_plddt = 0.0;
};

/// What the user sees of --min-plddt (MoleculeReadOptions::min_plddt), wherever structures are
/// read.
options::Spec min_plddt_spec();

/// True when `path` has a molecule extension read_molecule understands:
/// .sdf .mol .mol2 .pdb .ent .pqr .cif .mmcif .cif.gz (case-insensitive).
bool is_molecule_file(const std::filesystem::path& path);

/// True for a PDBx/mmCIF file: .cif, .mmcif or .cif.gz (case-insensitive).
bool is_mmcif_file(const std::filesystem::path& path);

/// True for a structure file read_structure_text reads: .pdb, .ent or is_mmcif_file
/// (case-insensitive).
bool is_structure_file(const std::filesystem::path& path);

/// The name of a structure file without its extensions: "1thl" for 1thl.pdb, 1THL.cif and
/// 1thl.cif.gz; the stem for any other file.
std::string structure_stem(const std::filesystem::path& path);

/// The structure in `path` as PDB text: a PDB file's own text; for mmCIF (is_mmcif_file, gzipped
/// or not, at most max_input_file_bytes once unpacked) the first model's atoms written by gemmi
/// as PDB records (ATOM/HETATM as the file's group_PDB says, alternate locations, B-factors and
/// chains kept; chain names longer than 2 characters shortened), so that every reader of PDB
/// text reads mmCIF the same way. `models`, when given, receives the file's model count. Throws
/// FileError, FormatError (gemmi's reason, with the file), InputError (no atom coordinates).
std::string read_structure_text(const std::filesystem::path& path, std::size_t* models = nullptr);

/// Reads the molecule in `path`, chosen by extension (see is_molecule_file):
/// - SDF/MOL/MOL2: the molecule options.record (records end at "$$$$" lines, MOL2 molecules
///   start at @<TRIPOS>MOLECULE); PDB and mmCIF (read_structure_text): every model-1 atom (RDKit's
///   reader with proximity bonding); PQR: read_pqr(). Hydrogens present in the file are kept.
/// - PDB alternate locations: one per atom. An atom without one is read; of an atom's
///   alternate locations the first in the file is read (usually 'A'), so an atom or residue
///   present only as 'B' is read too (the ATP of 1RDQ). An atom is its chain, residue number,
///   insertion code and name; where one residue position has alternate residue names
///   (microheterogeneity), only the first name's records are read.
/// - Radii: Bondi (surfcomp::bondi_radius) except PQR, whose radii are taken as given.
/// - Charges (e): see ChargeModel. Gasteiger or MMFF on a protein PDB is an OptionError. Computed
/// charges of implicit hydrogens (atoms the file does
///   not list) are added to their heavy atom, so the charges sum to the formal charge.
///   Isolated single-atom ions without Gasteiger parameters (Zn, Ca, Na, Cl, ...) get their
///   formal charge from the file, else their usual ionic charge (Na/K +1, Mg/Ca/Zn/Mn/Fe/Co/
///   Ni/Cu/Cd +2, F/Cl/Br/I -1).
/// - Lipophilicity: Wildman-Crippen contributions (S. A. Wildman, G. M. Crippen, J. Chem. Inf.
///   Comput. Sci. 39, 868 (1999)); implicit hydrogens' contributions are added to their heavy
///   atom, so the sum equals RDKit's MolLogP. PDB files carry no bond orders: a PDB ligand is
///   bonded by RDKit's proximity rule with single bonds only (aromatic rings and carbonyls are
///   therefore seen as saturated), so its f_i are rougher than those from SDF/MOL2. Whole
///   structures: protein_atom_lipophilicity(), 0 for hydrogens, water, ions and other
///   non-standard residues; a whole PDB/PQR file without any standard amino-acid residue (a
///   ligand written as PDB) is typed like a ligand selection.
/// - PDB: bonds RDKit's proximity rule makes to metal atoms are removed (PDB files do not
///   encode coordination), so metals are free ions. MOL2: an aromatic N with three neighbours
///   in a five-membered ring, which RDKit's reader charges +1, is made neutral (pyrrole NH)
///   when RDKit cannot kekulise the molecule otherwise. MOL2 bond records are checked before
///   RDKit sees them (RDKit 2022.09 crashes on an atom id outside the molecule).
/// Molecule::source is `path`, Molecule::title the file's title (molecule name, PDB HEADER
/// or the file stem).
/// - The file is read with read_input_file (a regular file of at most max_input_file_bytes);
///   every atom position must be finite and within max_coordinate_magnitude (input_file.hpp).
///   A PDB ATOM/HETATM record of model 1 needs numbers in its three coordinate columns.
/// Throws FileError (missing, unreadable or not a regular file, too large), FormatError
/// (unknown extension, RDKit parse or sanitisation failure, with RDKit's reason, a PDB record
/// without its coordinates, a coordinate beyond the limit), InputError (no atoms, unknown
/// element, non-finite coordinates, ligand absent — listing the HETATM residue names present
/// —, NaN Gasteiger charge, failed MMFF typing, a multi-molecule file without options.record,
/// a record beyond the file's count), OptionError (a computed charge model on PQR, a ligand
/// on SDF/MOL/MOL2).
Molecule read_molecule(const std::filesystem::path& path, const MoleculeReadOptions& options = {});

}  // namespace surfcomp::io
