// The PLY format's pieces shared by the reader (ply_read.cpp) and the writer (ply_write.cpp):
// its scalar type names and ranges, byte order, and the header. Not installed.
#pragma once

#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace surfcomp::mesh::io::detail {

/// The type a PLY type name stands for (both spellings: "float" and "float32", ...), or none.
std::optional<ValueType> parse_type_name(std::string_view name);
/// The name written for `type` ("char", "uchar", ..., "float", "double").
const char* type_name(ValueType type);
bool is_integer(ValueType type);
/// The smallest and largest values of an integer type (`type` must be one).
std::int64_t min_of(ValueType type);
std::int64_t max_of(ValueType type);
bool host_is_little_endian();
/// The value of type `type` stored at `p` (value_size(type) bytes), byte-swapped if `swap`.
double load_value(const char* p, ValueType type, bool swap);

struct PlyProperty {
  std::string name;
  bool is_list = false;
  ValueType type = ValueType::float32;      // scalar type, or the type of the list's items
  ValueType count_type = ValueType::uint8;  // lists only
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::size_t line = 0;  // header line that declared it
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  // byte offset of the data section
  std::size_t data_line = 0;    // number of the first line of the data section
};

/// The header at the start of `data` (the whole file). Throws FormatError naming `name` and
/// the line for anything but a well-formed header ending in 'end_header'.
PlyHeader parse_header(std::string_view data, const std::string& name);

}  // namespace surfcomp::mesh::io::detail
