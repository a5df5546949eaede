#include "surfcomp/core/io/pqr.hpp"

#include "molecule_reader_detail.hpp"
#include "surfcomp/core/elements.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/option_names.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp::io {
namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::istringstream stream(line);
  std::vector<std::string> fields;
  std::string field;
  while (stream >> field) fields.push_back(field);
  return fields;
}

double parse_real(const std::string& token, const char* what, const std::string& file,
                  std::size_t line) {
  const char* begin = token.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (token.empty() || end != begin + token.size()) {
    throw FormatError(file, line, std::string(what) + " '" + token + "' is not a number");
  }
  if (!std::isfinite(value)) {
    throw FormatError(file, line, std::string(what) + " '" + token + "' is not finite");
  }
  return value;
}

// A residue number, optionally followed by a one-letter insertion code (ignored).
int parse_residue_number(const std::string& token, const std::string& file, std::size_t line) {
  std::string digits = token;
  if (!digits.empty() && std::isalpha(static_cast<unsigned char>(digits.back()))) {
    digits.pop_back();
  }
  const char* begin = digits.c_str();
  char* end = nullptr;
  const long value = std::strtol(begin, &end, 10);
  if (digits.empty() || end != begin + digits.size() || value < -999999 || value > 9999999) {
    throw FormatError(file, line, "residue number '" + token + "' is not an integer");
  }
  return static_cast<int>(value);
}

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

// PQR has no element column: the atom name's first letter after leading digits ("1HB" -> H),
// or both letters of a two-letter atom named like its residue and like an element ("ZN" in
// residue ZN -> Zn, "CA" in residue CA -> Ca, but CA in ALA -> C).
std::string element_from_name(const std::string& name, const std::string& residue) {
  if (name.size() == 2 && upper(name) == upper(residue) && bondi_radius(name)) {
    return normalize_element(name);
  }
  for (char c : name) {
    if (std::isalpha(static_cast<unsigned char>(c))) return normalize_element(std::string(1, c));
    if (!std::isdigit(static_cast<unsigned char>(c))) break;
  }
  return {};
}

// HETATM records for RDKit's PDB reader, one residue "LIG 1 A", elements in columns 77-78.
std::string ligand_pdb_block(const Molecule& molecule) {
  std::string block;
  char line[96];
  for (std::size_t i = 0; i < molecule.atoms.size(); ++i) {
    const Atom& atom = molecule.atoms[i];
    std::string name = atom.name.substr(0, 4);
    if (name.size() < 4 && atom.element.size() == 1) name = " " + name;
    std::snprintf(line, sizeof line,
                  "HETATM%5d %-4s LIG A   1    %8.3f%8.3f%8.3f  1.00  0.00          %2s\n",
                  static_cast<int>((i + 1) % 100000), name.c_str(), atom.position.x(),
                  atom.position.y(), atom.position.z(), upper(atom.element).c_str());
    block += line;
  }
  return block + "END\n";
}

}  // namespace

Molecule read_pqr(const std::filesystem::path& path, const MoleculeReadOptions& options) {
  const std::string source = path.string();
  if (options.charges != ChargeModel::file) {
    throw OptionError(source +
                      ": a PQR file carries its own charges; only the 'file' charge "
                      "model applies");
  }
  if (options.min_plddt > 0.0) {
    throw OptionError(source + ": " + options::named("min_plddt") +
                      " reads the B-factor column of a PDB or mmCIF structure; a "
                      "PQR file holds radii there");
  }
  const std::string text = read_input_file(path);
  detail::check_single_record(options.record, source);
  Molecule molecule;
  molecule.source = source;
  molecule.charge_source = ChargeSource::file;
  std::istringstream stream(text);
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(stream, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> fields = split_fields(line);
    if (fields.empty()) continue;
    const std::string record = fields[0];
    if (record == "ENDMDL" || record == "END") break;
    if ((record == "HEADER" || record == "TITLE" || record == "COMPND") && molecule.title.empty()) {
      const std::size_t start = line.find_first_not_of(' ', record.size());
      if (start != std::string::npos) molecule.title = line.substr(start);
      continue;
    }
    const bool hetero = record.rfind("HETATM", 0) == 0;
    if (!hetero && record != "ATOM") continue;
    if (hetero && record.size() > 6) {  // "HETATM12345": serial fused to the record name
      fields[0] = record.substr(6);
    } else {
      fields.erase(fields.begin());
    }
    if (fields.size() != 9 && fields.size() != 10) {
      throw FormatError(source, line_number,
                        "expected 9 or 10 fields after " + record.substr(0, 6) +
                            " (serial, name, residue, [chain,] residue number, x, y, z, "
                            "charge, radius), found " +
                            std::to_string(fields.size()));
    }
    const bool has_chain = fields.size() == 10;
    const std::size_t k = has_chain ? 4 : 3;  // index of the residue number
    Atom atom;
    atom.hetero = hetero;
    atom.name = fields[1];
    atom.residue_name = fields[2];
    if (has_chain) atom.chain = fields[3];
    atom.residue_number = parse_residue_number(fields[k], source, line_number);
    atom.position = Eigen::Vector3d(parse_real(fields[k + 1], "x coordinate", source, line_number),
                                    parse_real(fields[k + 2], "y coordinate", source, line_number),
                                    parse_real(fields[k + 3], "z coordinate", source, line_number));
    check_read_position(atom.position, source + ":" + std::to_string(line_number),
                        "atom '" + atom.name + "'");
    atom.charge = parse_real(fields[k + 4], "charge", source, line_number);
    check_read_charge(atom.charge, source, line_number, "atom '" + atom.name + "'");
    atom.radius = parse_real(fields[k + 5], "radius", source, line_number);
    atom.element = element_from_name(atom.name, atom.residue_name);
    if (atom.element.empty() || !bondi_radius(atom.element)) {
      throw InputError(source + ":" + std::to_string(line_number) + ": atom '" + atom.name +
                       "' has no recognisable element");
    }
    check_read_radius(atom.radius, source, line_number, "atom '" + atom.name + "'");
    molecule.atoms.push_back(atom);
  }
  if (molecule.atoms.empty()) throw InputError(source + ": no ATOM/HETATM records (no atoms)");
  if (molecule.title.empty()) molecule.title = path.stem().string();

  if (options.ligand.empty()) {
    std::vector<Atom> atoms;
    for (const Atom& atom : molecule.atoms) {
      if (!detail::is_dropped_residue(atom.residue_name, options)) atoms.push_back(atom);
    }
    molecule.atoms = std::move(atoms);
    if (molecule.atoms.empty())
      throw InputError(source + ": no atoms left besides water and excluded residues");
  }
  if (!options.ligand.empty()) {
    const auto selected = select_ligand(molecule, parse_ligand_selector(options.ligand));
    std::vector<Atom> atoms;
    atoms.reserve(selected.size());
    for (std::size_t i : selected) atoms.push_back(molecule.atoms[i]);
    molecule.atoms = std::move(atoms);
  }
  if (options.assign_lipophilicity) {
    if (!options.ligand.empty() || !detail::has_standard_residue(molecule.atoms)) {
      const auto contributions =
          detail::crippen_contributions_of_pdb_block(ligand_pdb_block(molecule), source);
      if (contributions.size() != molecule.atoms.size()) {
        throw FormatError(source, "RDKit read " + std::to_string(contributions.size()) +
                                      " ligand atoms instead of " +
                                      std::to_string(molecule.atoms.size()));
      }
      for (std::size_t i = 0; i < contributions.size(); ++i) {
        molecule.atoms[i].lipophilicity = contributions[i];
      }
      molecule.lipophilicity_assigned = true;
    } else {
      detail::assign_protein_lipophilicity(molecule);
    }
  }
  validate_molecule(molecule);
  return molecule;
}

}  // namespace surfcomp::io
