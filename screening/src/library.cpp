// An open library: one library file, or a sharded library's index and its shards, opened as
// they are needed and closed least recently used first.
#include "surfcomp/screening/library.hpp"
#include "library_format.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"

#include <array>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <mutex>
#include <string>
#include <system_error>
#include <unistd.h>
#include <utility>
#include <vector>

namespace surfcomp::screening {

using namespace library_format;

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
