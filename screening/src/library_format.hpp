// The screening library's file format (src/ only, not installed), version library_format_version:
// a header, the entries' records and packed samples, an index and a trailer with checksums,
// read in place through a read-only mapping; and a sharded library's index of its shards.
// library_format.cpp encodes and decodes it, library_writer.cpp writes it, library.cpp opens a
// library file or a sharded library.
#pragma once

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/binary_stream.hpp"
#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/screening/library.hpp"

#include <Eigen/Core>

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace surfcomp::screening::library_format {

inline constexpr char kMagic[] = "SURFCLIB";
inline constexpr char kEndMagic[] = "SCLIBEND";
inline constexpr std::size_t kMagicBytes = 8;
inline constexpr std::size_t kHeaderBytes = 16;   // magic, version, reserved
inline constexpr std::size_t kTrailerBytes = 32;  // index offset, size, checksum, end magic

inline constexpr std::size_t kSampleAlignment = 64;
inline constexpr std::size_t kPackedHeaderBytes = 192;

/// Molecule format code of a PDB text stored compressed (format 5).
inline constexpr std::uint8_t kCompressedStructure = 4;

inline constexpr char kIndexMagic[] = "SURFCSET";
inline constexpr char kIndexEndMagic[] = "SCSETEND";
inline constexpr std::size_t kIndexTrailerBytes = 16;  // body checksum, end magic

/// The format's code in an entry's record. Throws InputError for a record without coordinates
/// (SMILES) or a .hsi file's (stored as its atoms' MDL block).
std::uint8_t format_code(io::RecordFormat format);

/// `value` as 32 bits. Throws InputError naming `what` when it does not fit.
std::uint32_t narrow32(std::size_t value, const char* what);

/// `bytes` rounded up to a multiple of kSampleAlignment.
std::size_t aligned(std::size_t bytes);

/// The record of an entry (format 5): the molecule, the site spheres, the described surface. A
/// structure's PDB text, a site's neighbourhood, is stored compressed: a fifth of its size.
std::vector<std::uint8_t> encode_record(const LibraryEntry& entry);

/// The bytes of a packed sample (format 4): its header, padded to kPackedHeaderBytes, the nine
/// arrays, the heteroatoms, zeros to a multiple of kSampleAlignment.
std::vector<std::uint8_t> encode_packed(const matching::PackedSampleView& v);

/// The packed sample of an entry: its own, or `sample` and `atoms` packed at `sigma`.
matching::PackedSample packed_of(const LibraryEntry& entry, double sigma);

/// Writes `bytes` to `out` as they are.
void write_bytes(std::ostream& out, const std::vector<std::uint8_t>& bytes);

/// The next double matrix of `r`, which must be 3 x `columns` and finite (else r.fail naming
/// `what`).
Eigen::Matrix3Xd three_rows(io::BinaryReader& r, Eigen::Index columns, const char* what);

/// The next doubles of `r`, which must be `size` finite values (else r.fail naming `what`).
Eigen::VectorXd vector_of(io::BinaryReader& r, Eigen::Index size, const char* what);

/// A file mapped read-only into memory, unmapped when destroyed.
class MappedFile {
 public:
  /// Maps `path`. Throws FileError when it is missing, unreadable or not a regular file, and
  /// FormatError when it is shorter than any library (kHeaderBytes + kTrailerBytes).
  explicit MappedFile(const std::filesystem::path& path);
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  ~MappedFile() {
    if (data_ != nullptr) ::munmap(const_cast<std::uint8_t*>(data_), size_);
  }
  const std::uint8_t* data() const { return data_; }
  std::size_t size() const { return size_; }
  /// Drops the resident pages wholly inside bytes [from, to) of the file (MADV_DONTNEED on the
  /// read-only mapping): they are read again from the file if touched again.
  void release(std::uint64_t from, std::uint64_t to) const {
    static const auto page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
    const std::uint64_t first_page = (from + page - 1) / page * page;  // the mapping starts on one
    const std::uint64_t end_page = std::min<std::uint64_t>(to, size_) / page * page;
    if (first_page < end_page) {
      ::madvise(const_cast<std::uint8_t*>(data_) + first_page, end_page - first_page,
                MADV_DONTNEED);
    }
  }

 private:
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

/// One library file (format 1 to 4), mapped, its header, index and trailer checked: a whole
/// library, or one shard of a sharded library whose entries begin at the library's entry
/// `first`. Entries are numbered within the file; messages give the library's numbers.
struct LibraryFile {
  LibraryFile(std::filesystem::path path_, std::size_t first_)
      : path(std::move(path_)), file(path), first(first_) {
    read_index();
  }

  std::filesystem::path path;
  MappedFile file;
  std::size_t first = 0;
  std::uint32_t version = 0;
  std::string settings;
  std::uint64_t index_checksum = 0;  // the trailer's
  std::vector<LibraryEntryInfo> infos;
  std::vector<std::uint64_t> offsets, sizes, checksums;  // of the entries (records in format 4)
  std::vector<std::uint64_t> sample_offsets, sample_sizes, sample_checksums;  // format 4

  std::size_t size() const { return infos.size(); }
  [[noreturn]] void fail(const std::string& reason) const {
    throw FormatError(path.string(), reason);
  }
  std::string where(std::size_t index) const {
    return "entry " + std::to_string(first + index + 1) + " (" + infos[index].name + ")";
  }
  void read_index();
  /// Format 4: entry `index`'s packed sample in place, its checksum and sizes checked.
  matching::PackedSampleView sample_view(std::size_t index) const;
  /// The entry's record decoded; for formats 1 to 3 also its sample and atoms.
  LibraryEntry decode_entry(std::size_t index) const;
  /// Checks entry `index`'s record (and format 4's sample) against its checksum.
  void verify(std::size_t index) const;
  /// MADV_DONTNEED on the pages wholly inside the records and samples of entries [begin, end).
  void release(std::size_t begin, std::size_t end) const;
};

}  // namespace surfcomp::screening::library_format
