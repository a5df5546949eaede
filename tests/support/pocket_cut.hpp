// A binding pocket cut out of a structure, for tests that need a site whose surface builds in
// seconds: the atoms within a margin of a ligand copy, written as a PDB file.
#pragma once

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/molecule.hpp"

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace surfcomp::test {

/// Writes to `output` (PDB) the atoms of `structure` within `margin` A of an atom of the copy of
/// ligand `residue` that select_ligand takes, that copy included, water left out; the atoms keep
/// their order and records. Throws what reading the structure or selecting the ligand throws.
inline void write_pocket(const std::filesystem::path& structure, const std::string& residue,
                         double margin, const std::filesystem::path& output) {
  const Molecule whole = io::read_molecule(structure);
  const std::vector<std::size_t> ligand = select_ligand(whole, LigandSelector{residue, {}, {}});
  Molecule cut = whole;
  cut.atoms.clear();
  for (const Atom& atom : whole.atoms) {
    if (is_water_residue(atom.residue_name)) continue;
    for (const std::size_t l : ligand) {
      if ((atom.position - whole.atoms[l].position).norm() <= margin) {
        cut.atoms.push_back(atom);
        break;
      }
    }
  }
  std::ofstream out(output);
  io::write_pdb(cut, out);
}

}  // namespace surfcomp::test
