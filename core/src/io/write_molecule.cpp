#include "surfcomp/core/io/write_molecule.hpp"

#include "surfcomp/core/error.hpp"

#include <cstdio>

namespace surfcomp::io {

void write_pdb(const Molecule& molecule, std::ostream& out) {
  for (std::size_t i = 0; i < molecule.atoms.size(); ++i) {
    const Atom& a = molecule.atoms[i];
    std::string name = a.name.empty() ? a.element : a.name;
    if (name.size() < 4 && a.element.size() == 1) name = " " + name;  // PDB column alignment
    char line[96];
    std::snprintf(line, sizeof line,
                  "%-6s%5zu %-4.4s %3.3s %1.1s%4d    %8.3f%8.3f%8.3f  1.00  0.00          %2.2s\n",
                  a.hetero || a.residue_name.empty() ? "HETATM" : "ATOM", (i + 1) % 100000,
                  name.c_str(), a.residue_name.empty() ? "MOL" : a.residue_name.c_str(),
                  a.chain.empty() ? "A" : a.chain.c_str(), a.residue_number, a.position.x(),
                  a.position.y(), a.position.z(), a.element.c_str());
    out << line;
  }
  out << "END\n";
}

std::string atoms_mol_block(const Molecule& molecule, const std::string& title) {
  const std::size_t n = molecule.atoms.size();
  if (n > 999) {
    throw InputError(title + ": " + std::to_string(n) +
                     " atoms do not fit an MDL V2000 block (at most 999)");
  }
  std::string block = title.substr(0, title.find_first_of("\r\n")) + "\n  surfcomp\n\n";
  char line[96];
  std::snprintf(line, sizeof line, "%3zu  0  0  0  0  0  0  0  0  0999 V2000\n", n);
  block += line;
  for (const Atom& atom : molecule.atoms) {
    // %10.4f holds -9999.9999 to 99999.9999; the bounds keep the rounding inside them.
    if (!(atom.position.minCoeff() > -9999.99995 && atom.position.maxCoeff() < 99999.99995)) {
      throw InputError(title + ": atom position outside the MDL format's columns (-9999.9999 to " +
                       "99999.9999 A)");
    }
    std::snprintf(line, sizeof line,
                  "%10.4f%10.4f%10.4f %-3.3s 0  0  0  0  0  0  0  0  0  0  0  0\n",
                  atom.position.x(), atom.position.y(), atom.position.z(), atom.element.c_str());
    block += line;
  }
  return block + "M  END\n";
}

}  // namespace surfcomp::io
