#include "surfcomp/core/protein_charges.hpp"

#include "surfcomp/core/elements.hpp"
#include "surfcomp/core/protein_lipophilicity.hpp"

#include <set>
#include <string>
#include <tuple>

namespace surfcomp {

std::optional<double> protein_atom_formal_charge(std::string_view residue,
                                                 std::string_view atom_name) {
  const std::string res = residue_key(residue);
  const std::string name = residue_key(atom_name);
  // A standard residue is one the lipophilicity table knows (its CA is always listed).
  if (!protein_atom_lipophilicity(res, "CA")) return std::nullopt;
  if (name == "OXT") return -0.5;
  if (res == "ASP" && (name == "OD1" || name == "OD2")) return -0.5;
  if (res == "GLU" && (name == "OE1" || name == "OE2")) return -0.5;
  if (res == "LYS" && name == "NZ") return 1.0;
  if (res == "ARG" && (name == "NE" || name == "NH1" || name == "NH2")) return 1.0 / 3.0;
  if (res == "HIP" && (name == "ND1" || name == "NE2")) return 0.5;
  return 0.0;
}

std::optional<int> usual_ionic_charge(std::string_view element) {
  const std::string e = normalize_element(element);
  if (e == "Li" || e == "Na" || e == "K") return 1;
  if (e == "Mg" || e == "Ca" || e == "Zn" || e == "Mn" || e == "Fe" || e == "Co" || e == "Ni" ||
      e == "Cu" || e == "Cd") {
    return 2;
  }
  if (e == "F" || e == "Cl" || e == "Br" || e == "I") return -1;
  return std::nullopt;
}

void assign_protein_formal_charges(Molecule& molecule) {
  using ResidueKey = std::tuple<std::string, int, std::string>;  // chain, number, name
  std::set<std::string> chains_started;
  std::set<ResidueKey> with_oxt;
  for (const Atom& atom : molecule.atoms) {
    if (residue_key(atom.name) == "OXT") {
      with_oxt.emplace(atom.chain, atom.residue_number, atom.residue_name);
    }
  }
  std::set<ResidueKey> n_terminal;
  for (const Atom& atom : molecule.atoms) {
    if (!protein_atom_formal_charge(atom.residue_name, atom.name)) continue;
    if (chains_started.insert(atom.chain).second) {
      n_terminal.emplace(atom.chain, atom.residue_number, atom.residue_name);
    }
  }
  for (Atom& atom : molecule.atoms) {
    const ResidueKey key(atom.chain, atom.residue_number, atom.residue_name);
    const std::string name = residue_key(atom.name);
    if (const auto q = protein_atom_formal_charge(atom.residue_name, atom.name)) {
      atom.charge = *q;
      if (name == "N" && n_terminal.count(key)) atom.charge += 1.0;
      if (name == "O" && with_oxt.count(key)) atom.charge = -0.5;
    } else if (const auto ion = usual_ionic_charge(atom.element); ion && atom.hetero) {
      atom.charge = *ion;
    } else {
      atom.charge = 0.0;
    }
  }
  molecule.charge_source = ChargeSource::residue_table;
}

}  // namespace surfcomp
