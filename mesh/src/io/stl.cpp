#include "surfcomp/mesh/io/stl.hpp"

#include "ply_format.hpp"
#include "stl_soup.hpp"
#include "surface_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "text_parsing.hpp"

#include <Eigen/Core>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace surfcomp::mesh::io {
namespace {

using detail::Location;
using detail::quote;
using detail::StlSoup;

constexpr std::uint64_t binary_header_bytes = 84;  // 80-byte header and the uint32 count
constexpr std::uint64_t binary_triangle_bytes = 50;

/// Gives each distinct corner (exact float32 equality) one vertex number, in order of first
/// appearance.
class CornerWelder {
 public:
  explicit CornerWelder(StlSoup& soup) : soup_(soup) {}

  void add(const std::array<float, 3>& corner) {
    std::array<std::uint32_t, 3> key;
    for (std::size_t c = 0; c < 3; ++c) {
      const float value = corner[c] + 0.0f;  // -0 becomes +0: the two are equal floats
      std::memcpy(&key[c], &value, sizeof(float));
    }
    const auto [at, added] = vertex_of_.try_emplace(key, static_cast<int>(vertex_of_.size()));
    if (added) soup_.positions.insert(soup_.positions.end(), corner.begin(), corner.end());
    soup_.triangles.push_back(at->second);
  }

 private:
  struct KeyHash {
    std::size_t operator()(const std::array<std::uint32_t, 3>& key) const {
      std::uint64_t h = key[0];
      h = h * 0x9E3779B97F4A7C15ull ^ key[1];
      h = h * 0x9E3779B97F4A7C15ull ^ key[2];
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };

  StlSoup& soup_;
  std::unordered_map<std::array<std::uint32_t, 3>, int, KeyHash> vertex_of_;
};

std::uint64_t binary_count(std::string_view data) {
  return static_cast<std::uint64_t>(
      detail::load_value(data.data() + 80, ValueType::uint32, !detail::host_is_little_endian()));
}

bool sized_as_binary(std::string_view data) {
  return data.size() >= binary_header_bytes &&
         data.size() == binary_header_bytes + binary_triangle_bytes * binary_count(data);
}

/// True if `word` is `keyword` in any letter case.
bool is_keyword(std::string_view word, std::string_view keyword) {
  if (word.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < word.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(word[i])) != keyword[i]) return false;
  }
  return true;
}

/// True for a file that starts with the word "solid" and holds text only (no control byte
/// other than white space), as an ASCII STL does and a binary one practically never.
bool is_ascii_stl(std::string_view data) {
  std::size_t start = 0;
  while (start < data.size() && detail::is_space(data[start])) ++start;
  const std::string_view rest = data.substr(start);
  if (rest.size() < 5 || !is_keyword(rest.substr(0, 5), "solid")) return false;
  if (rest.size() > 5 && !detail::is_space(rest[5])) return false;
  for (const char c : data) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && !detail::is_space(c)) || byte == 0x7f) return false;
  }
  return true;
}

[[noreturn]] void binary_size_error(std::string_view data, const std::string& name) {
  if (data.size() < binary_header_bytes) {
    throw FormatError(name,
                      "cut short: expected at least 84 bytes for a binary STL (an 80-byte "
                      "header and a triangle count), found " +
                          std::to_string(data.size()) +
                          " (and it is not an ASCII STL starting with 'solid')");
  }
  const std::uint64_t count = binary_count(data);
  const std::uint64_t expected = binary_header_bytes + binary_triangle_bytes * count;
  const std::string sizes = "expected " + std::to_string(expected) + " bytes for " +
                            std::to_string(count) + " triangles, found " +
                            std::to_string(data.size());
  if (data.size() < expected) throw FormatError(name, "cut short: " + sizes);
  throw FormatError(name, "has " + std::to_string(data.size() - expected) +
                              " bytes after its last triangle: " + sizes);
}

StlSoup read_binary(std::string_view data, const std::string& name) {
  const std::uint64_t count = binary_count(data);
  StlSoup soup;
  soup.triangles.reserve(3 * static_cast<std::size_t>(count));
  soup.positions.reserve(3 * static_cast<std::size_t>(count / 2 + 3));
  CornerWelder welder(soup);
  const bool swap = !detail::host_is_little_endian();
  for (std::uint64_t t = 0; t < count; ++t) {
    const std::size_t record = binary_header_bytes + binary_triangle_bytes * t;
    for (std::size_t k = 0; k < 3; ++k) {
      std::array<float, 3> corner;
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t offset = record + 12 + 12 * k + 4 * c;
        corner[c] =
            static_cast<float>(detail::load_value(data.data() + offset, ValueType::float32, swap));
        if (!std::isfinite(corner[c])) {
          throw FormatError(name, "byte " + std::to_string(offset) + " (triangle " +
                                      std::to_string(t + 1) + " of " + std::to_string(count) +
                                      "): expected a finite coordinate, found " +
                                      std::to_string(corner[c]));
        }
      }
      welder.add(corner);
    }
  }
  return soup;
}

/// The statements of an ASCII STL, one per line, with the line they are on.
class Statements {
 public:
  Statements(std::string_view data, const std::string& name) : lines_(data), name_(name) {}

  /// Moves to the next statement; false at the end of the file.
  bool next() {
    std::string_view line;
    if (!lines_.next_non_blank(line)) return false;
    detail::split_tokens(line, tokens_);
    return true;
  }

  /// Moves to the next statement, which must be there: `expected` says what it should be.
  void next(const std::string& expected) {
    if (!next()) {
      throw FormatError(name_, lines_.line_number(),
                        "expected " + expected + ", found the end of the file");
    }
  }

  /// True if the statement is the keywords `words`, with exactly `values` more tokens.
  bool is(std::initializer_list<std::string_view> words, std::size_t values = 0) const {
    if (tokens_.size() != words.size() + values) return false;
    std::size_t k = 0;
    for (const std::string_view word : words) {
      if (!is_keyword(tokens_[k++], word)) return false;
    }
    return true;
  }

  /// True if the statement starts with `keyword`.
  bool starts(std::string_view keyword) const { return is_keyword(tokens_[0], keyword); }

  [[noreturn]] void fail(const std::string& expected) const {
    std::string found = std::string(tokens_[0]);
    for (std::size_t k = 1; k < tokens_.size(); ++k) found += " " + std::string(tokens_[k]);
    throw FormatError(name_, lines_.line_number(),
                      "expected " + expected + ", found " + quote(found));
  }

  const std::vector<std::string_view>& tokens() const { return tokens_; }
  Location at() const { return Location{name_, lines_.line_number()}; }

 private:
  detail::LineCursor lines_;
  const std::string& name_;
  std::vector<std::string_view> tokens_;
};

StlSoup read_ascii(std::string_view data, const std::string& name) {
  StlSoup soup;
  CornerWelder welder(soup);
  Statements statements(data, name);
  std::size_t triangle = 0;
  bool first = true;
  while (statements.next()) {
    if (!statements.starts("solid")) {
      statements.fail(first ? "'solid [name]'" : "'solid [name]' or the end of the file");
    }
    first = false;
    while (true) {
      statements.next("'facet normal nx ny nz' or 'endsolid [name]'");
      if (statements.starts("endsolid")) break;
      if (!statements.starts("facet")) statements.fail("'facet normal nx ny nz' or 'endsolid'");
      ++triangle;
      const std::string of_triangle = " (triangle " + std::to_string(triangle) + ")";
      statements.next("'outer loop'" + of_triangle);
      if (!statements.is({"outer", "loop"})) statements.fail("'outer loop'" + of_triangle);
      for (int k = 1; k <= 3; ++k) {
        const std::string what = "'vertex x y z' (corner " + std::to_string(k) + " of triangle " +
                                 std::to_string(triangle) + ")";
        statements.next(what);
        if (!statements.is({"vertex"}, 3)) statements.fail(what);
        std::array<float, 3> corner;
        for (std::size_t c = 0; c < 3; ++c) {
          corner[c] = static_cast<float>(detail::parse_float(
              statements.tokens()[c + 1], statements.at(), "a finite coordinate"));
        }
        welder.add(corner);
      }
      statements.next("'endloop'" + of_triangle);
      if (!statements.is({"endloop"})) statements.fail("'endloop' after 3 corners" + of_triangle);
      statements.next("'endfacet'" + of_triangle);
      if (!statements.is({"endfacet"})) statements.fail("'endfacet'" + of_triangle);
    }
  }
  if (first) statements.fail("'solid [name]'");
  return soup;
}

Surface read_stl_data(std::string_view data, const std::string& name) {
  const StlSoup soup = detail::read_stl_soup(data, name);
  const auto n_vertices = static_cast<Eigen::Index>(soup.positions.size() / 3);
  const auto n_triangles = static_cast<Eigen::Index>(soup.triangles.size() / 3);
  detail::check_has_triangles(static_cast<std::size_t>(n_vertices),
                              static_cast<std::size_t>(n_triangles), name);
  using RowMajor3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using RowMajor3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
  Surface surface = Surface::from_arrays(
      Eigen::Map<const RowMajor3d>(soup.positions.data(), n_vertices, 3),
      Eigen::Map<const RowMajor3i>(soup.triangles.data(), n_triangles, 3), name);
  surface.set_position_type(ValueType::float32);
  detail::check_read_surface(surface, name);
  return surface;
}

}  // namespace

namespace detail {

StlSoup read_stl_soup(std::string_view data, const std::string& name) {
  if (sized_as_binary(data)) return read_binary(data, name);
  if (is_ascii_stl(data)) return read_ascii(data, name);
  binary_size_error(data, name);
}

}  // namespace detail

Surface read_stl(const std::filesystem::path& path) {
  return read_stl_data(surfcomp::io::read_input_file(path), path.string());
}

Surface read_stl(std::istream& in, const std::string& name) {
  return read_stl_data(detail::read_whole_stream(in, name), name);
}

}  // namespace surfcomp::mesh::io
