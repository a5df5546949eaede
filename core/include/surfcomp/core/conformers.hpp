// Conformers of a molecule from its connectivity: RDKit's ETKDG distance geometry (version 3;
// S. Wang, J. Witek, G. A. Landrum, S. Riniker, J. Chem. Inf. Model. 60, 2044 (2020)) followed
// by MMFF94 minimisation, seeded so that the same input gives the same conformers.
#pragma once

#include "surfcomp/core/io/molecule_records.hpp"

#include <string>
#include <vector>

namespace surfcomp {

struct ConformerOptions {
  /// Default 10. Conformers asked for; ETKDG may give fewer when some embeddings fail. >= 1.
  int count = 10;
  /// Default 42. Seed of ETKDG's random numbers; every molecule starts from this seed, so a
  /// molecule's conformers do not depend on the other molecules or on the thread count. >= 0.
  int seed = 42;
  /// Default 200. Most MMFF94 minimisation steps per conformer; 0 keeps the ETKDG geometry.
  /// A molecule MMFF94 cannot type keeps its ETKDG geometry. >= 0.
  int mmff_iterations = 200;
  /// Default true: the conformers keep the hydrogens made explicit for embedding. False: they
  /// are removed after minimisation, for a caller whose molecule lists none (a crystal ligand).
  bool hydrogens = true;
};

/// The conformers of `record`'s molecule (SMILES, SDF or MOL2 record; its coordinates, if any,
/// are not used), hydrogens made explicit (or removed: options.hydrogens), each as an MDL mol block
/// ending with "$$$$" whose title is record.name, in ETKDG's order. Runs on the calling thread
/// only. Throws OptionError for options outside their domain; InputError naming the record when
/// RDKit cannot parse or sanitise it, when it is a PDB/PQR structure, or when no conformer can be
/// embedded.
std::vector<std::string> generate_conformers(const io::MoleculeRecord& record,
                                             const ConformerOptions& options = {});

}  // namespace surfcomp
