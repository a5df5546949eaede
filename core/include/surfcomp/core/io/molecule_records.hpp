// The molecules of a multi-molecule input, one record at a time: SDF and MOL2 files, SMILES
// lists (.smi, and the tab-separated .dat/.dat.gz lists of DUD) and single structures (PDB,
// PQR). A library build (surfcomp::screening) reads its inputs through this.
#pragma once

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/molecule.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace surfcomp::io {

/// What the text of a MoleculeRecord holds.
enum class RecordFormat {
  mdl,        ///< an MDL mol block (an SDF record, "$$$$" line and SD tags included)
  mol2,       ///< one @<TRIPOS>MOLECULE section
  structure,  ///< a whole PDB file (its text), or a PQR file (text empty: read from source)
  smiles,     ///< a SMILES string (no coordinates)
  /// a .hsi file (text empty: read from source): a surface description and its heavy atoms,
  /// no molecule to read
  descriptors,
  /// a mesh file (text empty: read from source): a general surface, no molecule to read
  mesh,
};

/// One molecule of an input file.
struct MoleculeRecord {
  std::filesystem::path source;  ///< the file it comes from
  std::size_t record = 1;        ///< 1-based position in the file
  /// The record's name: an SDF/MOL2 title line, a SMILES line's name (.smi: the second field;
  /// .dat: the ID column, else the Mol_Title column), a PDB/PQR file's stem; "STEM:N" when the
  /// record has none.
  std::string name;
  RecordFormat format = RecordFormat::mdl;
  std::string text;  ///< the record (see RecordFormat)
};

/// True for the SMILES lists read_molecule_records reads: .smi, .dat, .dat.gz
/// (case-insensitive).
bool is_smiles_file(const std::filesystem::path& path);

/// True for the files read_molecule_records reads: is_molecule_file() or is_smiles_file().
bool is_record_file(const std::filesystem::path& path);

/// Every molecule of `path`, in file order, without parsing them:
/// - .sdf/.mol: the records ending at "$$$$" lines; .mol2: the @<TRIPOS>MOLECULE sections;
/// - .pdb/.ent/.pqr: one RecordFormat::structure record;
/// - .smi: one record per line that is not blank or a '#' comment: SMILES, then a name;
/// - .dat/.dat.gz (gzip): tab-separated, the first line a header "# Mol_Title ID SMILES" naming
///   the columns (the SMILES column is required), then one molecule per line.
/// The file is read with read_input_file (a .dat.gz is decompressed to at most
/// max_input_file_bytes). Throws FileError (as read_input_file; a damaged gzip stream),
/// FormatError (unknown extension, a .dat header without a SMILES column, a line with fewer
/// fields than the header, naming the line).
std::vector<MoleculeRecord> read_molecule_records(const std::filesystem::path& path);

/// The molecule of `record` with radii, charges and lipophilicity assigned as read_molecule
/// assigns them to the same molecule read from its own file (options.record is ignored).
/// Throws as read_molecule, and InputError for a SMILES record (it has no coordinates).
Molecule read_record_molecule(const MoleculeRecord& record,
                              const MoleculeReadOptions& options = {});

/// `record`'s molecule (an MDL, MOL2 or PDB text) with every atom moved by
/// x -> rotation x + translation, as an MDL mol block ending at "M  END" (no "$$$$" line), its
/// bonds and atom order the record's (a PDB record's bonds come from RDKit's proximity rule).
/// Throws FormatError naming record.source when RDKit cannot read the record, InputError for a
/// SMILES record or a PQR structure.
std::string moved_record_block(const MoleculeRecord& record, const Eigen::Matrix3d& rotation,
                               const Eigen::Vector3d& translation);

/// The atom coordinates (A) of a V2000 MDL mol block, in atom order, parsed as RDKit's reader
/// parses them; nullopt for a V3000 block or one whose counts or atom lines do not parse.
std::optional<std::vector<Eigen::Vector3d>> mdl_coordinates(const std::string& block);

}  // namespace surfcomp::io
