// PDBx/mmCIF through gemmi: the first model written as PDB records, which every structure
// reader then reads as it reads a PDB file.
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/read_molecule.hpp"

// Debian's gemmi-dev ships without its bundled stb_sprintf; the C library's snprintf does. GCC
// then checks gemmi's fixed-width PDB records against their buffer once inlined (and warns that a
// %c may be cut, which the widths rule out); the check is turned off for gemmi's code only.
#define USE_STD_SNPRINTF
#define GEMMI_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-truncation"
#include <gemmi/assembly.hpp>
#include <gemmi/cif.hpp>
#include <gemmi/mmcif.hpp>
#include <gemmi/to_pdb.hpp>
#pragma GCC diagnostic pop
#undef GEMMI_WRITE_IMPLEMENTATION

#include <algorithm>
#include <sstream>
#include <string>

namespace surfcomp::io {
namespace {

bool has_suffix(const std::string& name, const std::string& suffix) {
  return name.size() >= suffix.size() &&
         name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string lowercase_name(const std::filesystem::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name;
}

/// The first line of a parser's message (gemmi's PEGTL errors can span several).
std::string first_line(const std::string& message) { return message.substr(0, message.find('\n')); }

std::size_t atom_count(const gemmi::Model& model) {
  std::size_t atoms = 0;
  for (const gemmi::Chain& chain : model.chains) {
    for (const gemmi::Residue& residue : chain.residues) atoms += residue.atoms.size();
  }
  return atoms;
}

}  // namespace

options::Spec min_plddt_spec() {
  return {"min-plddt",
          options::Kind::real,
          "PDB/mmCIF structure: drop the residues whose B-factor (an AlphaFold model's pLDDT) is "
          "below this, before the surface is built (0: keep every residue)",
          "",
          0.0,
          100.0};
}

bool is_mmcif_file(const std::filesystem::path& path) {
  const MoleculeFormat* format = find_molecule_format(path);
  return format != nullptr && format->kind == MoleculeFileKind::mmcif;
}

bool is_structure_file(const std::filesystem::path& path) {
  const MoleculeFormat* format = find_molecule_format(path);
  return format != nullptr && serves(*format, MoleculeUse::structure);
}

std::string structure_stem(const std::filesystem::path& path) {
  std::filesystem::path name = path.filename();
  if (has_suffix(lowercase_name(path), ".cif.gz")) name = name.stem();
  return name.stem().string();
}

std::string read_structure_text(const std::filesystem::path& path, std::size_t* models) {
  if (!is_mmcif_file(path)) {
    std::string text = read_input_file(path);
    if (models != nullptr) {
      std::size_t count = 0;
      for (std::size_t at = text.find("MODEL "); at != std::string::npos;
           at = text.find("MODEL ", at + 6)) {
        if (at == 0 || text[at - 1] == '\n') ++count;
      }
      *models = std::max<std::size_t>(count, 1);
    }
    return text;
  }
  const std::string source = path.string();
  const std::string text =
      has_suffix(lowercase_name(path), ".gz") ? read_gzip_input_file(path) : read_input_file(path);
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw FormatError(source, "the file is empty");
  }
  gemmi::Structure structure;
  try {
    const gemmi::cif::Document document =
        gemmi::cif::read_memory(text.data(), text.size(), source.c_str());
    if (document.blocks.empty()) {
      throw FormatError(source, "cannot read it as mmCIF: it has no data_ block");
    }
    structure = gemmi::make_structure(document);
  } catch (const Error&) {
    throw;
  } catch (const std::out_of_range&) {
    // gemmi reaches past an empty table with .at(): a block without the rows a structure needs.
    throw FormatError(source,
                      "cannot read it as mmCIF: a table a structure needs is missing or "
                      "empty");
  } catch (const std::exception& e) {
    throw FormatError(source, "cannot read it as mmCIF: " + first_line(e.what()));
  }
  if (structure.models.empty() || atom_count(structure.models.front()) == 0) {
    throw InputError(source + ": the mmCIF file holds no atom coordinates (no _atom_site rows)");
  }
  if (models != nullptr) *models = structure.models.size();
  structure.models.erase(structure.models.begin() + 1, structure.models.end());
  const bool long_chain_name =
      std::any_of(structure.models.front().chains.begin(), structure.models.front().chains.end(),
                  [](const gemmi::Chain& chain) { return chain.name.size() > 2; });
  if (long_chain_name) gemmi::shorten_chain_names(structure);
  gemmi::PdbWriteOptions options;
  options.ter_records = false;
  std::ostringstream out;
  try {
    gemmi::write_minimal_pdb(structure, out, options);
  } catch (const std::exception& e) {
    throw FormatError(source, "cannot convert it to PDB records: " + first_line(e.what()));
  }
  return out.str();
}

}  // namespace surfcomp::io
