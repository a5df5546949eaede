// Building a screening library from molecule files: each record read (or its conformers
// generated), its surface built and sampled as `surfcomp match` does, in parallel (TBB), the
// entries written in input order whatever the thread count.
#pragma once

#include "surfcomp/core/conformers.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/mesh/molecular_surface.hpp"
#include "surfcomp/screening/library.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace surfcomp::screening {

/// How far a build has come, for a progress line.
struct BuildProgress {
  std::size_t records_done = 0;
  std::size_t records = 0;
  std::size_t entries = 0;  ///< entries written so far
  std::size_t skipped = 0;  ///< records skipped so far
  double seconds = 0.0;     ///< since the build started
};

struct LibraryBuildOptions {
  /// Default none: each record's own coordinates make one entry (conformer 0). With a value,
  /// ETKDG + MMFF conformers (generate_conformers) make the entries; SMILES records need this.
  std::optional<ConformerOptions> conformers;
  /// How the molecules are read (charges, lipophilicity); default as `surfcomp match`.
  io::MoleculeReadOptions read;
  /// The surface built for each entry; default as `surfcomp match`.
  mesh::MolecularSurfaceOptions surface;
  /// Default OverlayOptions::spacing. Cell edge of the surface sample, A; a screen refuses a
  /// library sampled otherwise than its overlay. > 0.
  double spacing = matching::OverlayOptions{}.spacing;
  /// Default 64. Most records in flight (being built or waiting for their turn to be written):
  /// bounds the memory a build holds. >= 1.
  std::size_t batch = 64;
  /// Default none. Called after each record is written or skipped, one call at a time.
  std::function<void(const BuildProgress&)> progress;
};

/// A record the build left out, and why.
struct SkippedRecord {
  std::string source;
  std::size_t record = 0;
  std::string name;
  std::string reason;  ///< the error's message, one line
};

struct LibraryBuildResult {
  std::size_t records = 0;  ///< records read from the inputs
  std::size_t entries = 0;  ///< entries written
  std::uint64_t bytes = 0;  ///< size of the library file
  std::vector<SkippedRecord> skipped;
  double seconds = 0.0;
};

/// The records of `inputs` in order: each file's records (io::read_molecule_records); a
/// directory stands for the record files (io::is_record_file) directly inside it, in name order.
/// Throws as read_molecule_records, and InputError for a path that is neither.
std::vector<io::MoleculeRecord> read_library_inputs(
    const std::vector<std::filesystem::path>& inputs);

/// The entries of one record: its own coordinates, or its conformers, each with its surface
/// sample and heteroatoms. Throws what reading the record, generating its conformers or
/// building a surface throws (surfcomp::Error).
std::vector<LibraryEntry> build_entries(const io::MoleculeRecord& record,
                                        const LibraryBuildOptions& options = {});

/// The `settings` text a build with `options` stores in its library.
std::string build_settings(const LibraryBuildOptions& options);

/// Builds the entries of every record (in parallel, TBB) and writes them, in record order then
/// conformer order, to `output` atomically: an interrupted or failed build leaves no file
/// there. A record whose entries cannot be built is skipped and listed in the result; the build
/// goes on. The file's bytes do not depend on the thread count. Throws OptionError for options
/// outside their domain (before any work), FileError when `output` cannot be written.
LibraryBuildResult build_library(const std::vector<io::MoleculeRecord>& records,
                                 const std::filesystem::path& output,
                                 const LibraryBuildOptions& options = {});

}  // namespace surfcomp::screening
