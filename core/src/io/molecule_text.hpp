// Text-level checks and edits of molecule files before RDKit parses them: what RDKit would
// read wrongly or crash on (cut PDB coordinates, MOL2 bond ids outside the molecule, alternate
// locations it would drop) and the choice of one record of a multi-molecule file.
#pragma once

#include "molecule_reader_detail.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace surfcomp::io::detail {

/// `text` without leading and trailing blanks (space, tab, CR, LF).
std::string trimmed(const std::string& text);

/// `text` (PDB) with one alternate location per atom, as RDKit would otherwise read only the
/// locations ' ', 'A' and '1' and lose an atom present only as 'B' (the ATP of 1RDQ). Records
/// without an alternate location stay. Of an atom's alternate locations the first in the file
/// stays, relabelled ' '; an atom is its chain, residue number, insertion code and name. Where
/// the alternate locations of one residue position carry different residue names
/// (microheterogeneity), only the first name's records stay. Each MODEL is treated alone.
std::string first_alternate_locations(const std::string& text);

/// `text` (PDB) without the ATOM/HETATM records of the residues whose records' mean B-factor
/// (columns 61-66) is below `min_plddt` (MoleculeReadOptions::min_plddt); a residue is its
/// name, chain, number and insertion code (columns 18-27). Other records stay. Throws
/// FormatError for a record whose B-factor column is not a number, InputError naming `source`
/// when no ATOM/HETATM record other than water is left.
std::string drop_low_plddt_residues(const std::string& text, double min_plddt,
                                    const std::string& source);

/// The text of molecule `record` (1-based) of an SDF or MOL2 text; see
/// MoleculeReadOptions::record. A file with one molecule (or none, for the parser to refuse)
/// is returned whole.
std::string select_record(const std::string& text, RdkitFormat format, std::size_t record,
                          const std::string& source);

/// The text of every molecule of an SDF or MOL2 text, in order (the records select_record
/// picks from).
std::vector<std::string> split_records(const std::string& text, RdkitFormat format);

/// Checks that every ATOM/HETATM record of the first model of a PDB text has three numbers in
/// its coordinate columns (31-38, 39-46, 47-54): RDKit reads a line cut inside them, or blank
/// columns, as zeros.
void check_pdb_coordinates(const std::string& text, const std::string& source);

/// The charge type line of the first @<TRIPOS>MOLECULE section ("" when absent).
std::string mol2_charge_type(const std::string& text);

/// RDKit's Mol2 reader indexes atoms by the bond records' atom ids without checking them and
/// crashes on an id outside the molecule (found by the robustness test and by fuzz_mol2).
/// Checks the first molecule's counts line, that it has one ATOM and at most one BOND section,
/// that its ATOM section holds that many records, that no atom's charge field holds a number
/// beyond max_charge_magnitude (check_read_charge), and that each of its bond records names two
/// atom ids in [1, atom count].
void check_mol2_structure(const std::string& text, const std::string& source);

}  // namespace surfcomp::io::detail
