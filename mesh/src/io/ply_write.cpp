#include "ply_format.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "text_parsing.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace surfcomp::mesh::io {
namespace {

using detail::host_is_little_endian;
using detail::max_of;
using detail::min_of;
using detail::quote;
using detail::type_name;

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

void write_ply(const Surface& s, std::ostream& out, PlyFormat format) {
  write_ply_stream(s, out, format);
  if (!out) throw FileError(s.source(), "writing PLY to the stream failed");
}

void write_ply(const Surface& s, const std::filesystem::path& path, PlyFormat format) {
  surfcomp::io::write_file_atomically(path,
                                      [&](std::ostream& out) { write_ply_stream(s, out, format); });
}

}  // namespace surfcomp::mesh::io
