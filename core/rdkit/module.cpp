// The RDKit module's one exported symbol: its entry points (rdkit_module.hpp).
#include "rdkit_module.hpp"

extern "C" __attribute__((visibility("default")))
const surfcomp::io::detail::RdkitModule surfcomp_rdkit_module_2 = {
    surfcomp::io::detail::rdkit_read_molecule, surfcomp::io::detail::rdkit_crippen_of_pdb_block,
    surfcomp::io::rdkit_moved_mol_block,       surfcomp::io::rdkit_moved_record_block,
    surfcomp::rdkit_generate_conformers,       surfcomp::options::set_spelling,
};
