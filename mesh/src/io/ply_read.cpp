#include "ply_format.hpp"
#include "surface_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "text_parsing.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace surfcomp::mesh::io {
namespace {

using detail::host_is_little_endian;
using detail::is_integer;
using detail::load_value;
using detail::Location;
using detail::max_of;
using detail::min_of;
using detail::parse_header;
using detail::PlyElement;
using detail::PlyHeader;
using detail::PlyProperty;
using detail::quote;
using detail::type_name;

constexpr std::size_t none = std::numeric_limits<std::size_t>::max();

// What the reader does with each element and property.
struct Roles {
  std::size_t vertex = none;         // index of element "vertex"
  std::size_t face = none;           // index of element "face", if any
  std::size_t face_indices = none;   // index of vertex_indices within the face element
  std::size_t strips = none;         // index of element "tristrips", if any
  std::size_t strip_indices = none;  // index of vertex_indices within the tristrips element
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

/// The index of the list property vertex_indices (or vertex_index) of element `e` (a face or
/// tristrips element), or none when there is no such element.
std::size_t index_list(const PlyHeader& header, std::size_t e, const std::string& name) {
  if (e == none) return none;
  const PlyElement& element = header.elements[e];
  std::size_t k = find_property(element, "vertex_indices");
  if (k == none) k = find_property(element, "vertex_index");
  if (k == none) {
    throw FormatError(
        name, element.line,
        "expected a list property 'vertex_indices' in element '" + element.name + "'");
  }
  const PlyProperty& indices = element.properties[k];
  if (!indices.is_list || !is_integer(indices.type)) {
    throw FormatError(name, element.line,
                      "expected '" + indices.name + "' to be a list of an integer type");
  }
  return k;
}

Roles assign_roles(const PlyHeader& header, const std::string& name) {
  Roles roles;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    if (header.elements[e].name == "vertex") roles.vertex = e;
    if (header.elements[e].name == "face") roles.face = e;
    if (header.elements[e].name == "tristrips") roles.strips = e;
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
  roles.face_indices = index_list(header, roles.face, name);
  roles.strip_indices = index_list(header, roles.strips, name);
  const auto count_of = [&](std::size_t e) {
    return e == none ? std::uint64_t{0} : header.elements[e].count;
  };
  if (count_of(roles.face) == 0 && count_of(roles.strips) == 0) {
    detail::check_has_triangles(vertex.count, 0, name);
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

/// Reads one tristrips item of `count` indices (RPly's convention: -1 ends a strip and starts
/// the next) and appends its triangles: in a strip s0 s1 s2 s3 ..., triangle j is
/// (sj, sj+1, sj+2) for even j and (sj+1, sj, sj+2) for odd j, so that all keep one
/// orientation; a triangle that repeats a vertex (a strip's way of turning) is skipped.
template <class Source>
void read_strip(Source& source, const PlyProperty& p, std::uint64_t count, int n_vertices,
                std::vector<int>& triangles) {
  std::array<int, 3> last{};  // the strip's last three vertices, oldest first
  std::size_t length = 0;     // vertices in the current strip so far
  for (std::uint64_t j = 0; j < count; ++j) {
    const std::int64_t index = source.list_index(p);
    if (index == -1) {
      length = 0;
      continue;
    }
    if (index < 0 || index >= n_vertices) {
      source.fail("expected a vertex index in 0.." + std::to_string(n_vertices - 1) +
                  " or -1 (a new strip), found " + std::to_string(index));
    }
    last = {last[1], last[2], static_cast<int>(index)};
    if (++length < 3) continue;
    if (last[0] == last[1] || last[1] == last[2] || last[0] == last[2]) continue;
    if (length % 2 == 1) {  // triangle j = length - 3 is even
      triangles.insert(triangles.end(), {last[0], last[1], last[2]});
    } else {
      triangles.insert(triangles.end(), {last[1], last[0], last[2]});
    }
  }
}

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
    const bool is_strip = e == roles.strips;
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
        if (is_strip && k == roles.strip_indices) {
          read_strip(source, p, count, roles.n_vertices, out.triangles);
          continue;
        }
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
  detail::check_has_triangles(vertex.count, ply.triangles.size() / 3, name);
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
  detail::check_read_surface(surface, name);
  return surface;
}

}  // namespace

Surface read_ply(const std::filesystem::path& path) {
  return read_ply_data(surfcomp::io::read_input_file(path), path.string());
}

Surface read_ply(std::istream& in, const std::string& name) {
  return read_ply_data(detail::read_whole_stream(in, name), name);
}

}  // namespace surfcomp::mesh::io
