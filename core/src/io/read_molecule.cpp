#include "surfcomp/core/io/read_molecule.hpp"

#include "molecule_reader_detail.hpp"
#include "surfcomp/core/elements.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/pqr.hpp"
#include "surfcomp/core/protein_lipophilicity.hpp"

#include <algorithm>

namespace surfcomp::io {

namespace detail {

void check_single_record(std::size_t record, const std::string& source) {
  if (record > 1) {
    throw InputError(source + ": record " + std::to_string(record) +
                     " asked for, the file holds 1 molecule");
  }
}

void check_read_atoms(const Molecule& molecule) {
  for (std::size_t i = 0; i < molecule.atoms.size(); ++i) {
    check_read_position(molecule.atoms[i].position, molecule.source, describe_atom(molecule, i));
  }
}

bool is_dropped_residue(std::string_view residue_name, const MoleculeReadOptions& options) {
  if (options.remove_water && is_water_residue(residue_name)) return true;
  const std::string name = residue_key(residue_name);
  return std::any_of(options.exclude_residues.begin(), options.exclude_residues.end(),
                     [&](const std::string& excluded) { return residue_key(excluded) == name; });
}

bool has_standard_residue(const std::vector<Atom>& atoms) {
  return std::any_of(atoms.begin(), atoms.end(), [](const Atom& atom) {
    return protein_atom_lipophilicity(atom.residue_name, "CA").has_value();
  });
}

void assign_protein_lipophilicity(Molecule& molecule) {
  for (Atom& atom : molecule.atoms) {
    atom.lipophilicity = protein_atom_lipophilicity(atom.residue_name, atom.name).value_or(0.0);
  }
  molecule.lipophilicity_assigned = true;
}

void assign_bondi_radii(Molecule& molecule) {
  for (std::size_t i = 0; i < molecule.atoms.size(); ++i) {
    Atom& atom = molecule.atoms[i];
    const auto radius = bondi_radius(atom.element);
    if (!radius) {
      throw InputError(molecule.source + ": atom " + std::to_string(i + 1) +
                       (atom.name.empty() ? "" : " (" + atom.name + ")") + " has element '" +
                       atom.element + "', which has no van der Waals radius");
    }
    atom.radius = *radius;
  }
}

}  // namespace detail

bool is_molecule_file(const std::filesystem::path& path) {
  const MoleculeFormat* format = find_molecule_format(path);
  return format != nullptr && serves(*format, MoleculeUse::molecule);
}

Molecule read_molecule(const std::filesystem::path& path, const MoleculeReadOptions& options) {
  const MoleculeFormat* format = find_molecule_format(path);
  if (format == nullptr || !serves(*format, MoleculeUse::molecule)) {
    throw FormatError(path.string(), "unknown molecule file extension '" +
                                         lowercase_extension(path) + "' (expected " +
                                         molecule_extensions(MoleculeUse::molecule) + ")");
  }
  switch (format->kind) {
    case MoleculeFileKind::pqr:
      return read_pqr(path, options);
    case MoleculeFileKind::pdb:
    case MoleculeFileKind::mmcif:
      return detail::read_with_rdkit(path, read_structure_text(path), detail::RdkitFormat::pdb,
                                     options);
    default:
      return detail::read_with_rdkit(path, read_input_file(path),
                                     format->kind == MoleculeFileKind::mol2
                                         ? detail::RdkitFormat::mol2
                                         : detail::RdkitFormat::mdl,
                                     options);
  }
}

}  // namespace surfcomp::io
