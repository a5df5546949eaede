#include "surfcomp/core/io/write_molecule.hpp"

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

}  // namespace surfcomp::io
