// Inside the module, core's functions that need RDKit are its own definitions, not calls through
// the module's table (which is how the library outside reaches them: src/io/rdkit_forwarding.cpp).
#include "rdkit_module.hpp"
#include "surfcomp/core/io/write_molecule.hpp"

namespace surfcomp::io::detail {

Molecule read_with_rdkit(const std::filesystem::path& path, const std::string& text,
                         RdkitFormat format, const MoleculeReadOptions& options) {
  return rdkit_read_molecule(path, text, format, options);
}

std::vector<double> crippen_contributions_of_pdb_block(const std::string& pdb_block,
                                                       const std::string& source) {
  return rdkit_crippen_of_pdb_block(pdb_block, source);
}

}  // namespace surfcomp::io::detail

namespace surfcomp::io {

std::string moved_mol_block(const std::filesystem::path& input, const Eigen::Matrix3d& rotation,
                            const Eigen::Vector3d& translation, std::size_t record) {
  return rdkit_moved_mol_block(input, rotation, translation, record);
}

std::string moved_record_block(const MoleculeRecord& record, const Eigen::Matrix3d& rotation,
                               const Eigen::Vector3d& translation) {
  return rdkit_moved_record_block(record, rotation, translation);
}

}  // namespace surfcomp::io

namespace surfcomp {

std::vector<std::string> generate_conformers(const io::MoleculeRecord& record,
                                             const ConformerOptions& options) {
  return rdkit_generate_conformers(record, options);
}

}  // namespace surfcomp
