// Meshes as they come: STL (binary and ASCII), PLY triangle strips, point clouds refused, the
// format registry, and what read_mesh tidies and notes (unused vertices, zero-area triangles).
#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/io/formats.hpp"
#include "surfcomp/mesh/io/obj.hpp"
#include "surfcomp/mesh/io/off.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/mesh/io/stl.hpp"
#include "surfcomp/mesh/repair.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp::mesh {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

/// Half the diagonal of the octahedron below, A: its vertices are (+-a, 0, 0), (0, +-a, 0),
/// (0, 0, +-a), so its area is 4 sqrt(3) a^2 and its volume 4/3 a^3.
constexpr double a = 1.5;
const double octahedron_area = 4.0 * std::sqrt(3.0) * a * a;
const double octahedron_volume = 4.0 / 3.0 * a * a * a;

/// The octahedron's vertices: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z.
Eigen::MatrixX3d octahedron_positions() {
  Eigen::MatrixX3d p(6, 3);
  p << a, 0, 0, -a, 0, 0, 0, a, 0, 0, -a, 0, 0, 0, a, 0, 0, -a;
  return p;
}

/// Its eight triangles, counter-clockwise seen from outside.
Eigen::MatrixX3i octahedron_faces() {
  Eigen::MatrixX3i f(8, 3);
  f << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return f;
}

/// A binary STL of the triangles (corners as float32, little-endian: the test machines are),
/// with an 80-byte header that starts with `header`.
std::string binary_stl(const Eigen::MatrixX3d& p, const Eigen::MatrixX3i& f,
                       const std::string& header) {
  std::string bytes(80, ' ');
  bytes.replace(0, header.size(), header);
  const auto count = static_cast<std::uint32_t>(f.rows());
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (Eigen::Index t = 0; t < f.rows(); ++t) {
    std::array<float, 12> values{};  // normal (left zero: the reader ignores it), 3 corners
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) values[3 + 3 * k + c] = static_cast<float>(p(f(t, k), c));
    }
    bytes.append(reinterpret_cast<const char*>(values.data()), sizeof(values));
    bytes.append(2, '\0');  // attribute byte count
  }
  return bytes;
}

std::string ascii_stl(const Eigen::MatrixX3d& p, const Eigen::MatrixX3i& f) {
  std::ostringstream out;
  out.precision(9);
  out << "solid octahedron\n";
  for (Eigen::Index t = 0; t < f.rows(); ++t) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (int k = 0; k < 3; ++k) {
      out << "      vertex " << p(f(t, k), 0) << ' ' << p(f(t, k), 1) << ' ' << p(f(t, k), 2)
          << '\n';
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid octahedron\n";
  return out.str();
}

using test::error_of;

/// The octahedron as an STL reader welds it: vertices in order of first appearance in the
/// triangles (0 2 4 1 3 5 of octahedron_positions), the faces renumbered to match.
Eigen::MatrixX3d welded_positions() {
  Eigen::MatrixX3d p(6, 3);
  p << a, 0, 0, 0, a, 0, 0, 0, a, -a, 0, 0, 0, -a, 0, 0, 0, -a;
  return p;
}

Eigen::MatrixX3i welded_faces() {
  Eigen::MatrixX3i f(8, 3);
  f << 0, 1, 2, 1, 3, 2, 3, 4, 2, 4, 0, 2, 1, 0, 5, 3, 1, 5, 4, 3, 5, 0, 4, 5;
  return f;
}

/// Expects the surface to be the octahedron: 6 vertices, 8 faces, a closed sphere of the
/// octahedron's area and (outward) volume.
void expect_octahedron(const Surface& s) {
  EXPECT_EQ(s.n_vertices(), 6u);
  EXPECT_EQ(s.n_faces(), 8u);
  const SurfaceMeasures m = measure_surface(s);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_EQ(m.boundary_edges, 0u);
  EXPECT_NEAR(m.area, octahedron_area, 1e-12);
  EXPECT_NEAR(m.volume, octahedron_volume, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// STL

TEST(MeshFormatsStl, BinaryOctahedronIsWeldedIntoSixVertices) {
  const TempDir dir;
  // The header starts with "solid", as many binary writers make it: the size decides.
  const fs::path path = dir.write(
      "oct.stl", binary_stl(octahedron_positions(), octahedron_faces(), "solid by a CAD tool"));
  ASSERT_EQ(fs::file_size(path), 84u + 50u * 8u);
  const Surface s = io::read_stl(path);
  expect_octahedron(s);
  // Vertices in order of first appearance: the corners of triangle 0, then the new ones of 1...
  EXPECT_EQ(s.positions(), welded_positions());
  EXPECT_EQ(s.faces(), welded_faces());
  EXPECT_EQ(s.position_type(), ValueType::float32);
  EXPECT_FALSE(s.has_normals());
  EXPECT_EQ(s.source(), path.string());
  // read_mesh picks the reader by extension, in any letter case.
  EXPECT_TRUE(io::is_mesh_file("X.STL"));
  const fs::path upper =
      dir.write("OCT.STL", binary_stl(octahedron_positions(), octahedron_faces(), "binary"));
  EXPECT_EQ(io::read_mesh(upper).faces(), welded_faces());
}

TEST(MeshFormatsStl, AsciiOctahedronGivesTheSameMesh) {
  const TempDir dir;
  const fs::path path = dir.write("oct.stl", ascii_stl(octahedron_positions(), octahedron_faces()));
  const Surface s = io::read_stl(path);
  expect_octahedron(s);
  EXPECT_EQ(s.positions(), welded_positions());
  EXPECT_EQ(s.faces(), welded_faces());
  // Keywords in any case, two solids one after the other, a stream as well as a file.
  std::string text = ascii_stl(octahedron_positions(), octahedron_faces().topRows(4));
  text += ascii_stl(octahedron_positions(), octahedron_faces().bottomRows(4));
  text.replace(0, 5, "SOLID");
  std::istringstream in(text);
  const Surface two = io::read_stl(in, "two.stl");
  EXPECT_EQ(two.faces(), welded_faces());
  EXPECT_EQ(two.source(), "two.stl");
}

TEST(MeshFormatsStl, PlusAndMinusZeroAreOneCorner) {
  const TempDir dir;
  std::string bytes = binary_stl(octahedron_positions(), octahedron_faces(), "");
  // Triangle 4's corner 0 is vertex 2, (0, a, 0): write its x as -0.
  const float minus_zero = -0.0f;
  std::memcpy(&bytes[84 + 50 * 4 + 12], &minus_zero, 4);
  const Surface s = io::read_stl(dir.write("oct.stl", bytes));
  EXPECT_EQ(s.n_vertices(), 6u);
  EXPECT_EQ(s.faces(), welded_faces());
}

TEST(MeshFormatsStl, BinaryOfTheWrongSizeIsCutShortOrHasTrailingBytes) {
  const TempDir dir;
  const std::string bytes = binary_stl(octahedron_positions(), octahedron_faces(), "binary");
  const fs::path cut = dir.write("cut.stl", bytes.substr(0, bytes.size() - 10));
  std::string message = error_of([&] { io::read_stl(cut); });
  EXPECT_EQ(message, cut.string() + ": cut short: expected 484 bytes for 8 triangles, found 474");
  EXPECT_THROW(io::read_stl(cut), FormatError);
  // The same for a binary file whose header starts with "solid".
  const std::string solid = binary_stl(octahedron_positions(), octahedron_faces(), "solid x");
  const fs::path cut_solid = dir.write("cut_solid.stl", solid.substr(0, 300));
  EXPECT_EQ(error_of([&] { io::read_mesh(cut_solid); }),
            cut_solid.string() + ": cut short: expected 484 bytes for 8 triangles, found 300");
  const fs::path longer = dir.write("long.stl", bytes + "xyz");
  EXPECT_EQ(error_of([&] { io::read_stl(longer); }),
            longer.string() +
                ": has 3 bytes after its last triangle: expected 484 bytes for 8 triangles, "
                "found 487");
  const fs::path tiny = dir.write("tiny.stl", bytes.substr(0, 40));
  message = error_of([&] { io::read_stl(tiny); });
  EXPECT_EQ(message.rfind(tiny.string() + ": cut short: expected at least 84 bytes", 0), 0u)
      << message;
  // A header and a count of zero: a valid file without triangles, refused.
  const fs::path empty = dir.write("empty.stl", bytes.substr(0, 80) + std::string(4, '\0'));
  EXPECT_EQ(error_of([&] { io::read_stl(empty); }),
            empty.string() + ": no vertices and no faces; surfcomp needs a triangle mesh");
}

TEST(MeshFormatsStl, MalformedAsciiNamesTheLine) {
  const TempDir dir;
  const std::string good = ascii_stl(octahedron_positions(), octahedron_faces());
  auto error_for = [&](const std::string& text) {
    const fs::path path = dir.write("bad.stl", text);
    return error_of([&] { io::read_stl(path); });
  };
  const std::string bad = (dir / "bad.stl").string();
  // Line 4 is the first corner of triangle 1.
  std::string text = good;
  text.replace(text.find("vertex 1.5 0 0"), 14, "vertex 1.5 0");
  EXPECT_EQ(error_for(text),
            bad + ":4: expected 'vertex x y z' (corner 1 of triangle 1), found 'vertex 1.5 0'");
  text = good;
  text.replace(text.find("vertex 1.5 0 0"), 14, "vertex 1.5 0 nan");
  EXPECT_EQ(error_for(text), bad + ":4: expected a finite coordinate, found 'nan'");
  text = good;
  text.replace(text.find("endloop"), 7, "vertex 0 0 0");
  EXPECT_EQ(error_for(text), bad +
                                 ":7: expected 'endloop' after 3 corners (triangle 1), found "
                                 "'vertex 0 0 0'");
  // Cut short: the end of the file where a statement was due.
  EXPECT_EQ(error_for(good.substr(0, good.find("endsolid"))).rfind(bad + ":57: expected", 0), 0u);
  EXPECT_NE(error_for(good.substr(0, good.find("endsolid"))).find("found the end of the file"),
            std::string::npos);
  EXPECT_EQ(error_for("solid x\nendsolid x\nfacet\n"),
            bad + ":3: expected 'solid [name]' or the end of the file, found 'facet'");
}

TEST(MeshFormatsStl, NonManifoldSoupNamesRepairWhichMendsIt) {
  const TempDir dir;
  // The octahedron with its first triangle given twice: edge 0-2 borders three triangles.
  Eigen::MatrixX3i twice(9, 3);
  twice << octahedron_faces(), octahedron_faces().row(0);
  const fs::path path = dir.write("twice.stl", binary_stl(octahedron_positions(), twice, ""));
  const std::string message = error_of([&] { io::read_mesh(path); });
  EXPECT_EQ(message.rfind(path.string() + ": face 8 makes the mesh non-manifold", 0), 0u)
      << message;
  EXPECT_NE(message.find("; repair splits"), std::string::npos) << message;
  EXPECT_THROW(io::read_stl(path), TopologyError);
  const RepairedMesh repaired = repair_mesh_file(path, 1000);
  expect_octahedron(repaired.surface);
  EXPECT_EQ(repaired.report.removed_faces, 1u);
}

TEST(MeshFormatsStl, CoordinatesBeyondTheLimitAreRefusedAlsoByRepair) {
  const TempDir dir;
  Eigen::MatrixX3d p = octahedron_positions();
  p(4, 2) = 2e6;
  const fs::path path = dir.write("far.stl", binary_stl(p, octahedron_faces(), ""));
  for (const bool repair : {false, true}) {
    SCOPED_TRACE(repair ? "--repair" : "read_stl");
    std::string message;
    try {
      if (repair) {
        repair_mesh_file(path, 1000);
      } else {
        io::read_stl(path);
      }
    } catch (const FormatError& e) {
      message = e.what();
    }
    EXPECT_EQ(message, path.string() +
                           ": vertex 2 has coordinate z = 2e+06 A, beyond the "
                           "accepted magnitude 1e+06 A");
  }
  // --repair now checks the other formats' coordinates too.
  std::ostringstream off;
  off << "OFF\n6 8 0\n";
  for (Eigen::Index i = 0; i < 6; ++i) off << p(i, 0) << ' ' << p(i, 1) << ' ' << p(i, 2) << '\n';
  for (Eigen::Index f = 0; f < 8; ++f) {
    off << "3 " << octahedron_faces()(f, 0) << ' ' << octahedron_faces()(f, 1) << ' '
        << octahedron_faces()(f, 2) << '\n';
  }
  const fs::path far_off = dir.write("far.off", off.str());
  EXPECT_THROW(io::read_off(far_off), FormatError);
  const std::string message = error_of([&] { repair_mesh_file(far_off, 1000); });
  EXPECT_EQ(message, far_off.string() +
                         ": vertex 4 has coordinate z = 2e+06 A, beyond the "
                         "accepted magnitude 1e+06 A");
}

// ---------------------------------------------------------------------------------------------
// PLY triangle strips and point clouds

const char* const ply_vertices =
    "ply\nformat ascii 1.0\nelement vertex 6\nproperty double x\nproperty double y\n"
    "property double z\n";
const char* const ply_vertex_data = "1.5 0 0\n-1.5 0 0\n0 1.5 0\n0 -1.5 0\n0 0 1.5\n0 0 -1.5\n";

TEST(MeshFormatsPly, TriangleStripsGiveTheTrianglesOfTheFaceList) {
  const TempDir dir;
  // Three strips: 0 2 4 1 3 (three triangles), 3 0 4 (one), and 2 0 5 3 1 1 5 2, whose
  // repeated 1 turns the strip: its triangles 3 (1 3 1) and 4 (1 1 5) are skipped.
  const std::string strips =
      std::string(ply_vertices) +
      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n" + ply_vertex_data +
      "18 0 2 4 1 3 -1 3 0 4 -1 2 0 5 3 1 1 5 2\n";
  const Surface s = io::read_ply(dir.write("strips.ply", strips));
  // Even triangles keep the strip's order, odd ones swap their first two corners.
  Eigen::MatrixX3i expected(8, 3);
  expected << 0, 2, 4, 4, 2, 1, 4, 1, 3, 3, 0, 4, 2, 0, 5, 5, 0, 3, 5, 3, 1, 5, 1, 2;
  EXPECT_EQ(s.faces(), expected);
  expect_octahedron(s);
  // The same triangles as a face list.
  std::string faces = std::string(ply_vertices) +
                      "element face 8\nproperty list uchar int vertex_indices\nend_header\n" +
                      ply_vertex_data;
  for (Eigen::Index f = 0; f < 8; ++f) {
    faces += "3 " + std::to_string(expected(f, 0)) + " " + std::to_string(expected(f, 1)) + " " +
             std::to_string(expected(f, 2)) + "\n";
  }
  EXPECT_EQ(io::read_ply(dir.write("faces.ply", faces)).faces(), s.faces());
  // Faces and strips in one file: the top four as faces, the bottom as one strip.
  const std::string both = std::string(ply_vertices) +
                           "element face 4\nproperty list uchar int vertex_indices\n"
                           "element tristrips 1\nproperty list uint8 int32 vertex_indices\n"
                           "end_header\n" +
                           ply_vertex_data + "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n" +
                           "8 2 0 5 3 1 1 5 2\n";
  const Surface mixed = io::read_ply(dir.write("both.ply", both));
  expect_octahedron(mixed);
  EXPECT_EQ(mixed.faces().bottomRows(3), expected.bottomRows(3));
  // An index outside the vertices (other than -1) is an error naming the line.
  std::string bad = strips;
  bad.replace(bad.find("18 0 2 4"), 8, "18 0 2 9");
  EXPECT_EQ(error_of([&] { io::read_ply(dir.write("bad.ply", bad)); }),
            (dir / "bad.ply").string() +
                ":16: expected a vertex index in 0..5 or -1 (a new strip), found 9");
}

TEST(MeshFormatsPly, PointCloudsAreRefusedInEveryFormat) {
  const TempDir dir;
  const std::string expected_tail =
      " vertices, no faces); surfcomp needs a triangle mesh: reconstruct a surface first (e.g. "
      "Poisson or ball pivoting)";
  // No face element at all, or one with no items.
  const fs::path cloud =
      dir.write("cloud.ply", std::string(ply_vertices) +
                                 "property float nx\nproperty float ny\nproperty float nz\n"
                                 "end_header\n1.5 0 0 1 0 0\n-1.5 0 0 -1 0 0\n0 1.5 0 0 1 0\n"
                                 "0 -1.5 0 0 -1 0\n0 0 1.5 0 0 1\n0 0 -1.5 0 0 -1\n");
  EXPECT_EQ(error_of([&] { io::read_mesh(cloud); }),
            cloud.string() + ": a point cloud (6" + expected_tail);
  EXPECT_THROW(io::read_ply(cloud), FormatError);
  const fs::path no_faces =
      dir.write("no_faces.ply", std::string(ply_vertices) +
                                    "element face 0\nproperty list uchar int vertex_indices\n"
                                    "end_header\n" +
                                    ply_vertex_data);
  EXPECT_EQ(error_of([&] { io::read_ply(no_faces); }),
            no_faces.string() + ": a point cloud (6" + expected_tail);
  const fs::path off = dir.write("cloud.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_EQ(error_of([&] { io::read_mesh(off); }),
            off.string() + ": a point cloud (3" + expected_tail);
  const fs::path obj = dir.write("cloud.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\n");
  EXPECT_EQ(error_of([&] { io::read_obj(obj); }),
            obj.string() + ": a point cloud (2" + expected_tail);
}

// ---------------------------------------------------------------------------------------------
// The registry

TEST(MeshFormatsRegistry, ExtensionsAndMessagesComeFromOneTable) {
  EXPECT_EQ(io::mesh_extensions(io::MeshUse::read), ".ply .stl .off .obj .vert .face");
  EXPECT_EQ(io::mesh_extensions(io::MeshUse::write), ".ply .off .obj");
  EXPECT_EQ(io::mesh_extensions(io::MeshUse::repair), ".ply .stl .off .obj");
  for (const io::MeshFormat& format : io::mesh_formats()) {
    SCOPED_TRACE(std::string(format.extension));
    EXPECT_TRUE(io::is_mesh_file("x" + std::string(format.extension)));
    EXPECT_EQ(io::find_mesh_format("dir/X" + std::string(format.extension)), &format);
    EXPECT_NE(format.read, nullptr);
    EXPECT_FALSE(format.name.empty());
  }
  EXPECT_EQ(io::find_mesh_format("x.pdb"), nullptr);
  EXPECT_FALSE(io::is_mesh_file("x.pdb"));

  const TempDir dir;
  const fs::path xyz = dir.write("t.xyz", "0 0 0\n");
  EXPECT_EQ(error_of([&] { io::read_mesh(xyz); }),
            xyz.string() +
                ": expected a mesh extension (.ply .stl .off .obj .vert .face), found "
                "'.xyz'");
  const Surface s = Surface::from_arrays(octahedron_positions(), octahedron_faces(), "oct");
  EXPECT_EQ(error_of([&] { io::write_mesh(s, dir / "t.stl"); }),
            (dir / "t.stl").string() +
                ": expected an extension surfcomp writes (.ply .off .obj), found '.stl'");
  EXPECT_FALSE(fs::exists(dir / "t.stl"));
  EXPECT_EQ(error_of([&] { repair_mesh_file(dir / "t.vert", 1000); }),
            (dir / "t.vert").string() + ": repair reads .ply .stl .off .obj meshes, found '.vert'");
  // Every writer's output reads back through the same table.
  for (const io::MeshFormat& format : io::mesh_formats()) {
    if (format.write == nullptr) continue;
    const fs::path path = dir / ("oct" + std::string(format.extension));
    io::write_mesh(s, path);
    EXPECT_EQ(io::read_mesh(path).faces(), octahedron_faces()) << path;
  }
}

// ---------------------------------------------------------------------------------------------
// What read_mesh tidies and notes

TEST(MeshFormatsReadMesh, UnusedVerticesAreDroppedWithTheirPropertiesAndNoted) {
  const TempDir dir;
  // The octahedron with two unused vertices, at file positions 2 and 7; each vertex carries
  // a normal and a charge equal to 10 times its file position.
  std::string text =
      "ply\nformat ascii 1.0\nelement vertex 8\nproperty double x\nproperty double y\n"
      "property double z\nproperty float nx\nproperty float ny\nproperty float nz\n"
      "property short charge\nelement face 8\nproperty list uchar int vertex_indices\n"
      "end_header\n"
      "1.5 0 0 1 0 0 0\n-1.5 0 0 -1 0 0 10\n9 9 9 0 0 1 20\n0 1.5 0 0 1 0 30\n"
      "0 -1.5 0 0 -1 0 40\n0 0 1.5 0 0 1 50\n0 0 -1.5 0 0 -1 60\n-9 -9 -9 0 0 1 70\n";
  // File vertex of each octahedron vertex: 0 1 3 4 5 6.
  const std::array<int, 6> file_vertex{0, 1, 3, 4, 5, 6};
  const Eigen::MatrixX3i f = octahedron_faces();
  for (Eigen::Index t = 0; t < 8; ++t) {
    text += "3";
    for (int k = 0; k < 3; ++k) text += " " + std::to_string(file_vertex[f(t, k)]);
    text += "\n";
  }
  const fs::path path = dir.write("lonely.ply", text);
  EXPECT_EQ(io::read_ply(path).n_vertices(), 8u);  // the format reader keeps what the file has

  std::vector<std::string> notes;
  const Surface s = io::read_mesh(path, &notes);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0], path.string() + ": dropped 2 unused vertices");
  expect_octahedron(s);
  EXPECT_EQ(s.positions(), octahedron_positions());
  EXPECT_EQ(s.faces(), octahedron_faces());
  ASSERT_TRUE(s.has_normals());
  EXPECT_TRUE(s.normals().isApprox(octahedron_positions() / a));
  EXPECT_EQ(s.normal_type(), ValueType::float32);
  ASSERT_TRUE(s.has_property("charge"));
  EXPECT_EQ(s.property_type("charge"), ValueType::int16);
  for (int v = 0; v < 6; ++v) EXPECT_EQ(s.property("charge", v), 10.0 * file_vertex[v]) << v;
  // The one-argument form gives the same surface.
  EXPECT_EQ(io::read_mesh(path).positions(), s.positions());
  EXPECT_EQ(io::read_mesh(path).property("charge"), s.property("charge"));
}

/// The octahedron with vertex 6, the midpoint of edge 0-2, splitting triangle 0 in two, and the
/// zero-area triangle (0, 2, 6) closing the crack on the other side of the edge: a closed
/// manifold mesh of 7 vertices and 10 triangles, the last one of zero area.
std::string octahedron_with_a_flat_triangle_off() {
  return "OFF\n7 10 0\n1.5 0 0\n-1.5 0 0\n0 1.5 0\n0 -1.5 0\n0 0 1.5\n0 0 -1.5\n0.75 0.75 0\n"
         "3 0 6 4\n3 6 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n"
         "3 0 2 6\n";
}

TEST(MeshFormatsReadMesh, ZeroAreaTrianglesAreNotedAndRepairRemovesThem) {
  const TempDir dir;
  const fs::path path = dir.write("flat.off", octahedron_with_a_flat_triangle_off());
  std::vector<std::string> notes;
  const Surface s = io::read_mesh(path, &notes);
  EXPECT_EQ(s.n_faces(), 10u);  // noted, not dropped
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0],
            path.string() + ": 1 zero-area triangle (face 9, counted from 0); repair removes it");
  const SurfaceMeasures m = measure_surface(s);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_NEAR(m.area, octahedron_area, 1e-12);

  /// The smallest triangle area of `r`.
  const auto min_area = [](const Surface& r) {
    const Eigen::MatrixX3d p = r.positions();
    const Eigen::MatrixX3i f = r.faces();
    double smallest = INFINITY;
    for (Eigen::Index t = 0; t < f.rows(); ++t) {
      const Eigen::Vector3d u = p.row(f(t, 1)) - p.row(f(t, 0));
      const Eigen::Vector3d v = p.row(f(t, 2)) - p.row(f(t, 0));
      smallest = std::min(smallest, 0.5 * u.cross(v).norm());
    }
    return smallest;
  };
  EXPECT_EQ(min_area(s), 0.0);
  const RepairedMesh from_file = repair_mesh_file(path, 1000);
  const RepairedMesh from_arrays = repair_triangles(s.positions(), s.faces(), "flat");
  for (const RepairedMesh* r : {&from_file, &from_arrays}) {
    EXPECT_EQ(r->report.removed_faces, 1u);
    EXPECT_EQ(r->report.summary(), "removed 1 degenerate or duplicate face");
    EXPECT_GT(min_area(r->surface), 0.1);
    const SurfaceMeasures after = measure_surface(r->surface);
    EXPECT_EQ(after.euler_characteristic, 2);
    EXPECT_EQ(after.boundary_edges, 0u);
    EXPECT_NEAR(after.area, octahedron_area, 1e-12);
    EXPECT_NEAR(after.volume, octahedron_volume, 1e-12);
  }
  // A mesh without such triangles or unused vertices gets no note.
  notes.clear();
  io::read_mesh(dir.write("oct.stl", binary_stl(octahedron_positions(), octahedron_faces(), "")),
                &notes);
  EXPECT_TRUE(notes.empty());
}

}  // namespace
}  // namespace surfcomp::mesh
