#include "surfcomp/mesh/io/ply.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "text_parsing.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>

namespace surfcomp::mesh::io {
namespace {

using detail::Location;
using detail::quote;

constexpr std::size_t none = std::numeric_limits<std::size_t>::max();

// ---------------------------------------------------------------------------------------------
// Types

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

template <class T>
T load_as(const unsigned char* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

/// The value of type `type` stored at `p` (value_size(type) bytes), byte-swapped if `swap`.
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

// ---------------------------------------------------------------------------------------------
// Header

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

// What the reader does with each element and property.
struct Roles {
  std::size_t vertex = none;        // index of element "vertex"
  std::size_t face = none;          // index of element "face", if any
  std::size_t face_indices = none;  // index of vertex_indices within the face element
  std::array<std::size_t, 3> position{none, none, none};
  std::array<std::size_t, 3> normal{none, none, none};
  bool has_normals = false;
  int n_vertices = 0;
};

std::size_t find_property(const PlyElement& element, const std::string& name) {
  for (std::size_t k = 0; k < element.properties.size(); ++k) {
    if (element.properties[k].name == name) return k;
  }
  return none;
}

Roles assign_roles(const PlyHeader& header, const std::string& name) {
  Roles roles;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    if (header.elements[e].name == "vertex") roles.vertex = e;
    if (header.elements[e].name == "face") roles.face = e;
  }
  if (roles.vertex == none) {
    throw FormatError(name, header.data_line - 1, "expected an element 'vertex' in the header");
  }
  const PlyElement& vertex = header.elements[roles.vertex];
  if (vertex.count > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
    throw FormatError(name, vertex.line,
                      "expected at most " + std::to_string(std::numeric_limits<int>::max()) +
                          " vertices, found " + std::to_string(vertex.count));
  }
  roles.n_vertices = static_cast<int>(vertex.count);
  const std::array<const char*, 3> xyz{"x", "y", "z"};
  const std::array<const char*, 3> nxyz{"nx", "ny", "nz"};
  for (std::size_t c = 0; c < 3; ++c) {
    roles.position[c] = find_property(vertex, xyz[c]);
    if (roles.position[c] == none || vertex.properties[roles.position[c]].is_list) {
      throw FormatError(name, vertex.line,
                        std::string("expected a scalar vertex property '") + xyz[c] + "'");
    }
    roles.normal[c] = find_property(vertex, nxyz[c]);
  }
  roles.has_normals = std::all_of(roles.normal.begin(), roles.normal.end(), [&](std::size_t k) {
    return k != none && !vertex.properties[k].is_list;
  });
  if (!roles.has_normals) roles.normal = {none, none, none};
  if (roles.face != none) {
    const PlyElement& face = header.elements[roles.face];
    roles.face_indices = find_property(face, "vertex_indices");
    if (roles.face_indices == none) roles.face_indices = find_property(face, "vertex_index");
    if (roles.face_indices == none) {
      throw FormatError(name, face.line,
                        "expected a list property 'vertex_indices' in element 'face'");
    }
    const PlyProperty& indices = face.properties[roles.face_indices];
    if (!indices.is_list || !is_integer(indices.type)) {
      throw FormatError(name, face.line,
                        "expected '" + indices.name + "' to be a list of an integer type");
    }
  }
  return roles;
}

/// Rejects element counts that the bytes after the header cannot hold, before anything is
/// reserved.
void check_counts(const PlyHeader& header, std::size_t data_bytes, const std::string& name) {
  std::uint64_t remaining = data_bytes;
  for (const PlyElement& element : header.elements) {
    std::uint64_t min_bytes = 0;
    for (const PlyProperty& p : element.properties) {
      if (header.format == PlyFormat::ascii) {
        min_bytes += 2;  // one character and a separator
      } else {
        min_bytes += value_size(p.is_list ? p.count_type : p.type);
      }
    }
    detail::check_count_fits(element.count, min_bytes, remaining, Location{name, element.line},
                             "items of element '" + element.name + "'");
    remaining -= element.count * min_bytes;
  }
}

// ---------------------------------------------------------------------------------------------
// Data sources: one element item at a time, ascii or binary.

class AsciiSource {
 public:
  AsciiSource(std::string_view text, std::size_t first_line, const std::string& name)
      : lines_(text, first_line), name_(name) {}

  void begin_item(const PlyElement& element, std::uint64_t index) {
    if (!lines_.next_non_blank(line_)) {
      throw FormatError(name_, lines_.line_number(),
                        "expected item " + std::to_string(index + 1) + " of " +
                            std::to_string(element.count) + " of element '" + element.name +
                            "', found the end of the file");
    }
    detail::split_tokens(line_, tokens_);
    next_ = 0;
  }

  double scalar(const PlyProperty& p) { return parse(next_token(p), p.type, p); }

  std::uint64_t list_count(const PlyProperty& p) {
    const std::string_view token = next_token(p);
    const auto count = static_cast<std::uint64_t>(detail::parse_integer(
        token, at(), "a list length for '" + p.name + "'", 0, max_of(p.count_type)));
    if (count > tokens_.size() - next_) {
      fail("expected " + std::to_string(count) + " items of list '" + p.name + "', found " +
           std::to_string(tokens_.size() - next_) + " values left on the line");
    }
    return count;
  }

  std::int64_t list_index(const PlyProperty& p) {
    return detail::parse_integer(next_token(p), at(), "an index of list '" + p.name + "'",
                                 min_of(p.type), max_of(p.type));
  }

  void skip_list(const PlyProperty&, std::uint64_t count) { next_ += count; }

  void end_item(const PlyElement& element) {
    if (next_ != tokens_.size()) {
      fail("expected " + std::to_string(next_) + " values for an item of element '" + element.name +
           "', found more: " + quote(tokens_[next_]));
    }
  }

  void finish() {
    std::string_view extra;
    if (lines_.next_non_blank(extra)) {
      fail("expected the end of the file after the last element, found " + quote(extra));
    }
  }

  [[noreturn]] void fail(const std::string& reason) const {
    throw FormatError(name_, lines_.line_number(), reason);
  }

 private:
  Location at() const { return Location{name_, lines_.line_number()}; }

  std::string_view next_token(const PlyProperty& p) {
    if (next_ >= tokens_.size()) {
      fail("expected a value for property '" + p.name + "', found the end of the line");
    }
    return tokens_[next_++];
  }

  double parse(std::string_view token, ValueType type, const PlyProperty& p) const {
    const std::string what = std::string("a ") + type_name(type) + " for property '" + p.name + "'";
    switch (type) {
      case ValueType::float32:
        return detail::parse_float(token, at(), what, false);
      case ValueType::float64:
        return detail::parse_double(token, at(), what, false);
      default:
        return static_cast<double>(
            detail::parse_integer(token, at(), what, min_of(type), max_of(type)));
    }
  }

  detail::LineCursor lines_;
  const std::string& name_;
  std::string_view line_;
  std::vector<std::string_view> tokens_;
  std::size_t next_ = 0;
};

class BinarySource {
 public:
  BinarySource(std::string_view data, std::size_t data_offset, bool swap, const std::string& name)
      : data_(data), offset_(data_offset), swap_(swap), name_(name) {}

  void begin_item(const PlyElement& element, std::uint64_t index) {
    element_ = &element;
    index_ = index;
  }

  double scalar(const PlyProperty& p) { return take(p.type, p); }

  std::uint64_t list_count(const PlyProperty& p) {
    const double count = take(p.count_type, p);
    if (count < 0) {
      fail("expected a list length >= 0 for '" + p.name + "', found " +
           std::to_string(static_cast<std::int64_t>(count)));
    }
    const auto n = static_cast<std::uint64_t>(count);
    if (n > (data_.size() - position_) / value_size(p.type)) {
      fail("expected " + std::to_string(n) + " items of list '" + p.name + "', found only " +
           std::to_string(data_.size() - position_) + " bytes left (truncated data)");
    }
    return n;
  }

  std::int64_t list_index(const PlyProperty& p) {
    return static_cast<std::int64_t>(take(p.type, p));
  }

  void skip_list(const PlyProperty& p, std::uint64_t count) {
    position_ += static_cast<std::size_t>(count) * value_size(p.type);
  }

  void end_item(const PlyElement&) {}

  void finish() {
    element_ = nullptr;
    if (position_ != data_.size()) {
      fail("expected the end of the file after the last element, found " +
           std::to_string(data_.size() - position_) + " more bytes");
    }
  }

  [[noreturn]] void fail(const std::string& reason) const {
    std::string where = "byte " + std::to_string(offset_ + position_);
    if (element_ != nullptr) {
      where += " (item " + std::to_string(index_ + 1) + " of " + std::to_string(element_->count) +
               " of element '" + element_->name + "')";
    }
    throw FormatError(name_, where + ": " + reason);
  }

 private:
  double take(ValueType type, const PlyProperty& p) {
    const std::size_t size = value_size(type);
    if (data_.size() - position_ < size) {
      fail("expected a " + std::string(type_name(type)) + " for property '" + p.name +
           "', found the end of the file (truncated data)");
    }
    const double value = load_value(data_.data() + position_, type, swap_);
    position_ += size;
    return value;
  }

  std::string_view data_;
  std::size_t offset_;
  bool swap_;
  const std::string& name_;
  std::size_t position_ = 0;
  const PlyElement* element_ = nullptr;
  std::uint64_t index_ = 0;
};

// ---------------------------------------------------------------------------------------------
// Reading

struct PlyData {
  std::vector<std::vector<double>> vertex_columns;  // one per vertex property (lists: empty)
  std::vector<int> triangles;                       // 3 per triangle
};

template <class Source>
PlyData read_data(const PlyHeader& header, const Roles& roles, Source& source) {
  PlyData out;
  const PlyElement& vertex = header.elements[roles.vertex];
  out.vertex_columns.resize(vertex.properties.size());
  std::vector<bool> must_be_finite(vertex.properties.size(), false);
  for (std::size_t c = 0; c < 3; ++c) {
    must_be_finite[roles.position[c]] = true;
    if (roles.has_normals) must_be_finite[roles.normal[c]] = true;
  }
  std::vector<int> polygon;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    if (element.properties.empty()) continue;  // an item without properties has no bytes
    const bool is_vertex = e == roles.vertex;
    const bool is_face = e == roles.face;
    if (is_vertex) {
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        if (!element.properties[k].is_list) out.vertex_columns[k].reserve(element.count);
      }
    }
    if (is_face) out.triangles.reserve(3 * element.count);
    for (std::uint64_t i = 0; i < element.count; ++i) {
      source.begin_item(element, i);
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const PlyProperty& p = element.properties[k];
        if (!p.is_list) {
          const double value = source.scalar(p);
          if (is_vertex) {
            if (must_be_finite[k] && !std::isfinite(value)) {
              source.fail("expected a finite value for property '" + p.name + "', found " +
                          std::to_string(value));
            }
            out.vertex_columns[k].push_back(value);
          }
          continue;
        }
        const std::uint64_t count = source.list_count(p);
        if (!is_face || k != roles.face_indices) {
          source.skip_list(p, count);
          continue;
        }
        if (count < 3) {
          source.fail("expected a polygon of at least 3 vertices, found " + std::to_string(count));
        }
        polygon.clear();
        for (std::uint64_t j = 0; j < count; ++j) {
          const std::int64_t index = source.list_index(p);
          if (index < 0 || index >= roles.n_vertices) {
            source.fail("expected a vertex index in 0.." + std::to_string(roles.n_vertices - 1) +
                        ", found " + std::to_string(index));
          }
          polygon.push_back(static_cast<int>(index));
        }
        for (std::size_t j = 1; j + 1 < polygon.size(); ++j) {
          out.triangles.insert(out.triangles.end(), {polygon[0], polygon[j], polygon[j + 1]});
        }
      }
      source.end_item(element);
    }
  }
  source.finish();
  return out;
}

/// The common type of three properties, or float64 if they differ.
ValueType common_type(const PlyElement& element, const std::array<std::size_t, 3>& k) {
  const ValueType t = element.properties[k[0]].type;
  const bool same = element.properties[k[1]].type == t && element.properties[k[2]].type == t;
  return same ? t : ValueType::float64;
}

Surface read_ply_data(std::string_view data, const std::string& name) {
  const PlyHeader header = parse_header(data, name);
  check_counts(header, data.size() - header.data_offset, name);
  const Roles roles = assign_roles(header, name);
  const std::string_view body = data.substr(header.data_offset);
  PlyData ply;
  if (header.format == PlyFormat::ascii) {
    AsciiSource source(body, header.data_line, name);
    ply = read_data(header, roles, source);
  } else {
    const bool file_little = header.format == PlyFormat::binary_little_endian;
    BinarySource source(body, header.data_offset, file_little != host_is_little_endian(), name);
    ply = read_data(header, roles, source);
  }

  const PlyElement& vertex = header.elements[roles.vertex];
  const Eigen::Index n = roles.n_vertices;
  Eigen::MatrixX3d positions(n, 3);
  for (Eigen::Index c = 0; c < 3; ++c) {
    const auto& column = ply.vertex_columns[roles.position[static_cast<std::size_t>(c)]];
    for (Eigen::Index i = 0; i < n; ++i) positions(i, c) = column[static_cast<std::size_t>(i)];
  }
  const auto n_triangles = static_cast<Eigen::Index>(ply.triangles.size() / 3);
  const Eigen::MatrixX3i faces =
      Eigen::Map<const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(ply.triangles.data(),
                                                                               n_triangles, 3);
  Surface surface = Surface::from_arrays(positions, faces, name);
  surface.set_position_type(common_type(vertex, roles.position));
  if (roles.has_normals) {
    Eigen::MatrixX3d normals(n, 3);
    for (Eigen::Index c = 0; c < 3; ++c) {
      const auto& column = ply.vertex_columns[roles.normal[static_cast<std::size_t>(c)]];
      for (Eigen::Index i = 0; i < n; ++i) normals(i, c) = column[static_cast<std::size_t>(i)];
    }
    surface.set_normals(normals);
    surface.set_normal_type(common_type(vertex, roles.normal));
  }
  for (std::size_t k = 0; k < vertex.properties.size(); ++k) {
    const PlyProperty& p = vertex.properties[k];
    const bool is_geometry =
        std::find(roles.position.begin(), roles.position.end(), k) != roles.position.end() ||
        std::find(roles.normal.begin(), roles.normal.end(), k) != roles.normal.end();
    if (p.is_list || is_geometry) continue;
    surface.set_property(p.name, Eigen::Map<const Eigen::VectorXd>(ply.vertex_columns[k].data(), n),
                         p.type);
  }
  return surface;
}

// ---------------------------------------------------------------------------------------------
// Writing

struct OutColumn {
  std::string name;
  ValueType type;
  Eigen::VectorXd values;
};

std::vector<OutColumn> output_columns(const Surface& s) {
  std::vector<OutColumn> columns;
  const Eigen::MatrixX3d positions = s.positions();
  const std::array<const char*, 3> xyz{"x", "y", "z"};
  const std::array<const char*, 3> nxyz{"nx", "ny", "nz"};
  for (Eigen::Index c = 0; c < 3; ++c) {
    columns.push_back({xyz[static_cast<std::size_t>(c)], s.position_type(), positions.col(c)});
  }
  if (s.has_normals()) {
    const Eigen::MatrixX3d normals = s.normals();
    for (Eigen::Index c = 0; c < 3; ++c) {
      columns.push_back({nxyz[static_cast<std::size_t>(c)], s.normal_type(), normals.col(c)});
    }
  }
  const std::size_t n_geometry = columns.size();
  for (const std::string& name : s.property_names()) {
    const bool bad_name = name.empty() || std::any_of(name.begin(), name.end(), detail::is_space);
    const bool taken = std::any_of(columns.begin(), columns.begin() + static_cast<long>(n_geometry),
                                   [&](const OutColumn& c) { return c.name == name; });
    if (bad_name || taken) {
      throw InputError(s.source() + ": property " + quote(name) +
                       " cannot be written to PLY (empty, contains whitespace, or repeats a "
                       "coordinate or normal name)");
    }
    columns.push_back({name, s.property_type(name), s.property(name)});
  }
  return columns;
}

[[noreturn]] void unrepresentable(const Surface& s, const OutColumn& column, Eigen::Index vertex) {
  throw InputError(s.source() + ": value " + std::to_string(column.values(vertex)) +
                   " of property '" + column.name + "' at vertex " + std::to_string(vertex) +
                   " does not fit its storage type " + type_name(column.type));
}

/// The value as an integer of the column's type; throws unless it is integral and in range.
std::int64_t checked_integer(const Surface& s, const OutColumn& column, Eigen::Index vertex) {
  const double v = column.values(vertex);
  if (!(v == std::trunc(v)) || v < static_cast<double>(min_of(column.type)) ||
      v > static_cast<double>(max_of(column.type))) {
    unrepresentable(s, column, vertex);
  }
  return static_cast<std::int64_t>(v);
}

float checked_float(const Surface& s, const OutColumn& column, Eigen::Index vertex) {
  const double v = column.values(vertex);
  if (std::isfinite(v) && std::fabs(v) > static_cast<double>(FLT_MAX)) {
    unrepresentable(s, column, vertex);
  }
  return static_cast<float>(v);
}

template <class T>
void append_bytes(std::string& out, T value, bool swap) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

void append_binary(std::string& out, const Surface& s, const OutColumn& column, Eigen::Index i,
                   bool swap) {
  switch (column.type) {
    case ValueType::int8:
      return append_bytes(out, static_cast<std::int8_t>(checked_integer(s, column, i)), swap);
    case ValueType::uint8:
      return append_bytes(out, static_cast<std::uint8_t>(checked_integer(s, column, i)), swap);
    case ValueType::int16:
      return append_bytes(out, static_cast<std::int16_t>(checked_integer(s, column, i)), swap);
    case ValueType::uint16:
      return append_bytes(out, static_cast<std::uint16_t>(checked_integer(s, column, i)), swap);
    case ValueType::int32:
      return append_bytes(out, static_cast<std::int32_t>(checked_integer(s, column, i)), swap);
    case ValueType::uint32:
      return append_bytes(out, static_cast<std::uint32_t>(checked_integer(s, column, i)), swap);
    case ValueType::float32:
      return append_bytes(out, checked_float(s, column, i), swap);
    case ValueType::float64:
      return append_bytes(out, column.values(i), swap);
  }
}

void append_text(std::string& out, const Surface& s, const OutColumn& column, Eigen::Index i) {
  switch (column.type) {
    case ValueType::float32:
      return detail::append_number(out, checked_float(s, column, i));
    case ValueType::float64:
      return detail::append_number(out, column.values(i));
    default:
      return detail::append_number(out, checked_integer(s, column, i));
  }
}

void write_ply_stream(const Surface& s, std::ostream& out, PlyFormat format) {
  const std::vector<OutColumn> columns = output_columns(s);
  const Eigen::MatrixX3i faces = s.faces();
  const bool file_little = format == PlyFormat::binary_little_endian;
  const bool swap = format != PlyFormat::ascii && file_little != host_is_little_endian();

  std::string buffer = "ply\nformat ";
  buffer += format == PlyFormat::ascii ? "ascii"
            : file_little              ? "binary_little_endian"
                                       : "binary_big_endian";
  buffer += " 1.0\ncomment surfcomp\nelement vertex " + std::to_string(s.n_vertices()) + "\n";
  for (const OutColumn& column : columns) {
    buffer += std::string("property ") + type_name(column.type) + " " + column.name + "\n";
  }
  buffer += "element face " + std::to_string(faces.rows()) +
            "\nproperty list uchar int vertex_indices\nend_header\n";

  constexpr std::size_t flush_at = std::size_t{1} << 20;
  auto flush = [&out, &buffer] {
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
  };
  const auto n = static_cast<Eigen::Index>(s.n_vertices());
  for (Eigen::Index i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (format == PlyFormat::ascii) {
        if (c > 0) buffer += ' ';
        append_text(buffer, s, columns[c], i);
      } else {
        append_binary(buffer, s, columns[c], i, swap);
      }
    }
    if (format == PlyFormat::ascii) buffer += '\n';
    if (buffer.size() >= flush_at) flush();
  }
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (format == PlyFormat::ascii) {
      buffer += '3';
      for (Eigen::Index k = 0; k < 3; ++k) {
        buffer += ' ';
        detail::append_number(buffer, static_cast<std::int64_t>(faces(f, k)));
      }
      buffer += '\n';
    } else {
      buffer += '\3';
      for (Eigen::Index k = 0; k < 3; ++k) {
        append_bytes(buffer, static_cast<std::int32_t>(faces(f, k)), swap);
      }
    }
    if (buffer.size() >= flush_at) flush();
  }
  flush();
}

}  // namespace

Surface read_ply(const std::filesystem::path& path) {
  return read_ply_data(detail::read_whole_file(path), path.string());
}

Surface read_ply(std::istream& in, const std::string& name) {
  return read_ply_data(detail::read_whole_stream(in, name), name);
}

void write_ply(const Surface& s, std::ostream& out, PlyFormat format) {
  write_ply_stream(s, out, format);
  if (!out) throw FileError(s.source(), "writing PLY to the stream failed");
}

void write_ply(const Surface& s, const std::filesystem::path& path, PlyFormat format) {
  surfcomp::io::write_file_atomically(path,
                                      [&](std::ostream& out) { write_ply_stream(s, out, format); });
}

}  // namespace surfcomp::mesh::io
