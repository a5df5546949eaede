// Screening libraries (.sclib): many molecules' conformers (or many binding sites), each entry
// holding what the first two stages of a screen read (the overlay's surface sample, packed in
// single precision with its self-overlaps, and the heteroatoms) and the molecule itself, from
// which the last stage rebuilds the surface of a finalist; a site entry also holds its spheres, an
// entry made from a .hsi file its surface. A library of meshes holds one general mesh an entry
// (its surface, no molecule), screened by shape (shape_screen.hpp). A library is one file, or an
// index of shards.
//
// Layout of format 5 (little-endian, core/io/binary_stream.hpp encodings; docs/screening.md):
//   header   "SURFCLIB", u32 format version, u32 0
//   records  one per entry: the molecule (format: 0 MDL, 1 MOL2, 2 PDB, 3 none, a mesh entry,
//            4 PDB compressed with gzip; text), the site spheres, the bytes of a described
//            surface (LibraryEntry::surface)
//   samples  from a 64-byte boundary, one per entry, each on a 64-byte boundary: the packed
//            sample (matching::PackedSampleView: a 192-byte header, nine float arrays, the
//            heteroatoms), read in place by the first stage, in entry order
//   index    u64 count; per entry u64 record offset, size and checksum (FNV-1a 64), u64 sample
//            offset, size and checksum (XXH3 64), string name, string source, u32 record,
//            u32 conformer, u32 heavy atoms, u32 site spheres; string settings
//   trailer  u64 index offset, u64 index size, u64 index checksum, "SCLIBEND"
// Format 4 is format 5 without compressed PDB text. Formats 1 to 3 (one region of entries, each the
// molecule, the sample in double precision, the heteroatoms, from 2 the site spheres, from 3 a
// described surface; an index without the sample columns) are still read; their samples are packed
// when the first stage asks for them.
//
// A sharded library (a build of many records, library_build.hpp) is an index file listing
// format-5 library files (format 4 from earlier builds), its shards, whose entries follow each
// other in its order:
//   header   "SURFCSET", u32 index version, u32 0
//   body     u64 shard count; per shard string path (relative to the index's folder, '/'
//            separated), u64 entries, u64 file size, u64 the shard's index checksum (its
//            trailer's); string settings
//   trailer  u64 checksum of the body (FNV-1a 64), "SCSETEND"
// The files are memory-mapped and entries are decoded on demand, by index or by name. A library
// file's index is decoded when it is opened (about 150 bytes an entry); a sharded library keeps
// only a few shards open, mapped with their index decoded, so that its memory does not grow with
// its entries.
#pragma once

#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/matching/packed_overlay.hpp"
#include "surfcomp/matching/site.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace surfcomp::screening {

/// The format version write_library writes; Library reads it and versions 1 to 4.
inline constexpr std::uint32_t library_format_version = 5;

/// The version of a sharded library's index that write_library_index writes and Library reads.
inline constexpr std::uint32_t library_index_version = 1;

/// How a site entry's structure text is read: `read` without its pLDDT cut, which the build
/// applied already (the text keeps no B-factors).
io::MoleculeReadOptions site_entry_read_options(io::MoleculeReadOptions read);

/// What the index says of an entry (it is read without decoding the entry).
struct LibraryEntryInfo {
  std::string name;                ///< the molecule's name (io::MoleculeRecord::name)
  std::string source;              ///< the input file it came from
  std::uint32_t record = 0;        ///< 1-based record of that file
  std::uint32_t conformer = 0;     ///< 1-based generated conformer; 0 = the record's coordinates
  std::uint32_t heavy_atoms = 0;   ///< atoms other than hydrogen (a site: of its structure)
  std::uint32_t site_spheres = 0;  ///< a binding site's spheres; 0 for a molecule
};

/// One library entry: a molecule in one conformation, or a binding site on a structure, and its
/// samples for the overlay.
struct LibraryEntry {
  LibraryEntryInfo info;
  /// The molecule with this conformer's coordinates: an MDL mol block (SDF records and
  /// generated conformers, hydrogens explicit for the latter), a MOL2 section or a PDB text.
  /// molecule.source, record and name repeat info.
  io::MoleculeRecord molecule;
  /// The surface sample and the heteroatoms (matching::sample_atoms; none for a site): for a
  /// molecule, matching::sample_molecule (kind atoms); for a site, matching::sample_surface of its
  /// pocket lining (matching::pocket_lining); for a .hsi file, of its surface (kind surface).
  /// Read from format 4, the packed single-precision values in double.
  matching::SurfaceSample sample;
  matching::AtomSample atoms;
  matching::SampleKind kind = matching::SampleKind::surface;
  /// The sample and atoms packed for the first stage. Empty (no points) in an entry being built
  /// until the writer packs it, unless its builder packed it already.
  matching::PackedSample packed;
  /// A binding site's spheres (molsurf::BindingSite::spheres); empty for a molecule. The
  /// molecule is then the site's structure (PDB text).
  std::vector<molsurf::SiteSphere> site;
  /// An entry made from a .hsi file: its surface and heavy atoms, encoded as a .hsi file
  /// without critical points (harmonic::io::encode_hsi), from which the last stage describes
  /// the entry instead of rebuilding a surface; `molecule` then holds only the heavy atoms (an
  /// MDL block without bonds, io::atoms_mol_block). An entry made from a mesh file: the mesh
  /// (its vertices, normals and triangles, in its own coordinates), encoded the same way
  /// without atoms; `molecule` is then an io::RecordFormat::mesh record without text. Empty
  /// for every other entry.
  std::vector<std::uint8_t> surface;
};

/// An entry's packed sample for the first stage: a view into the mapped file, or of a sample
/// packed on reading (formats 1 to 3, or a Gaussian width other than the stored one). Valid
/// while the library and this object live; move-only.
struct PackedEntry {
  matching::PackedSampleView view;
  std::unique_ptr<matching::PackedSample> owned;  ///< what `view` shows when not the file
  std::shared_ptr<const void> file;               ///< keeps the shard `view` points into mapped
};

/// Appends entries to a library being written to `out`; finish() writes the samples' region, the
/// index and the trailer. Entries keep the order they are added in. The samples wait in a
/// temporary file until finish().
class LibraryWriter {
 public:
  /// Writes the header. `settings` is free text stored in the index (how the library was
  /// built), shown by `surfcomp library info`; `sigma` the Gaussian width (A) entries' samples
  /// are packed with when they come unpacked. Throws FileError when no temporary file can be
  /// made.
  LibraryWriter(std::ostream& out, std::string settings,
                double sigma = matching::OverlayOptions{}.sigma);
  LibraryWriter(const LibraryWriter&) = delete;
  LibraryWriter& operator=(const LibraryWriter&) = delete;
  ~LibraryWriter();

  /// Encodes and writes `entry` (its packed sample, packing it first when empty). Throws
  /// InputError for an entry whose sample is empty or whose arrays differ in size, or whose
  /// text does not fit the format's 32-bit lengths.
  void add(const LibraryEntry& entry);
  /// Writes the index and the trailer; no entry may be added after it.
  void finish();
  /// Entries added so far.
  std::size_t size() const;
  /// Bytes written so far.
  std::uint64_t bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes `entries` as a library at `path`, atomically (io::write_file_atomically).
void write_library(const std::filesystem::path& path, const std::vector<LibraryEntry>& entries,
                   const std::string& settings = "",
                   double sigma = matching::OverlayOptions{}.sigma);

/// Writes at `path`, atomically, the index of a sharded library whose shards are the format-5
/// library files `shards` (paths relative to `path`'s folder, in entry order), with `settings`
/// (how the library was built, as a whole file stores them). Each shard is opened and checked
/// as Library opens a file, and listed with its entries, size and index checksum. Throws
/// InputError for no shard or a path that is not relative, and what Library throws for a shard
/// (naming it); `path` is then left as it was.
void write_library_index(const std::filesystem::path& path,
                         const std::vector<std::filesystem::path>& shards,
                         const std::string& settings);

/// A library opened for reading, one file or a sharded library's index and the shards it lists:
/// memory-mapped, a file's header, index and trailer checked on opening; entries are decoded (and
/// their checksums verified) when asked for. The entries of a sharded library are its shards'
/// entries in the index's order, numbered from 0 across the shards. A shard is opened (mapped, its
/// index decoded and checked) when one of its entries is read; at most a few stay open, the least
/// recently read closed first, and release() closes those a stream has passed. Thread-safe (a
/// shard being read stays mapped until its reader is done).
class Library {
 public:
  /// Opens and checks `path`, a library file or an index. Throws FileError (missing, unreadable,
  /// not a regular file) and FormatError naming the file for anything that is not a library of
  /// this version: a wrong magic, version, size or checksum, an index entry outside the entries'
  /// region. For an index, each shard is checked without reading its index, naming the shard:
  /// FileError for a missing one, FormatError for one whose size, entry count or index checksum
  /// (its trailer's) is not what the index lists (a cut, replaced or rebuilt shard) or whose
  /// format version is not 4. A shard's own index is checked when the shard is opened: the
  /// accessors below then throw FormatError naming it.
  explicit Library(const std::filesystem::path& path);
  Library(Library&&) noexcept;
  Library& operator=(Library&&) noexcept;
  ~Library();

  std::size_t size() const;  ///< entries
  /// What the index says of entry `index`; std::out_of_range for an index >= size().
  LibraryEntryInfo info(std::size_t index) const;
  /// Entry `index`, decoded. Throws FormatError naming the file and the entry when its bytes
  /// do not match their checksum or do not decode; std::out_of_range for an index >= size().
  LibraryEntry entry(std::size_t index) const;
  /// Entry `index`'s packed sample at Gaussian width `sigma` (A): in place for format 4 when it
  /// was packed at that width, else packed now. Checks the sample's checksum and sizes; throws
  /// as entry().
  PackedEntry packed(std::size_t index, double sigma) const;
  /// The encoded size of entry `index`, bytes.
  std::uint64_t entry_bytes(std::size_t index) const;
  /// The indices of the entries named `name`, in library order (empty when none is): a scan of
  /// the index, O(entries).
  std::vector<std::size_t> find(const std::string& name) const;

  /// Checks every entry's record and sample against their checksums, without decoding them:
  /// reads the whole library once. Throws FormatError naming the file (the shard) and the entry
  /// of the first that does not match.
  void verify() const;
  /// Tells the kernel that the pages of entries [begin, end) (their records and samples, the
  /// pages wholly inside those regions) are not needed for now: MADV_DONTNEED on the read-only
  /// mapping, so that a reader streaming through a library larger than memory, releasing what
  /// it has read, keeps its resident memory bounded; closes the shards whose last entry is in
  /// the range (a reader streaming in order is past them). The entries stay readable: a page
  /// touched again is read again from the file (or the page cache), a shard opened again; views
  /// from packed() stay valid. Throws std::out_of_range unless begin <= end <= size().
  void release(std::size_t begin, std::size_t end) const;

  /// The format version of the file, or of the shards of a sharded library (4).
  std::uint32_t version() const;
  /// The build settings stored in the file, or in the index of a sharded library.
  const std::string& settings() const;
  /// The bytes of the file, or of the index and every shard.
  std::uint64_t file_bytes() const;
  /// The path opened: the file, or the index.
  const std::filesystem::path& path() const;
  /// The files the entries are in: 1 for a library file, the shards an index lists.
  std::size_t shards() const;
  /// The shards open now (mapped, their index decoded), beyond those a PackedEntry keeps: 1 for
  /// a library file.
  std::size_t open_shards() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace surfcomp::screening
