#include "surfcomp/core/molecule.hpp"

#include "surfcomp/core/error.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp {
std::string residue_key(std::string_view name) {
  std::string key;
  for (char c : name) {
    if (c != ' ') key.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  }
  return key;
}

bool is_water_residue(std::string_view residue_name) {
  const std::string name = residue_key(residue_name);
  return name == "HOH" || name == "WAT" || name == "DOD";
}

namespace {

std::string without_blanks(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c != ' ') out.push_back(c);
  }
  return out;
}

/// "A, B, C" of the first `most` entries, ", ..." when there are more.
std::string listed(const std::vector<std::string>& items, std::size_t most) {
  std::string list;
  for (std::size_t i = 0; i < items.size() && i < most; ++i) list += (i > 0 ? ", " : "") + items[i];
  if (items.size() > most) list += ", ...";
  return list;
}

}  // namespace

LigandSelector parse_ligand_selector(std::string_view text) {
  std::vector<std::string> fields(1);
  for (const char c : text) {
    if (c == ':') {
      fields.emplace_back();
    } else {
      fields.back().push_back(c);
    }
  }
  const auto refuse = [&](const std::string& why) {
    throw OptionError("'" + std::string(text) +
                      "' is not a ligand RESIDUE[:CHAIN[:NUMBER]]: " + why);
  };
  if (fields.size() > 3) refuse("more than three fields");
  LigandSelector selector;
  selector.residue_name = without_blanks(fields[0]);
  if (selector.residue_name.empty()) refuse("no residue name");
  if (fields.size() > 1 && !without_blanks(fields[1]).empty()) selector.chain = fields[1];
  if (fields.size() > 2 && !without_blanks(fields[2]).empty()) {
    const std::string number = without_blanks(fields[2]);
    std::size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(number, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != number.size()) refuse("the residue number '" + number + "' is not an integer");
    selector.residue_number = value;
  }
  return selector;
}

std::vector<std::size_t> select_ligand(const Molecule& molecule, const LigandSelector& selector) {
  using Copy = std::pair<std::string, int>;  // chain, residue number
  const std::string wanted = residue_key(selector.residue_name);
  const auto named = [&](const Atom& atom) {
    return atom.hetero && residue_key(atom.residue_name) == wanted;
  };
  const auto asked = [&](const Atom& atom) {
    return (!selector.chain || without_blanks(atom.chain) == without_blanks(*selector.chain)) &&
           (!selector.residue_number || atom.residue_number == *selector.residue_number);
  };
  std::set<Copy> copies;  // of the name, anywhere
  std::optional<Copy> first;
  for (const Atom& atom : molecule.atoms) {
    if (!named(atom)) continue;
    const Copy copy{atom.chain, atom.residue_number};
    copies.insert(copy);
    if (asked(atom) && (!first || copy < *first)) first = copy;
  }
  if (copies.empty()) {
    std::vector<std::string> present;
    for (const Atom& atom : molecule.atoms) {
      if (atom.hetero &&
          std::find(present.begin(), present.end(), atom.residue_name) == present.end()) {
        present.push_back(atom.residue_name);
      }
    }
    throw InputError(molecule.source + ": no HETATM residue named '" + selector.residue_name +
                     "'; HETATM residues present: " +
                     (present.empty() ? std::string("none") : listed(present, 10)));
  }
  if (!first) {
    std::string asked_for;
    if (selector.chain) asked_for += " in chain '" + *selector.chain + "'";
    if (selector.residue_number)
      asked_for += " numbered " + std::to_string(*selector.residue_number);
    std::vector<std::string> present;
    present.reserve(copies.size());
    for (const auto& [chain, number] : copies)
      present.push_back("chain '" + chain + "' number " + std::to_string(number));
    throw InputError(molecule.source + ": no copy of HETATM residue '" + selector.residue_name +
                     "'" + asked_for + "; its copies: " + listed(present, 10));
  }
  std::vector<std::size_t> selected;
  for (std::size_t i = 0; i < molecule.atoms.size(); ++i) {
    const Atom& atom = molecule.atoms[i];
    if (named(atom) && atom.chain == first->first && atom.residue_number == first->second)
      selected.push_back(i);
  }
  return selected;
}

std::string describe_atom(const Molecule& molecule, std::size_t index) {
  const Atom& atom = molecule.atoms[index];
  std::string text = "atom " + std::to_string(index + 1) + " (" + atom.element;
  if (!atom.name.empty()) text += " " + atom.name;
  if (!atom.residue_name.empty()) {
    text += " " + atom.residue_name + " " + std::to_string(atom.residue_number) + atom.chain;
  }
  return text + ")";
}

bool carries_ionic_group(const Molecule& molecule) {
  if (!molecule.ionisable_atoms.empty()) return true;
  const std::vector<Atom>& atoms = molecule.atoms;
  bool formal = false;
  for (const Atom& atom : atoms) {
    if (atom.formal_charge == 0) continue;
    formal = true;
    const bool balanced = std::any_of(atoms.begin(), atoms.end(), [&](const Atom& other) {
      return other.formal_charge * atom.formal_charge < 0 &&
             (other.position - atom.position).norm() < charge_pair_bond_length;
    });
    if (!balanced) return true;
  }
  if (formal) return false;
  double net = 0.0;
  for (const Atom& atom : atoms) net += atom.charge;
  return std::abs(net) >= 0.5;
}

void validate_molecule(const Molecule& molecule) {
  const std::string& file = molecule.source.empty() ? std::string("<molecule>") : molecule.source;
  if (molecule.atoms.empty()) throw InputError(file + ": the molecule has no atoms");
  for (std::size_t i = 0; i < molecule.atoms.size(); ++i) {
    const Atom& atom = molecule.atoms[i];
    if (!atom.position.allFinite()) {
      throw InputError(file + ": " + describe_atom(molecule, i) + " has a non-finite coordinate");
    }
    if (!std::isfinite(atom.charge)) {
      throw InputError(file + ": " + describe_atom(molecule, i) + " has a non-finite charge");
    }
    if (!std::isfinite(atom.lipophilicity)) {
      throw InputError(file + ": " + describe_atom(molecule, i) +
                       " has a non-finite lipophilicity increment");
    }
    if (!(std::isfinite(atom.radius) && atom.radius > 0.0)) {
      throw InputError(file + ": " + describe_atom(molecule, i) + " has no valid radius (" +
                       std::to_string(atom.radius) + ")");
    }
  }
}

void transform_molecule(Molecule& molecule, const Eigen::Matrix3d& rotation,
                        const Eigen::Vector3d& translation) {
  for (Atom& atom : molecule.atoms) atom.position = rotation * atom.position + translation;
}

}  // namespace surfcomp
