#include "surfcomp/mesh/io/obj.hpp"

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

/// The 0-based vertex of an OBJ face corner `a`, `a/b`, `a//c` or `a/b/c`, given the number
/// of vertices read so far.
int corner_vertex(std::string_view corner, std::size_t n_vertices, const Location& at) {
  const std::string_view number = corner.substr(0, corner.find('/'));
  const auto n = static_cast<std::int64_t>(n_vertices);
  const std::string what = "a vertex number in 1.." + std::to_string(n) + " or -" +
                           std::to_string(n) + "..-1 in face corner " + quote(corner);
  if (n == 0) throw FormatError(at.file, at.line, "expected a vertex before the first face");
  const std::int64_t value = detail::parse_integer(number, at, what, -n, n);
  if (value == 0) throw FormatError(at.file, at.line, "expected " + what + ", found 0");
  return static_cast<int>(value > 0 ? value - 1 : n + value);
}

}  // namespace

Surface read_obj(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::string data = surfcomp::io::read_input_file(path);
  detail::LineCursor lines(data);
  std::vector<double> positions;  // 3 per vertex
  std::vector<int> triangles;     // 3 per triangle
  std::vector<int> polygon;
  std::vector<std::string_view> tokens;
  std::string_view line;
  while (lines.next(line)) {
    detail::split_tokens(detail::strip_comment(line), tokens);
    if (tokens.empty()) continue;
    const Location at{name, lines.line_number()};
    if (tokens[0] == "v") {
      if (tokens.size() < 4 || tokens.size() > 7) {
        throw FormatError(name, at.line,
                          "expected 'v x y z [w | r g b]', found " +
                              std::to_string(tokens.size() - 1) + " values");
      }
      if (positions.size() / 3 >= static_cast<std::size_t>(std::numeric_limits<int>::max())) {
        throw FormatError(name, at.line, "expected at most 2^31-1 vertices");
      }
      for (std::size_t c = 1; c <= 3; ++c) {
        positions.push_back(detail::parse_double(tokens[c], at, "a finite coordinate"));
      }
    } else if (tokens[0] == "f") {
      if (tokens.size() < 4) {
        throw FormatError(
            name, at.line,
            "expected a face of at least 3 corners, found " + std::to_string(tokens.size() - 1));
      }
      polygon.clear();
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        polygon.push_back(corner_vertex(tokens[k], positions.size() / 3, at));
      }
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
        triangles.insert(triangles.end(), {polygon[0], polygon[k], polygon[k + 1]});
      }
    }
  }
  detail::check_has_triangles(positions.size() / 3, triangles.size() / 3, name);
  const Eigen::MatrixX3d vertex_positions =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
          positions.data(), static_cast<Eigen::Index>(positions.size() / 3), 3);
  const Eigen::MatrixX3i faces =
      Eigen::Map<const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(
          triangles.data(), static_cast<Eigen::Index>(triangles.size() / 3), 3);
  Surface surface = Surface::from_arrays(vertex_positions, faces, name);
  detail::check_read_surface(surface, name);
  return surface;
}

void write_obj(const Surface& s, const std::filesystem::path& path) {
  surfcomp::io::write_file_atomically(path, [&s](std::ostream& out) {
    const Eigen::MatrixX3d positions = s.positions();
    const Eigen::MatrixX3i faces = s.faces();
    std::string text = "# surfcomp\n";
    for (Eigen::Index i = 0; i < positions.rows(); ++i) {
      text += 'v';
      for (Eigen::Index c = 0; c < 3; ++c) {
        text += ' ';
        detail::append_number(text, positions(i, c));
      }
      text += '\n';
    }
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      text += 'f';
      for (Eigen::Index c = 0; c < 3; ++c) {
        text += ' ';
        detail::append_number(text, static_cast<std::int64_t>(faces(f, c)) + 1);
      }
      text += '\n';
    }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

}  // namespace surfcomp::mesh::io
