// What the files of a library build share (src/ only, not installed): the items a build is made
// of, their build in order, the build's log and its input hashes. library_entries.cpp makes a
// record's entries, library_build_pipeline.cpp builds items in parallel and writes them in
// order, library_build_log.cpp reads and writes the log and hashes the inputs,
// library_sharded_build.cpp cuts a build into shards it can resume, and site_library.cpp makes
// the items of pocket libraries.
#pragma once

#include "surfcomp/core/io/binary_stream.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/screening/library_build.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace surfcomp::screening::detail {

/// Where item `index` of a build comes from, for the list of skipped items.
struct ItemOrigin {
  std::string source;
  std::size_t record = 0;
  std::string name;
};

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

/// Throws OptionError for build options outside their domain.
void check_build_options(const LibraryBuildOptions& options);

/// `text` on one line: line breaks become spaces.
std::string one_line(std::string text);

/// The number of atoms of `molecule` that are not hydrogens.
std::uint32_t heavy_atom_count(const Molecule& molecule);

/// Builds the entries of items [begin, end) in parallel and writes them in item order to
/// `output` atomically; an item whose build throws is skipped and listed.
LibraryBuildResult build_in_order(const BuildItems& items, std::size_t begin, std::size_t end,
                                  const std::filesystem::path& output, const std::string& settings,
                                  const LibraryBuildOptions& options);

/// The items of a build of molecule records: one per record, its entries build_entries'.
BuildItems record_items(const std::vector<io::MoleculeRecord>& records,
                        const LibraryBuildOptions& options);

/// The items of a pocket library from a site list: one per site.
BuildItems site_items(const std::vector<SiteRequest>& sites, const LibraryBuildOptions& options);

/// The items of a pocket library of structures: one per structure, an entry per pocket
/// detect_pockets finds in it (built in parallel). A structure without a pocket fails as an item;
/// a pocket whose entry cannot be built is skipped alone (record: its rank).
BuildItems pocket_items(const std::vector<std::filesystem::path>& structures,
                        const LibraryBuildOptions& options);

/// Throws OptionError for build options that do not apply to sites or pockets.
void check_site_options(const LibraryBuildOptions& options);

/// What a file is for an input hash: its path, size and modification time (its bytes are read
/// when it is built).
void file_identity(const std::filesystem::path& file, io::BinaryWriter& bytes);

/// What a build's log (write_build_log) says: records, entries and the skipped records. Throws
/// FileError when `path` cannot be read, FormatError naming it and the line for a line that is
/// not what write_build_log writes.
LibraryBuildResult read_build_log(const std::filesystem::path& path);

/// `value` as 16 lowercase hexadecimal digits.
std::string hex64(std::uint64_t value);

/// The 64-bit hash of what items [begin, end) are built from (BuildItems::identity).
std::uint64_t input_hash(const BuildItems& items, std::size_t begin, std::size_t end);

}  // namespace surfcomp::screening::detail
