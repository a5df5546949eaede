// core's functions that need RDKit, each a call into the RDKit module (rdkit_module.hpp), which is
// loaded by the first of them.
#include "rdkit_module.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/loadable_module.hpp"

namespace surfcomp::io::detail {
namespace {

/// The module, loaded by the first call, with the caller's spelling of options handed over.
const RdkitModule& rdkit_module() {
  static const RdkitModule& module =
      *static_cast<const RdkitModule*>(module_symbol(kRdkitModuleFile, kRdkitModuleSymbol));
  module.set_spelling(options::spelling());
  return module;
}

}  // namespace

Molecule read_with_rdkit(const std::filesystem::path& path, const std::string& text,
                         RdkitFormat format, const MoleculeReadOptions& options) {
  return rdkit_module().read_molecule(path, text, format, options);
}

std::vector<double> crippen_contributions_of_pdb_block(const std::string& pdb_block,
                                                       const std::string& source) {
  return rdkit_module().crippen_of_pdb_block(pdb_block, source);
}

}  // namespace surfcomp::io::detail

namespace surfcomp::io {

std::string moved_mol_block(const std::filesystem::path& input, const Eigen::Matrix3d& rotation,
                            const Eigen::Vector3d& translation, std::size_t record) {
  return detail::rdkit_module().moved_mol_block(input, rotation, translation, record);
}

std::string moved_record_block(const MoleculeRecord& record, const Eigen::Matrix3d& rotation,
                               const Eigen::Vector3d& translation) {
  return detail::rdkit_module().moved_record_block(record, rotation, translation);
}

}  // namespace surfcomp::io

namespace surfcomp {

std::vector<std::string> generate_conformers(const io::MoleculeRecord& record,
                                             const ConformerOptions& options) {
  return io::detail::rdkit_module().generate_conformers(record, options);
}

}  // namespace surfcomp
