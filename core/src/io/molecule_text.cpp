#include "molecule_text.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_names.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

namespace surfcomp::io::detail {
namespace {

/// Where the line of `text` starting at `begin` ends: after its newline, or at the text's end.
std::size_t line_end(const std::string& text, std::size_t begin) {
  const std::size_t newline = text.find('\n', begin);
  return newline == std::string::npos ? text.size() : newline + 1;
}

bool is_atom_record(const std::string& line) {
  return line.compare(0, 6, "ATOM  ") == 0 || line.compare(0, 6, "HETATM") == 0;
}

/// The [begin, end) byte ranges of the molecules in an SDF text (each ends after its "$$$$"
/// line; a non-blank rest without one is a molecule too) or MOL2 text (each starts at its
/// @<TRIPOS>MOLECULE line; the first from the start of the text, with the comments before it).
std::vector<std::pair<std::size_t, std::size_t>> record_spans(const std::string& text,
                                                              RdkitFormat format) {
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  std::size_t record_begin = 0;
  std::size_t begin = 0;
  const auto has_content = [&](std::size_t from, std::size_t to) {
    return !trimmed(text.substr(from, to - from)).empty();
  };
  while (begin < text.size()) {
    const std::size_t end = line_end(text, begin);
    const std::string line = text.substr(begin, end - begin);
    if (format == RdkitFormat::mdl && line.compare(0, 4, "$$$$") == 0) {
      if (has_content(record_begin, begin)) spans.emplace_back(record_begin, end);
      record_begin = end;
    } else if (format == RdkitFormat::mol2 && trimmed(line) == "@<TRIPOS>MOLECULE") {
      if (!spans.empty()) spans.back().second = begin;
      spans.emplace_back(spans.empty() ? 0 : begin, text.size());
    }
    begin = end;
  }
  if (format == RdkitFormat::mdl && has_content(record_begin, text.size())) {
    spans.emplace_back(record_begin, text.size());
  }
  return spans;
}

std::optional<long> parse_integer(const std::string& token) {
  if (token.empty()) return std::nullopt;
  const char* begin = token.c_str();
  char* end = nullptr;
  const long value = std::strtol(begin, &end, 10);
  if (end != begin + token.size()) return std::nullopt;
  return value;
}

std::vector<std::string> fields_of(const std::string& line) {
  std::istringstream stream(line);
  std::vector<std::string> fields;
  for (std::string field; stream >> field;) fields.push_back(field);
  return fields;
}

}  // namespace

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

/// `text` (PDB) with one alternate location per atom, as RDKit would otherwise read only the
/// locations ' ', 'A' and '1' and lose an atom present only as 'B' (the ATP of 1RDQ). Records
/// without an alternate location stay. Of an atom's alternate locations the first in the file
/// stays, relabelled ' '; an atom is its chain, residue number, insertion code and name. Where
/// the alternate locations of one residue position carry different residue names
/// (microheterogeneity), only the first name's records stay. Each MODEL is treated alone.
std::string first_alternate_locations(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  std::map<std::string, std::string> residue_name_at;  // residue position -> first name
  std::map<std::string, char> location_of;             // atom -> its first alternate location
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t end = line_end(text, begin);
    std::string line = text.substr(begin, end - begin);
    begin = end;
    if (line.compare(0, 6, "MODEL ") == 0) {
      residue_name_at.clear();
      location_of.clear();
    }
    const bool atom_record = is_atom_record(line);
    // Columns 13-16 atom name, 17 alternate location, 18-20 residue name, 22-27 chain, residue
    // number and insertion code.
    if (!atom_record || line.size() < 27 || line[16] == ' ') {
      out += line;
      continue;
    }
    const std::string position = line.substr(21, 6);
    const std::string residue_name = line.substr(17, 3);
    if (residue_name_at.emplace(position, residue_name).first->second != residue_name) continue;
    const char location = line[16];
    if (location_of.emplace(position + line.substr(12, 4), location).first->second != location) {
      continue;
    }
    line[16] = ' ';
    out += line;
  }
  return out;
}

std::string drop_low_plddt_residues(const std::string& text, double min_plddt,
                                    const std::string& source) {
  struct Mean {
    double sum = 0.0;
    std::size_t count = 0;
  };
  std::map<std::string, Mean> residues;
  std::size_t begin = 0;
  std::size_t line_number = 0;
  while (begin < text.size()) {
    const std::size_t end = line_end(text, begin);
    const std::string line = text.substr(begin, end - begin);
    begin = end;
    ++line_number;
    if (!is_atom_record(line)) continue;
    const std::string field = line.size() > 60 ? trimmed(line.substr(60, 6)) : "";
    char* parsed = nullptr;
    const double b_factor = field.empty() ? 0.0 : std::strtod(field.c_str(), &parsed);
    if (field.empty() || parsed != field.c_str() + field.size() || !std::isfinite(b_factor)) {
      throw FormatError(source, line_number,
                        "the B-factor (pLDDT, columns 61-66) is " +
                            (field.empty() ? std::string("missing") : "'" + field + "'") +
                            ", not a number, in this " + line.substr(0, 6) + " record");
    }
    Mean& mean = residues[line.substr(17, 10)];
    mean.sum += b_factor;
    ++mean.count;
  }
  std::string out;
  out.reserve(text.size());
  bool kept_any = false;
  begin = 0;
  while (begin < text.size()) {
    const std::size_t end = line_end(text, begin);
    const std::string line = text.substr(begin, end - begin);
    begin = end;
    if (is_atom_record(line)) {
      const Mean& mean = residues.at(line.substr(17, 10));
      if (mean.sum < min_plddt * static_cast<double>(mean.count)) continue;
      if (!is_water_residue(line.substr(17, 3))) kept_any = true;
    }
    out += line;
  }
  if (!kept_any) {
    throw InputError(source + ": no residue has a pLDDT (B-factor) of at least " +
                     [&] {
                       std::ostringstream number;
                       number << min_plddt;
                       return number.str();
                     }() +
                     " (" + options::named("min_plddt") + ")");
  }
  return out;
}

/// The text of molecule `record` (1-based) of an SDF or MOL2 text; see
/// MoleculeReadOptions::record. A file with one molecule (or none, for the parser to refuse)
/// is returned whole.
std::string select_record(const std::string& text, RdkitFormat format, std::size_t record,
                          const std::string& source) {
  const auto spans = record_spans(text, format);
  const std::size_t count = spans.size();
  if (count <= 1) {
    check_single_record(record, source);
    return text;
  }
  if (record == 0) {
    throw InputError(source + ": the file holds " + std::to_string(count) +
                     " molecules; choose one with " + options::named("record") + " N (1 to " +
                     std::to_string(count) + ")");
  }
  if (record > count) {
    throw InputError(source + ": record " + std::to_string(record) + " asked for, the file holds " +
                     std::to_string(count) + " molecules");
  }
  const auto& [begin, end] = spans[record - 1];
  return text.substr(begin, end - begin);
}

std::vector<std::string> split_records(const std::string& text, RdkitFormat format) {
  std::vector<std::string> records;
  for (const auto& [begin, end] : record_spans(text, format)) {
    records.push_back(text.substr(begin, end - begin));
  }
  return records;
}

/// Checks that every ATOM/HETATM record of the first model of a PDB text has three numbers in
/// its coordinate columns (31-38, 39-46, 47-54): RDKit reads a line cut inside them, or blank
/// columns, as zeros.
void check_pdb_coordinates(const std::string& text, const std::string& source) {
  std::size_t begin = 0;
  std::size_t line_number = 0;
  while (begin < text.size()) {
    const std::size_t end = line_end(text, begin);
    std::string line = text.substr(begin, end - begin);
    begin = end;
    ++line_number;
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    if (line.compare(0, 6, "ENDMDL") == 0) return;
    if (!is_atom_record(line)) continue;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const std::size_t column = 30 + 8 * axis;
      const std::string field = line.size() > column ? trimmed(line.substr(column, 8)) : "";
      char* parsed = nullptr;
      if (!field.empty()) std::strtod(field.c_str(), &parsed);
      if (field.empty() || parsed != field.c_str() + field.size()) {
        throw FormatError(
            source, line_number,
            std::string(1, static_cast<char>('x' + axis)) + " coordinate (columns " +
                std::to_string(column + 1) + "-" + std::to_string(column + 8) + ") is " +
                (field.empty() ? std::string("missing") : "'" + field + "', not a number") +
                " in this " + line.substr(0, 6) + " record");
      }
    }
  }
}

// The charge type line of the first @<TRIPOS>MOLECULE section ("" when absent).
std::string mol2_charge_type(const std::string& text) {
  std::istringstream stream(text);
  std::string line;
  while (std::getline(stream, line)) {
    if (trimmed(line) != "@<TRIPOS>MOLECULE") continue;
    for (int i = 0; i < 4 && std::getline(stream, line); ++i) {
      if (i == 3) return trimmed(line);
    }
  }
  return {};
}

// RDKit's Mol2 reader indexes atoms by the bond records' atom ids without checking them and
// crashes on an id outside the molecule (found by the robustness test). Checks the first
// molecule's counts line, that it has one ATOM and at most one BOND section, that its ATOM
// section holds that many records and that each of its bond records names two atom ids in
// [1, atom count].
void check_mol2_structure(const std::string& text, const std::string& source) {
  const std::vector<std::string> lines = [&]() {
    std::vector<std::string> out;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);) out.push_back(line);
    return out;
  }();
  // A header as RDKit sees one: its first field is the section's name ("@<TRIPOS>BOND x" too).
  auto section = [&](const std::string& name, std::size_t from) {
    for (std::size_t i = from; i < lines.size(); ++i) {
      const std::vector<std::string> fields = fields_of(lines[i]);
      if (!fields.empty() && fields[0] == name) return i;
    }
    return lines.size();
  };
  const std::size_t molecule = section("@<TRIPOS>MOLECULE", 0);
  if (molecule + 2 >= lines.size()) {
    throw FormatError(source, "no @<TRIPOS>MOLECULE section with a counts line");
  }
  const std::vector<std::string> counts = fields_of(lines[molecule + 2]);
  const std::optional<long> atom_count = counts.empty() ? std::nullopt : parse_integer(counts[0]);
  const std::optional<long> bond_count =
      counts.size() < 2 ? std::optional<long>(0) : parse_integer(counts[1]);
  if (!atom_count || !bond_count || *atom_count <= 0 || *bond_count < 0) {
    throw FormatError(source, molecule + 3, "expected the atom and bond counts");
  }
  auto records_after = [&](std::size_t header, long count, std::size_t min_fields,
                           const char* what) {
    std::vector<std::size_t> records;
    for (std::size_t i = header + 1; i < lines.size() && static_cast<long>(records.size()) < count;
         ++i) {
      const std::string line = trimmed(lines[i]);
      if (line.empty()) continue;
      if (line[0] == '@' || fields_of(line).size() < min_fields) {
        throw FormatError(source, i + 1,
                          "expected " + std::to_string(count) + " " + what + " records");
      }
      records.push_back(i);
    }
    if (static_cast<long>(records.size()) < count) {
      throw FormatError(source, "expected " + std::to_string(count) + " " + what +
                                    " records, found " + std::to_string(records.size()));
    }
    return records;
  };
  // RDKit reads the records of the last ATOM and BOND sections of a molecule; the checks below
  // read the first (a second BOND section naming atom 0 crashed it: fuzz_mol2). One of each.
  const std::size_t next_molecule = section("@<TRIPOS>MOLECULE", molecule + 1);
  for (const char* name : {"@<TRIPOS>ATOM", "@<TRIPOS>BOND"}) {
    const std::size_t first = section(name, molecule);
    const std::size_t second = first < next_molecule ? section(name, first + 1) : lines.size();
    if (second < next_molecule) {
      throw FormatError(source, second + 1,
                        std::string("a second ") + name + " section in one molecule");
    }
  }
  const std::size_t atoms = section("@<TRIPOS>ATOM", molecule);
  for (std::size_t i : records_after(atoms, *atom_count, 6, "ATOM")) {
    // atom_id atom_name x y z atom_type [subst_id [subst_name [charge ...]]]
    const std::vector<std::string> fields = fields_of(lines[i]);
    if (fields.size() < 9) continue;
    char* end = nullptr;
    const double charge = std::strtod(fields[8].c_str(), &end);
    if (end == fields[8].c_str() || *end != '\0') continue;  // RDKit's reader judges the field
    check_read_charge(charge, source, i + 1, "atom " + fields[0] + " (" + fields[1] + ")");
  }
  if (*bond_count == 0) return;
  const std::size_t bonds = section("@<TRIPOS>BOND", atoms);
  for (std::size_t i : records_after(bonds, *bond_count, 4, "BOND")) {
    const std::vector<std::string> fields = fields_of(lines[i]);
    for (std::size_t k : {std::size_t{1}, std::size_t{2}}) {
      const std::optional<long> id = parse_integer(fields[k]);
      if (!id || *id < 1 || *id > *atom_count) {
        throw FormatError(
            source, i + 1,
            "bond atom id '" + fields[k] + "' is not in [1, " + std::to_string(*atom_count) + "]");
      }
    }
  }
}

}  // namespace surfcomp::io::detail
