// libFuzzer harness: the screening library reader (screening::Library). Each input is opened as
// a library twice: as given, and with every checksum it holds (each entry's record and, from
// format 4, sample checksum, in the index, and the index's, in the trailer) recomputed where the
// trailer and index can be walked, so that mutations reach the decoding of the index and the
// entries instead of stopping at a checksum. Every entry is decoded, its packed sample read and
// scored against itself, looked up by name, and an entry's described surface (.hsi bytes) is
// decoded too.
#include "fuzz_input.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/binary_stream.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/screening/library.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace {

constexpr std::size_t kHeaderBytes = 16;   // "SURFCLIB", u32 version, u32 0
constexpr std::size_t kTrailerBytes = 32;  // u64 index offset, size, checksum, "SCLIBEND"

std::uint64_t load_u64(const std::vector<std::uint8_t>& bytes, std::size_t offset) {
  std::uint64_t value = 0;
  for (int i = 7; i >= 0; --i) value = (value << 8) | bytes[offset + static_cast<std::size_t>(i)];
  return value;
}

std::uint32_t load_u32(const std::vector<std::uint8_t>& bytes, std::size_t offset) {
  std::uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = (value << 8) | bytes[offset + static_cast<std::size_t>(i)];
  return value;
}

void store_u64(std::vector<std::uint8_t>& bytes, std::size_t offset, std::uint64_t value) {
  for (int i = 0; i < 8; ++i)
    bytes[offset + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(value >> (8 * i));
}

/// Walks the index as the reader does (without its checks) and rewrites each entry's checksum
/// that lies inside the file; stops where the index no longer parses.
void repair_entry_checksums(std::vector<std::uint8_t>& bytes, std::uint32_t version,
                            std::size_t index_offset, std::size_t index_end) {
  std::size_t at = index_offset;
  const auto need = [&](std::size_t n) { return n <= index_end - at; };
  const auto skip_string = [&]() {
    if (!need(4)) return false;
    const std::uint32_t length = load_u32(bytes, at);
    at += 4;
    if (!need(length)) return false;
    at += length;
    return true;
  };
  if (!need(8)) return;
  const std::uint64_t count = load_u64(bytes, at);
  at += 8;
  for (std::uint64_t e = 0; e < count; ++e) {
    if (!need(24)) return;
    const std::uint64_t offset = load_u64(bytes, at);
    const std::uint64_t size = load_u64(bytes, at + 8);
    if (offset <= index_offset && size <= index_offset - offset) {
      store_u64(bytes, at + 16, surfcomp::io::fnv1a64(bytes.data() + offset, size));
    }
    at += 24;
    if (version >= 4) {  // the packed sample's offset, size and XXH3 checksum
      if (!need(24)) return;
      const std::uint64_t sample = load_u64(bytes, at);
      const std::uint64_t sample_size = load_u64(bytes, at + 8);
      if (sample <= index_offset && sample_size <= index_offset - sample) {
        store_u64(bytes, at + 16, surfcomp::io::xxh3_64(bytes.data() + sample, sample_size));
      }
      at += 24;
    }
    if (!skip_string() || !skip_string()) return;
    const std::size_t fields = version >= 2 ? 16 : 12;
    if (!need(fields)) return;
    at += fields;
  }
}

/// `bytes` with its checksums recomputed, or nothing when the trailer does not locate an index.
std::optional<std::vector<std::uint8_t>> repaired(std::vector<std::uint8_t> bytes) {
  if (bytes.size() < kHeaderBytes + kTrailerBytes) return std::nullopt;
  const std::size_t trailer = bytes.size() - kTrailerBytes;
  const std::uint64_t index_offset = load_u64(bytes, trailer);
  if (index_offset < kHeaderBytes || index_offset > trailer) return std::nullopt;
  const std::uint32_t version = load_u32(bytes, 8);
  repair_entry_checksums(bytes, version, index_offset, trailer);
  store_u64(bytes, trailer + 8, trailer - index_offset);
  store_u64(bytes, trailer + 16,
            surfcomp::io::fnv1a64(bytes.data() + index_offset, trailer - index_offset));
  return bytes;
}

void read_library(const std::filesystem::path& path) {
  try {
    const surfcomp::screening::Library library(path);
    for (std::size_t i = 0; i < library.size(); ++i) {
      try {
        const surfcomp::screening::LibraryEntry entry = library.entry(i);
        (void)library.find(entry.info.name);
        const surfcomp::screening::PackedEntry packed = library.packed(i, 1.0);
        if (packed.view.header.points > 0) {
          const surfcomp::matching::PackedQuery query{
              surfcomp::matching::PackedSample(packed.view)};
          (void)query.fast_score(packed.view, {});
        }
        if (!entry.surface.empty()) {
          (void)surfcomp::harmonic::io::decode_hsi(entry.surface, path.string());
        }
      } catch (const surfcomp::Error&) {
      }
    }
  } catch (const surfcomp::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static surfcomp::fuzz::ScratchFile scratch(".sclib");
  read_library(scratch.write(data, size));
  const auto fixed = repaired(std::vector<std::uint8_t>(data, data + size));
  if (fixed && !std::equal(fixed->begin(), fixed->end(), data)) {
    read_library(scratch.write(fixed->data(), fixed->size()));
  }
  return 0;
}
