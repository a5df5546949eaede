// ETKDG + MMFF conformers through RDKit. Part of the RDKit module (rdkit_module.hpp).
#include "surfcomp/core/conformers.hpp"
#include "rdkit_module.hpp"

#include "surfcomp/core/error.hpp"

#include <GraphMol/DistGeomHelpers/Embedder.h>
#include <GraphMol/FileParsers/FileParsers.h>
#include <GraphMol/ForceFieldHelpers/MMFF/AtomTyper.h>
#include <GraphMol/ForceFieldHelpers/MMFF/MMFF.h>
#include <GraphMol/GraphMol.h>
#include <GraphMol/MolOps.h>
#include <GraphMol/SmilesParse/SmilesParse.h>
#include <RDGeneral/RDLog.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp {
namespace {

std::string describe(const io::MoleculeRecord& record) {
  return record.source.string() + ": record " + std::to_string(record.record) + " (" + record.name +
         ")";
}

std::unique_ptr<RDKit::RWMol> parse(const io::MoleculeRecord& record) {
  switch (record.format) {
    case io::RecordFormat::smiles:
      return std::unique_ptr<RDKit::RWMol>(RDKit::SmilesToMol(record.text));
    case io::RecordFormat::mdl:
      return std::unique_ptr<RDKit::RWMol>(RDKit::MolBlockToMol(record.text, true, false));
    case io::RecordFormat::mol2:
      return std::unique_ptr<RDKit::RWMol>(RDKit::Mol2BlockToMol(record.text, true, false));
    case io::RecordFormat::structure:
    case io::RecordFormat::descriptors:
    case io::RecordFormat::mesh:
      break;
  }
  throw InputError(describe(record) +
                   ": conformers are generated from SMILES, SDF or MOL2 records, not from a "
                   "PDB/PQR structure, a .hsi file or a mesh");
}

std::vector<std::string> embed(const io::MoleculeRecord& record, const ConformerOptions& options) {
  std::unique_ptr<RDKit::RWMol> mol = parse(record);
  if (!mol || mol->getNumAtoms() == 0)
    throw InputError(describe(record) + ": RDKit could not read the molecule");
  RDKit::MolOps::addHs(*mol);
  RDKit::DGeomHelpers::EmbedParameters params = RDKit::DGeomHelpers::ETKDGv3;
  params.randomSeed = options.seed;
  params.numThreads = 1;
  params.clearConfs = true;
  std::vector<int> ids;
  RDKit::DGeomHelpers::EmbedMultipleConfs(*mol, ids, static_cast<unsigned>(options.count), params);
  if (ids.empty()) throw InputError(describe(record) + ": ETKDG could not embed the molecule");
  if (options.mmff_iterations > 0) {
    RDKit::MMFF::MMFFMolProperties properties(*mol);
    if (properties.isValid()) {
      std::vector<std::pair<int, double>> results;
      RDKit::MMFF::MMFFOptimizeMoleculeConfs(*mol, results, 1, options.mmff_iterations);
    }
  }
  if (!options.hydrogens) RDKit::MolOps::removeHs(*mol);
  mol->setProp(RDKit::common_properties::_Name, record.name);
  std::vector<std::string> blocks;
  blocks.reserve(ids.size());
  for (int id : ids) blocks.push_back(RDKit::MolToMolBlock(*mol, true, id) + "$$$$\n");
  return blocks;
}

}  // namespace

std::vector<std::string> rdkit_generate_conformers(const io::MoleculeRecord& record,
                                                   const ConformerOptions& options) {
  if (options.count < 1)
    throw OptionError("conformer count must be at least 1, got " + std::to_string(options.count));
  if (options.seed < 0)
    throw OptionError("conformer seed must be >= 0, got " + std::to_string(options.seed));
  if (options.mmff_iterations < 0) {
    throw OptionError("MMFF iterations must be >= 0, got " +
                      std::to_string(options.mmff_iterations));
  }
  const RDLog::LogStateSetter quiet;  // RDKit's warnings would go to stderr
  try {
    return embed(record, options);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    std::string reason = e.what();
    for (char& c : reason) {
      if (c == '\n' || c == '\r') c = ' ';
    }
    throw InputError(describe(record) + ": RDKit: " + reason);
  }
}

}  // namespace surfcomp
