#include "surfcomp/screening/library.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/binary_stream.hpp"
#include "surfcomp/core/io/input_file.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace surfcomp::screening {
namespace {

constexpr char kMagic[] = "SURFCLIB";
constexpr char kEndMagic[] = "SCLIBEND";
constexpr std::size_t kMagicBytes = 8;
constexpr std::size_t kHeaderBytes = 16;   // magic, version, reserved
constexpr std::size_t kTrailerBytes = 32;  // index offset, size, checksum, end magic

std::uint8_t format_code(io::RecordFormat format) {
  switch (format) {
    case io::RecordFormat::mdl:
      return 0;
    case io::RecordFormat::mol2:
      return 1;
    case io::RecordFormat::structure:
      return 2;
    case io::RecordFormat::mesh:
      return 3;
    case io::RecordFormat::descriptors:
      throw InputError("a library entry from a .hsi file stores its atoms as an MDL block");
    case io::RecordFormat::smiles:
      break;
  }
  throw InputError("a library entry needs a molecule with coordinates, not a SMILES string");
}

std::uint32_t narrow32(std::size_t value, const char* what) {
  if (value > std::numeric_limits<std::uint32_t>::max())
    throw InputError(std::string("library entry: ") + what + " too large for the format");
  return static_cast<std::uint32_t>(value);
}

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "format 4 samples are read in place as little-endian floats");

constexpr std::size_t kSampleAlignment = 64;
constexpr std::size_t kPackedHeaderBytes = 192;

std::size_t aligned(std::size_t bytes) {
  return (bytes + kSampleAlignment - 1) / kSampleAlignment * kSampleAlignment;
}

/// Molecule format code of a PDB text stored compressed (format 5).
constexpr std::uint8_t kCompressedStructure = 4;

/// The record of an entry (format 5): the molecule, the site spheres, the described surface. A
/// structure's PDB text, a site's neighbourhood, is stored compressed: a fifth of its size.
std::vector<std::uint8_t> encode_record(const LibraryEntry& entry) {
  narrow32(entry.molecule.text.size(), "molecule text");
  io::BinaryWriter w;
  const bool compressed =
      entry.molecule.format == io::RecordFormat::structure && !entry.molecule.text.empty();
  w.u8(compressed ? kCompressedStructure : format_code(entry.molecule.format));
  w.string(compressed ? io::gzip(entry.molecule.text) : entry.molecule.text);
  w.u64(entry.site.size());
  for (const molsurf::SiteSphere& sphere : entry.site) {
    for (int k = 0; k < 3; ++k) w.f64(sphere.center(k));
    w.f64(sphere.radius);
  }
  w.blob(entry.surface);
  return w.bytes();
}

/// The bytes of a packed sample (format 4): its header, padded to kPackedHeaderBytes, the nine
/// arrays, the heteroatoms, zeros to a multiple of kSampleAlignment.
std::vector<std::uint8_t> encode_packed(const matching::PackedSampleView& v) {
  const matching::PackedHeader& h = v.header;
  io::BinaryWriter w;
  w.u32(h.points);
  w.u32(h.atoms);
  w.u8(static_cast<std::uint8_t>(h.kind));
  w.zeros(7);
  for (int k = 0; k < 3; ++k) w.f64(h.centroid(k));
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) w.f64(h.axes(r, c));
  }
  for (const double value : {h.self_shape, h.self_esp, h.self_lp, h.squares_esp, h.squares_lp,
                             h.squares_weight, h.atom_self, h.sigma})
    w.f64(value);
  w.zeros(kPackedHeaderBytes - w.bytes().size());
  for (std::size_t k = 0; k < 9 * v.padded_points(); ++k) w.f32(v.arrays[k]);
  for (std::size_t k = 0; k < std::size_t{3} * h.atoms; ++k) w.f32(v.atom_points[k]);
  for (std::size_t k = 0; k < h.atoms; ++k) w.u32(v.atom_elements[k]);
  w.zeros(aligned(w.bytes().size()) - w.bytes().size());
  return w.bytes();
}

/// The packed sample of an entry: its own, or `sample` and `atoms` packed at `sigma`.
matching::PackedSample packed_of(const LibraryEntry& entry, double sigma) {
  const matching::SurfaceSample& s = entry.sample;
  const auto n = static_cast<Eigen::Index>(s.size());
  if (entry.packed.header().points > 0) return entry.packed;
  if (n == 0) throw InputError("library entry " + entry.info.name + ": its sample is empty");
  if (s.normals.cols() != n || s.weights.size() != n || s.esp.size() != n || s.lp.size() != n ||
      static_cast<std::size_t>(entry.atoms.points.cols()) != entry.atoms.size()) {
    throw InputError("library entry " + entry.info.name + ": its sample's arrays differ in size");
  }
  return matching::PackedSample(s, entry.atoms, sigma, entry.kind);
}

void write_bytes(std::ostream& out, const std::vector<std::uint8_t>& bytes) {
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

Eigen::Matrix3Xd three_rows(io::BinaryReader& r, Eigen::Index columns, const char* what) {
  const Eigen::MatrixXd m = r.double_matrix();
  if (m.rows() != 3 || m.cols() != columns) {
    r.fail(std::string(what) + " is " + std::to_string(m.rows()) + " x " +
           std::to_string(m.cols()) + ", expected 3 x " + std::to_string(columns));
  }
  if (!m.allFinite()) r.fail(std::string(what) + " holds a value that is not finite");
  return m;
}

Eigen::VectorXd vector_of(io::BinaryReader& r, Eigen::Index size, const char* what) {
  Eigen::VectorXd v = r.doubles();
  if (v.size() != size) {
    r.fail(std::string(what) + " holds " + std::to_string(v.size()) + " values, expected " +
           std::to_string(size));
  }
  if (!v.allFinite()) r.fail(std::string(what) + " holds a value that is not finite");
  return v;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

struct LibraryWriter::Impl {
  std::ostream* out = nullptr;
  std::string settings;
  double sigma = 1.0;
  std::uint64_t offset = 0;        // bytes written to `out`
  std::FILE* samples = nullptr;    // the samples' region, until finish()
  std::uint64_t samples_size = 0;  // bytes in it
  /// Per entry: record offset, size, checksum, sample offset (in the region), size, checksum.
  std::vector<std::array<std::uint64_t, 6>> places;
  io::BinaryWriter names;  // per entry: name, source, record, conformer, heavy atoms, spheres
  bool finished = false;

  ~Impl() {
    if (samples != nullptr) std::fclose(samples);
  }
};

LibraryWriter::LibraryWriter(std::ostream& out, std::string settings, double sigma)
    : impl_(std::make_unique<Impl>()) {
  impl_->out = &out;
  impl_->settings = std::move(settings);
  impl_->sigma = sigma;
  impl_->samples = std::tmpfile();
  if (impl_->samples == nullptr)
    throw FileError("<temporary file>", "cannot create one for the library's samples");
  io::BinaryWriter header;
  for (std::size_t i = 0; i < kMagicBytes; ++i) header.u8(static_cast<std::uint8_t>(kMagic[i]));
  header.u32(library_format_version);
  header.u32(0);
  write_bytes(out, header.bytes());
  impl_->offset = kHeaderBytes;
}

LibraryWriter::~LibraryWriter() = default;

void LibraryWriter::add(const LibraryEntry& entry) {
  if (impl_->finished) throw std::logic_error("LibraryWriter::add after finish");
  const std::vector<std::uint8_t> record = encode_record(entry);
  const matching::PackedSample packed = packed_of(entry, impl_->sigma);
  const std::vector<std::uint8_t> sample = encode_packed(packed.view());
  write_bytes(*impl_->out, record);
  if (std::fwrite(sample.data(), 1, sample.size(), impl_->samples) != sample.size())
    throw FileError("<temporary file>", "cannot write the library's samples (disk full?)");
  impl_->places.push_back({impl_->offset, record.size(), io::fnv1a64(record.data(), record.size()),
                           impl_->samples_size, sample.size(),
                           io::xxh3_64(sample.data(), sample.size())});
  io::BinaryWriter& x = impl_->names;
  x.string(entry.info.name);
  x.string(entry.info.source);
  x.u32(entry.info.record);
  x.u32(entry.info.conformer);
  x.u32(entry.info.heavy_atoms);
  x.u32(narrow32(entry.site.size(), "site sphere count"));
  impl_->offset += record.size();
  impl_->samples_size += sample.size();
}

void LibraryWriter::finish() {
  if (impl_->finished) return;
  impl_->finished = true;
  // The samples' region, from the next 64-byte boundary.
  const std::uint64_t region = impl_->places.empty() ? impl_->offset : aligned(impl_->offset);
  write_bytes(*impl_->out, std::vector<std::uint8_t>(region - impl_->offset, 0));
  std::rewind(impl_->samples);
  std::vector<char> buffer(std::size_t{1} << 20);
  std::uint64_t copied = 0;
  while (copied < impl_->samples_size) {
    const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), impl_->samples);
    if (got == 0) throw FileError("<temporary file>", "cannot read back the library's samples");
    impl_->out->write(buffer.data(), static_cast<std::streamsize>(got));
    copied += got;
  }
  std::fclose(impl_->samples);
  impl_->samples = nullptr;
  impl_->offset = region + impl_->samples_size;

  io::BinaryWriter index;
  index.u64(impl_->places.size());
  io::BinaryReader names(impl_->names.bytes().data(), impl_->names.bytes().size(), "<index>");
  for (const auto& place : impl_->places) {
    for (int k = 0; k < 6; ++k) index.u64(k == 3 ? region + place[3] : place[k]);
    index.string(names.string());
    index.string(names.string());
    for (int k = 0; k < 4; ++k) index.u32(names.u32());
  }
  index.string(impl_->settings);
  const std::vector<std::uint8_t>& bytes = index.bytes();
  write_bytes(*impl_->out, bytes);
  io::BinaryWriter trailer;
  trailer.u64(impl_->offset);
  trailer.u64(bytes.size());
  trailer.u64(io::fnv1a64(bytes.data(), bytes.size()));
  for (std::size_t i = 0; i < kMagicBytes; ++i) trailer.u8(static_cast<std::uint8_t>(kEndMagic[i]));
  write_bytes(*impl_->out, trailer.bytes());
  impl_->offset += bytes.size() + kTrailerBytes;
}

std::size_t LibraryWriter::size() const { return impl_->places.size(); }

std::uint64_t LibraryWriter::bytes() const {
  return impl_->offset + (impl_->finished ? 0 : impl_->samples_size);
}

void write_library(const std::filesystem::path& path, const std::vector<LibraryEntry>& entries,
                   const std::string& settings, double sigma) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    LibraryWriter writer(out, settings, sigma);
    for (const LibraryEntry& entry : entries) writer.add(entry);
    writer.finish();
  });
}

namespace {

constexpr char kIndexMagic[] = "SURFCSET";
constexpr char kIndexEndMagic[] = "SCSETEND";
constexpr std::size_t kIndexTrailerBytes = 16;  // body checksum, end magic

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

MappedFile::MappedFile(const std::filesystem::path& path) {
  const std::string name = path.string();
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT) throw FileError(name, "no such file");
    throw FileError(name, std::string("cannot open for reading (") + std::strerror(error) + ")");
  }
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
    ::close(fd);
    throw FileError(name, "not a regular file");
  }
  const auto size = static_cast<std::size_t>(status.st_size);
  if (size < kHeaderBytes + kTrailerBytes) {
    ::close(fd);
    throw FormatError(name,
                      "not a surfcomp library (" + std::to_string(size) + " bytes, too short)");
  }
  void* mapped = ::mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0);
  const int error = errno;
  ::close(fd);
  if (mapped == MAP_FAILED)
    throw FileError(name, std::string("cannot map into memory (") + std::strerror(error) + ")");
  data_ = static_cast<const std::uint8_t*>(mapped);
  size_ = size;
}

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

void LibraryFile::read_index() {
  const std::uint8_t* data = file.data();
  const std::size_t size = file.size();
  if (std::memcmp(data, kMagic, kMagicBytes) != 0)
    fail("not a surfcomp library (no SURFCLIB magic)");
  io::BinaryReader header(data + kMagicBytes, kHeaderBytes - kMagicBytes, path.string());
  version = header.u32();
  if (version < 1 || version > library_format_version) {
    fail("library format version " + std::to_string(version) +
         ", this program reads versions 1 to " + std::to_string(library_format_version));
  }
  const std::uint8_t* trailer_data = data + size - kTrailerBytes;
  if (std::memcmp(trailer_data + kTrailerBytes - kMagicBytes, kEndMagic, kMagicBytes) != 0)
    fail("the library is truncated (no SCLIBEND trailer at the end)");
  io::BinaryReader trailer(trailer_data, kTrailerBytes - kMagicBytes, path.string());
  const std::uint64_t index_offset = trailer.u64();
  const std::uint64_t index_size = trailer.u64();
  index_checksum = trailer.u64();
  const std::uint64_t index_end = size - kTrailerBytes;
  if (index_offset < kHeaderBytes || index_offset > index_end ||
      index_size != index_end - index_offset) {
    fail("the trailer's index offset " + std::to_string(index_offset) + " and size " +
         std::to_string(index_size) + " do not fit the file's " + std::to_string(size) + " bytes");
  }
  if (io::fnv1a64(data + index_offset, index_size) != index_checksum)
    fail("the index does not match its checksum (a damaged file)");
  io::BinaryReader r(data + index_offset, index_size, path.string());
  const std::uint64_t count = r.u64();
  // Each index record takes at least 44 bytes: a count beyond that is damage, not a reason to
  // reserve memory.
  if (count > r.remaining() / 44) r.fail("entry count " + std::to_string(count) + " too large");
  for (auto* column : {&offsets, &sizes, &checksums}) column->reserve(count);
  if (version >= 4) {
    for (auto* column : {&sample_offsets, &sample_sizes, &sample_checksums}) column->reserve(count);
  }
  infos.reserve(count);
  // Records (the entries before format 4) follow each other from the header; format 4's samples
  // follow each other in the 64-byte-aligned region between the records and the index.
  std::uint64_t previous_end = kHeaderBytes;
  std::uint64_t previous_sample_end = 0;
  for (std::uint64_t e = 0; e < count; ++e) {
    const std::uint64_t offset = r.u64();
    const std::uint64_t bytes = r.u64();
    const std::uint64_t checksum = r.u64();
    std::uint64_t sample_offset = 0, sample_bytes = 0, sample_checksum = 0;
    if (version >= 4) {
      sample_offset = r.u64();
      sample_bytes = r.u64();
      sample_checksum = r.u64();
    }
    LibraryEntryInfo info;
    info.name = r.string();
    info.source = r.string();
    info.record = r.u32();
    info.conformer = r.u32();
    info.heavy_atoms = r.u32();
    if (version >= 2) info.site_spheres = r.u32();
    const std::string entry = "entry " + std::to_string(first + e + 1) + " (" + info.name + ")";
    if (offset != previous_end || bytes > index_offset - offset) {
      fail(entry + ": offset " + std::to_string(offset) + " and size " + std::to_string(bytes) +
           " do not follow the previous entry within the entries' region");
    }
    previous_end = offset + bytes;
    if (version >= 4) {
      const bool in_order =
          e == 0 ? sample_offset >= previous_end && sample_offset % kSampleAlignment == 0
                 : sample_offset == previous_sample_end;
      if (!in_order || sample_bytes < kPackedHeaderBytes || sample_bytes % kSampleAlignment != 0 ||
          sample_bytes > index_offset - sample_offset) {
        fail(entry + ": its sample's offset " + std::to_string(sample_offset) + " and size " +
             std::to_string(sample_bytes) +
             " do not follow the previous sample within the samples' region");
      }
      previous_sample_end = sample_offset + sample_bytes;
      sample_offsets.push_back(sample_offset);
      sample_sizes.push_back(sample_bytes);
      sample_checksums.push_back(sample_checksum);
    }
    offsets.push_back(offset);
    sizes.push_back(bytes);
    checksums.push_back(checksum);
    infos.push_back(std::move(info));
    // The index's pages decoded so far go as the reading goes, so that they and the decoded
    // index are not resident together (the index is about 150 bytes an entry).
    if (e % 8192 == 8191) file.release(index_offset, index_end - r.remaining());
  }
  const std::uint64_t entries_end = version >= 4 && count > 0 ? previous_sample_end : previous_end;
  if (version >= 4 && count > 0 && aligned(previous_end) != sample_offsets.front())
    fail("the samples do not begin at the first 64-byte boundary after the records");
  if (entries_end != index_offset) fail("the entries do not end where the index begins");
  settings = r.string();
  if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes after the index");
  file.release(index_offset, size);
}

matching::PackedSampleView LibraryFile::sample_view(std::size_t index) const {
  const std::uint8_t* bytes = file.data() + sample_offsets[index];
  const std::size_t bytes_size = sample_sizes[index];
  if (io::xxh3_64(bytes, bytes_size) != sample_checksums[index])
    fail(where(index) + ": its sample does not match its checksum (a damaged file)");
  io::BinaryReader r(bytes, bytes_size, path.string() + " " + where(index));
  matching::PackedSampleView v;
  matching::PackedHeader& h = v.header;
  h.points = r.u32();
  h.atoms = r.u32();
  const std::uint8_t kind = r.u8();
  if (kind > 1) r.fail("unknown sample kind " + std::to_string(kind));
  h.kind = static_cast<matching::SampleKind>(kind);
  for (int k = 0; k < 7; ++k) r.u8();
  for (int k = 0; k < 3; ++k) h.centroid(k) = r.f64();
  for (int row = 0; row < 3; ++row) {
    for (int c = 0; c < 3; ++c) h.axes(row, c) = r.f64();
  }
  for (double* value : {&h.self_shape, &h.self_esp, &h.self_lp, &h.squares_esp, &h.squares_lp,
                        &h.squares_weight, &h.atom_self, &h.sigma})
    *value = r.f64();
  if (!h.centroid.allFinite() || !h.axes.allFinite() || !std::isfinite(h.self_shape) ||
      !std::isfinite(h.self_esp) || !std::isfinite(h.self_lp) || !std::isfinite(h.squares_esp) ||
      !std::isfinite(h.squares_lp) || !std::isfinite(h.squares_weight) ||
      !std::isfinite(h.atom_self) || !(h.sigma > 0.0) || !std::isfinite(h.sigma))
    r.fail("the sample's header holds a value that is not finite, or a width that is not > 0");
  const std::uint64_t floats =
      9 * static_cast<std::uint64_t>(v.padded_points()) + 3 * std::uint64_t{h.atoms};
  const std::uint64_t used = kPackedHeaderBytes + 4 * floats + 4 * std::uint64_t{h.atoms};
  if (aligned(used) != bytes_size)
    r.fail("the sample's " + std::to_string(h.points) + " points and " + std::to_string(h.atoms) +
           " atoms do not fill its " + std::to_string(bytes_size) + " bytes");
  v.arrays = reinterpret_cast<const float*>(bytes + kPackedHeaderBytes);
  v.atom_points = v.arrays + 9 * v.padded_points();
  v.atom_elements =
      reinterpret_cast<const std::uint32_t*>(v.atom_points + std::size_t{3} * h.atoms);
  // x - x is 0 for a finite x and NaN otherwise: one pass the compiler vectorises.
  float nan_if_any = 0.0F;
  for (std::uint64_t k = 0; k < floats; ++k) nan_if_any += v.arrays[k] - v.arrays[k];
  if (nan_if_any != 0.0F) r.fail("the sample holds a value that is not finite");
  return v;
}

LibraryEntry LibraryFile::decode_entry(std::size_t index) const {
  const LibraryEntryInfo& info = infos[index];
  const std::uint8_t* bytes = file.data() + offsets[index];
  const std::size_t bytes_size = sizes[index];
  const std::string at = path.string() + " " + where(index);
  if (io::fnv1a64(bytes, bytes_size) != checksums[index])
    fail(where(index) + " does not match its checksum (a damaged file)");
  io::BinaryReader r(bytes, bytes_size, at);
  LibraryEntry entry;
  entry.info = info;
  const std::uint8_t format = r.u8();
  if (format > (version >= 5 ? kCompressedStructure : 3))
    r.fail("unknown molecule format code " + std::to_string(format));
  constexpr io::RecordFormat kFormats[] = {io::RecordFormat::mdl, io::RecordFormat::mol2,
                                           io::RecordFormat::structure, io::RecordFormat::mesh,
                                           io::RecordFormat::structure};
  entry.molecule.format = kFormats[format];
  entry.molecule.text = r.string();
  if (format == kCompressedStructure) entry.molecule.text = io::gunzip(entry.molecule.text, at);
  entry.molecule.source = info.source;
  entry.molecule.record = info.record;
  entry.molecule.name = info.name;
  if (version < 4) {
    matching::SurfaceSample& s = entry.sample;
    const Eigen::MatrixXd points = r.double_matrix();
    if (points.rows() != 3 || !points.allFinite())
      r.fail("the sample's points are not a finite 3 x N array");
    s.points = points;
    const Eigen::Index n = s.points.cols();
    s.normals = three_rows(r, n, "the sample's normals");
    s.weights = vector_of(r, n, "the sample's weights");
    s.esp = vector_of(r, n, "the sample's ESP");
    s.lp = vector_of(r, n, "the sample's LP");
    const std::uint64_t atoms = r.u64();
    if (atoms > r.remaining() / 28) r.fail("atom count " + std::to_string(atoms) + " too large");
    entry.atoms.points.resize(3, static_cast<Eigen::Index>(atoms));
    for (std::uint64_t a = 0; a < atoms; ++a) {
      entry.atoms.elements.push_back(r.string());
      Eigen::Vector3d position;
      for (int k = 0; k < 3; ++k) position(k) = r.f64();
      io::check_read_position(position, at, "heteroatom " + std::to_string(a + 1));
      entry.atoms.points.col(static_cast<Eigen::Index>(a)) = position;
    }
  }
  if (version >= 2) {
    const std::uint64_t spheres = r.u64();
    if (spheres != info.site_spheres) {
      r.fail(std::to_string(spheres) + " site spheres, the index says " +
             std::to_string(info.site_spheres));
    }
    for (std::uint64_t k = 0; k < spheres; ++k) {
      molsurf::SiteSphere sphere;
      for (int d = 0; d < 3; ++d) sphere.center(d) = r.f64();
      sphere.radius = r.f64();
      if (!sphere.center.allFinite() || !std::isfinite(sphere.radius) || !(sphere.radius > 0.0))
        r.fail("site sphere " + std::to_string(k + 1) + " is not a finite centre and radius > 0");
      entry.site.push_back(sphere);
    }
  }
  if (version >= 3) entry.surface = r.blob();
  if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes after the entry");
  return entry;
}

void LibraryFile::verify(std::size_t index) const {
  if (io::fnv1a64(file.data() + offsets[index], sizes[index]) != checksums[index])
    fail(where(index) + " does not match its checksum (a damaged file)");
  if (version >= 4 && io::xxh3_64(file.data() + sample_offsets[index], sample_sizes[index]) !=
                          sample_checksums[index])
    fail(where(index) + ": its sample does not match its checksum (a damaged file)");
}

void LibraryFile::release(std::size_t begin, std::size_t end) const {
  if (begin >= end) return;
  file.release(offsets[begin], offsets[end - 1] + sizes[end - 1]);
  if (version >= 4)
    file.release(sample_offsets[begin], sample_offsets[end - 1] + sample_sizes[end - 1]);
}

}  // namespace

void write_library_index(const std::filesystem::path& path,
                         const std::vector<std::filesystem::path>& shards,
                         const std::string& settings) {
  if (shards.empty()) throw InputError(path.string() + ": a library index needs a shard");
  io::BinaryWriter body;
  body.u64(shards.size());
  for (const std::filesystem::path& shard : shards) {
    if (shard.empty() || !shard.is_relative())
      throw InputError(path.string() + ": shard path '" + shard.string() + "' is not relative");
    const LibraryFile file(path.parent_path() / shard, 0);
    if (file.version != library_format_version)
      file.fail("format version " + std::to_string(file.version) + "; a shard must be version " +
                std::to_string(library_format_version));
    body.string(shard.generic_string());
    body.u64(file.size());
    body.u64(file.file.size());
    body.u64(file.index_checksum);
  }
  body.string(settings);
  io::BinaryWriter header;
  for (std::size_t i = 0; i < kMagicBytes; ++i)
    header.u8(static_cast<std::uint8_t>(kIndexMagic[i]));
  header.u32(library_index_version);
  header.u32(0);
  io::BinaryWriter trailer;
  trailer.u64(io::fnv1a64(body.bytes().data(), body.bytes().size()));
  for (std::size_t i = 0; i < kMagicBytes; ++i)
    trailer.u8(static_cast<std::uint8_t>(kIndexEndMagic[i]));
  io::write_file_atomically(path, [&](std::ostream& out) {
    for (const io::BinaryWriter* part : {&header, &body, &trailer}) write_bytes(out, part->bytes());
  });
}

// ---------------------------------------------------------------------------------------------

namespace {

/// What a sharded library's index lists of a shard.
struct ListedShard {
  std::filesystem::path path;
  std::size_t first = 0;  // the library's number of its first entry
  std::uint64_t entries = 0, file_size = 0, index_checksum = 0;
};

/// Reads `count` bytes at `offset` of the open file `fd` (named `name`) into `out`.
void read_at(int fd, const std::string& name, std::uint64_t offset, std::size_t count,
             std::uint8_t* out) {
  std::size_t done = 0;
  while (done < count) {
    const ::ssize_t got =
        ::pread(fd, out + done, count - done, static_cast<::off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) throw FileError(name, "cannot read " + std::to_string(count) + " bytes");
    done += static_cast<std::size_t>(got);
  }
}

/// Checks a shard against what the index `index` lists without mapping it: its size, its
/// header's magic and version, its trailer's end magic and index checksum, its entry count (a
/// stat and 56 bytes read). Its index and entries are checked when it is opened (LibraryFile).
void check_listed_shard(const ListedShard& shard, const std::string& index) {
  const std::string name = shard.path.string();
  const std::string listed = ", the index " + index + " lists ";
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(shard.path, error);
  if (error) {
    if (error == std::errc::no_such_file_or_directory) throw FileError(name, "no such file");
    throw FileError(name, "cannot read (" + error.message() + ")");
  }
  if (size != shard.file_size) {
    throw FormatError(name, std::to_string(size) + " bytes" + listed +
                                std::to_string(shard.file_size) + " (a cut or replaced shard)");
  }
  if (size < kHeaderBytes + kTrailerBytes) throw FormatError(name, "too short for a library");
  const int fd = ::open(shard.path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw FileError(name, std::string("cannot open (") + std::strerror(errno) + ")");
  std::array<std::uint8_t, kHeaderBytes> header{};
  std::array<std::uint8_t, kTrailerBytes> trailer{};
  std::array<std::uint8_t, 8> count{};
  try {
    read_at(fd, name, 0, header.size(), header.data());
    read_at(fd, name, size - kTrailerBytes, trailer.size(), trailer.data());
    const std::uint64_t index_offset = io::BinaryReader(trailer.data(), 8, name).u64();
    if (index_offset < kHeaderBytes || index_offset > size - kTrailerBytes - count.size()) {
      throw FormatError(name, "the trailer's index offset " + std::to_string(index_offset) +
                                  " does not fit the file's " + std::to_string(size) + " bytes");
    }
    read_at(fd, name, index_offset, count.size(), count.data());
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  if (std::memcmp(header.data(), kMagic, kMagicBytes) != 0)
    throw FormatError(name, "not a surfcomp library (no SURFCLIB magic)");
  // Shards of format 4 (an earlier program's sharded builds) are read as the one files are.
  const std::uint32_t version = io::BinaryReader(header.data() + kMagicBytes, 4, name).u32();
  if (version < 4 || version > library_format_version) {
    throw FormatError(name, "format version " + std::to_string(version) +
                                "; a shard must be version 4 to " +
                                std::to_string(library_format_version));
  }
  if (std::memcmp(trailer.data() + kTrailerBytes - kMagicBytes, kEndMagic, kMagicBytes) != 0)
    throw FormatError(name, "the library is truncated (no SCLIBEND trailer at the end)");
  if (io::BinaryReader(trailer.data() + 16, 8, name).u64() != shard.index_checksum) {
    throw FormatError(name, "its index checksum is not the one the index " + index +
                                " lists (a shard rebuilt or replaced since)");
  }
  const std::uint64_t entries = io::BinaryReader(count.data(), 8, name).u64();
  if (entries != shard.entries)
    throw FormatError(
        name, std::to_string(entries) + " entries" + listed + std::to_string(shard.entries));
}

}  // namespace

// ---------------------------------------------------------------------------------------------

struct Library::Impl {
  /// The shards a sharded library keeps open (mapped, their index decoded) at most, beyond those
  /// pinned by a PackedEntry: enough for a block of a streaming screen that crosses a shard's end.
  static constexpr std::size_t kOpenShards = 4;

  std::filesystem::path path;
  std::vector<ListedShard> listed;  // a sharded library's shards; empty for a library file
  std::vector<std::size_t> ends;    // entries in shards 0..k (the file: one)
  std::string settings;             // the file's, or the index's
  std::uint32_t version = 0;
  std::uint64_t bytes = 0;  // of the file, or of the index and the shards

  mutable std::mutex mutex;                                      // guards `open` and `recent`
  mutable std::vector<std::shared_ptr<const LibraryFile>> open;  // per shard; null when closed
  mutable std::vector<std::size_t> recent;  // open shards, least recently used first

  /// Reads the index `index` (mapped from `path`) and checks every shard it lists
  /// (check_listed_shard).
  void read_shard_list(const MappedFile& index);
  /// Shard `k`, opened now when it is not open (closing the least recently used beyond
  /// kOpenShards).
  std::shared_ptr<const LibraryFile> shard(std::size_t k) const;
  /// The shard holding entry `index` and the entry's number in it; std::out_of_range beyond the
  /// last entry.
  std::pair<std::shared_ptr<const LibraryFile>, std::size_t> locate(std::size_t index) const {
    const auto it = std::upper_bound(ends.begin(), ends.end(), index);
    if (it == ends.end()) {
      throw std::out_of_range("library entry " + std::to_string(index) + " of " +
                              std::to_string(ends.empty() ? 0 : ends.back()));
    }
    const auto k = static_cast<std::size_t>(it - ends.begin());
    std::shared_ptr<const LibraryFile> file = shard(k);
    const std::size_t local = index - file->first;
    return {std::move(file), local};
  }
  std::size_t first_of(std::size_t k) const { return k == 0 ? 0 : ends[k - 1]; }
};

std::shared_ptr<const LibraryFile> Library::Impl::shard(std::size_t k) const {
  const std::lock_guard<std::mutex> lock(mutex);
  if (listed.empty()) return open.front();  // a library file stays open
  if (open[k] == nullptr) {
    const ListedShard& s = listed[k];
    auto file = std::make_shared<const LibraryFile>(s.path, s.first);
    // check_listed_shard compared the trailer, read_index the index with it: what remains is a
    // shard replaced since the library was opened.
    if (file->size() != s.entries || file->index_checksum != s.index_checksum)
      file->fail("changed since the library was opened");
    open[k] = std::move(file);
  }
  const auto used = std::find(recent.begin(), recent.end(), k);
  if (used != recent.end()) recent.erase(used);
  recent.push_back(k);
  while (recent.size() > kOpenShards) {
    open[recent.front()].reset();
    recent.erase(recent.begin());
  }
  return open[k];
}

void Library::Impl::read_shard_list(const MappedFile& index) {
  const std::string name = path.string();
  const std::uint8_t* data = index.data();
  const std::size_t size = index.size();
  io::BinaryReader header(data + kMagicBytes, kHeaderBytes - kMagicBytes, name);
  const std::uint32_t index_version = header.u32();
  if (index_version != library_index_version) {
    throw FormatError(name, "library index version " + std::to_string(index_version) +
                                ", this program reads version " +
                                std::to_string(library_index_version));
  }
  const std::uint8_t* trailer_data = data + size - kIndexTrailerBytes;
  if (std::memcmp(trailer_data + kIndexTrailerBytes - kMagicBytes, kIndexEndMagic, kMagicBytes) !=
      0)
    throw FormatError(name, "the library index is truncated (no SCSETEND trailer at the end)");
  const std::size_t body_size = size - kHeaderBytes - kIndexTrailerBytes;
  if (io::fnv1a64(data + kHeaderBytes, body_size) !=
      io::BinaryReader(trailer_data, kIndexTrailerBytes, name).u64())
    throw FormatError(name, "the library index does not match its checksum (a damaged file)");
  io::BinaryReader r(data + kHeaderBytes, body_size, name);
  const std::uint64_t count = r.u64();
  // Each shard takes at least 28 bytes.
  if (count == 0 || count > r.remaining() / 28)
    r.fail("shard count " + std::to_string(count) + " is not one the index can hold");
  std::size_t first = 0;
  for (std::uint64_t k = 0; k < count; ++k) {
    ListedShard shard;
    const std::filesystem::path relative = r.string();
    shard.entries = r.u64();
    shard.file_size = r.u64();
    shard.index_checksum = r.u64();
    if (relative.empty() || !relative.is_relative())
      r.fail("shard path '" + relative.string() + "' is not relative to the index's folder");
    shard.path = path.parent_path() / relative;
    shard.first = first;
    check_listed_shard(shard, name);
    first += shard.entries;
    bytes += shard.file_size;
    ends.push_back(first);
    listed.push_back(std::move(shard));
  }
  settings = r.string();
  if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes after the index");
  version = library_format_version;
  open.resize(listed.size());
}

Library::Library(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  {
    const MappedFile file(path);
    if (std::memcmp(file.data(), kIndexMagic, kMagicBytes) == 0) {
      impl_->bytes = file.size();
      impl_->read_shard_list(file);
      return;
    }
  }
  auto file = std::make_shared<const LibraryFile>(path, 0);
  impl_->settings = file->settings;
  impl_->version = file->version;
  impl_->bytes = file->file.size();
  impl_->ends.push_back(file->size());
  impl_->open.push_back(std::move(file));
}

Library::Library(Library&&) noexcept = default;
Library& Library::operator=(Library&&) noexcept = default;
Library::~Library() = default;

std::size_t Library::size() const { return impl_->ends.back(); }

LibraryEntryInfo Library::info(std::size_t index) const {
  const auto [file, local] = impl_->locate(index);
  return file->infos[local];
}

std::uint64_t Library::entry_bytes(std::size_t index) const {
  const auto [file, local] = impl_->locate(index);
  return file->sizes[local];
}

LibraryEntry Library::entry(std::size_t index) const {
  const auto [file, local] = impl_->locate(index);
  LibraryEntry entry = file->decode_entry(local);
  if (file->version >= 4) {
    entry.packed = matching::PackedSample(file->sample_view(local));
    entry.sample = entry.packed.sample();
    entry.atoms = entry.packed.atoms();
    entry.kind = entry.packed.header().kind;
  }
  return entry;
}

PackedEntry Library::packed(std::size_t index, double sigma) const {
  auto [file, local] = impl_->locate(index);
  PackedEntry out;
  if (file->version >= 4) {
    out.view = file->sample_view(local);
    if (out.view.header.sigma == sigma) {
      out.file = std::move(file);  // the view points into its mapping
      return out;
    }
    const matching::PackedSample stored(out.view);
    out.owned = std::make_unique<matching::PackedSample>(stored.sample(), stored.atoms(), sigma,
                                                         stored.header().kind);
  } else {
    const LibraryEntry entry = file->decode_entry(local);
    if (entry.sample.size() == 0) return out;  // no points: the first stage scores it 0
    out.owned = std::make_unique<matching::PackedSample>(entry.sample, entry.atoms, sigma,
                                                         matching::SampleKind::surface);
  }
  out.view = out.owned->view();
  return out;
}

std::vector<std::size_t> Library::find(const std::string& name) const {
  // A scan of the index: no table by name is kept, whose nodes would cost a screen of millions
  // of entries about 100 bytes each for a lookup it never makes.
  std::vector<std::size_t> found;
  for (std::size_t k = 0; k < impl_->ends.size(); ++k) {
    const std::shared_ptr<const LibraryFile> file = impl_->shard(k);
    for (std::size_t e = 0; e < file->size(); ++e) {
      if (file->infos[e].name == name) found.push_back(file->first + e);
    }
  }
  return found;
}

void Library::verify() const {
  for (std::size_t k = 0; k < impl_->ends.size(); ++k) {
    const std::shared_ptr<const LibraryFile> file = impl_->shard(k);
    for (std::size_t e = 0; e < file->size(); ++e) file->verify(e);
  }
}

void Library::release(std::size_t begin, std::size_t end) const {
  if (begin > end || end > size()) {
    throw std::out_of_range("library entries [" + std::to_string(begin) + ", " +
                            std::to_string(end) + ") of " + std::to_string(size()));
  }
  if (begin == end) return;
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  const auto first_shard = static_cast<std::size_t>(
      std::upper_bound(impl_->ends.begin(), impl_->ends.end(), begin) - impl_->ends.begin());
  for (std::size_t k = first_shard; k < impl_->ends.size() && impl_->first_of(k) < end; ++k) {
    const std::size_t first = impl_->first_of(k), last = impl_->ends[k];
    std::shared_ptr<const LibraryFile>& file = impl_->open[k];
    if (file == nullptr) continue;
    if (!impl_->listed.empty() && last <= end) {  // its last entry released: a stream is past it
      file.reset();
      impl_->recent.erase(std::find(impl_->recent.begin(), impl_->recent.end(), k));
    } else {
      file->release(std::max(begin, first) - first, std::min(end, last) - first);
    }
  }
}

std::uint32_t Library::version() const { return impl_->version; }

const std::string& Library::settings() const { return impl_->settings; }

std::uint64_t Library::file_bytes() const { return impl_->bytes; }

const std::filesystem::path& Library::path() const { return impl_->path; }

std::size_t Library::shards() const { return impl_->ends.size(); }

std::size_t Library::open_shards() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return static_cast<std::size_t>(std::count_if(impl_->open.begin(), impl_->open.end(),
                                                [](const auto& file) { return file != nullptr; }));
}

io::MoleculeReadOptions site_entry_read_options(io::MoleculeReadOptions read) {
  read.min_plddt = 0.0;
  return read;
}

}  // namespace surfcomp::screening
