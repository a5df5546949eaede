#include "ply_format.hpp"

#include "surfcomp/core/error.hpp"
#include "text_parsing.hpp"

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace surfcomp::mesh::io::detail {
namespace {

struct TypeName {
  const char* name;
  ValueType type;
};
// Both spellings of every type; the first of each pair is the one written.
constexpr std::array<TypeName, 16> type_names{{{"char", ValueType::int8},
                                               {"int8", ValueType::int8},
                                               {"uchar", ValueType::uint8},
                                               {"uint8", ValueType::uint8},
                                               {"short", ValueType::int16},
                                               {"int16", ValueType::int16},
                                               {"ushort", ValueType::uint16},
                                               {"uint16", ValueType::uint16},
                                               {"int", ValueType::int32},
                                               {"int32", ValueType::int32},
                                               {"uint", ValueType::uint32},
                                               {"uint32", ValueType::uint32},
                                               {"float", ValueType::float32},
                                               {"float32", ValueType::float32},
                                               {"double", ValueType::float64},
                                               {"float64", ValueType::float64}}};

template <class T>
T load_as(const unsigned char* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

}  // namespace

std::optional<ValueType> parse_type_name(std::string_view name) {
  for (const auto& t : type_names) {
    if (name == t.name) return t.type;
  }
  return std::nullopt;
}

const char* type_name(ValueType type) {
  for (const auto& t : type_names) {
    if (t.type == type) return t.name;
  }
  return "double";
}

bool is_integer(ValueType type) { return type != ValueType::float32 && type != ValueType::float64; }

std::int64_t min_of(ValueType type) {
  switch (type) {
    case ValueType::int8:
      return INT8_MIN;
    case ValueType::int16:
      return INT16_MIN;
    case ValueType::int32:
      return INT32_MIN;
    default:
      return 0;
  }
}

std::int64_t max_of(ValueType type) {
  switch (type) {
    case ValueType::int8:
      return INT8_MAX;
    case ValueType::uint8:
      return UINT8_MAX;
    case ValueType::int16:
      return INT16_MAX;
    case ValueType::uint16:
      return UINT16_MAX;
    case ValueType::int32:
      return INT32_MAX;
    default:
      return UINT32_MAX;
  }
}

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

double load_value(const char* p, ValueType type, bool swap) {
  unsigned char b[8];
  const std::size_t size = value_size(type);
  std::memcpy(b, p, size);
  if (swap) std::reverse(b, b + size);
  switch (type) {
    case ValueType::int8:
      return load_as<std::int8_t>(b);
    case ValueType::uint8:
      return load_as<std::uint8_t>(b);
    case ValueType::int16:
      return load_as<std::int16_t>(b);
    case ValueType::uint16:
      return load_as<std::uint16_t>(b);
    case ValueType::int32:
      return load_as<std::int32_t>(b);
    case ValueType::uint32:
      return load_as<std::uint32_t>(b);
    case ValueType::float32:
      return static_cast<double>(load_as<float>(b));
    case ValueType::float64:
      return load_as<double>(b);
  }
  return 0.0;
}

PlyHeader parse_header(std::string_view data, const std::string& name) {
  detail::LineCursor lines(data);
  std::string_view line;
  std::vector<std::string_view> tokens;
  if (!lines.next(line)) throw FormatError(name, 1, "expected 'ply', found an empty file");
  detail::split_tokens(line, tokens);
  if (tokens.size() != 1 || tokens[0] != "ply") {
    throw FormatError(name, 1, "expected 'ply' as the first line, found " + quote(line));
  }
  PlyHeader header;
  bool have_format = false;
  while (lines.next(line)) {
    const std::size_t number = lines.line_number();
    detail::split_tokens(line, tokens);
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "end_header") {
      if (tokens.size() != 1) {
        throw FormatError(name, number, "expected 'end_header' alone, found " + quote(line));
      }
      if (!have_format) {
        throw FormatError(name, number, "expected a 'format' line before 'end_header'");
      }
      header.data_offset = lines.position();
      header.data_line = number + 1;
      return header;
    }
    if (keyword == "format") {
      if (have_format) throw FormatError(name, number, "expected one 'format' line, found two");
      if (tokens.size() != 3 || tokens[2] != "1.0") {
        throw FormatError(name, number, "expected 'format <encoding> 1.0', found " + quote(line));
      }
      if (tokens[1] == "ascii") {
        header.format = PlyFormat::ascii;
      } else if (tokens[1] == "binary_little_endian") {
        header.format = PlyFormat::binary_little_endian;
      } else if (tokens[1] == "binary_big_endian") {
        header.format = PlyFormat::binary_big_endian;
      } else {
        throw FormatError(
            name, number,
            "expected ascii, binary_little_endian or binary_big_endian, found " + quote(tokens[1]));
      }
      have_format = true;
    } else if (keyword == "element") {
      if (tokens.size() != 3) {
        throw FormatError(name, number, "expected 'element <name> <count>', found " + quote(line));
      }
      PlyElement element;
      element.name = std::string(tokens[1]);
      for (const auto& other : header.elements) {
        if (other.name == element.name) {
          throw FormatError(name, number,
                            "expected each element once, found a second " + quote(element.name));
        }
      }
      element.count = static_cast<std::uint64_t>(
          detail::parse_integer(tokens[2], Location{name, number}, "an element count", 0,
                                std::numeric_limits<std::int64_t>::max()));
      element.line = number;
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) {
        throw FormatError(name, number, "expected an 'element' line before the first property");
      }
      PlyProperty property;
      const bool is_list = tokens.size() >= 2 && tokens[1] == "list";
      if (is_list ? tokens.size() != 5 : tokens.size() != 3) {
        throw FormatError(name, number,
                          "expected 'property <type> <name>' or 'property list <count type> "
                          "<item type> <name>', found " +
                              quote(line));
      }
      const std::size_t type_at = is_list ? 3 : 1;
      const auto type = parse_type_name(tokens[type_at]);
      if (!type) {
        throw FormatError(name, number,
                          "expected a PLY type (char, uchar, short, ushort, int, "
                          "uint, float, double or int8...float64), found " +
                              quote(tokens[type_at]));
      }
      property.type = *type;
      property.is_list = is_list;
      if (is_list) {
        const auto count_type = parse_type_name(tokens[2]);
        if (!count_type || !is_integer(*count_type)) {
          throw FormatError(
              name, number,
              "expected an integer type for the list count, found " + quote(tokens[2]));
        }
        property.count_type = *count_type;
      }
      property.name = std::string(tokens[type_at + 1]);
      auto& properties = header.elements.back().properties;
      for (const auto& other : properties) {
        if (other.name == property.name) {
          throw FormatError(name, number,
                            "expected each property of an element once, found a "
                            "second " +
                                quote(property.name));
        }
      }
      properties.push_back(std::move(property));
    } else {
      throw FormatError(name, number,
                        "expected a header line (format, element, property, comment, obj_info "
                        "or end_header), found " +
                            quote(line));
    }
  }
  throw FormatError(name, lines.line_number(), "expected 'end_header', found the end of the file");
}

}  // namespace surfcomp::mesh::io::detail
