// Writing molecules: a PDB writer for the Molecule model, and a moved copy of an SDF/MOL/MOL2
// file that keeps its bonds (for `surfcomp match --aligned-out`).
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

/// Molecule `record` of an SDF/MOL/MOL2 file (as MoleculeReadOptions::record: 1-based, 0 = the
/// file's only molecule), every atom moved by x -> rotation x + translation, as an MDL mol
/// block (SDF record with $$$$). Bonds and atom order are the file's. Throws FileError,
/// FormatError, InputError as read_molecule, and InputError for another format.
std::string moved_mol_block(const std::filesystem::path& input, const Eigen::Matrix3d& rotation,
                            const Eigen::Vector3d& translation, std::size_t record = 0);

}  // namespace surfcomp::io
