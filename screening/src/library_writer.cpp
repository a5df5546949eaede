// Writing libraries: a library file entry by entry (LibraryWriter), and a sharded library's
// index of its shards.
#include "library_format.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"

#include <string>
#include <utility>
#include <vector>

namespace surfcomp::screening {

using namespace library_format;

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

}  // namespace surfcomp::screening
