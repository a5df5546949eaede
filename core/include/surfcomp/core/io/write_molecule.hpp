// Writing molecules: a PDB writer for the Molecule model, an MDL block of atoms alone, and a
// moved copy of an SDF/MOL/MOL2 file that keeps its bonds (for `surfcomp match --aligned-out`).
#pragma once

#include "surfcomp/core/molecule.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>

namespace surfcomp::io {

/// PDB HETATM (or ATOM, for non-hetero atoms) records of every atom, charge in the occupancy
/// column's place is not written: occupancy 1.00, B-factor 0.00; then END.
void write_pdb(const Molecule& molecule, std::ostream& out);

/// An MDL V2000 mol block ending at "M  END" (no "$$$$" line) of the molecule's atoms, elements
/// and positions only: no bonds, no charges (a molecule known only by its atoms, such as the
/// heavy atoms a .hsi file keeps). `title` is the block's first line. Throws InputError when a
/// coordinate does not fit the format's columns (-9999.9999 to 99999.9999 A) or there are more
/// than 999 atoms.
std::string atoms_mol_block(const Molecule& molecule, const std::string& title);

/// Molecule `record` of an SDF/MOL/MOL2 file (as MoleculeReadOptions::record: 1-based, 0 = the
/// file's only molecule), every atom moved by x -> rotation x + translation, as an MDL mol
/// block (SDF record with $$$$). Bonds and atom order are the file's. Throws FileError,
/// FormatError, InputError as read_molecule, and InputError for another format.
std::string moved_mol_block(const std::filesystem::path& input, const Eigen::Matrix3d& rotation,
                            const Eigen::Vector3d& translation, std::size_t record = 0);

}  // namespace surfcomp::io
