// Every mesh reader, fed hundreds of randomly truncated and corrupted copies of valid files,
// either returns a consistent Surface or throws a surfcomp::Error: never another exception, a
// crash, a hang or undefined behaviour (CI runs this suite under ASan and UBSan).
#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/io/msms.hpp"
#include "surfcomp/mesh/io/obj.hpp"
#include "surfcomp/mesh/io/off.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/mesh/io/stl.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

namespace surfcomp::mesh {
namespace {

namespace fs = std::filesystem;

/// Seed of every mutation stream; SURFCOMP_FUZZ_SEED overrides it.
unsigned base_seed() {
  if (const char* env = std::getenv("SURFCOMP_FUZZ_SEED")) {
    return static_cast<unsigned>(std::strtoul(env, nullptr, 10));
  }
  return 20240611u;
}

using test::TempDir;

void write_bytes(const fs::path& path, const std::string& bytes) {
  // A new file rather than a truncated old one: ext4 flushes truncated-and-rewritten files to
  // disk on close, which would make this test I/O bound.
  std::error_code ignored;
  fs::remove(path, ignored);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A closed UV sphere of radius 10 A: 2 poles and 7 rings of 12 vertices, 168 triangles.
Surface uv_sphere() {
  const int rings = 7;
  const int segments = 12;
  const double pi = std::acos(-1.0);
  Eigen::MatrixX3d p(2 + rings * segments, 3);
  p.row(0) << 0, 0, 10;
  for (int r = 0; r < rings; ++r) {
    const double theta = pi * (r + 1) / (rings + 1);
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * pi * s / segments;
      p.row(1 + r * segments + s) << 10 * std::sin(theta) * std::cos(phi),
          10 * std::sin(theta) * std::sin(phi), 10 * std::cos(theta);
    }
  }
  const int south = 1 + rings * segments;
  p.row(south) << 0, 0, -10;
  std::vector<Eigen::RowVector3i> tris;
  auto at = [&](int r, int s) { return 1 + r * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) {
    tris.emplace_back(0, at(0, s), at(0, s + 1));
    for (int r = 0; r + 1 < rings; ++r) {
      tris.emplace_back(at(r, s), at(r + 1, s), at(r + 1, s + 1));
      tris.emplace_back(at(r, s), at(r + 1, s + 1), at(r, s + 1));
    }
    tris.emplace_back(south, at(rings - 1, s + 1), at(rings - 1, s));
  }
  Eigen::MatrixX3i f(static_cast<Eigen::Index>(tris.size()), 3);
  for (std::size_t i = 0; i < tris.size(); ++i) f.row(static_cast<Eigen::Index>(i)) = tris[i];
  Surface surface = Surface::from_arrays(p, f, "uv_sphere");
  surface.compute_normals();
  const Eigen::Index n = p.rows();
  Eigen::VectorXd esp(n), label(n), depth(n), count(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    esp(i) = std::sin(0.37 * static_cast<double>(i)) * 12.5;
    label(i) = static_cast<double>(i % 7) - 3;
    depth(i) = static_cast<double>(static_cast<float>(p(i, 2) * 0.1));
    count(i) = static_cast<double>(i * 97 % 1000);
  }
  surface.set_property("esp", esp);
  surface.set_property("label", label, ValueType::int8);
  surface.set_property("depth", depth, ValueType::float32);
  surface.set_property("count", count, ValueType::uint16);
  return surface;
}

std::string ply_bytes(const Surface& s, io::PlyFormat format) {
  std::ostringstream out;
  io::write_ply(s, out, format);
  return out.str();
}

/// The sphere as MSMS files, with the three-line header.
std::pair<std::string, std::string> msms_bytes(const Surface& s) {
  const Eigen::MatrixX3d p = s.positions();
  const Eigen::MatrixX3d n = s.normals();
  const Eigen::MatrixX3i f = s.faces();
  std::ostringstream vert, face;
  vert << "# MSMS solvent excluded surface vertices for sphere.xyzr\n"
       << "#vertex #sphere density probe_r\n"
       << p.rows() << " 1 1.00 1.50\n";
  vert.setf(std::ios::fixed);
  vert.precision(3);
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    vert << p(i, 0) << ' ' << p(i, 1) << ' ' << p(i, 2) << ' ' << n(i, 0) << ' ' << n(i, 1) << ' '
         << n(i, 2) << " 0 1 2\n";
  }
  face << "# MSMS solvent excluded surface faces for sphere.xyzr\n"
       << "#faces  #sphere density probe_r\n"
       << f.rows() << " 1 1.00 1.50\n";
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    face << f(i, 0) + 1 << ' ' << f(i, 1) + 1 << ' ' << f(i, 2) + 1 << " 1 1\n";
  }
  return {vert.str(), face.str()};
}

std::string off_bytes(const Surface& s) {
  const Eigen::MatrixX3d p = s.positions();
  const Eigen::MatrixX3i f = s.faces();
  std::ostringstream out;
  out.precision(17);
  out << "OFF\n# a sphere\n" << p.rows() << ' ' << f.rows() << " 0\n";
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    out << p(i, 0) << ' ' << p(i, 1) << ' ' << p(i, 2) << '\n';
  }
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    out << "3 " << f(i, 0) << ' ' << f(i, 1) << ' ' << f(i, 2)
        << (i % 5 == 0 ? " 255 0 0\n" : "\n");  // some faces carry a colour
  }
  return out.str();
}

/// OBJ with every corner form: a, a/t, a//n, a/t/n and negative (relative) numbers.
std::string obj_bytes(const Surface& s) {
  const Eigen::MatrixX3d p = s.positions();
  const Eigen::MatrixX3i f = s.faces();
  std::ostringstream out;
  out.precision(17);
  out << "# a sphere\nmtllib sphere.mtl\no sphere\n";
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    out << "v " << p(i, 0) << ' ' << p(i, 1) << ' ' << p(i, 2) << "\nvn 0 0 1\nvt 0.5 0.5\n";
  }
  out << "g all\ns 1\n";
  const Eigen::Index n = p.rows();
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    out << 'f';
    for (Eigen::Index k = 0; k < 3; ++k) {
      const int v = f(i, k) + 1;
      switch ((i + k) % 5) {
        case 0:
          out << ' ' << v;
          break;
        case 1:
          out << ' ' << v << '/' << v;
          break;
        case 2:
          out << ' ' << v << "//" << v;
          break;
        case 3:
          out << ' ' << v << '/' << v << '/' << v;
          break;
        default:
          out << ' ' << v - 1 - n;
          break;
      }
    }
    out << '\n';
  }
  return out.str();
}

/// Binary STL (little-endian, as the test machines are): a header starting with "solid", as many
/// binary writers make it, and one 50-byte record per triangle.
std::string stl_binary_bytes(const Surface& s) {
  const Eigen::MatrixX3d p = s.positions();
  const Eigen::MatrixX3i f = s.faces();
  std::string out = "solid sphere (binary)";
  out.resize(80, ' ');
  const auto count = static_cast<std::uint32_t>(f.rows());
  out.append(reinterpret_cast<const char*>(&count), sizeof(count));
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    float values[12] = {0, 0, 1};
    for (Eigen::Index k = 0; k < 3; ++k) {
      for (Eigen::Index c = 0; c < 3; ++c)
        values[3 + 3 * k + c] = static_cast<float>(p(f(i, k), c));
    }
    out.append(reinterpret_cast<const char*>(values), sizeof(values));
    out.append(2, '\0');
  }
  return out;
}

std::string stl_ascii_bytes(const Surface& s) {
  const Eigen::MatrixX3d p = s.positions();
  const Eigen::MatrixX3i f = s.faces();
  std::ostringstream out;
  out.precision(9);
  out << "solid sphere\n";
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    out << "facet normal 0 0 1\n outer loop\n";
    for (Eigen::Index k = 0; k < 3; ++k) {
      out << "  vertex " << p(f(i, k), 0) << ' ' << p(f(i, k), 1) << ' ' << p(f(i, k), 2) << '\n';
    }
    out << " endloop\nendfacet\n";
  }
  out << "endsolid sphere\n";
  return out.str();
}

/// Line boundaries of `bytes`: start offsets of every line.
std::vector<std::size_t> line_starts(const std::string& bytes) {
  std::vector<std::size_t> starts{0};
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (bytes[i] == '\n' && i + 1 < bytes.size()) starts.push_back(i + 1);
  }
  return starts;
}

/// One random corruption of `bytes`; `kind` receives its description.
std::string mutate(const std::string& bytes, std::mt19937& rng, std::string& kind,
                   bool& truncated) {
  auto uniform = [&rng](std::size_t lo, std::size_t hi) {  // inclusive
    return std::uniform_int_distribution<std::size_t>(lo, hi)(rng);
  };
  // A quarter of the byte edits go to the first 512 bytes, where the headers are.
  auto position = [&](std::size_t size) {
    if (size == 0) return std::size_t{0};
    const std::size_t end = uniform(0, 3) == 0 ? std::min<std::size_t>(size, 512) : size;
    return uniform(0, end - 1);
  };
  static const std::string textual = "0123456789-+.eE \n\t/#nainf";
  static const char* const extremes[] = {
      "-1",      "0",   "4294967296", "99999999999999999999", "1e308",
      "-1e-320", "nan", "inf",        "2147483647",           "3"};
  std::string out = bytes;
  truncated = false;
  switch (uniform(0, 6)) {
    case 0: {
      const std::size_t size = bytes.empty() ? 0 : uniform(0, bytes.size() - 1);
      out.resize(size);
      kind = "truncate to " + std::to_string(size) + " bytes";
      truncated = true;
      break;
    }
    case 1: {
      const std::size_t n = uniform(1, 8);
      kind = "replace " + std::to_string(n) + " bytes";
      for (std::size_t i = 0; i < n && !out.empty(); ++i) {
        out[position(out.size())] = static_cast<char>(uniform(0, 255));
      }
      break;
    }
    case 2: {
      const std::size_t n = uniform(1, 8);
      kind = "flip bits in " + std::to_string(n) + " bytes";
      for (std::size_t i = 0; i < n && !out.empty(); ++i) {
        out[position(out.size())] ^= static_cast<char>(1u << uniform(0, 7));
      }
      break;
    }
    case 3: {
      const std::size_t n = uniform(1, 16);
      std::string garbage;
      const bool text = uniform(0, 1) == 0;
      for (std::size_t i = 0; i < n; ++i) {
        garbage +=
            text ? textual[uniform(0, textual.size() - 1)] : static_cast<char>(uniform(0, 255));
      }
      const std::size_t at = position(out.size() + 1);
      out.insert(at, garbage);
      kind = "insert " + std::to_string(n) + " garbage bytes at " + std::to_string(at);
      break;
    }
    case 4: {
      const auto starts = line_starts(bytes);
      const std::size_t line = uniform(0, starts.size() - 1);
      const std::size_t end = line + 1 < starts.size() ? starts[line + 1] : bytes.size();
      out.insert(end, bytes.substr(starts[line], end - starts[line]));
      kind = "duplicate line " + std::to_string(line + 1);
      break;
    }
    case 5: {
      const auto starts = line_starts(bytes);
      const std::size_t line = uniform(0, starts.size() - 1);
      const std::size_t end = line + 1 < starts.size() ? starts[line + 1] : bytes.size();
      out.erase(starts[line], end - starts[line]);
      kind = "delete line " + std::to_string(line + 1);
      break;
    }
    default: {
      // Replace one number-like run with an extreme value (header counts, indices...).
      std::size_t at = position(out.size());
      while (at < out.size() && !std::isdigit(static_cast<unsigned char>(out[at]))) ++at;
      std::size_t end = at;
      while (end < out.size() && std::isdigit(static_cast<unsigned char>(out[end]))) ++end;
      const char* value = extremes[uniform(0, std::size(extremes) - 1)];
      out.replace(at, end - at, value);
      kind = std::string("replace a number at ") + std::to_string(at) + " with " + value;
      break;
    }
  }
  return out;
}

/// Why `s` is not a consistent surface, or "" if it is.
std::string inconsistency(const Surface& s) {
  const auto n = static_cast<int>(s.n_vertices());
  if (static_cast<std::size_t>(s.positions().rows()) != s.n_vertices()) return "vertex count";
  const Eigen::MatrixX3i f = s.faces();
  if (static_cast<std::size_t>(f.rows()) != s.n_faces()) return "face count";
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    for (Eigen::Index k = 0; k < 3; ++k) {
      if (f(i, k) < 0 || f(i, k) >= n) return "face " + std::to_string(i) + " out of range";
    }
    if (f(i, 0) == f(i, 1) || f(i, 1) == f(i, 2) || f(i, 0) == f(i, 2)) {
      return "face " + std::to_string(i) + " repeats a vertex";
    }
  }
  if (!s.positions().allFinite()) return "non-finite position";
  if (s.has_normals() && !s.normals().allFinite()) return "non-finite normal";
  for (const auto& name : s.property_names()) {
    if (static_cast<std::size_t>(s.property(name).size()) != s.n_vertices()) {
      return "property " + name + " has the wrong size";
    }
  }
  return "";
}

/// A valid input: the files to write (name, bytes) and how to read them.
struct Input {
  std::vector<std::pair<std::string, std::string>> files;
  std::function<Surface(const TempDir&)> read;
};

struct Tally {
  int read = 0;
  int rejected = 0;
  int truncations = 0;
  int truncations_rejected = 0;
};

/// Reads `iterations` corrupted copies of `input` and checks every outcome.
Tally fuzz(const Input& input, int iterations, unsigned seed) {
  TempDir dir;
  Tally tally;
  for (const auto& [name, bytes] : input.files) write_bytes(dir / name, bytes);
  // The unmodified input reads.
  const Surface original = input.read(dir);
  EXPECT_EQ(inconsistency(original), "");
  std::mt19937 rng(seed);
  int reported = 0;
  for (int i = 0; i < iterations; ++i) {
    const std::size_t which =
        std::uniform_int_distribution<std::size_t>(0, input.files.size() - 1)(rng);
    std::string kind;
    bool truncated = false;
    const auto& [name, bytes] = input.files[which];
    write_bytes(dir / name, mutate(bytes, rng, kind, truncated));
    const std::string what = "iteration " + std::to_string(i) + " (seed " + std::to_string(seed) +
                             ", " + name + ": " + kind + ")";
    tally.truncations += truncated;
    try {
      const Surface s = input.read(dir);
      ++tally.read;
      const std::string problem = inconsistency(s);
      if (!problem.empty() && reported++ < 10) ADD_FAILURE() << what << ": " << problem;
    } catch (const Error&) {
      ++tally.rejected;
      tally.truncations_rejected += truncated;
    } catch (const std::exception& e) {
      if (reported++ < 10) ADD_FAILURE() << what << ": not a surfcomp::Error: " << e.what();
    } catch (...) {
      if (reported++ < 10) ADD_FAILURE() << what << ": unknown exception";
    }
    write_bytes(dir / name, bytes);
  }
  std::cout << "seed " << seed << ": " << iterations << " corrupted copies, " << tally.read
            << " read, " << tally.rejected << " rejected (" << tally.truncations_rejected << " of "
            << tally.truncations << " truncations)\n";
  return tally;
}

Input ply_input(const std::string& bytes) {
  return {{{"mesh.ply", bytes}}, [](const TempDir& d) { return io::read_ply(d / "mesh.ply"); }};
}

constexpr int iterations = 300;

TEST(MeshReaderRobustness, PlyAsciiSmall) {
  const Tally t =
      fuzz(ply_input(ply_bytes(uv_sphere(), io::PlyFormat::ascii)), iterations, base_seed() + 1);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_GT(t.rejected, iterations / 4);
}

TEST(MeshReaderRobustness, PlyAsciiWithSkippedElements) {
  // Hand-written: a vertex list property, an edge element and polygon faces are all skipped
  // or split by the reader, so their code paths see the corruption too.
  const std::string text =
      "ply\nformat ascii 1.0\ncomment pyramid\nelement vertex 5\nproperty float x\n"
      "property float y\nproperty float z\nproperty list uchar float uv\nproperty uchar tag\n"
      "element edge 2\nproperty int vertex1\nproperty list ushort int more\n"
      "element face 5\nproperty uchar red\nproperty list uchar uint vertex_index\nend_header\n"
      "0 0 0 2 0.5 0.5 10\n1 0 0 0 11\n1 1 0 1 7 12\n0 1 0 0 13\n0.5 0.5 1 0 14\n"
      "0 2 5 6\n1 0\n255 4 0 3 2 1\n0 3 0 1 4\n0 3 1 2 4\n0 3 2 3 4\n0 3 3 0 4\n";
  const Tally t = fuzz(ply_input(text), iterations, base_seed() + 2);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_GT(t.rejected, iterations / 4);
}

TEST(MeshReaderRobustness, PlyBinarySmall) {
  const Surface s = uv_sphere();
  for (const auto format :
       {io::PlyFormat::binary_little_endian, io::PlyFormat::binary_big_endian}) {
    const Tally t = fuzz(ply_input(ply_bytes(s, format)), iterations / 2,
                         base_seed() + 3 + static_cast<unsigned>(format));
    EXPECT_EQ(t.read + t.rejected, iterations / 2);
    EXPECT_EQ(t.truncations_rejected, t.truncations);  // binary data has no slack
    EXPECT_GT(t.truncations, 0);
  }
}

TEST(MeshReaderRobustness, PlyTriangleStrips) {
  // An octahedron as three strips (one turned by a repeated vertex) beside one face.
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
      "property float z\nelement tristrips 1\nproperty list int int vertex_indices\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "1.5 0 0\n-1.5 0 0\n0 1.5 0\n0 -1.5 0\n0 0 1.5\n0 0 -1.5\n"
      "14 0 2 4 1 3 -1 2 0 5 3 1 1 5 2\n3 3 0 4\n";
  const Tally t = fuzz(ply_input(text), iterations, base_seed() + 5);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_GT(t.rejected, iterations / 4);
}

TEST(MeshReaderRobustness, StlBinary) {
  const Input input{{{"mesh.stl", stl_binary_bytes(uv_sphere())}},
                    [](const TempDir& d) { return io::read_stl(d / "mesh.stl"); }};
  const Tally t = fuzz(input, iterations, base_seed() + 50);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_EQ(t.truncations_rejected, t.truncations);  // the size must match the count
  EXPECT_GT(t.truncations, 0);
}

TEST(MeshReaderRobustness, StlAscii) {
  const Input input{{{"mesh.stl", stl_ascii_bytes(uv_sphere())}},
                    [](const TempDir& d) { return io::read_stl(d / "mesh.stl"); }};
  const Tally t = fuzz(input, iterations, base_seed() + 51);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_GT(t.rejected, iterations / 4);
}

TEST(MeshReaderRobustness, MasifPlyAscii) {
  SURFCOMP_SHARED_OR_SKIP(path, "surfaces/masif/1EWY_A.ply");
  const Tally t = fuzz(ply_input(read_bytes(path)), iterations, base_seed() + 10);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_GT(t.rejected, iterations / 4);
}

TEST(MeshReaderRobustness, MasifPlyBinary) {
  SURFCOMP_SHARED_OR_SKIP(path, "surfaces/masif/1EWY_A.ply");
  const std::string binary = ply_bytes(io::read_ply(path), io::PlyFormat::binary_little_endian);
  const Tally t = fuzz(ply_input(binary), iterations, base_seed() + 11);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_EQ(t.truncations_rejected, t.truncations);
  EXPECT_GT(t.truncations, 0);
}

TEST(MeshReaderRobustness, Msms) {
  const auto [vert, face] = msms_bytes(uv_sphere());
  const Input input{{{"mesh.vert", vert}, {"mesh.face", face}},
                    [](const TempDir& d) { return io::read_msms(d / "mesh.vert"); }};
  const Tally t = fuzz(input, iterations, base_seed() + 20);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_GT(t.rejected, iterations / 4);
}

TEST(MeshReaderRobustness, MsmsLysozymeWithoutHeader) {
  SURFCOMP_SHARED_OR_SKIP(vert, "surfaces/lysozyme-msms/geometry/Lys1.vert");
  const Input input{
      {{"lys.vert", read_bytes(vert)}, {"lys.face", read_bytes(vert.parent_path() / "Lys1.face")}},
      [](const TempDir& d) { return io::read_msms(d / "lys"); }};
  const Tally t = fuzz(input, iterations, base_seed() + 21);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_GT(t.rejected, 0);
}

TEST(MeshReaderRobustness, Off) {
  const Input input{{{"mesh.off", off_bytes(uv_sphere())}},
                    [](const TempDir& d) { return io::read_off(d / "mesh.off"); }};
  const Tally t = fuzz(input, iterations, base_seed() + 30);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_GT(t.rejected, iterations / 4);
}

TEST(MeshReaderRobustness, Obj) {
  const Input input{{{"mesh.obj", obj_bytes(uv_sphere())}},
                    [](const TempDir& d) { return io::read_obj(d / "mesh.obj"); }};
  const Tally t = fuzz(input, iterations, base_seed() + 40);
  EXPECT_EQ(t.read + t.rejected, iterations);
  EXPECT_GT(t.rejected, iterations / 6);
}

}  // namespace
}  // namespace surfcomp::mesh
