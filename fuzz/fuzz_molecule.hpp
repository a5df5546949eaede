// The body of the molecule-reader harnesses (fuzz_sdf, fuzz_mol2, fuzz_pdb, fuzz_pqr).
#pragma once

#include "fuzz_input.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace surfcomp::fuzz {

/// Aborts (a finding) when a molecule read without error breaks read_molecule's promises:
/// at least one atom, finite coordinates, charges and radii, radii > 0.
inline void check_molecule(const Molecule& molecule) {
  if (molecule.atoms.empty()) {
    std::fprintf(stderr, "read_molecule returned no atoms without an error\n");
    std::abort();
  }
  for (const Atom& atom : molecule.atoms) {
    if (!atom.position.allFinite() || !std::isfinite(atom.charge) ||
        !std::isfinite(atom.lipophilicity) || !(atom.radius > 0.0 && std::isfinite(atom.radius))) {
      std::fprintf(stderr, "read_molecule returned atom '%s' with a non-finite value or radius\n",
                   atom.name.c_str());
      std::abort();
    }
  }
}

/// Reads the input as a molecule file with `extension` (read_molecule chooses the format by
/// it). With `select_ligand` (PDB, PQR), a successful read is followed by a second one that
/// selects the first HETATM residue as the ligand. surfcomp::Error is the documented failure;
/// anything else escapes and is a finding.
inline void fuzz_molecule_reader(const std::uint8_t* data, std::size_t size, const char* extension,
                                 bool select_ligand) {
  static ScratchFile file(extension);
  const std::filesystem::path& path = file.write(data, size);
  try {
    const Molecule molecule = io::read_molecule(path);
    check_molecule(molecule);
    if (!select_ligand) return;
    for (const Atom& atom : molecule.atoms) {
      if (!atom.hetero) continue;
      io::MoleculeReadOptions options;
      options.ligand = atom.residue_name;
      check_molecule(io::read_molecule(path, options));
      break;
    }
  } catch (const Error&) {
  }
}

}  // namespace surfcomp::fuzz
