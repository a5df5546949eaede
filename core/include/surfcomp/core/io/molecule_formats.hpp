// The molecule file formats surfcomp reads, in one table: each extension, what it holds and who
// reads it. is_molecule_file, is_structure_file, is_mmcif_file, is_smiles_file, is_record_file
// and every list of extensions in a message or help text are derived from it, as the mesh
// formats are from mesh::io::mesh_formats().
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace surfcomp::io {

/// What a molecule file holds, which says how it is read.
enum class MoleculeFileKind {
  mdl,     ///< SDF or MOL: MDL blocks, one molecule each (RDKit)
  mol2,    ///< Tripos MOL2 (RDKit)
  pdb,     ///< a PDB structure
  mmcif,   ///< a PDBx/mmCIF structure (gemmi), read as PDB text
  pqr,     ///< PDB with charges and radii (APBS, pdb2pqr)
  smiles,  ///< a SMILES list, one per line (records only)
  table,   ///< a tab-separated SMILES table with a header line (records only)
};

/// One molecule file format, known by the ending of a file's name.
struct MoleculeFormat {
  std::string_view extension;  ///< lowercase, with the dot; may be double (".cif.gz")
  std::string_view name;       ///< what the format is, for help texts
  MoleculeFileKind kind;
};

/// Every molecule format, in the order messages list them:
/// .sdf .mol .mol2 .pdb .ent .cif .mmcif .cif.gz .pqr .smi .dat .dat.gz.
const std::vector<MoleculeFormat>& molecule_formats();

/// The format of `path` by the ending of its name (letter case ignored; the longest ending
/// that is a format's, so "x.cif.gz" is .cif.gz), or null. Looks at the name, not the file.
const MoleculeFormat* find_molecule_format(const std::filesystem::path& path);

/// What a caller wants of a molecule file.
enum class MoleculeUse {
  molecule,   ///< one molecule (read_molecule): all but the SMILES lists and tables
  records,    ///< its records (read_molecule_records): every format
  structure,  ///< a protein structure: PDB and mmCIF
};

/// True when `format` serves `use`.
bool serves(const MoleculeFormat& format, MoleculeUse use);

/// The extensions of the formats that serve `use`, in molecule_formats() order, separated by
/// spaces (".pdb .ent .cif .mmcif .cif.gz" for MoleculeUse::structure), for help texts and
/// "expected ..." messages.
std::string molecule_extensions(MoleculeUse use);

}  // namespace surfcomp::io
