#include "surfcomp/core/io/binary_stream.hpp"

#include "surfcomp/core/error.hpp"

#include <cstring>
#include <limits>

// xxHash (Debian libxxhash-dev), compiled into this file: no library to load at run time.
#define XXH_INLINE_ALL
#include <xxhash.h>

namespace surfcomp::io {
namespace {

/// Throws unless both dimensions of a stored matrix fit Eigen's signed index (an empty matrix
/// may have any such shape; the caller checks the element count against the bytes left).
void check_dimensions(const BinaryReader& reader, std::uint64_t rows, std::uint64_t cols) {
  constexpr auto max_index = static_cast<std::uint64_t>(std::numeric_limits<Eigen::Index>::max());
  if (rows > max_index || cols > max_index) {
    reader.fail("matrix dimensions " + std::to_string(rows) + " x " + std::to_string(cols) +
                " beyond the addressable range");
  }
}

}  // namespace

std::uint64_t fnv1a64(const std::uint8_t* data, std::size_t size) {
  std::uint64_t hash = 14695981039346656037ull;
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= data[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

std::uint64_t xxh3_64(const std::uint8_t* data, std::size_t size) {
  return XXH3_64bits(data, size);
}

void BinaryWriter::f32(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  u32(bits);
}

void BinaryWriter::zeros(std::size_t count) { bytes_.insert(bytes_.end(), count, 0); }

void BinaryWriter::u32(std::uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8)
    bytes_.push_back(static_cast<std::uint8_t>(value >> shift));
}

void BinaryWriter::u64(std::uint64_t value) {
  for (int shift = 0; shift < 64; shift += 8)
    bytes_.push_back(static_cast<std::uint8_t>(value >> shift));
}

void BinaryWriter::f64(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  u64(bits);
}

void BinaryWriter::string(const std::string& value) {
  u32(static_cast<std::uint32_t>(value.size()));
  bytes_.insert(bytes_.end(), value.begin(), value.end());
}

void BinaryWriter::blob(const std::vector<std::uint8_t>& value) {
  u64(value.size());
  bytes_.insert(bytes_.end(), value.begin(), value.end());
}

void BinaryWriter::ints(const std::vector<int>& values) {
  u64(values.size());
  for (int v : values) i32(v);
}

void BinaryWriter::doubles(const Eigen::Ref<const Eigen::VectorXd>& values) {
  u64(static_cast<std::uint64_t>(values.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i) f64(values(i));
}

void BinaryWriter::int_matrix(
    const Eigen::Ref<const Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic>>& m) {
  u64(static_cast<std::uint64_t>(m.rows()));
  u64(static_cast<std::uint64_t>(m.cols()));
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) i32(m(r, c));
  }
}

void BinaryWriter::double_matrix(const Eigen::Ref<const Eigen::MatrixXd>& m) {
  u64(static_cast<std::uint64_t>(m.rows()));
  u64(static_cast<std::uint64_t>(m.cols()));
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) f64(m(r, c));
  }
}

BinaryReader::BinaryReader(const std::uint8_t* data, std::size_t size, std::string source)
    : data_(data), size_(size), source_(std::move(source)) {}

void BinaryReader::fail(const std::string& what) const {
  throw FormatError(source_, "byte " + std::to_string(offset_) + ": " + what);
}

void BinaryReader::need(std::size_t bytes, const char* what) {
  if (bytes > remaining()) {
    fail(std::string("truncated: ") + what + " needs " + std::to_string(bytes) + " bytes, " +
         std::to_string(remaining()) + " left");
  }
}

std::uint8_t BinaryReader::u8() {
  need(1, "a byte");
  return data_[offset_++];
}

std::uint32_t BinaryReader::u32() {
  need(4, "a 32-bit integer");
  std::uint32_t value = 0;
  for (int k = 0; k < 4; ++k) value |= static_cast<std::uint32_t>(data_[offset_ + k]) << (8 * k);
  offset_ += 4;
  return value;
}

std::uint64_t BinaryReader::u64() {
  need(8, "a 64-bit integer");
  std::uint64_t value = 0;
  for (int k = 0; k < 8; ++k) value |= static_cast<std::uint64_t>(data_[offset_ + k]) << (8 * k);
  offset_ += 8;
  return value;
}

double BinaryReader::f64() {
  const std::uint64_t bits = u64();
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::uint64_t BinaryReader::count(std::size_t element_size, const char* what) {
  const std::uint64_t n = u64();
  if (element_size > 0 && n > remaining() / element_size) {
    fail(std::string("a count of ") + std::to_string(n) + " " + what +
         " cannot fit in the remaining " + std::to_string(remaining()) + " bytes");
  }
  return n;
}

std::string BinaryReader::string() {
  const std::uint32_t n = u32();
  need(n, "a string");
  std::string value(reinterpret_cast<const char*>(data_ + offset_), n);
  offset_ += n;
  return value;
}

std::vector<std::uint8_t> BinaryReader::blob() {
  const std::uint64_t n = count(1, "bytes");
  std::vector<std::uint8_t> value(data_ + offset_, data_ + offset_ + n);
  offset_ += n;
  return value;
}

std::vector<int> BinaryReader::ints() {
  const std::uint64_t n = count(4, "integers");
  std::vector<int> values(n);
  for (auto& v : values) v = i32();
  return values;
}

Eigen::VectorXd BinaryReader::doubles() {
  const std::uint64_t n = count(8, "doubles");
  Eigen::VectorXd values(static_cast<Eigen::Index>(n));
  for (Eigen::Index i = 0; i < values.size(); ++i) values(i) = f64();
  return values;
}

Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic> BinaryReader::int_matrix() {
  const std::uint64_t rows = u64();
  const std::uint64_t cols = u64();
  check_dimensions(*this, rows, cols);
  if (cols != 0 && rows > remaining() / 4 / cols) fail("an integer matrix larger than the file");
  Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic> m(static_cast<Eigen::Index>(rows),
                                                       static_cast<Eigen::Index>(cols));
  // Element by element in row-major order: an empty matrix of many rows costs nothing.
  for (Eigen::Index i = 0; i < m.size(); ++i) m(i / m.cols(), i % m.cols()) = i32();
  return m;
}

Eigen::MatrixXd BinaryReader::double_matrix() {
  const std::uint64_t rows = u64();
  const std::uint64_t cols = u64();
  check_dimensions(*this, rows, cols);
  if (cols != 0 && rows > remaining() / 8 / cols) fail("a matrix larger than the file");
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  for (Eigen::Index i = 0; i < m.size(); ++i) m(i / m.cols(), i % m.cols()) = f64();
  return m;
}

}  // namespace surfcomp::io
