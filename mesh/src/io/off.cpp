#include "surfcomp/mesh/io/off.hpp"

#include "surface_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "text_parsing.hpp"

#include <limits>

namespace surfcomp::mesh::io {
namespace {

using detail::Location;
using detail::quote;

/// The next line with content after '#' comments are removed, split into `tokens`.
bool next_content(detail::LineCursor& lines, std::vector<std::string_view>& tokens) {
  std::string_view line;
  while (lines.next(line)) {
    detail::split_tokens(detail::strip_comment(line), tokens);
    if (!tokens.empty()) return true;
  }
  return false;
}

[[noreturn]] void end_of_file(const detail::LineCursor& lines, const std::string& name,
                              const std::string& expected) {
  throw FormatError(name, lines.line_number(),
                    "expected " + expected + ", found the end of the file");
}

}  // namespace

Surface read_off(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::string data = surfcomp::io::read_input_file(path);
  detail::LineCursor lines(data);
  std::vector<std::string_view> tokens;
  if (!next_content(lines, tokens)) end_of_file(lines, name, "'OFF'");
  if (tokens[0] != "OFF") {
    throw FormatError(name, lines.line_number(), "expected 'OFF', found " + quote(tokens[0]));
  }
  if (tokens.size() == 1) {
    if (!next_content(lines, tokens)) end_of_file(lines, name, "the counts '#V #F #E'");
  } else {
    tokens.erase(tokens.begin());
  }
  const Location counts_at{name, lines.line_number()};
  if (tokens.size() != 3) {
    throw FormatError(
        name, counts_at.line,
        "expected the counts '#V #F #E', found " + std::to_string(tokens.size()) + " values");
  }
  constexpr std::int64_t max_int = std::numeric_limits<int>::max();
  const std::int64_t n_vertices = detail::parse_integer(tokens[0], counts_at, "#V", 0, max_int);
  const std::int64_t n_faces = detail::parse_integer(tokens[1], counts_at, "#F", 0, max_int);
  detail::parse_integer(tokens[2], counts_at, "#E", 0, std::numeric_limits<std::int64_t>::max());
  // At least "0 0 0\n" per vertex and "3 0 1 2\n" per face.
  const std::uint64_t vertex_bytes = 6 * static_cast<std::uint64_t>(n_vertices);
  detail::check_count_fits(static_cast<std::uint64_t>(n_vertices), 6, lines.remaining_bytes(),
                           counts_at, "vertices");
  detail::check_count_fits(static_cast<std::uint64_t>(n_faces), 8,
                           lines.remaining_bytes() - vertex_bytes, counts_at, "faces");

  Eigen::MatrixX3d positions(n_vertices, 3);
  for (Eigen::Index i = 0; i < n_vertices; ++i) {
    if (!next_content(lines, tokens)) {
      end_of_file(lines, name,
                  "vertex " + std::to_string(i + 1) + " of " + std::to_string(n_vertices));
    }
    const Location at{name, lines.line_number()};
    if (tokens.size() != 3) {
      throw FormatError(
          name, at.line,
          "expected a vertex 'x y z', found " + std::to_string(tokens.size()) + " values");
    }
    for (Eigen::Index c = 0; c < 3; ++c) {
      positions(i, c) =
          detail::parse_double(tokens[static_cast<std::size_t>(c)], at, "a finite coordinate");
    }
  }
  std::vector<int> triangles;
  triangles.reserve(3 * static_cast<std::size_t>(n_faces));
  std::vector<int> polygon;
  for (std::int64_t f = 0; f < n_faces; ++f) {
    if (!next_content(lines, tokens)) {
      end_of_file(lines, name, "face " + std::to_string(f + 1) + " of " + std::to_string(n_faces));
    }
    const Location at{name, lines.line_number()};
    const auto corners = static_cast<std::size_t>(detail::parse_integer(
        tokens[0], at, "a polygon size >= 3", 3, static_cast<std::int64_t>(tokens.size()) - 1));
    polygon.clear();
    for (std::size_t k = 1; k <= corners; ++k) {
      polygon.push_back(static_cast<int>(
          detail::parse_integer(tokens[k], at, "a vertex index", 0, n_vertices - 1)));
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      triangles.insert(triangles.end(), {polygon[0], polygon[k], polygon[k + 1]});
    }
  }
  if (next_content(lines, tokens)) {
    throw FormatError(name, lines.line_number(),
                      "expected the end of the file after " + std::to_string(n_faces) +
                          " faces, found " + quote(tokens[0]));
  }
  detail::check_has_triangles(static_cast<std::size_t>(n_vertices), triangles.size() / 3, name);
  const Eigen::MatrixX3i faces =
      Eigen::Map<const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(
          triangles.data(), static_cast<Eigen::Index>(triangles.size() / 3), 3);
  Surface surface = Surface::from_arrays(positions, faces, name);
  detail::check_read_surface(surface, name);
  return surface;
}

void write_off(const Surface& s, const std::filesystem::path& path) {
  surfcomp::io::write_file_atomically(path, [&s](std::ostream& out) {
    const Eigen::MatrixX3d positions = s.positions();
    const Eigen::MatrixX3i faces = s.faces();
    std::string text =
        "OFF\n" + std::to_string(positions.rows()) + " " + std::to_string(faces.rows()) + " 0\n";
    for (Eigen::Index i = 0; i < positions.rows(); ++i) {
      for (Eigen::Index c = 0; c < 3; ++c) {
        if (c > 0) text += ' ';
        detail::append_number(text, positions(i, c));
      }
      text += '\n';
    }
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      text += '3';
      for (Eigen::Index c = 0; c < 3; ++c) {
        text += ' ';
        detail::append_number(text, static_cast<std::int64_t>(faces(f, c)));
      }
      text += '\n';
    }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

}  // namespace surfcomp::mesh::io
