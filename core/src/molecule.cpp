#include "surfcomp/core/molecule.hpp"

#include "surfcomp/core/error.hpp"

#include <cctype>
#include <cmath>
#include <string>

namespace surfcomp {
std::string residue_key(std::string_view name) {
  std::string key;
  for (char c : name) {
    if (c != ' ') key.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  }
  return key;
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
