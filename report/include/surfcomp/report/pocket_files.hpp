// The pockets of a structure as files: a JSON document (each pocket's rank, score, volume,
// centre, lining residues and alpha spheres) and PDB HETATM records of the alpha sphere centres
// for viewing. `surfcomp pockets` and the Python module write them with these functions.
#pragma once

#include "surfcomp/molsurf/pockets.hpp"

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace surfcomp::report {

/// The pockets of one structure and how they were found.
struct PocketSet {
  std::string input;                ///< the structure's name (a path)
  molsurf::PocketOptions options;   ///< the detection's parameters
  molsurf::StructurePockets found;  ///< its models, protein atoms and pockets
};

/// The JSON document, indented by two spaces, ending with a newline: input, models,
/// protein_atoms, parameters and pockets (rank, score, volume in A^3, buriedness, center,
/// lining_residues, lining_atoms 1-based as in the file's atom order, spheres as [x, y, z, r]).
std::string pockets_json(const PocketSet& set);

/// One HETATM record per alpha sphere: atom name APOL, residue STP numbered by the pocket's rank
/// (as fpocket writes them), the sphere's radius as B-factor; then END.
void write_pockets_pdb(const std::vector<molsurf::Pocket>& pockets, std::ostream& out);

}  // namespace surfcomp::report
