#include "surfcomp/core/io/molecule_formats.hpp"

#include <algorithm>
#include <cctype>

namespace surfcomp::io {

const std::vector<MoleculeFormat>& molecule_formats() {
  static const std::vector<MoleculeFormat> formats = {
      {".sdf", "SDF (MDL structure-data file)", MoleculeFileKind::mdl},
      {".mol", "MDL molfile", MoleculeFileKind::mdl},
      {".mol2", "Tripos MOL2", MoleculeFileKind::mol2},
      {".pdb", "PDB", MoleculeFileKind::pdb},
      {".ent", "PDB (as the PDB archive names it)", MoleculeFileKind::pdb},
      {".cif", "PDBx/mmCIF", MoleculeFileKind::mmcif},
      {".mmcif", "PDBx/mmCIF", MoleculeFileKind::mmcif},
      {".cif.gz", "PDBx/mmCIF, gzip-compressed", MoleculeFileKind::mmcif},
      {".pqr", "PQR (PDB with charges and radii)", MoleculeFileKind::pqr},
      {".smi", "SMILES list", MoleculeFileKind::smiles},
      {".dat", "SMILES table (tab-separated, a header line)", MoleculeFileKind::table},
      {".dat.gz", "SMILES table, gzip-compressed", MoleculeFileKind::table},
  };
  return formats;
}

const MoleculeFormat* find_molecule_format(const std::filesystem::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const MoleculeFormat* found = nullptr;
  for (const MoleculeFormat& format : molecule_formats()) {
    const std::string_view ending = format.extension;
    if (name.size() > ending.size() &&
        name.compare(name.size() - ending.size(), ending.size(), ending) == 0 &&
        (found == nullptr || ending.size() > found->extension.size()))
      found = &format;
  }
  return found;
}

bool serves(const MoleculeFormat& format, MoleculeUse use) {
  switch (use) {
    case MoleculeUse::molecule:
      return format.kind != MoleculeFileKind::smiles && format.kind != MoleculeFileKind::table;
    case MoleculeUse::records:
      return true;
    case MoleculeUse::structure:
      return format.kind == MoleculeFileKind::pdb || format.kind == MoleculeFileKind::mmcif;
  }
  return false;
}

std::string molecule_extensions(MoleculeUse use) {
  std::string out;
  for (const MoleculeFormat& format : molecule_formats()) {
    if (!serves(format, use)) continue;
    if (!out.empty()) out += ' ';
    out += format.extension;
  }
  return out;
}

}  // namespace surfcomp::io
