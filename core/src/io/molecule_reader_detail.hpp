// Internal pieces shared by the molecule readers (read_molecule.cpp, rdkit_reader.cpp, pqr.cpp).
// Not installed; RDKit types stay inside rdkit_reader.cpp.
#pragma once

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/molecule.hpp"

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace surfcomp::io::detail {

/// The formats read through RDKit.
enum class RdkitFormat { mdl, mol2, pdb };

/// Throws InputError naming `source` when `record` (MoleculeReadOptions::record) asks for a
/// molecule after the first of a file that holds one.
void check_single_record(std::size_t record, const std::string& source);

/// Checks every atom position of a molecule just read with check_read_position (finite, within
/// max_coordinate_magnitude); FormatError naming molecule.source and the atom.
void check_read_atoms(const Molecule& molecule);

/// True when a whole-structure read drops this residue: water (if options.remove_water) or a
/// name in options.exclude_residues (blanks ignored, case-insensitive).
bool is_dropped_residue(std::string_view residue_name, const MoleculeReadOptions& options);

/// True when some atom belongs to a residue protein_atom_lipophilicity() knows.
bool has_standard_residue(const std::vector<Atom>& atoms);

/// Sets every atom's lipophilicity from protein_atom_lipophilicity(), 0 where it has no value
/// (hydrogens, ions, ligands, non-standard residues).
void assign_protein_lipophilicity(Molecule& molecule);

/// Assigns Bondi radii; throws InputError naming molecule.source and the atom for an element
/// with none.
void assign_bondi_radii(Molecule& molecule);

/// Reads `text` (the content of molecule file `path`) with RDKit; see read_molecule().
Molecule read_with_rdkit(const std::filesystem::path& path, const std::string& text,
                         RdkitFormat format, const MoleculeReadOptions& options);

/// Wildman-Crippen contributions, one per atom and in order, of the molecule in `pdb_block`
/// (HETATM records with element columns), bonded by RDKit's proximity rule; implicit
/// hydrogens' contributions are added to their heavy atom. Throws FormatError naming `source`
/// when RDKit cannot read or sanitise the block.
std::vector<double> crippen_contributions_of_pdb_block(const std::string& pdb_block,
                                                       const std::string& source);

}  // namespace surfcomp::io::detail
