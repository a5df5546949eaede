#include "surfcomp/mesh/io/msms.hpp"

#include "surface_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "text_parsing.hpp"

#include <limits>
#include <optional>

namespace surfcomp::mesh::io {
namespace {

using detail::Location;
using detail::quote;

/// The data lines of one MSMS file, after its optional header; `claimed` is the header's count.
struct MsmsLines {
  std::optional<std::int64_t> claimed;
  std::size_t header_line = 0;  // the count line, when there is a header
};

/// Skips the optional header ('#' lines, then a count line) and returns its count.
MsmsLines skip_header(detail::LineCursor& lines, const std::string& name) {
  MsmsLines out;
  detail::LineCursor peek = lines;
  std::string_view line;
  if (!peek.next(line) || line.empty() || line[0] != '#') return out;
  bool more = false;
  while ((more = lines.next(line)) && !line.empty() && line[0] == '#') {
  }
  out.header_line = lines.line_number();
  if (!more) {
    throw FormatError(name, out.header_line,
                      "expected the MSMS count line after the '#' comments, found the end of "
                      "the file");
  }
  std::vector<std::string_view> tokens;
  detail::split_tokens(line, tokens);
  const Location at{name, out.header_line};
  if (tokens.size() != 4) {
    throw FormatError(name, out.header_line,
                      "expected the MSMS count line 'count n_spheres density probe_radius' after "
                      "the '#' comments, found " +
                          quote(line));
  }
  out.claimed = detail::parse_integer(tokens[0], at, "a count", 0, std::numeric_limits<int>::max());
  detail::parse_integer(tokens[1], at, "a sphere count", 0, std::numeric_limits<int>::max());
  detail::parse_double(tokens[2], at, "a density");
  detail::parse_double(tokens[3], at, "a probe radius");
  return out;
}

void check_claimed(const MsmsLines& header, std::size_t found, const std::string& name,
                   const char* what) {
  if (header.claimed && static_cast<std::size_t>(*header.claimed) != found) {
    throw FormatError(name, header.header_line,
                      "the header claims " + std::to_string(*header.claimed) + " " + what +
                          ", found " + std::to_string(found));
  }
}

struct MsmsVertices {
  std::vector<double> positions;  // 3 per vertex
  std::vector<double> normals;    // 3 per vertex
};

MsmsVertices read_vert(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::string data = surfcomp::io::read_input_file(path);
  detail::LineCursor lines(data);
  const MsmsLines header = skip_header(lines, name);
  MsmsVertices out;
  std::string_view line;
  std::vector<std::string_view> tokens;
  static const char* const columns[] = {"x", "y", "z", "nx", "ny", "nz"};
  while (lines.next_non_blank(line)) {
    const Location at{name, lines.line_number()};
    detail::split_tokens(line, tokens);
    if (tokens.size() < 6 || tokens.size() > 9) {
      throw FormatError(name, at.line,
                        "expected 'x y z nx ny nz [face sphere type]' (6 to 9 values), found " +
                            std::to_string(tokens.size()) + " values");
    }
    if (out.positions.size() / 3 >= static_cast<std::size_t>(std::numeric_limits<int>::max())) {
      throw FormatError(name, at.line, "expected at most 2^31-1 vertices");
    }
    for (std::size_t k = 0; k < 6; ++k) {
      const double v = detail::parse_double(tokens[k], at, std::string("a finite ") + columns[k]);
      (k < 3 ? out.positions : out.normals).push_back(v);
    }
    for (std::size_t k = 6; k < tokens.size(); ++k) {
      detail::parse_integer(tokens[k], at, "an integer (face, sphere or type number)",
                            std::numeric_limits<std::int64_t>::min(),
                            std::numeric_limits<std::int64_t>::max());
    }
  }
  check_claimed(header, out.positions.size() / 3, name, "vertices");
  return out;
}

std::vector<int> read_face(const std::filesystem::path& path, std::size_t n_vertices) {
  const std::string name = path.string();
  const std::string data = surfcomp::io::read_input_file(path);
  detail::LineCursor lines(data);
  const MsmsLines header = skip_header(lines, name);
  std::vector<int> triangles;
  std::string_view line;
  std::vector<std::string_view> tokens;
  const auto max_vertex = static_cast<std::int64_t>(n_vertices);
  while (lines.next_non_blank(line)) {
    const Location at{name, lines.line_number()};
    detail::split_tokens(line, tokens);
    if (tokens.size() < 3 || tokens.size() > 5) {
      throw FormatError(name, at.line,
                        "expected 'v1 v2 v3 [type sphere]' (3 to 5 values), found " +
                            std::to_string(tokens.size()) + " values");
    }
    for (std::size_t k = 0; k < 3; ++k) {
      triangles.push_back(static_cast<int>(
          detail::parse_integer(tokens[k], at, "a vertex number", 1, max_vertex) - 1));
    }
    for (std::size_t k = 3; k < tokens.size(); ++k) {
      detail::parse_integer(tokens[k], at, "an integer (type or sphere number)",
                            std::numeric_limits<std::int64_t>::min(),
                            std::numeric_limits<std::int64_t>::max());
    }
  }
  check_claimed(header, triangles.size() / 3, name, "faces");
  return triangles;
}

}  // namespace

Surface read_msms(const std::filesystem::path& path) {
  std::filesystem::path base = path;
  if (path.extension() == ".vert" || path.extension() == ".face") base.replace_extension();
  const std::filesystem::path vert = base.string() + ".vert";
  const std::filesystem::path face = base.string() + ".face";
  const MsmsVertices vertices = read_vert(vert);
  const std::vector<int> triangles = read_face(face, vertices.positions.size() / 3);
  detail::check_has_triangles(vertices.positions.size() / 3, triangles.size() / 3, path.string());
  const auto n = static_cast<Eigen::Index>(vertices.positions.size() / 3);
  using RowMajor3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using RowMajor3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
  const Eigen::MatrixX3d positions = Eigen::Map<const RowMajor3d>(vertices.positions.data(), n, 3);
  const Eigen::MatrixX3i faces = Eigen::Map<const RowMajor3i>(
      triangles.data(), static_cast<Eigen::Index>(triangles.size() / 3), 3);
  Surface surface = Surface::from_arrays(positions, faces, face.string());
  surface.set_source(vert.string());
  surface.set_normals(Eigen::Map<const RowMajor3d>(vertices.normals.data(), n, 3));
  detail::check_read_surface(surface, vert.string());
  return surface;
}

}  // namespace surfcomp::mesh::io
