#include "surfcomp/core/io/molecule_records.hpp"

#include "molecule_reader_detail.hpp"
#include "molecule_text.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp::io {
namespace {

/// Whether the file is a gzip-compressed SMILES table (.dat.gz).
bool is_gzipped_list(const std::filesystem::path& path) {
  const MoleculeFormat* format = find_molecule_format(path);
  return format != nullptr && format->kind == MoleculeFileKind::table &&
         format->extension == ".dat.gz";
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = line.find(separator, begin);
    fields.push_back(detail::trimmed(line.substr(begin, end - begin)));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return fields;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

std::string fallback_name(const std::filesystem::path& path, std::size_t record) {
  return path.stem().string() + ":" + std::to_string(record);
}

std::vector<MoleculeRecord> smi_records(const std::filesystem::path& path,
                                        const std::string& text) {
  std::vector<MoleculeRecord> records;
  for (const std::string& line : lines_of(text)) {
    const std::string content = detail::trimmed(line);
    if (content.empty() || content.front() == '#') continue;
    std::istringstream fields(content);
    MoleculeRecord record;
    record.source = path;
    record.record = records.size() + 1;
    record.format = RecordFormat::smiles;
    fields >> record.text >> record.name;
    if (record.name.empty()) record.name = fallback_name(path, record.record);
    records.push_back(std::move(record));
  }
  return records;
}

std::vector<MoleculeRecord> dat_records(const std::filesystem::path& path,
                                        const std::string& text) {
  const std::string source = path.string();
  const std::vector<std::string> lines = lines_of(text);
  if (lines.empty() || detail::trimmed(lines.front()).empty() ||
      detail::trimmed(lines.front()).front() != '#') {
    throw FormatError(source, 1, "expected a header line such as '# Mol_Title<TAB>ID<TAB>SMILES'");
  }
  const std::vector<std::string> header = split(detail::trimmed(lines.front()).substr(1), '\t');
  const auto column = [&](const char* name) {
    const auto found = std::find(header.begin(), header.end(), name);
    return found == header.end() ? std::string::npos
                                 : static_cast<std::size_t>(found - header.begin());
  };
  const std::size_t smiles_column = column("SMILES");
  if (smiles_column == std::string::npos)
    throw FormatError(source, 1, "the header names no SMILES column");
  std::size_t name_column = column("ID");
  if (name_column == std::string::npos) name_column = column("Mol_Title");
  std::vector<MoleculeRecord> records;
  for (std::size_t l = 1; l < lines.size(); ++l) {
    if (detail::trimmed(lines[l]).empty()) continue;
    const std::vector<std::string> fields = split(lines[l], '\t');
    if (fields.size() < header.size()) {
      throw FormatError(source, l + 1,
                        "expected " + std::to_string(header.size()) +
                            " tab-separated fields, got " + std::to_string(fields.size()));
    }
    MoleculeRecord record;
    record.source = path;
    record.record = records.size() + 1;
    record.format = RecordFormat::smiles;
    record.text = fields[smiles_column];
    record.name = name_column == std::string::npos || fields[name_column].empty()
                      ? fallback_name(path, record.record)
                      : fields[name_column];
    records.push_back(std::move(record));
  }
  return records;
}

/// The first line of a mol block or the line after @<TRIPOS>MOLECULE.
std::string title_of(const std::string& text, RecordFormat format) {
  const std::vector<std::string> lines = lines_of(text);
  if (format == RecordFormat::mdl) return lines.empty() ? "" : detail::trimmed(lines.front());
  for (std::size_t l = 0; l + 1 < lines.size(); ++l) {
    if (detail::trimmed(lines[l]) == "@<TRIPOS>MOLECULE") return detail::trimmed(lines[l + 1]);
  }
  return "";
}

}  // namespace

bool is_smiles_file(const std::filesystem::path& path) {
  const MoleculeFormat* format = find_molecule_format(path);
  return format != nullptr &&
         (format->kind == MoleculeFileKind::smiles || format->kind == MoleculeFileKind::table);
}

bool is_record_file(const std::filesystem::path& path) {
  return is_molecule_file(path) || is_smiles_file(path);
}

std::vector<MoleculeRecord> read_molecule_records(const std::filesystem::path& path) {
  const MoleculeFormat* found = find_molecule_format(path);
  if (found == nullptr) {
    throw FormatError(path.string(), "unknown molecule list extension '" +
                                         lowercase_extension(path) + "' (expected " +
                                         molecule_extensions(MoleculeUse::records) + ")");
  }
  const MoleculeFileKind kind = found->kind;
  if (kind == MoleculeFileKind::table) {
    return dat_records(path,
                       is_gzipped_list(path) ? read_gzip_input_file(path) : read_input_file(path));
  }
  if (kind == MoleculeFileKind::smiles) return smi_records(path, read_input_file(path));
  if (kind == MoleculeFileKind::pqr || serves(*found, MoleculeUse::structure)) {
    MoleculeRecord record;
    record.source = path;
    record.name = structure_stem(path);
    record.format = RecordFormat::structure;
    // Readable now, not when the record is read; mmCIF is kept as PDB text.
    if (kind == MoleculeFileKind::pqr) {
      read_input_file(path);
    } else {
      record.text = read_structure_text(path);
    }
    return {record};
  }
  const bool mol2 = kind == MoleculeFileKind::mol2;  // else MDL: the table's last kind
  const detail::RdkitFormat format = mol2 ? detail::RdkitFormat::mol2 : detail::RdkitFormat::mdl;
  const RecordFormat record_format = mol2 ? RecordFormat::mol2 : RecordFormat::mdl;
  std::vector<MoleculeRecord> records;
  for (std::string& text : detail::split_records(read_input_file(path), format)) {
    MoleculeRecord record;
    record.source = path;
    record.record = records.size() + 1;
    record.format = record_format;
    record.name = title_of(text, record_format);
    if (record.name.empty()) record.name = fallback_name(path, record.record);
    record.text = std::move(text);
    records.push_back(std::move(record));
  }
  return records;
}

Molecule read_record_molecule(const MoleculeRecord& record, const MoleculeReadOptions& options) {
  MoleculeReadOptions single = options;
  single.record = 0;
  switch (record.format) {
    case RecordFormat::structure:
      if (record.text.empty()) return read_molecule(record.source, single);
      return detail::read_with_rdkit(record.source, record.text, detail::RdkitFormat::pdb, single);
    case RecordFormat::smiles:
      throw InputError(record.source.string() + ": record " + std::to_string(record.record) + " (" +
                       record.name + ") is a SMILES string without coordinates");
    case RecordFormat::descriptors:
      throw InputError(record.source.string() +
                       ": a .hsi file keeps a surface and heavy atoms, not a molecule to read");
    case RecordFormat::mesh:
      throw InputError(record.source.string() + ": a mesh, not a molecule to read");
    case RecordFormat::mol2:
      return detail::read_with_rdkit(record.source, record.text, detail::RdkitFormat::mol2, single);
    case RecordFormat::mdl:
      break;
  }
  return detail::read_with_rdkit(record.source, record.text, detail::RdkitFormat::mdl, single);
}

std::optional<std::vector<Eigen::Vector3d>> mdl_coordinates(const std::string& block) {
  // Header: three lines, then the counts line "aaabbb...V2000".
  std::size_t at = 0;
  for (int line = 0; line < 3; ++line) {
    at = block.find('\n', at);
    if (at == std::string::npos) return std::nullopt;
    ++at;
  }
  const std::size_t counts_end = block.find('\n', at);
  if (counts_end == std::string::npos) return std::nullopt;
  const std::string counts = block.substr(at, counts_end - at);
  if (counts.find("V2000") == std::string::npos || counts.size() < 3) return std::nullopt;
  std::size_t atoms = 0;
  try {
    atoms = static_cast<std::size_t>(std::stoul(counts.substr(0, 3)));
  } catch (const std::exception&) {
    return std::nullopt;
  }
  std::vector<Eigen::Vector3d> out;
  out.reserve(atoms);
  at = counts_end + 1;
  for (std::size_t a = 0; a < atoms; ++a) {
    const std::size_t end = block.find('\n', at);
    if (end == std::string::npos || end - at < 30) return std::nullopt;
    Eigen::Vector3d p;
    for (int c = 0; c < 3; ++c) {
      const std::string field = block.substr(at + 10 * static_cast<std::size_t>(c), 10);
      char* stop = nullptr;
      p(c) = std::strtod(field.c_str(), &stop);
      if (stop == field.c_str()) return std::nullopt;
    }
    if (!p.allFinite()) return std::nullopt;
    out.push_back(p);
    at = end + 1;
  }
  return out;
}

}  // namespace surfcomp::io
