// PQR files (PDB-like records carrying a charge and a radius per atom, as written by pdb2pqr).
#pragma once

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/molecule.hpp"

#include <filesystem>

namespace surfcomp::io {

/// Reads the ATOM/HETATM records of the first model of a PQR file. Each record is split at
/// whitespace after the record name: serial, atom name, residue name, [chain,] residue number,
/// x, y, z (A), charge (e), radius (A); charges and radii are taken as given
/// (Molecule::charge_source = file). The element is the atom name's first letter after leading
/// digits, or its first two letters for a single-atom residue named like an element (ZN, CA,
/// CL, NA, MG ...). `options.ligand` selects a HETATM residue as in read_molecule (its f_i
/// then come from RDKit's Wildman-Crippen typing of the proximity-bonded residue);
/// otherwise whole-structure f_i come from protein_atom_lipophilicity().
/// Throws FileError, FormatError (record with a wrong field count or an unparsable number,
/// naming file and line), InputError (no atoms, non-finite value, ligand absent),
/// OptionError (options.charges other than ChargeModel::file).
Molecule read_pqr(const std::filesystem::path& path, const MoleculeReadOptions& options = {});

}  // namespace surfcomp::io
