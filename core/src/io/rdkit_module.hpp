// The interface between surfcomp::core and its RDKit module, libsurfcomp_rdkit.so (core/rdkit/):
// reading SDF/MOL, MOL2 and PDB files, Crippen contributions, moved mol blocks and ETKDG + MMFF
// conformers, the work that needs RDKit's twenty shared libraries. The module alone links them,
// and core loads it on the first of these calls (rdkit_forwarding.cpp), so that a run that reads
// no molecule through RDKit (`--version`, a mesh, a PQR file, a .hsi file) does not map and
// initialise RDKit (docs/decisions.md#loadable-modules).
//
// The module is surfcomp code built with core's own sources, so its entry points take and return
// core's types and throw core's errors (surfcomp::Error and its kinds) as the functions they stand
// for document.
#pragma once

#include "molecule_reader_detail.hpp"
#include "surfcomp/core/conformers.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_names.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace surfcomp::io::detail {

/// The module file and its one exported symbol, a `const RdkitModule`.
constexpr const char* kRdkitModuleFile = "libsurfcomp_rdkit.so";
constexpr const char* kRdkitModuleSymbol = "surfcomp_rdkit_module_2";

/// The module's entry points, each the function of core it is named after.
struct RdkitModule {
  /// read_with_rdkit (molecule_reader_detail.hpp)
  Molecule (*read_molecule)(const std::filesystem::path& path, const std::string& text,
                            RdkitFormat format, const MoleculeReadOptions& options);
  /// crippen_contributions_of_pdb_block (molecule_reader_detail.hpp)
  std::vector<double> (*crippen_of_pdb_block)(const std::string& pdb_block,
                                              const std::string& source);
  /// io::moved_mol_block (write_molecule.hpp)
  std::string (*moved_mol_block)(const std::filesystem::path& input,
                                 const Eigen::Matrix3d& rotation,
                                 const Eigen::Vector3d& translation, std::size_t record);
  /// io::moved_record_block (molecule_records.hpp)
  std::string (*moved_record_block)(const MoleculeRecord& record, const Eigen::Matrix3d& rotation,
                                    const Eigen::Vector3d& translation);
  /// generate_conformers (conformers.hpp)
  std::vector<std::string> (*generate_conformers)(const MoleculeRecord& record,
                                                  const ConformerOptions& options);
  /// options::set_spelling: the module holds its own copy of core, so the caller's spelling of
  /// the options its messages name is handed over before each call.
  void (*set_spelling)(options::Spelling spelling);
};

// The module's definitions (core/rdkit/), named apart from core's functions that call them.
Molecule rdkit_read_molecule(const std::filesystem::path& path, const std::string& text,
                             RdkitFormat format, const MoleculeReadOptions& options);
std::vector<double> rdkit_crippen_of_pdb_block(const std::string& pdb_block,
                                               const std::string& source);

}  // namespace surfcomp::io::detail

namespace surfcomp::io {
std::string rdkit_moved_mol_block(const std::filesystem::path& input,
                                  const Eigen::Matrix3d& rotation,
                                  const Eigen::Vector3d& translation, std::size_t record);
std::string rdkit_moved_record_block(const MoleculeRecord& record, const Eigen::Matrix3d& rotation,
                                     const Eigen::Vector3d& translation);
}  // namespace surfcomp::io

namespace surfcomp {
std::vector<std::string> rdkit_generate_conformers(const io::MoleculeRecord& record,
                                                   const ConformerOptions& options);
}  // namespace surfcomp
