#include "surfcomp/screening/library_build.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/binary_stream.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/mesh/io/formats.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/mesh/length_unit.hpp"
#include "surfcomp/molsurf/load_surface.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <memory>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::screening {
namespace {

void check_options(const LibraryBuildOptions& options) {
  if (!(options.spacing > 0.0) || !std::isfinite(options.spacing))
    throw OptionError("library spacing must be finite and > 0, got " +
                      std::to_string(options.spacing));
  if (!(options.sigma > 0.0) || !std::isfinite(options.sigma))
    throw OptionError("library sigma must be finite and > 0, got " + std::to_string(options.sigma));
  if (options.batch < 1) throw OptionError("library build batch must be at least 1");
  if (options.shard_records < 1)
    throw OptionError(options::named("shard_records") + " must be at least 1, got 0");
  if (!(options.lining_radius > 0.0) || !std::isfinite(options.lining_radius))
    throw OptionError(options::named("site_overlay_radius") + " must be finite and > 0, got " +
                      std::to_string(options.lining_radius));
  if (!(options.site.sphere_radius > 0.0) || !std::isfinite(options.site.sphere_radius))
    throw OptionError(options::named("site_radius") + " must be finite and > 0, got " +
                      std::to_string(options.site.sphere_radius));
  if (!(options.site.surface_margin >= 0.0) || !std::isfinite(options.site.surface_margin))
    throw OptionError(options::named("site_margin") + " must be finite and >= 0, got " +
                      std::to_string(options.site.surface_margin));
  if (options.conformers) {
    const ConformerOptions& c = *options.conformers;
    if (c.count < 1)
      throw OptionError(options::named("conformers") + " must be at least 1, got " +
                        std::to_string(c.count));
    if (c.seed < 0)
      throw OptionError(options::named("seed") + " must be >= 0, got " + std::to_string(c.seed));
    if (c.mmff_iterations < 0) throw OptionError("MMFF iterations must be >= 0");
  }
}

std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

/// `text` as one field of a log line: a tab, like a line break, becomes a space.
std::string log_field(std::string text) {
  text = one_line(std::move(text));
  std::replace(text.begin(), text.end(), '\t', ' ');
  return text;
}

constexpr const char* kLogColumns = "# source\trecord\tname\treason";

std::uint32_t heavy_atom_count(const Molecule& molecule) {
  return static_cast<std::uint32_t>(
      std::count_if(molecule.atoms.begin(), molecule.atoms.end(),
                    [](const Atom& atom) { return atom.element != "H"; }));
}

bool is_library_input(const std::filesystem::path& path) {
  return io::is_record_file(path) || harmonic::io::is_hsi_file(path) ||
         mesh::io::is_mesh_file(path);
}

/// The entry of a mesh file: the mesh as read (repaired with options.repair; held to the
/// surface's vertex limit) with the normals and curvature molsurf::load_mesh_surface gives it (its
/// length unit automatic; a .hsi file's surface carries them), and the sample of its surface
/// pooled in cells of options.spacing of that unit, which the format keeps for every entry; a
/// shape screen matches the meshes themselves.
LibraryEntry mesh_entry(const io::MoleculeRecord& record, const LibraryBuildOptions& options) {
  const std::string extension = io::lowercase_extension(record.source);
  if (extension == ".vert" || extension == ".face") {
    throw InputError(record.source.string() +
                     ": an MSMS surface is a molecule's, in A: build the library from the "
                     "molecule");
  }
  molsurf::SurfaceInputOptions input;
  input.surface = options.surface;
  input.repair = options.repair;
  molsurf::LoadedSurface loaded =
      molsurf::load_mesh_surface(molsurf::read_mesh_input(record.source, input).surface, input);
  mesh::Surface& surface = loaded.surface;
  const mesh::LengthUnit unit = loaded.unit;
  LibraryEntry entry;
  entry.info.name = record.name;
  entry.info.source = record.source.string();
  entry.info.record = static_cast<std::uint32_t>(record.record);
  entry.molecule = record;
  entry.sample = matching::sample_surface(surface, options.spacing * unit.value);
  entry.kind = matching::SampleKind::surface;
  entry.packed =
      matching::PackedSample(entry.sample, entry.atoms, options.sigma * unit.value, entry.kind);
  harmonic::SurfaceDescriptors stored;
  stored.surface = std::move(surface);
  entry.surface = harmonic::io::encode_hsi(stored);
  return entry;
}

/// The entry of a .hsi file: its surface's samples, its heavy atoms as an MDL block, and its
/// surface without critical points for the last stage (the full match).
LibraryEntry hsi_entry(const io::MoleculeRecord& record, const LibraryBuildOptions& options) {
  harmonic::SurfaceDescriptors described = harmonic::io::read_hsi(record.source);
  // A .hsi made from a mesh has neither: the entry would be scored without chemistry.
  if (described.atoms.empty())
    throw InputError(record.source.string() + ": the .hsi keeps no atoms (made from a mesh?)");
  for (const char* property : {mesh::property::esp, mesh::property::lp}) {
    if (!described.surface.has_property(property))
      throw InputError(record.source.string() + ": the .hsi surface has no " + property);
  }
  Molecule atoms;
  for (const harmonic::SurfaceAtom& atom : described.atoms) {
    Atom a;
    a.element = atom.element;
    a.position = atom.position;
    atoms.atoms.push_back(std::move(a));
  }
  LibraryEntry entry;
  entry.info.name = record.name;
  entry.info.source = record.source.string();
  entry.info.record = static_cast<std::uint32_t>(record.record);
  entry.info.heavy_atoms = static_cast<std::uint32_t>(described.atoms.size());
  entry.molecule = record;
  entry.molecule.format = io::RecordFormat::mdl;
  entry.molecule.text = io::atoms_mol_block(atoms, record.name) + "$$$$\n";
  entry.sample = matching::sample_surface(described.surface, options.spacing);
  entry.atoms = matching::sample_atoms(described.atoms);
  entry.kind = matching::SampleKind::surface;
  entry.packed = matching::PackedSample(entry.sample, entry.atoms, options.sigma, entry.kind);
  described.critical_points.clear();
  entry.surface = harmonic::io::encode_hsi(described);
  return entry;
}

}  // namespace

std::vector<io::MoleculeRecord> read_library_inputs(
    const std::vector<std::filesystem::path>& inputs) {
  std::vector<io::MoleculeRecord> records;
  const auto append = [&](const std::filesystem::path& file) {
    // A mesh or a .hsi file is one record, read when its entry is built.
    const bool is_mesh = mesh::io::is_mesh_file(file);
    if (is_mesh || harmonic::io::is_hsi_file(file)) {
      io::MoleculeRecord record;
      record.source = file;
      record.name = file.stem().string();
      record.format = is_mesh ? io::RecordFormat::mesh : io::RecordFormat::descriptors;
      records.push_back(std::move(record));
      return;
    }
    std::vector<io::MoleculeRecord> read = io::read_molecule_records(file);
    records.insert(records.end(), std::make_move_iterator(read.begin()),
                   std::make_move_iterator(read.end()));
  };
  for (const std::filesystem::path& input : inputs) {
    if (std::filesystem::is_directory(input)) {
      std::vector<std::filesystem::path> files;
      for (const auto& item : std::filesystem::directory_iterator(input)) {
        // An MSMS surface is a .vert and a .face file: one record, its .vert.
        if (item.is_regular_file() && is_library_input(item.path()) &&
            io::lowercase_extension(item.path()) != ".face")
          files.push_back(item.path());
      }
      std::sort(files.begin(), files.end());
      for (const auto& file : files) append(file);
    } else if (is_library_input(input)) {
      append(input);
    } else {
      throw InputError(
          input.string() +
          ": not a molecule file or list (.sdf .mol .mol2 .pdb .ent .cif .cif.gz .pqr .smi .dat "
          ".dat.gz), a .hsi file, a mesh (" +
          mesh::io::mesh_extensions(mesh::io::MeshUse::read) + ") nor a directory");
    }
  }
  const auto is_mesh = [](const io::MoleculeRecord& r) {
    return r.format == io::RecordFormat::mesh;
  };
  const auto meshes = std::count_if(records.begin(), records.end(), is_mesh);
  if (meshes > 0 && static_cast<std::size_t>(meshes) < records.size()) {
    const auto other = std::find_if_not(records.begin(), records.end(), is_mesh);
    throw InputError("a library holds molecules or meshes, not both: " + other->source.string() +
                     " is not a mesh, " +
                     std::find_if(records.begin(), records.end(), is_mesh)->source.string() +
                     " is");
  }
  if (records.empty()) {
    std::string names;
    for (const std::filesystem::path& input : inputs)
      names += (names.empty() ? "" : ", ") + input.string();
    throw FileError(names,
                    inputs.size() == 1 ? "holds no molecule record" : "hold no molecule record");
  }
  return records;
}

std::vector<LibraryEntry> build_entries(const io::MoleculeRecord& record,
                                        const LibraryBuildOptions& options, BuildTimes* times) {
  const bool is_mesh = record.format == io::RecordFormat::mesh;
  if (is_mesh || record.format == io::RecordFormat::descriptors) {
    if (options.conformers) {
      throw InputError(std::string(is_mesh ? "a mesh" : "a .hsi file") +
                       " has fixed coordinates: " + options::named("conformers") +
                       " does not apply to it");
    }
    const Stopwatch clock;
    std::vector<LibraryEntry> entries{is_mesh ? mesh_entry(record, options)
                                              : hsi_entry(record, options)};
    if (times != nullptr) times->entries += clock.elapsed_s();
    return entries;
  }
  std::vector<io::MoleculeRecord> conformations;
  if (options.conformers) {
    const Stopwatch clock;
    for (std::string& block : generate_conformers(record, *options.conformers)) {
      io::MoleculeRecord conformer = record;
      conformer.format = io::RecordFormat::mdl;
      conformer.text = std::move(block);
      conformations.push_back(std::move(conformer));
    }
    if (times != nullptr) times->conformers += clock.elapsed_s();
  } else if (record.format == io::RecordFormat::smiles) {
    throw InputError("a SMILES record has no coordinates: generate conformers (" +
                     options::named("conformers") + " N)");
  } else if (record.format == io::RecordFormat::structure && record.text.empty()) {
    throw InputError("a PQR structure cannot go into a library (write it as PDB or SDF)");
  } else {
    conformations.push_back(record);
  }
  const Stopwatch clock;
  std::vector<LibraryEntry> entries;
  std::optional<Molecule> first;  // generated conformers: one molecule, other coordinates
  for (std::size_t c = 0; c < conformations.size(); ++c) {
    // The conformers of one record share their atoms, charges and lipophilicity, which depend
    // on the bonds alone: the first is read whole, the others take its atoms with their own
    // coordinates (as reading their blocks gives them, checked in tests).
    std::optional<Molecule> molecule;
    if (first && options.conformers) {
      const std::optional<std::vector<Eigen::Vector3d>> positions =
          io::mdl_coordinates(conformations[c].text);
      if (positions && positions->size() == first->atoms.size()) {
        molecule = *first;
        for (std::size_t a = 0; a < positions->size(); ++a)
          molecule->atoms[a].position = (*positions)[a];
      }
    }
    if (!molecule) molecule = io::read_record_molecule(conformations[c], options.read);
    if (!first) first = *molecule;
    LibraryEntry entry;
    entry.info.name = record.name;
    entry.info.source = record.source.string();
    entry.info.record = static_cast<std::uint32_t>(record.record);
    entry.info.conformer = options.conformers ? static_cast<std::uint32_t>(c + 1) : 0;
    entry.info.heavy_atoms = heavy_atom_count(*molecule);
    entry.molecule = std::move(conformations[c]);
    entry.sample = matching::sample_molecule(*molecule, options.spacing, options.surface);
    entry.atoms = matching::sample_atoms(harmonic::surface_atoms(*molecule));
    entry.kind = matching::SampleKind::atoms;
    entry.packed = matching::PackedSample(entry.sample, entry.atoms, options.sigma, entry.kind);
    entries.push_back(std::move(entry));
  }
  if (times != nullptr) times->entries += clock.elapsed_s();
  return entries;
}

std::string build_settings(const LibraryBuildOptions& options, bool sites) {
  std::ostringstream text;
  if (sites) {
    text << "sites (site_radius " << options.site.sphere_radius << ", chain_contact_radius "
         << options.site.chain_contact_radius << ", surface_margin " << options.site.surface_margin
         << ", lining_radius " << options.lining_radius << ")\n";
  } else if (options.conformers) {
    text << "conformers " << options.conformers->count << " (ETKDGv3 seed "
         << options.conformers->seed << ", MMFF94 " << options.conformers->mmff_iterations
         << " iterations)\n";
  } else {
    text << "conformers 0 (the records' coordinates)\n";
  }
  text << "spacing " << options.spacing << "\n";
  text << "sigma " << options.sigma << "\n";
  text << "sample " << (sites ? "surface" : "atoms (screening surface; .hsi inputs: surface)")
       << "\n";
  text << "probe_radius " << options.surface.ses.probe_radius << "\n";
  text << "vertex_density " << options.surface.ses.vertex_density << "\n";
  return text.str();
}

namespace {

/// Where item `index` of a build comes from, for the list of skipped items.
struct ItemOrigin {
  std::string source;
  std::size_t record = 0;
  std::string name;
};

}  // namespace

/// What a build is made of: `count` items in order (molecule records, the sites of a list, or
/// structures and their pockets), each built into its entries.
struct BuildItems {
  std::size_t count = 0;
  /// The entries of item i. An entry the item leaves out (one pocket of a structure) is added
  /// to `skipped`; a failure of the whole item throws.
  std::function<std::vector<LibraryEntry>(std::size_t, BuildTimes&, std::vector<SkippedRecord>&)>
      build;
  std::function<ItemOrigin(std::size_t)> origin;
  /// Writes what item i is built from, for a shard's input hash.
  std::function<void(std::size_t, io::BinaryWriter&)> identity;
  std::string settings;         ///< build_settings of the build
  const char* noun = "record";  ///< an item, in messages
};

namespace {

/// Builds the entries of items [begin, end) in parallel and writes them in item order to
/// `output` atomically; an item whose build throws is skipped and listed.
LibraryBuildResult build_in_order(const BuildItems& items, std::size_t begin, std::size_t end,
                                  const std::filesystem::path& output, const std::string& settings,
                                  const LibraryBuildOptions& options) {
  const Stopwatch clock;
  const std::size_t count = end - begin;
  LibraryBuildResult result;
  result.records = count;
  // A pipeline: items go out in order, are built in parallel and are written in order, at
  // most options.batch of them in flight.
  struct Built {
    std::size_t index = 0;
    std::vector<LibraryEntry> entries;
    std::vector<SkippedRecord> skipped;
    BuildTimes times;
    std::string error;
  };
  struct NothingBuilt {};  // abandons the output: no library of nothing, an old file kept
  try {
    io::write_file_atomically(output, [&](std::ostream& out) {
      LibraryWriter writer(out, settings, options.sigma);
      std::size_t next = 0;
      tbb::parallel_pipeline(
          options.batch,
          tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                              [&](tbb::flow_control& control) -> std::size_t {
                                                if (next == count) {
                                                  control.stop();
                                                  return 0;
                                                }
                                                return next++;
                                              }) &
              tbb::make_filter<std::size_t, std::shared_ptr<Built>>(
                  tbb::filter_mode::parallel,
                  [&](std::size_t index) {
                    auto built = std::make_shared<Built>();
                    built->index = index;
                    try {
                      built->entries = items.build(begin + index, built->times, built->skipped);
                    } catch (const std::bad_alloc&) {
                      built->error = "out of memory";
                    } catch (const std::exception& e) {
                      built->error = one_line(e.what());
                      if (built->error.empty()) built->error = "unknown error";
                    }
                    return built;
                  }) &
              tbb::make_filter<std::shared_ptr<Built>, void>(
                  tbb::filter_mode::serial_in_order, [&](const std::shared_ptr<Built>& built) {
                    result.times.conformers += built->times.conformers;
                    result.times.entries += built->times.entries;
                    result.skipped.insert(result.skipped.end(), built->skipped.begin(),
                                          built->skipped.end());
                    if (!built->error.empty()) {
                      ItemOrigin o = items.origin(begin + built->index);
                      result.skipped.push_back(
                          {std::move(o.source), o.record, std::move(o.name), built->error});
                    } else {
                      for (const LibraryEntry& entry : built->entries) writer.add(entry);
                    }
                    if (options.progress) {
                      options.progress({built->index + 1, count, writer.size(),
                                        result.skipped.size(), clock.elapsed_s()});
                    }
                  }));
      if (writer.size() == 0) throw NothingBuilt{};
      writer.finish();
      result.entries = writer.size();
      result.bytes = writer.bytes();
    });
  } catch (const NothingBuilt&) {
  }
  result.seconds = clock.elapsed_s();
  return result;
}

/// The items of a build of molecule records: one per record, its entries build_entries'.
BuildItems record_items(const std::vector<io::MoleculeRecord>& records,
                        const LibraryBuildOptions& options) {
  BuildItems items;
  items.count = records.size();
  items.build = [&records, &options](std::size_t i, BuildTimes& times,
                                     std::vector<SkippedRecord>&) {
    return build_entries(records[i], options, &times);
  };
  items.origin = [&records](std::size_t i) {
    return ItemOrigin{records[i].source.string(), records[i].record, records[i].name};
  };
  items.identity = [&records](std::size_t i, io::BinaryWriter& bytes) {
    bytes.string(records[i].source.string());
    bytes.u64(records[i].record);
    bytes.string(records[i].name);
    bytes.u8(static_cast<std::uint8_t>(records[i].format));
    bytes.string(records[i].text);
  };
  items.settings = build_settings(options);
  items.noun = "molecule record";
  return items;
}

/// What a file is for an input hash: its path, size and modification time (its bytes are read
/// when it is built).
void file_identity(const std::filesystem::path& file, io::BinaryWriter& bytes) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  bytes.string(file.string());
  bytes.u64(error ? 0 : static_cast<std::uint64_t>(size));
  const auto modified = std::filesystem::last_write_time(file, error);
  bytes.u64(error ? 0 : static_cast<std::uint64_t>(modified.time_since_epoch().count()));
}

/// What a build's log (write_build_log) says: records, entries and the skipped records. Throws
/// FileError when `path` cannot be read, FormatError naming it and the line for a line that is
/// not what write_build_log writes.
LibraryBuildResult read_build_log(const std::filesystem::path& path) {
  std::istringstream lines(io::read_input_file(path));
  LibraryBuildResult result;
  std::string line;
  const auto fail = [&](std::size_t number, const std::string& reason) {
    throw FormatError(path.string(), number, reason);
  };
  std::size_t skipped = 0;
  const std::size_t summary_at = std::getline(lines, line) ? line.rfind(": ") : std::string::npos;
  if (line.rfind("# surfcomp library build -> ", 0) != 0 || summary_at == std::string::npos ||
      std::sscanf(line.c_str() + summary_at, ": %zu records, %zu entries, %zu skipped",
                  &result.records, &result.entries, &skipped) != 3)
    fail(1, "not the first line of a library build's log");
  if (!std::getline(lines, line) || line != kLogColumns) fail(2, "not the log's column line");
  for (std::size_t number = 3; std::getline(lines, line); ++number) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, '\t');) fields.push_back(cell);
    char* rest = nullptr;
    const std::size_t record = fields.size() == 4 ? std::strtoull(fields[1].c_str(), &rest, 10) : 0;
    if (fields.size() != 4 || rest == fields[1].c_str() || *rest != '\0')
      fail(number, "not a skipped record (source, record, name, reason, tab-separated)");
    result.skipped.push_back({fields[0], record, fields[2], fields[3]});
  }
  if (result.skipped.size() != skipped) {
    fail(1, "says " + std::to_string(skipped) + " records were skipped, the log lists " +
                std::to_string(result.skipped.size()));
  }
  return result;
}

std::string hex64(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

/// The 64-bit hash of what items [begin, end) are built from (BuildItems::identity).
std::uint64_t input_hash(const BuildItems& items, std::size_t begin, std::size_t end) {
  io::BinaryWriter bytes;
  for (std::size_t i = begin; i < end; ++i) items.identity(i, bytes);
  return io::xxh3_64(bytes.bytes().data(), bytes.bytes().size());
}

}  // namespace

void write_build_log(std::ostream& out, const std::filesystem::path& library,
                     const LibraryBuildResult& result) {
  out << "# surfcomp library build -> " << library.string() << ": " << result.records
      << " records, " << result.entries << " entries, " << result.skipped.size() << " skipped\n"
      << kLogColumns << '\n';
  for (const SkippedRecord& s : result.skipped) {
    out << log_field(s.source) << '\t' << s.record << '\t' << log_field(s.name) << '\t'
        << log_field(s.reason) << '\n';
  }
}

LibraryBuildResult build_library(const std::vector<io::MoleculeRecord>& records,
                                 const std::filesystem::path& output,
                                 const LibraryBuildOptions& options) {
  return ShardedLibraryBuild(records, output, options).run();
}

std::filesystem::path shard_folder(const std::filesystem::path& output) {
  return output.parent_path() / (output.filename().string() + ".d");
}

struct ShardedLibraryBuild::Impl {
  Impl(std::filesystem::path output_, LibraryBuildOptions options_)
      : output(std::move(output_)), options(std::move(options_)) {}

  /// Plans the build of `items_` (made with this object's options): checks the options, cuts
  /// the items into shards and hashes each shard's inputs. Throws OptionError for options
  /// outside their domain, InputError when there is no item.
  void plan(BuildItems items_);

  BuildItems items;
  std::filesystem::path output, folder;
  LibraryBuildOptions options;
  std::string settings;               // items.settings: the index's, and each shard's first lines
  std::size_t count = 0;              // shards
  std::vector<std::uint64_t> hashes;  // input_hash of each shard (more than one shard)
  std::size_t resumed = 0, resumed_entries = 0;

  std::size_t begin(std::size_t k) const { return k * options.shard_records; }
  std::size_t end(std::size_t k) const {
    return std::min(items.count, (k + 1) * options.shard_records);
  }
  std::filesystem::path file(std::size_t k, const char* extension) const {
    char name[32];
    std::snprintf(name, sizeof name, "%06zu%s", k + 1, extension);
    return folder / name;
  }
  std::filesystem::path library_file(std::size_t k) const { return file(k, ".sclib"); }
  std::filesystem::path log_file(std::size_t k) const { return file(k, ".log"); }
  std::filesystem::path manifest_file() const { return folder / "manifest.txt"; }

  /// Shard k's settings: the build's, then its number, records and input hash.
  std::string shard_settings(std::size_t k) const {
    return settings + "shard " + std::to_string(k + 1) + " of " + std::to_string(count) +
           ": records " + std::to_string(begin(k) + 1) + "-" + std::to_string(end(k)) + " of " +
           std::to_string(items.count) + ", inputs " + hex64(hashes[k]) + "\n";
  }
  std::string manifest() const {
    std::ostringstream text;
    text << "surfcomp library build manifest 1\nrecords " << items.count << "\nshard-records "
         << options.shard_records << "\nshards " << count << "\n";
    std::istringstream lines(settings);
    for (std::string line; std::getline(lines, line);) text << "settings " << line << "\n";
    for (std::size_t k = 0; k < count; ++k) {
      text << "shard " << library_file(k).stem().string() << " records " << begin(k) + 1 << "-"
           << end(k) << " inputs " << hex64(hashes[k]) << "\n";
    }
    return text.str();
  }
  /// Shard k's log when the shard is finished (its log written and, unless all its records
  /// were skipped, its library file there), else none.
  std::optional<LibraryBuildResult> finished(std::size_t k) const {
    if (!std::filesystem::exists(log_file(k))) return std::nullopt;
    LibraryBuildResult log = read_build_log(log_file(k));
    if (log.entries > 0 && !std::filesystem::exists(library_file(k))) return std::nullopt;
    return log;
  }
  /// Throws InputError naming the manifest unless it is this build's.
  void check_manifest() const;
  /// Throws what opening or verifying the first bad shard file throws, or FormatError naming it
  /// when its settings are not its own.
  void verify_shards() const;
};

void ShardedLibraryBuild::Impl::check_manifest() const {
  const std::filesystem::path path = manifest_file();
  const std::string advice =
      "; resume with the same inputs and options, or remove " + folder.string() + " to start again";
  if (!std::filesystem::exists(path))
    throw InputError(path.string() + ": missing, so the folder holds no build to resume" + advice);
  std::istringstream found(io::read_input_file(path)), expected(manifest());
  std::string was, now;
  for (std::size_t number = 1;; ++number) {
    const bool more_found = static_cast<bool>(std::getline(found, was));
    const bool more_expected = static_cast<bool>(std::getline(expected, now));
    if (!more_found && !more_expected) return;
    if (more_found && more_expected && was == now) continue;
    throw InputError(path.string() + ":" + std::to_string(number) +
                     ": records another build's inputs or options ('" + (more_found ? was : "") +
                     "' where this build has '" + (more_expected ? now : "") + "')" + advice);
  }
}

void ShardedLibraryBuild::Impl::verify_shards() const {
  // The shards are checked in parallel; the first bad one in shard order is reported.
  std::vector<std::exception_ptr> errors(count);
  tbb::parallel_for(std::size_t{0}, count, [&](std::size_t k) {
    const std::filesystem::path path = library_file(k);
    if (!std::filesystem::exists(path)) return;
    try {
      const Library shard(path);
      // A shard of an earlier format (whole structures in its site entries) is not mixed in.
      if (shard.version() != library_format_version) {
        throw FormatError(path.string(), "format version " + std::to_string(shard.version()) +
                                             ", written by an earlier surfcomp; remove " +
                                             folder.string() + " to build again");
      }
      if (shard.shards() != 1 || shard.settings() != shard_settings(k)) {
        throw FormatError(path.string(), "its settings are not those of shard " +
                                             std::to_string(k + 1) + " of this build");
      }
      shard.verify();
    } catch (...) {
      errors[k] = std::current_exception();
    }
  });
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

void ShardedLibraryBuild::Impl::plan(BuildItems items_) {
  check_options(options);
  items = std::move(items_);
  if (items.count == 0)
    throw InputError(output.string() + ": no " + items.noun + " to build it from");
  folder = shard_folder(output);
  settings = items.settings;
  count = (items.count + options.shard_records - 1) / options.shard_records;
  if (count == 1) return;  // one library file: no shard to name
  hashes.resize(count);
  tbb::parallel_for(std::size_t{0}, count,
                    [&](std::size_t k) { hashes[k] = input_hash(items, begin(k), end(k)); });
}

ShardedLibraryBuild::ShardedLibraryBuild(const std::vector<io::MoleculeRecord>& records,
                                         std::filesystem::path output, LibraryBuildOptions options)
    : impl_(std::make_unique<Impl>(std::move(output), std::move(options))) {
  impl_->plan(record_items(records, impl_->options));
}

ShardedLibraryBuild::~ShardedLibraryBuild() = default;

std::size_t ShardedLibraryBuild::shards() const { return impl_->count; }

const std::filesystem::path& ShardedLibraryBuild::folder() const { return impl_->folder; }

void ShardedLibraryBuild::prepare() {
  namespace fs = std::filesystem;
  Impl& m = *impl_;
  if (!fs::exists(m.folder)) {
    std::error_code error;
    if (!fs::create_directory(m.folder, error) && error) {
      throw FileError(m.folder.string(),
                      "cannot create the folder of the shards (" + error.message() + ")");
    }
    io::write_file_atomically(m.manifest_file(), [&](std::ostream& out) { out << m.manifest(); });
    return;
  }
  if (!m.options.resume) {
    throw FileError(m.folder.string(),
                    "the shard folder of an earlier build is in the way; continue that build "
                    "with " +
                        options::named("resume") + ", or remove the folder");
  }
  if (!fs::is_directory(m.folder)) throw FileError(m.folder.string(), "not a folder; remove it");
  m.check_manifest();
  m.verify_shards();
  for (std::size_t k = 0; k < m.count; ++k) {
    if (const std::optional<LibraryBuildResult> log = m.finished(k)) {
      ++m.resumed;
      m.resumed_entries += log->entries;
    }
  }
  for (const fs::directory_entry& item : fs::directory_iterator(m.folder)) {
    std::error_code ignored;
    if (item.is_regular_file() && io::is_temporary_file(item.path()))
      fs::remove(item.path(), ignored);
  }
}

LibraryBuildResult ShardedLibraryBuild::build(std::size_t rank, std::size_t ranks) {
  if (ranks == 0 || rank >= ranks)
    throw std::invalid_argument("ShardedLibraryBuild::build: rank outside [0, ranks)");
  const Impl& m = *impl_;
  const Stopwatch clock;
  std::vector<std::size_t> unfinished;
  std::size_t records = 0;
  for (std::size_t k = rank; k < m.count; k += ranks) {
    if (m.finished(k)) continue;
    unfinished.push_back(k);
    records += m.end(k) - m.begin(k);
  }
  LibraryBuildResult result;
  result.shards = m.count;
  for (const std::size_t k : unfinished) {
    LibraryBuildOptions options = m.options;
    if (m.options.progress) {
      options.progress = [&](const BuildProgress& p) {
        m.options.progress({result.records + p.records_done, records, result.entries + p.entries,
                            result.skipped.size() + p.skipped, clock.elapsed_s()});
      };
    }
    const std::filesystem::path file = m.library_file(k);
    const LibraryBuildResult shard =
        build_in_order(m.items, m.begin(k), m.end(k), file, m.shard_settings(k), options);
    io::write_file_atomically(m.log_file(k),
                              [&](std::ostream& out) { write_build_log(out, file, shard); });
    result.records += shard.records;
    result.entries += shard.entries;
    result.bytes += shard.bytes;
    result.skipped.insert(result.skipped.end(), shard.skipped.begin(), shard.skipped.end());
    result.times.conformers += shard.times.conformers;
    result.times.entries += shard.times.entries;
  }
  result.seconds = clock.elapsed_s();
  return result;
}

LibraryBuildResult ShardedLibraryBuild::finish() const {
  const Impl& m = *impl_;
  LibraryBuildResult result;
  result.records = m.items.count;
  result.shards = m.count;
  result.shards_resumed = m.resumed;
  result.entries_resumed = m.resumed_entries;
  std::vector<std::filesystem::path> listed;
  for (std::size_t k = 0; k < m.count; ++k) {
    const std::optional<LibraryBuildResult> log = m.finished(k);
    if (!log) {
      throw FileError(m.log_file(k).string(), "shard " + std::to_string(k + 1) + " of " +
                                                  std::to_string(m.count) + " is not finished");
    }
    result.entries += log->entries;
    result.skipped.insert(result.skipped.end(), log->skipped.begin(), log->skipped.end());
    if (log->entries > 0) listed.push_back(m.folder.filename() / m.library_file(k).filename());
  }
  if (result.entries == 0) return result;
  write_library_index(m.output, listed, m.settings);
  result.bytes = std::filesystem::file_size(m.output);
  for (const std::filesystem::path& shard : listed)
    result.bytes += std::filesystem::file_size(m.output.parent_path() / shard);
  return result;
}

LibraryBuildResult ShardedLibraryBuild::run() {
  Impl& m = *impl_;
  if (m.count == 1)
    return build_in_order(m.items, 0, m.items.count, m.output, m.settings, m.options);
  const Stopwatch clock;
  prepare();
  const LibraryBuildResult built = build();
  LibraryBuildResult result = finish();
  result.times = built.times;
  result.seconds = clock.elapsed_s();
  return result;
}

std::vector<SiteRequest> read_site_list(const std::filesystem::path& list) {
  const std::string text = io::read_input_file(list);
  std::vector<SiteRequest> sites;
  std::istringstream lines(text);
  std::string line;
  for (std::size_t number = 1; std::getline(lines, line); ++number) {
    std::istringstream fields(line);
    std::vector<std::string> words;
    for (std::string word; fields >> word;) words.push_back(word);
    if (words.empty() || words.front().front() == '#') continue;
    const std::string where = list.string() + ":" + std::to_string(number) + ": ";
    if (words.size() < 2) {
      throw InputError(where +
                       "expected 'STRUCTURE LIGAND [CHAIN]', 'STRUCTURE x,y,z,r [x,y,z,r ...]' or "
                       "'STRUCTURE pocket N'");
    }
    SiteRequest site;
    site.line = number;
    site.structure = words[0];
    if (site.structure.is_relative()) site.structure = list.parent_path() / site.structure;
    const std::string stem = io::structure_stem(words[0]);
    if (residue_key(words[1]) == "POCKET") {  // no residue name is six letters long
      char* end = nullptr;
      const long rank = words.size() == 3 ? std::strtol(words[2].c_str(), &end, 10) : 0;
      if (words.size() != 3 || end == words[2].c_str() || *end != '\0' || rank < 1 ||
          rank > 1000000) {
        throw InputError(where + "expected 'STRUCTURE pocket N' with N a pocket rank >= 1");
      }
      site.pocket_rank = static_cast<int>(rank);
      site.pocket = true;
      site.name = stem + ":pocket" + std::to_string(rank);
    } else if (words[1].find(',') != std::string::npos) {
      for (std::size_t w = 1; w < words.size(); ++w) {
        const std::optional<molsurf::SiteSphere> sphere = molsurf::parse_site_sphere(words[w]);
        if (!sphere) {
          throw InputError(where + "'" + words[w] + "' is not a sphere x,y,z,r with r > 0 (A)");
        }
        site.spheres.push_back(*sphere);
      }
      site.name = stem + ":spheres" + std::to_string(number);
    } else {
      if (words.size() > 3) {
        throw InputError(where + "expected 'STRUCTURE LIGAND [CHAIN]', got " +
                         std::to_string(words.size()) + " fields");
      }
      site.ligand = LigandSelector{words[1], {}, {}};
      site.name = stem + ":" + words[1];
      if (words.size() == 3) {
        site.ligand->chain = words[2];
        site.name += ":" + words[2];
      }
    }
    sites.push_back(std::move(site));
  }
  if (sites.empty()) throw FileError(list.string(), "lists no site");
  return sites;
}

std::vector<std::filesystem::path> structure_files(
    const std::vector<std::filesystem::path>& inputs) {
  std::vector<std::filesystem::path> files;
  for (const std::filesystem::path& input : inputs) {
    if (std::filesystem::is_directory(input)) {
      std::vector<std::filesystem::path> inside;
      for (const auto& item : std::filesystem::directory_iterator(input)) {
        if (item.is_regular_file() && io::is_structure_file(item.path()))
          inside.push_back(item.path());
      }
      std::sort(inside.begin(), inside.end());
      files.insert(files.end(), inside.begin(), inside.end());
    } else if (io::is_structure_file(input)) {
      files.push_back(input);
    } else {
      throw InputError(input.string() +
                       ": not a structure file (.pdb .ent .cif .mmcif .cif.gz) nor a directory");
    }
  }
  if (files.empty()) {
    std::string names;
    for (const std::filesystem::path& input : inputs)
      names += (names.empty() ? "" : ", ") + input.string();
    throw FileError(names,
                    inputs.size() == 1 ? "holds no structure file" : "hold no structure file");
  }
  return files;
}

namespace {

/// The entry of site `request` on `structure`, read from request.structure (for a pocket, its
/// pocket_structure).
LibraryEntry site_entry(const Molecule& structure, const SiteRequest& request,
                        const LibraryBuildOptions& options) {
  molsurf::BindingSite site = request.ligand
                                  ? molsurf::binding_site(structure, *request.ligand, options.site)
                                  : molsurf::binding_site(structure, request.spheres, options.site);
  const harmonic::DescriptorOptions describing;
  site.surface_margin = molsurf::site_surface_margin(site.surface_margin, describing.patch.radius);
  // The entry keeps the site's neighbourhood, not the structure (a margin of 0 keeps every atom),
  // and is built from that text read back, as the screen will read it.
  LibraryEntry entry;
  entry.molecule.source = request.structure;
  entry.molecule.record = request.line;
  entry.molecule.name = request.name;
  entry.molecule.format = io::RecordFormat::structure;
  std::ostringstream pdb;
  io::write_pdb(
      site.surface_margin == 0.0
          ? site.structure
          : molsurf::site_neighbourhood(site.structure, site.spheres,
                                        site.surface_margin + molsurf::neighbourhood_beyond_margin),
      pdb);
  entry.molecule.text = pdb.str();
  entry.info.heavy_atoms = heavy_atom_count(site.structure);
  site.structure = io::read_record_molecule(entry.molecule, site_entry_read_options(options.read));
  const harmonic::SurfaceDescriptors described = matching::describe_site(
      molsurf::build_site_surface(site, options.surface), site.structure, site.spheres, describing);
  const std::vector<bool> in_site = matching::critical_points_in_site(described, site.spheres);
  const std::vector<bool> lining =
      matching::pocket_lining(described, &in_site, options.lining_radius);
  entry.info.name = request.name;
  entry.info.source = request.structure.string();
  entry.info.record = static_cast<std::uint32_t>(request.line);
  entry.info.site_spheres = static_cast<std::uint32_t>(site.spheres.size());
  entry.sample = matching::sample_surface(described.surface, options.spacing, &lining);
  if (entry.sample.size() == 0)
    throw InputError(request.name + ": the site's pocket lining has no vertex");
  entry.kind = matching::SampleKind::surface;
  entry.packed = matching::PackedSample(entry.sample, entry.atoms, options.sigma, entry.kind);
  entry.site = std::move(site.spheres);
  return entry;
}

/// The settings lines a pocket library adds to build_settings: the structures' pLDDT cut and,
/// when pockets are detected, how (a resumed build must detect them the same way).
std::string site_settings(const LibraryBuildOptions& options, bool detects_pockets) {
  std::ostringstream text;
  text << "min_plddt " << options.read.min_plddt << "\n";
  if (detects_pockets) {
    const molsurf::PocketOptions& p = options.pockets;
    text << "pockets (min_sphere_radius " << p.min_sphere_radius << ", max_sphere_radius "
         << p.max_sphere_radius << ", min_buriedness " << p.min_buriedness << ", buried_distance "
         << p.buried_distance << ", cluster_distance " << p.cluster_distance << ", min_spheres "
         << p.min_spheres << ", max_volume " << p.max_volume << ")\n";
  }
  return text.str();
}

/// The items of a pocket library from a site list: one per site.
BuildItems site_items(const std::vector<SiteRequest>& sites, const LibraryBuildOptions& options) {
  BuildItems items;
  items.count = sites.size();
  items.build = [&sites, &options](std::size_t i, BuildTimes& times, std::vector<SkippedRecord>&) {
    const Stopwatch clock;
    std::vector<LibraryEntry> entries{build_site_entry(sites[i], options)};
    times.entries += clock.elapsed_s();
    return entries;
  };
  items.origin = [&sites](std::size_t i) {
    return ItemOrigin{sites[i].structure.string(), sites[i].line, sites[i].name};
  };
  items.identity = [&sites](std::size_t i, io::BinaryWriter& bytes) {
    const SiteRequest& site = sites[i];
    file_identity(site.structure, bytes);
    bytes.u64(site.line);
    bytes.string(site.name);
    bytes.string(site.ligand ? site.ligand->residue_name + ":" + site.ligand->chain.value_or("")
                             : "");
    for (const molsurf::SiteSphere& sphere : site.spheres) {
      bytes.f64(sphere.center.x());
      bytes.f64(sphere.center.y());
      bytes.f64(sphere.center.z());
      bytes.f64(sphere.radius);
    }
  };
  const bool detects_pockets = std::any_of(
      sites.begin(), sites.end(), [](const SiteRequest& site) { return site.pocket_rank > 0; });
  items.settings = build_settings(options, true) + site_settings(options, detects_pockets);
  items.noun = "site";
  return items;
}

/// The items of a pocket library of structures: one per structure, an entry per pocket
/// detect_pockets finds in it (built in parallel). A structure without a pocket fails as an item;
/// a pocket whose entry cannot be built is skipped alone (record: its rank).
BuildItems pocket_items(const std::vector<std::filesystem::path>& structures,
                        const LibraryBuildOptions& options) {
  BuildItems items;
  items.count = structures.size();
  items.build = [&structures, &options](std::size_t i, BuildTimes& times,
                                        std::vector<SkippedRecord>& skipped) {
    const Stopwatch clock;
    const std::filesystem::path& file = structures[i];
    const Molecule structure = molsurf::pocket_structure(io::read_molecule(file, options.read));
    std::vector<molsurf::Pocket> pockets = molsurf::detect_pockets(structure, options.pockets);
    if (pockets.empty()) throw InputError("no pocket found");
    const double detection_seconds = clock.elapsed_s();
    const std::string stem = io::structure_stem(file);
    std::vector<SiteRequest> requests(pockets.size());
    std::vector<std::optional<LibraryEntry>> built(pockets.size());
    std::vector<std::string> errors(pockets.size());
    std::vector<double> seconds(pockets.size(), 0.0);
    tbb::parallel_for(std::size_t{0}, pockets.size(), [&](std::size_t k) {
      const Stopwatch pocket_clock;
      SiteRequest& request = requests[k];
      request.line = static_cast<std::size_t>(pockets[k].rank);
      request.structure = file;
      request.spheres = std::move(pockets[k].spheres);
      request.name = stem + ":pocket" + std::to_string(pockets[k].rank);
      request.pocket = true;
      try {
        built[k] = site_entry(structure, request, options);
      } catch (const std::bad_alloc&) {
        errors[k] = "out of memory";
      } catch (const std::exception& e) {
        errors[k] = one_line(e.what());
      }
      seconds[k] = pocket_clock.elapsed_s();
    });
    std::vector<LibraryEntry> entries;
    for (std::size_t k = 0; k < built.size(); ++k) {
      if (built[k]) {
        entries.push_back(std::move(*built[k]));
      } else {
        skipped.push_back({file.string(), requests[k].line, requests[k].name, errors[k]});
      }
    }
    if (entries.empty()) throw InputError("no pocket's entry could be built (" + errors[0] + ")");
    // The detection's time, then each pocket's: core time, as the other builds count it.
    times.entries += detection_seconds + std::accumulate(seconds.begin(), seconds.end(), 0.0);
    return entries;
  };
  items.origin = [&structures](std::size_t i) {
    return ItemOrigin{structures[i].string(), 0, io::structure_stem(structures[i])};
  };
  items.identity = [&structures](std::size_t i, io::BinaryWriter& bytes) {
    file_identity(structures[i], bytes);
  };
  items.settings = build_settings(options, true) + site_settings(options, true);
  items.noun = "structure";
  return items;
}

void check_site_options(const LibraryBuildOptions& options) {
  if (options.conformers)
    throw OptionError(options::named("conformers") + " does not apply to sites or pockets");
}

}  // namespace

ShardedLibraryBuild::ShardedLibraryBuild(const std::vector<SiteRequest>& sites,
                                         std::filesystem::path output, LibraryBuildOptions options)
    : impl_(std::make_unique<Impl>(std::move(output), std::move(options))) {
  check_site_options(impl_->options);
  impl_->plan(site_items(sites, impl_->options));
}

ShardedLibraryBuild::ShardedLibraryBuild(const PocketStructures& structures,
                                         std::filesystem::path output, LibraryBuildOptions options)
    : impl_(std::make_unique<Impl>(std::move(output), std::move(options))) {
  check_site_options(impl_->options);
  impl_->plan(pocket_items(structures.files, impl_->options));
}

LibraryEntry build_site_entry(const SiteRequest& request, const LibraryBuildOptions& options) {
  Molecule structure = io::read_molecule(request.structure, options.read);
  if (request.pocket_rank > 0) {
    SiteRequest found = request;
    found.spheres =
        molsurf::pocket_site(structure, request.pocket_rank, options.pockets, options.site).spheres;
    return site_entry(molsurf::pocket_structure(structure), found, options);
  }
  if (request.pocket) structure = molsurf::pocket_structure(structure);
  return site_entry(structure, request, options);
}

LibraryBuildResult build_site_library(const std::vector<SiteRequest>& sites,
                                      const std::filesystem::path& output,
                                      const LibraryBuildOptions& options) {
  return ShardedLibraryBuild(sites, output, options).run();
}

LibraryBuildResult build_pocket_library(const PocketStructures& structures,
                                        const std::filesystem::path& output,
                                        const LibraryBuildOptions& options) {
  return ShardedLibraryBuild(structures, output, options).run();
}

}  // namespace surfcomp::screening
