// libFuzzer harness: the .hsi decoder (decode_hsi). Each input is decoded twice: as given, and
// with the header's payload size and checksum recomputed for the bytes after the header, so
// that mutations reach the payload's parsing instead of stopping at the checksum.
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/binary_stream.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace {

constexpr std::size_t kHeaderSize = 8 + 4 + 4 + 8 + 8;  // magic, version, byte order, size, sum

void store_u64(std::vector<std::uint8_t>& bytes, std::size_t offset, std::uint64_t value) {
  for (int i = 0; i < 8; ++i) bytes[offset + i] = static_cast<std::uint8_t>(value >> (8 * i));
}

void decode(const std::vector<std::uint8_t>& bytes) {
  try {
    surfcomp::harmonic::io::decode_hsi(bytes, "fuzz.hsi");
  } catch (const surfcomp::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> bytes(data, data + size);
  decode(bytes);
  if (size < kHeaderSize) return 0;
  const std::size_t payload = size - kHeaderSize;
  store_u64(bytes, 16, payload);
  store_u64(bytes, 24, surfcomp::io::fnv1a64(bytes.data() + kHeaderSize, payload));
  decode(bytes);
  return 0;
}
