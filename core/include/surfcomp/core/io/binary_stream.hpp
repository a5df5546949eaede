// Little-endian binary encoding with bounds-checked decoding, for the project's own binary
// files (.hsi). Values are written byte by byte in little-endian order whatever the host, so a
// file is byte-identical across machines; every read checks the remaining length first.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace surfcomp::io {

/// FNV-1a 64-bit hash of `size` bytes (the .hsi checksum; detects corruption, not tampering).
std::uint64_t fnv1a64(const std::uint8_t* data, std::size_t size);

/// XXH3 64-bit hash of `size` bytes (xxHash): the checksum of data read in bulk, at memory speed
/// (a library's packed samples); detects corruption, not tampering.
std::uint64_t xxh3_64(const std::uint8_t* data, std::size_t size);

/// Appends little-endian encodings to a byte buffer.
class BinaryWriter {
 public:
  void u8(std::uint8_t value) { bytes_.push_back(value); }
  void u32(std::uint32_t value);
  void u64(std::uint64_t value);
  void i32(std::int32_t value) { u32(static_cast<std::uint32_t>(value)); }
  void f64(double value);
  void f32(float value);
  void zeros(std::size_t count);                                  ///< `count` zero bytes (padding)
  void string(const std::string& value);                          ///< u32 length, then the bytes
  void blob(const std::vector<std::uint8_t>& value);              ///< u64 length, then the bytes
  void ints(const std::vector<int>& values);                      ///< u64 count, then i32 each
  void doubles(const Eigen::Ref<const Eigen::VectorXd>& values);  ///< u64 count, then f64 each
  void int_matrix(const Eigen::Ref<const Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic>>& m);
  void double_matrix(
      const Eigen::Ref<const Eigen::MatrixXd>& m);  ///< u64 rows, u64 cols, row-major

  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

/// Decodes what BinaryWriter wrote. Every read that would pass the end, and every count that
/// could not fit in the remaining bytes, throws FormatError naming `source` and the offset.
class BinaryReader {
 public:
  BinaryReader(const std::uint8_t* data, std::size_t size, std::string source);

  std::uint8_t u8();
  std::uint32_t u32();
  std::uint64_t u64();
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  double f64();
  std::string string();
  std::vector<std::uint8_t> blob();
  std::vector<int> ints();
  Eigen::VectorXd doubles();
  Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic> int_matrix();
  Eigen::MatrixXd double_matrix();

  std::size_t offset() const { return offset_; }
  std::size_t remaining() const { return size_ - offset_; }
  const std::string& source() const { return source_; }
  /// Throws FormatError "source: byte OFFSET: what" — for checks made by the caller.
  [[noreturn]] void fail(const std::string& what) const;

 private:
  void need(std::size_t bytes, const char* what);
  std::uint64_t count(std::size_t element_size, const char* what);

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
  std::string source_;
};

}  // namespace surfcomp::io
