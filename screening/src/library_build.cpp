#include "surfcomp/screening/library_build.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/overlay_sample.hpp"

#include <tbb/parallel_pipeline.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <utility>

namespace surfcomp::screening {
namespace {

void check_options(const LibraryBuildOptions& options) {
  if (!(options.spacing > 0.0) || !std::isfinite(options.spacing))
    throw OptionError("library spacing must be finite and > 0, got " +
                      std::to_string(options.spacing));
  if (options.batch < 1) throw OptionError("library build batch must be at least 1");
  if (options.conformers) {
    const ConformerOptions& c = *options.conformers;
    if (c.count < 1)
      throw OptionError("--conformers must be at least 1, got " + std::to_string(c.count));
    if (c.seed < 0) throw OptionError("--seed must be >= 0, got " + std::to_string(c.seed));
    if (c.mmff_iterations < 0) throw OptionError("MMFF iterations must be >= 0");
  }
}

std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

std::uint32_t heavy_atom_count(const Molecule& molecule) {
  return static_cast<std::uint32_t>(
      std::count_if(molecule.atoms.begin(), molecule.atoms.end(),
                    [](const Atom& atom) { return atom.element != "H"; }));
}

}  // namespace

std::vector<io::MoleculeRecord> read_library_inputs(
    const std::vector<std::filesystem::path>& inputs) {
  std::vector<io::MoleculeRecord> records;
  const auto append = [&](const std::filesystem::path& file) {
    std::vector<io::MoleculeRecord> read = io::read_molecule_records(file);
    records.insert(records.end(), std::make_move_iterator(read.begin()),
                   std::make_move_iterator(read.end()));
  };
  for (const std::filesystem::path& input : inputs) {
    if (std::filesystem::is_directory(input)) {
      std::vector<std::filesystem::path> files;
      for (const auto& item : std::filesystem::directory_iterator(input)) {
        if (item.is_regular_file() && io::is_record_file(item.path())) files.push_back(item.path());
      }
      std::sort(files.begin(), files.end());
      for (const auto& file : files) append(file);
    } else if (io::is_record_file(input)) {
      append(input);
    } else {
      throw InputError(input.string() +
                       ": not a molecule file or list (.sdf .mol .mol2 .pdb .ent .pqr .smi .dat "
                       ".dat.gz) nor a directory");
    }
  }
  return records;
}

std::vector<LibraryEntry> build_entries(const io::MoleculeRecord& record,
                                        const LibraryBuildOptions& options) {
  std::vector<io::MoleculeRecord> conformations;
  if (options.conformers) {
    for (std::string& block : generate_conformers(record, *options.conformers)) {
      io::MoleculeRecord conformer = record;
      conformer.format = io::RecordFormat::mdl;
      conformer.text = std::move(block);
      conformations.push_back(std::move(conformer));
    }
  } else if (record.format == io::RecordFormat::smiles) {
    throw InputError("a SMILES record has no coordinates: generate conformers (--conformers N)");
  } else if (record.format == io::RecordFormat::structure && record.text.empty()) {
    throw InputError("a PQR structure cannot go into a library (write it as PDB or SDF)");
  } else {
    conformations.push_back(record);
  }
  std::vector<LibraryEntry> entries;
  for (std::size_t c = 0; c < conformations.size(); ++c) {
    const Molecule molecule = io::read_record_molecule(conformations[c], options.read);
    const mesh::Surface surface = mesh::build_molecular_surface(molecule, options.surface);
    LibraryEntry entry;
    entry.info.name = record.name;
    entry.info.source = record.source.string();
    entry.info.record = static_cast<std::uint32_t>(record.record);
    entry.info.conformer = options.conformers ? static_cast<std::uint32_t>(c + 1) : 0;
    entry.info.heavy_atoms = heavy_atom_count(molecule);
    entry.molecule = std::move(conformations[c]);
    entry.sample = matching::sample_surface(surface, options.spacing);
    entry.atoms = matching::sample_atoms(harmonic::surface_atoms(molecule));
    entries.push_back(std::move(entry));
  }
  return entries;
}

std::string build_settings(const LibraryBuildOptions& options) {
  std::ostringstream text;
  if (options.conformers) {
    text << "conformers " << options.conformers->count << " (ETKDGv3 seed "
         << options.conformers->seed << ", MMFF94 " << options.conformers->mmff_iterations
         << " iterations)\n";
  } else {
    text << "conformers 0 (the records' coordinates)\n";
  }
  text << "spacing " << options.spacing << "\n";
  text << "probe_radius " << options.surface.ses.probe_radius << "\n";
  text << "vertex_density " << options.surface.ses.vertex_density << "\n";
  return text.str();
}

LibraryBuildResult build_library(const std::vector<io::MoleculeRecord>& records,
                                 const std::filesystem::path& output,
                                 const LibraryBuildOptions& options) {
  check_options(options);
  const Stopwatch clock;
  LibraryBuildResult result;
  result.records = records.size();
  // A pipeline: records go out in order, are built in parallel and are written in order, at
  // most options.batch of them in flight.
  struct Built {
    std::size_t index = 0;
    std::vector<LibraryEntry> entries;
    std::string error;
  };
  io::write_file_atomically(output, [&](std::ostream& out) {
    LibraryWriter writer(out, build_settings(options));
    std::size_t next = 0;
    tbb::parallel_pipeline(
        options.batch,
        tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                            [&](tbb::flow_control& control) -> std::size_t {
                                              if (next == records.size()) {
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
                    built->entries = build_entries(records[index], options);
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
                  const io::MoleculeRecord& record = records[built->index];
                  if (!built->error.empty()) {
                    result.skipped.push_back(
                        {record.source.string(), record.record, record.name, built->error});
                  } else {
                    for (const LibraryEntry& entry : built->entries) writer.add(entry);
                  }
                  if (options.progress) {
                    options.progress({built->index + 1, records.size(), writer.size(),
                                      result.skipped.size(), clock.elapsed_s()});
                  }
                }));
    writer.finish();
    result.entries = writer.size();
    result.bytes = writer.bytes();
  });
  result.seconds = clock.elapsed_s();
  return result;
}

}  // namespace surfcomp::screening
