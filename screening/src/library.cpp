#include "surfcomp/screening/library.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/binary_stream.hpp"
#include "surfcomp/core/io/input_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>
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

std::vector<std::uint8_t> encode(const LibraryEntry& entry) {
  const matching::SurfaceSample& s = entry.sample;
  const auto n = static_cast<Eigen::Index>(s.size());
  if (s.normals.cols() != n || s.weights.size() != n || s.esp.size() != n || s.lp.size() != n ||
      static_cast<std::size_t>(entry.atoms.points.cols()) != entry.atoms.size()) {
    throw InputError("library entry " + entry.info.name + ": its sample's arrays differ in size");
  }
  narrow32(entry.molecule.text.size(), "molecule text");
  io::BinaryWriter w;
  w.u8(format_code(entry.molecule.format));
  w.string(entry.molecule.text);
  w.double_matrix(s.points);
  w.double_matrix(s.normals);
  w.doubles(s.weights);
  w.doubles(s.esp);
  w.doubles(s.lp);
  w.u64(entry.atoms.size());
  for (std::size_t a = 0; a < entry.atoms.size(); ++a) {
    w.string(entry.atoms.elements[a]);
    for (int k = 0; k < 3; ++k) w.f64(entry.atoms.points(k, static_cast<Eigen::Index>(a)));
  }
  w.u64(entry.site.size());
  for (const matching::SiteSphere& sphere : entry.site) {
    for (int k = 0; k < 3; ++k) w.f64(sphere.center(k));
    w.f64(sphere.radius);
  }
  w.blob(entry.surface);
  return w.bytes();
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
  std::uint64_t offset = 0;
  io::BinaryWriter index;  // the per-entry records, count prepended at finish()
  std::size_t count = 0;
  bool finished = false;
};

LibraryWriter::LibraryWriter(std::ostream& out, std::string settings)
    : impl_(std::make_unique<Impl>()) {
  impl_->out = &out;
  impl_->settings = std::move(settings);
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
  const std::vector<std::uint8_t> bytes = encode(entry);
  write_bytes(*impl_->out, bytes);
  io::BinaryWriter& x = impl_->index;
  x.u64(impl_->offset);
  x.u64(bytes.size());
  x.u64(io::fnv1a64(bytes.data(), bytes.size()));
  x.string(entry.info.name);
  x.string(entry.info.source);
  x.u32(entry.info.record);
  x.u32(entry.info.conformer);
  x.u32(entry.info.heavy_atoms);
  x.u32(narrow32(entry.site.size(), "site sphere count"));
  impl_->offset += bytes.size();
  ++impl_->count;
}

void LibraryWriter::finish() {
  if (impl_->finished) return;
  impl_->finished = true;
  io::BinaryWriter index;
  index.u64(impl_->count);
  std::vector<std::uint8_t> bytes = index.bytes();
  bytes.insert(bytes.end(), impl_->index.bytes().begin(), impl_->index.bytes().end());
  io::BinaryWriter settings;
  settings.string(impl_->settings);
  bytes.insert(bytes.end(), settings.bytes().begin(), settings.bytes().end());
  write_bytes(*impl_->out, bytes);
  io::BinaryWriter trailer;
  trailer.u64(impl_->offset);
  trailer.u64(bytes.size());
  trailer.u64(io::fnv1a64(bytes.data(), bytes.size()));
  for (std::size_t i = 0; i < kMagicBytes; ++i) trailer.u8(static_cast<std::uint8_t>(kEndMagic[i]));
  write_bytes(*impl_->out, trailer.bytes());
  impl_->offset += bytes.size() + kTrailerBytes;
}

std::size_t LibraryWriter::size() const { return impl_->count; }

std::uint64_t LibraryWriter::bytes() const { return impl_->offset; }

void write_library(const std::filesystem::path& path, const std::vector<LibraryEntry>& entries,
                   const std::string& settings) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    LibraryWriter writer(out, settings);
    for (const LibraryEntry& entry : entries) writer.add(entry);
    writer.finish();
  });
}

// ---------------------------------------------------------------------------------------------

struct Library::Impl {
  std::filesystem::path path;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  std::uint32_t version = 0;
  std::string settings;
  std::vector<LibraryEntryInfo> infos;
  std::vector<std::uint64_t> offsets, sizes, checksums;
  std::multimap<std::string, std::size_t> by_name;

  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (data != nullptr) ::munmap(const_cast<std::uint8_t*>(data), size);
  }

  [[noreturn]] void fail(const std::string& reason) const {
    throw FormatError(path.string(), reason);
  }
  void map();
  void read_index();
};

void Library::Impl::map() {
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
  size = static_cast<std::size_t>(status.st_size);
  if (size < kHeaderBytes + kTrailerBytes) {
    ::close(fd);
    fail("not a surfcomp library (" + std::to_string(size) + " bytes, too short)");
  }
  void* mapped = ::mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0);
  ::close(fd);
  if (mapped == MAP_FAILED) {
    throw FileError(name, std::string("cannot map into memory (") + std::strerror(errno) + ")");
  }
  data = static_cast<const std::uint8_t*>(mapped);
}

void Library::Impl::read_index() {
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
  const std::uint64_t index_checksum = trailer.u64();
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
  std::uint64_t previous_end = kHeaderBytes;
  for (std::uint64_t e = 0; e < count; ++e) {
    const std::uint64_t offset = r.u64();
    const std::uint64_t bytes = r.u64();
    const std::uint64_t checksum = r.u64();
    LibraryEntryInfo info;
    info.name = r.string();
    info.source = r.string();
    info.record = r.u32();
    info.conformer = r.u32();
    info.heavy_atoms = r.u32();
    if (version >= 2) info.site_spheres = r.u32();
    if (offset != previous_end || bytes > index_offset - offset) {
      fail("entry " + std::to_string(e + 1) + " (" + info.name + "): offset " +
           std::to_string(offset) + " and size " + std::to_string(bytes) +
           " do not follow the previous entry within the entries' region");
    }
    previous_end = offset + bytes;
    offsets.push_back(offset);
    sizes.push_back(bytes);
    checksums.push_back(checksum);
    by_name.emplace(info.name, infos.size());
    infos.push_back(std::move(info));
  }
  if (previous_end != index_offset) fail("the entries do not end where the index begins");
  settings = r.string();
  if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes after the index");
}

Library::Library(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->map();
  impl_->read_index();
}

Library::Library(Library&&) noexcept = default;
Library& Library::operator=(Library&&) noexcept = default;
Library::~Library() = default;

std::size_t Library::size() const { return impl_->infos.size(); }

const LibraryEntryInfo& Library::info(std::size_t index) const { return impl_->infos.at(index); }

std::uint64_t Library::entry_bytes(std::size_t index) const { return impl_->sizes.at(index); }

LibraryEntry Library::entry(std::size_t index) const {
  const LibraryEntryInfo& info = impl_->infos.at(index);
  const std::uint8_t* bytes = impl_->data + impl_->offsets[index];
  const std::size_t size = impl_->sizes[index];
  const std::string where =
      impl_->path.string() + " entry " + std::to_string(index + 1) + " (" + info.name + ")";
  if (io::fnv1a64(bytes, size) != impl_->checksums[index])
    throw FormatError(impl_->path.string(), "entry " + std::to_string(index + 1) + " (" +
                                                info.name +
                                                ") does not match its checksum (a damaged file)");
  io::BinaryReader r(bytes, size, where);
  LibraryEntry entry;
  entry.info = info;
  const std::uint8_t format = r.u8();
  if (format > 2) r.fail("unknown molecule format code " + std::to_string(format));
  entry.molecule.format = format == 0   ? io::RecordFormat::mdl
                          : format == 1 ? io::RecordFormat::mol2
                                        : io::RecordFormat::structure;
  entry.molecule.text = r.string();
  entry.molecule.source = info.source;
  entry.molecule.record = info.record;
  entry.molecule.name = info.name;
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
    io::check_read_position(position, where, "heteroatom " + std::to_string(a + 1));
    entry.atoms.points.col(static_cast<Eigen::Index>(a)) = position;
  }
  if (impl_->version >= 2) {
    const std::uint64_t spheres = r.u64();
    if (spheres != info.site_spheres) {
      r.fail(std::to_string(spheres) + " site spheres, the index says " +
             std::to_string(info.site_spheres));
    }
    for (std::uint64_t k = 0; k < spheres; ++k) {
      matching::SiteSphere sphere;
      for (int d = 0; d < 3; ++d) sphere.center(d) = r.f64();
      sphere.radius = r.f64();
      if (!sphere.center.allFinite() || !std::isfinite(sphere.radius) || !(sphere.radius > 0.0))
        r.fail("site sphere " + std::to_string(k + 1) + " is not a finite centre and radius > 0");
      entry.site.push_back(sphere);
    }
  }
  if (impl_->version >= 3) entry.surface = r.blob();
  if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes after the entry");
  return entry;
}

std::vector<std::size_t> Library::find(const std::string& name) const {
  std::vector<std::size_t> found;
  const auto [begin, end] = impl_->by_name.equal_range(name);
  for (auto it = begin; it != end; ++it) found.push_back(it->second);
  return found;  // a multimap keeps equal keys in insertion order: library order
}

std::uint32_t Library::version() const { return impl_->version; }

const std::string& Library::settings() const { return impl_->settings; }

std::uint64_t Library::file_bytes() const { return impl_->size; }

const std::filesystem::path& Library::path() const { return impl_->path; }

}  // namespace surfcomp::screening
