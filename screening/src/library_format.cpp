// The library file format (library_format.hpp): an entry's record and packed sample encoded,
// a library file mapped and its index, records and samples decoded and checked.
#include "library_format.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <limits>
#include <string>
#include <sys/stat.h>
#include <utility>

namespace surfcomp::screening::library_format {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "format 4 samples are read in place as little-endian floats");

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

std::size_t aligned(std::size_t bytes) {
  return (bytes + kSampleAlignment - 1) / kSampleAlignment * kSampleAlignment;
}

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

}  // namespace surfcomp::screening::library_format
