#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/io/msms.hpp"
#include "surfcomp/mesh/io/obj.hpp"
#include "surfcomp/mesh/io/off.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace surfcomp::mesh {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// True if the two arrays hold the same doubles bit for bit.
bool same_bits(const Eigen::Ref<const Eigen::MatrixXd>& a,
               const Eigen::Ref<const Eigen::MatrixXd>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  const Eigen::MatrixXd ca = a;
  const Eigen::MatrixXd cb = b;
  const std::size_t bytes = sizeof(double) * static_cast<std::size_t>(ca.size());
  return std::memcmp(ca.data(), cb.data(), bytes) == 0;
}

/// Expects `b` to equal `a` exactly: geometry, normals, properties and their storage types.
void expect_identical(const Surface& a, const Surface& b) {
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  ASSERT_EQ(a.n_faces(), b.n_faces());
  EXPECT_TRUE(same_bits(a.positions(), b.positions()));
  EXPECT_EQ(a.faces(), b.faces());
  ASSERT_EQ(a.has_normals(), b.has_normals());
  if (a.has_normals()) {
    EXPECT_TRUE(same_bits(a.normals(), b.normals()));
  }
  EXPECT_EQ(a.position_type(), b.position_type());
  EXPECT_EQ(a.normal_type(), b.normal_type());
  ASSERT_EQ(a.property_names(), b.property_names());
  for (const auto& name : a.property_names()) {
    EXPECT_TRUE(same_bits(a.property(name), b.property(name))) << name;
    EXPECT_EQ(a.property_type(name), b.property_type(name)) << name;
  }
}

/// A regular tetrahedron-like closed surface with coordinates that are not short decimals.
Surface tetrahedron() {
  Eigen::MatrixX3d p(4, 3);
  p << 0.1, 1.0 / 3.0, -2.0 / 7.0,          //
      1.0e-7, 2.718281828459045, 0.3,       //
      -1.4142135623730951, 0.0, 1e5 / 3.0,  //
      0.5, -0.6, std::acos(-1.0);
  Eigen::MatrixX3i f(4, 3);
  f << 0, 2, 1,  //
      0, 1, 3,   //
      0, 3, 2,   //
      1, 2, 3;
  return Surface::from_arrays(p, f, "tetrahedron");
}

TEST(MeshIoPly, ReadsMasifAsciiWithItsProperties) {
  SURFCOMP_SHARED_OR_SKIP(path, "surfaces/masif/1EWY_A.ply");
  const Surface s = io::read_ply(path);
  EXPECT_EQ(s.n_vertices(), 5890u);
  EXPECT_EQ(s.n_faces(), 11780u);
  const std::vector<std::string> expected{"charge", "hbond", "hphob", "iface"};
  EXPECT_EQ(s.property_names(), expected);
  for (const auto& name : expected) EXPECT_EQ(s.property_type(name), ValueType::float32);
  EXPECT_EQ(s.position_type(), ValueType::float32);
  EXPECT_EQ(s.normal_type(), ValueType::float32);
  ASSERT_TRUE(s.has_normals());
  // First data line: 44.561 31.963 -0.147 -0.24525 0 -1.6 0 0.63311 0.639227 -0.436532
  const Eigen::MatrixX3d p = s.positions();
  const Eigen::MatrixX3d n = s.normals();
  EXPECT_EQ(p(0, 0), static_cast<double>(44.561f));
  EXPECT_EQ(p(0, 1), static_cast<double>(31.963f));
  EXPECT_EQ(p(0, 2), static_cast<double>(-0.147f));
  EXPECT_EQ(s.property("charge", 0), static_cast<double>(-0.24525f));
  EXPECT_EQ(s.property("hbond", 0), 0.0);
  EXPECT_EQ(s.property("hphob", 0), static_cast<double>(-1.6f));
  EXPECT_EQ(s.property("iface", 0), 0.0);
  EXPECT_EQ(n(0, 0), static_cast<double>(0.63311f));
  EXPECT_EQ(n(0, 1), static_cast<double>(0.639227f));
  EXPECT_EQ(n(0, 2), static_cast<double>(-0.436532f));
  // Second line: 16.128 37.209 3.968 -0.989814 -0.992405 -0.4 0 ...
  EXPECT_EQ(p(1, 0), static_cast<double>(16.128f));
  EXPECT_EQ(s.property("hbond", 1), static_cast<double>(-0.992405f));
  const SurfaceMeasures m = measure_surface(s);
  EXPECT_EQ(m.euler_characteristic, 0);
  EXPECT_EQ(s.source(), path.string());
}

void check_binary_round_trip(io::PlyFormat format) {
  SURFCOMP_SHARED_OR_SKIP(path, "surfaces/masif/1EWY_A.ply");
  const Surface ascii = io::read_ply(path);
  std::stringstream first;
  io::write_ply(ascii, first, format);
  const std::string first_bytes = first.str();
  // 5890 vertices * 10 floats + 11780 faces * (1 + 3 * 4) bytes after the header.
  const std::size_t header_size = first_bytes.find("end_header\n") + 11;
  EXPECT_EQ(first_bytes.size() - header_size, 5890u * 40u + 11780u * 13u);
  EXPECT_NE(first_bytes.find("comment surfcomp\n"), std::string::npos);
  EXPECT_NE(first_bytes.find("property float charge\n"), std::string::npos);
  EXPECT_NE(first_bytes.find("property list uchar int vertex_indices\n"), std::string::npos);

  const Surface binary = io::read_ply(first, "first.ply");
  expect_identical(ascii, binary);
  std::stringstream second;
  io::write_ply(binary, second, format);
  EXPECT_TRUE(second.str() == first_bytes) << "second binary write differs from the first";

  TempDir dir;
  io::write_ply(binary, dir / "third.ply", format);
  EXPECT_TRUE(read_bytes(dir / "third.ply") == first_bytes);
}

TEST(MeshIoPly, BinaryLittleEndianRoundTripIsBitExact) {
  check_binary_round_trip(io::PlyFormat::binary_little_endian);
}

TEST(MeshIoPly, BinaryBigEndianRoundTripIsBitExact) {
  check_binary_round_trip(io::PlyFormat::binary_big_endian);
}

TEST(MeshIoPly, BigAndLittleEndianFilesAreByteReversals) {
  Surface s = tetrahedron();
  s.set_property("q", Eigen::Vector4d(1.5, -2.25, 3.0, 0.0), ValueType::float32);
  std::stringstream le, be;
  io::write_ply(s, le, io::PlyFormat::binary_little_endian);
  io::write_ply(s, be, io::PlyFormat::binary_big_endian);
  const std::string l = le.str(), b = be.str();
  const std::size_t hl = l.find("end_header\n") + 11, hb = b.find("end_header\n") + 11;
  ASSERT_EQ(l.size() - hl, b.size() - hb);
  // First value: x of vertex 0 as a double, 0.1 = 0x3FB999999999999A.
  std::string x_le = l.substr(hl, 8), x_be = b.substr(hb, 8);
  std::reverse(x_be.begin(), x_be.end());
  EXPECT_EQ(x_le, x_be);
  EXPECT_EQ(static_cast<unsigned char>(b[hb]), 0x3Fu);
  EXPECT_EQ(static_cast<unsigned char>(b[hb + 1]), 0xB9u);
}

TEST(MeshIoPly, AsciiRoundTripOfDoublesIsExact) {
  Surface s = tetrahedron();
  s.compute_normals();
  s.set_property("esp", Eigen::Vector4d(0.1, 1.0 / 3.0, -2.5e17, 1e-300));
  s.set_property("lp", Eigen::Vector4d(std::acos(-1.0), -0.0, 123456789.123456789, 5e-324));
  s.set_property("charge", Eigen::Vector4d(-0.24525, 0.1, 1e30, -3.4e38), ValueType::float32);
  s.set_property("label", Eigen::Vector4d(-128, 127, 0, 5), ValueType::int8);
  s.set_property("count", Eigen::Vector4d(0, 65535, 7, 4294967295.0), ValueType::uint32);
  std::stringstream text;
  io::write_ply(s, text, io::PlyFormat::ascii);
  EXPECT_NE(text.str().find("format ascii 1.0\ncomment surfcomp\nelement vertex 4\n"),
            std::string::npos);
  EXPECT_NE(text.str().find("property double esp\n"), std::string::npos);
  EXPECT_NE(text.str().find("property char label\n"), std::string::npos);
  const Surface back = io::read_ply(text, "ascii.ply");
  ASSERT_EQ(back.property_names(), s.property_names());
  EXPECT_EQ(back.property("esp", 1), 1.0 / 3.0);
  EXPECT_EQ(back.property("lp", 3), 5e-324);
  EXPECT_EQ(back.property("label", 0), -128.0);
  EXPECT_EQ(back.property("count", 3), 4294967295.0);
  EXPECT_EQ(back.property("charge", 0), static_cast<double>(-0.24525f));
  EXPECT_TRUE(same_bits(back.positions(), s.positions()));
  EXPECT_TRUE(same_bits(back.normals(), s.normals()));
  EXPECT_TRUE(same_bits(back.property("esp"), s.property("esp")));
  EXPECT_TRUE(same_bits(back.property("lp"), s.property("lp")));
  EXPECT_EQ(back.property_type("label"), ValueType::int8);
  EXPECT_EQ(back.property_type("count"), ValueType::uint32);
  // float32 values become their float rounding, in ascii as in binary.
  Eigen::Vector4d charge_as_float;
  for (int i = 0; i < 4; ++i) charge_as_float(i) = static_cast<float>(s.property("charge", i));
  EXPECT_TRUE(same_bits(back.property("charge"), charge_as_float));
  // A second ascii write of what was read gives the same text.
  std::stringstream again;
  io::write_ply(back, again, io::PlyFormat::ascii);
  EXPECT_EQ(again.str().substr(again.str().find("end_header")),
            text.str().substr(text.str().find("end_header")));
}

/// `text` with every "\n" replaced by "\r\n", up to `end` (npos: everywhere).
std::string with_crlf(const std::string& text, std::size_t end = std::string::npos) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n' && i < end) out += '\r';
    out += text[i];
  }
  return out;
}

TEST(MeshIoPly, ReadsWindowsLineEndings) {
  Surface s = tetrahedron();
  s.set_property("esp", Eigen::Vector4d(0.1, 0.2, 0.3, 0.4));
  std::stringstream ascii, binary;
  io::write_ply(s, ascii, io::PlyFormat::ascii);
  io::write_ply(s, binary, io::PlyFormat::binary_little_endian);
  std::istringstream ascii_crlf(with_crlf(ascii.str()));
  expect_identical(s, io::read_ply(ascii_crlf, "crlf.ply"));
  // Only the header of a binary file has lines.
  const std::string b = binary.str();
  std::istringstream binary_crlf(with_crlf(b, b.find("end_header\n") + 11));
  expect_identical(s, io::read_ply(binary_crlf, "crlf.ply"));
}

TEST(MeshIoPly, WriteRejectsValuesOutsideTheirStorageType) {
  Surface s = tetrahedron();
  s.set_property("small", Eigen::Vector4d(1, 2, 300, 4), ValueType::int8);
  std::stringstream out;
  try {
    io::write_ply(s, out);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'small' at vertex 2"), std::string::npos) << e.what();
  }
  Surface t = tetrahedron();
  t.set_property("fraction", Eigen::Vector4d(1, 2.5, 3, 4), ValueType::int16);
  EXPECT_THROW(io::write_ply(t, out), InputError);
  Surface u = tetrahedron();
  u.set_property("x", Eigen::Vector4d(1, 2, 3, 4));
  EXPECT_THROW(io::write_ply(u, out), InputError);
}

constexpr const char* octahedron_vertices = "0 0 1\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n0 0 -1\n";

TEST(MeshIoPly, SkipsOtherElementsListsAndSplitsPolygons) {
  // An ascii square pyramid: a quad base (split into 2 triangles) and 4 sides; a vertex list
  // property, a face colour and an edge element are skipped.
  const std::string text =
      "ply\nformat ascii 1.0\ncomment pyramid\nobj_info made by hand\n"
      "element vertex 5\nproperty double x\nproperty double y\nproperty double z\n"
      "property list uchar float texcoord\nproperty ushort tag\n"
      "element edge 2\nproperty int vertex1\nproperty int vertex2\n"
      "element face 5\nproperty uchar red\nproperty list uchar uint vertex_index\n"
      "end_header\n"
      "0 0 0 2 0.5 0.5 10\n1 0 0 0 11\n1 1 0 1 7 12\n0 1 0 0 13\n0.5 0.5 1 0 14\n"
      "0 1\n1 2\n"
      "255 4 0 3 2 1\n0 3 0 1 4\n0 3 1 2 4\n0 3 2 3 4\n0 3 3 0 4\n\n";
  std::istringstream in(text);
  const Surface s = io::read_ply(in, "pyramid.ply");
  EXPECT_EQ(s.n_vertices(), 5u);
  EXPECT_EQ(s.n_faces(), 6u);
  EXPECT_FALSE(s.has_normals());
  EXPECT_EQ(s.property_names(), std::vector<std::string>{"tag"});
  EXPECT_EQ(s.property_type("tag"), ValueType::uint16);
  EXPECT_EQ(s.property("tag", 4), 14.0);
  const Eigen::MatrixX3i f = s.faces();
  EXPECT_EQ(f.row(0), Eigen::RowVector3i(0, 3, 2));
  EXPECT_EQ(f.row(1), Eigen::RowVector3i(0, 2, 1));
  const SurfaceMeasures m = measure_surface(s);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_EQ(m.boundary_edges, 0u);
  EXPECT_NEAR(m.volume, 1.0 / 3.0, 1e-12);
}

/// Appends `value` to `out` as big-endian bytes.
template <class T>
void put_be(std::string& out, T value) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

TEST(MeshIoPly, BinaryBigEndianSkipsOtherElements) {
  // An octahedron in big-endian binary with mixed types, an edge element before the faces and
  // a uint16 list count with int16 indices.
  std::string data =
      "ply\nformat binary_big_endian 1.0\nelement vertex 6\nproperty float x\n"
      "property float y\nproperty float z\nproperty list int int junk\nproperty short level\n"
      "element edge 1\nproperty list uchar int ends\n"
      "element face 8\nproperty list ushort short vertex_indices\nproperty double area\n"
      "end_header\n";
  const float xyz[6][3] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  for (int v = 0; v < 6; ++v) {
    for (float c : xyz[v]) put_be(data, c);
    put_be<std::int32_t>(data, v % 2);  // list of 0 or 1 ints
    if (v % 2) put_be<std::int32_t>(data, 99);
    put_be<std::int16_t>(data, static_cast<std::int16_t>(-v));
  }
  data += '\2';
  put_be<std::int32_t>(data, 0);
  put_be<std::int32_t>(data, 1);
  const int tris[8][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1},
                          {5, 2, 1}, {5, 3, 2}, {5, 4, 3}, {5, 1, 4}};
  for (const auto& t : tris) {
    put_be<std::uint16_t>(data, 3);
    for (int i : t) put_be<std::int16_t>(data, static_cast<std::int16_t>(i));
    put_be(data, 0.5);
  }
  std::istringstream in(data);
  const Surface s = io::read_ply(in, "octahedron.ply");
  EXPECT_EQ(s.n_vertices(), 6u);
  EXPECT_EQ(s.n_faces(), 8u);
  EXPECT_EQ(s.property("level", 5), -5.0);
  EXPECT_EQ(s.property_type("level"), ValueType::int16);
  EXPECT_EQ(s.positions()(3, 0), -1.0);
  const SurfaceMeasures m = measure_surface(s);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_NEAR(m.volume, 4.0 / 3.0, 1e-12);

  // The same file cut anywhere in its data is rejected.
  const std::size_t data_start = data.find("end_header\n") + 11;
  for (std::size_t cut = data_start; cut < data.size(); cut += 7) {
    std::istringstream truncated(data.substr(0, cut));
    EXPECT_THROW(io::read_ply(truncated, "cut.ply"), FormatError) << cut;
  }
}

std::string ascii_ply(const std::string& vertex_count, const std::string& vertices,
                      const std::string& faces, const std::string& face_count = "8") {
  return "ply\nformat ascii 1.0\nelement vertex " + vertex_count +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + face_count +
         "\nproperty list uchar int vertex_indices\nend_header\n" + vertices + faces;
}

constexpr const char* octahedron_faces =
    "3 0 1 2\n3 0 2 3\n3 0 3 4\n3 0 4 1\n3 5 2 1\n3 5 3 2\n3 5 4 3\n3 5 1 4\n";

/// The message of the surfcomp::Error that reading `text` as PLY throws, or "" if none.
template <class E>
std::string ply_error(const std::string& text) {
  std::istringstream in(text);
  try {
    io::read_ply(in, "bad.ply");
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

TEST(MeshIoPly, MalformedInputGivesFormatErrorsWithLineNumbers) {
  // The valid file reads.
  std::istringstream good(ascii_ply("6", octahedron_vertices, octahedron_faces));
  EXPECT_EQ(io::read_ply(good, "good.ply").n_faces(), 8u);

  // A header claiming 10^12 vertices fails at the header, before any element is read or
  // allocated.
  const std::string huge =
      ply_error<FormatError>(ascii_ply("1000000000000", octahedron_vertices, octahedron_faces));
  EXPECT_NE(huge.find("bad.ply:3: the header claims 1000000000000 items of element 'vertex'"),
            std::string::npos)
      << huge;
  const std::string many =
      ply_error<FormatError>(ascii_ply("4000000", octahedron_vertices, octahedron_faces));
  EXPECT_NE(many.find("claims 4000000"), std::string::npos) << many;

  // Line 11 is the first data line.
  const std::string nan = ply_error<FormatError>(
      ascii_ply("6", "0 0 1\nnan 0 0\n0 1 0\n-1 0 0\n0 -1 0\n0 0 -1\n", octahedron_faces));
  EXPECT_NE(nan.find("bad.ply:11: expected a finite value for property 'x'"), std::string::npos)
      << nan;
  const std::string inf = ply_error<FormatError>(
      ascii_ply("6", "0 0 1\n1 0 0\n0 1 0\n-1 0 0\n0 -1 inf\n0 0 -1\n", octahedron_faces));
  EXPECT_NE(inf.find("bad.ply:14:"), std::string::npos) << inf;
  const std::string index =
      ply_error<FormatError>(ascii_ply("6", octahedron_vertices,
                                       "3 0 1 2\n3 0 2 6\n3 0 3 4\n3 0 4 1\n"
                                       "3 5 2 1\n3 5 3 2\n3 5 4 3\n3 5 1 4\n"));
  EXPECT_NE(index.find("bad.ply:17: expected a vertex index in 0..5, found 6"), std::string::npos)
      << index;
  const std::string word = ply_error<FormatError>(
      ascii_ply("6", "0 0 1\n1 0 0\n0 one 0\n-1 0 0\n0 -1 0\n0 0 -1\n", octahedron_faces));
  EXPECT_NE(word.find("bad.ply:12: expected a float for property 'y', found 'one'"),
            std::string::npos)
      << word;
  const std::string short_line = ply_error<FormatError>(
      ascii_ply("6", "0 0 1\n1 0 0\n0 1\n-1 0 0\n0 -1 0\n0 0 -1\n", octahedron_faces));
  EXPECT_NE(short_line.find("bad.ply:12: expected a value for property 'z'"), std::string::npos)
      << short_line;
  const std::string missing =
      ply_error<FormatError>(ascii_ply("6", octahedron_vertices, "3 0 1 2\n3 0 2 3\n"));
  EXPECT_NE(missing.find("expected item 3 of 8 of element 'face', found the end of the file"),
            std::string::npos)
      << missing;
  const std::string extra =
      ply_error<FormatError>(ascii_ply("6", octahedron_vertices, octahedron_faces, "7"));
  EXPECT_NE(extra.find("bad.ply:23: expected the end of the file"), std::string::npos) << extra;
  const std::string two = ply_error<FormatError>(
      ascii_ply("6", octahedron_vertices, std::string("2 0 1\n") + octahedron_faces));
  EXPECT_NE(two.find("at least 3 vertices, found 2"), std::string::npos) << two;

  EXPECT_NE(ply_error<FormatError>("plx\n").find("bad.ply:1: expected 'ply'"), std::string::npos);
  EXPECT_NE(ply_error<FormatError>("ply\nformat ascii 1.0\nelement vertex 0\n")
                .find("expected 'end_header', found the end of the file"),
            std::string::npos);
  EXPECT_NE(ply_error<FormatError>("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n"
                                   "end_header\n")
                .find("bad.ply:4: expected a PLY type"),
            std::string::npos);
  EXPECT_NE(ply_error<FormatError>("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                   "end_header\n0\n")
                .find("expected a scalar vertex property 'y'"),
            std::string::npos);

  // Faces that are each fine but together non-manifold: three triangles on one edge.
  const std::string fan = ply_error<TopologyError>(
      ascii_ply("5", "0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n", "3 0 1 2\n3 1 0 3\n3 0 1 4\n", "3"));
  EXPECT_NE(fan.find("bad.ply: face 2"), std::string::npos) << fan;

  EXPECT_THROW(io::read_ply(fs::path("/nonexistent/none.ply")), FileError);
}

TEST(MeshIoPly, TruncatedBinaryIsAFormatError) {
  Surface s = tetrahedron();
  std::stringstream out;
  io::write_ply(s, out, io::PlyFormat::binary_little_endian);
  const std::string bytes = out.str();
  std::istringstream cut(bytes.substr(0, bytes.size() - 1));
  try {
    io::read_ply(cut, "cut.ply");
    FAIL() << "expected FormatError";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("item 4 of 4 of element 'face'"), std::string::npos)
        << e.what();
  }
  // A binary header claiming more vertices than the bytes can hold.
  std::string big = bytes;
  big.replace(big.find("vertex 4"), 8, "vertex 9999999");
  std::istringstream claims(big);
  EXPECT_THROW(io::read_ply(claims, "big.ply"), FormatError);
}

// ---------------------------------------------------------------------------------------------
// MSMS

TEST(MeshIoMsms, ReadsLysozymeWithNormals) {
  SURFCOMP_SHARED_OR_SKIP(vert, "surfaces/lysozyme-msms/geometry/Lys1.vert");
  const Surface s = io::read_msms(vert);
  EXPECT_EQ(s.n_vertices(), 7201u);
  EXPECT_EQ(s.n_faces(), 14398u);
  ASSERT_TRUE(s.has_normals());
  // First lines: "-19.183 20.964 10.129 -0.425 0.166 -0.890 ..." and "1 4659 2 3 3".
  EXPECT_EQ(s.positions().row(0), Eigen::RowVector3d(-19.183, 20.964, 10.129));
  EXPECT_EQ(s.normals().row(0), Eigen::RowVector3d(-0.425, 0.166, -0.890));
  EXPECT_EQ(s.faces().row(0), Eigen::RowVector3i(0, 4658, 1));
  const SurfaceMeasures m = measure_surface(s);
  EXPECT_EQ(m.boundary_edges, 0u);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_GT(m.volume, 0.0);

  // The .face path and the base name give the same surface.
  const fs::path base = vert.parent_path() / "Lys1";
  expect_identical(s, io::read_msms(base));
  expect_identical(s, io::read_msms(vert.parent_path() / "Lys1.face"));

  // A copy with MSMS headers reads identically.
  TempDir dir;
  write_text(dir / "lys.vert",
             "# MSMS solvent excluded surface vertices for lys1.xyzr\n"
             "#vertex #sphere density probe_r\n"
             "   7201    1001  1.00  1.50\n" +
                 read_bytes(vert));
  write_text(dir / "lys.face",
             "# MSMS solvent excluded surface faces for lys1.xyzr\n"
             "#faces  #sphere density probe_r\n"
             "  14398    1001  1.00  1.50\n" +
                 read_bytes(vert.parent_path() / "Lys1.face"));
  expect_identical(s, io::read_msms(dir / "lys.vert"));

  // A header whose count disagrees with the data is an error naming the count line.
  write_text(dir / "bad.vert", "# MSMS\n#vertex\n   7200    1001  1.00  1.50\n" + read_bytes(vert));
  write_text(dir / "bad.face", read_bytes(dir / "lys.face"));
  try {
    io::read_msms(dir / "bad.vert");
    FAIL() << "expected FormatError";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.vert:3: the header claims 7200 vertices, found 7201"),
              std::string::npos)
        << e.what();
  }
}

TEST(MeshIoMsms, MalformedFilesGiveFormatErrors) {
  TempDir dir;
  write_text(dir / "oct.vert",
             "0 0 1 0 0 1 0 1 2\n1 0 0 1 0 0 0 1 2\n0 1 0 0 1 0 0 1 2\n"
             "-1 0 0 -1 0 0 0 1 2\n0 -1 0 0 -1 0 0 1 2\n0 0 -1 0 0 -1 0 1 2\n");
  write_text(dir / "oct.face",
             "1 2 3 1 1\n1 3 4 1 1\n1 4 5 1 1\n1 5 2 1 1\n6 3 2 1 1\n6 4 3 1 1\n6 5 4 1 1\n"
             "6 2 5 1 1\n");
  const Surface s = io::read_msms(dir / "oct");
  EXPECT_EQ(s.n_vertices(), 6u);
  EXPECT_EQ(s.n_faces(), 8u);
  EXPECT_NEAR(measure_surface(s).volume, 4.0 / 3.0, 1e-12);

  write_text(dir / "oct.face", "1 2 3 1 1\n1 3 7 1 1\n");
  try {
    io::read_msms(dir / "oct.vert");
    FAIL() << "expected FormatError";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("oct.face:2: expected a vertex number (an integer in "
                                         "1..6), found '7'"),
              std::string::npos)
        << e.what();
  }
  write_text(dir / "oct.face", "1 2 3 1 1\n1 3 0 1 1\n");
  EXPECT_THROW(io::read_msms(dir / "oct.vert"), FormatError);
  write_text(dir / "nan.vert", "0 0 nan 0 0 1 0 1 2\n");
  write_text(dir / "nan.face", "");
  EXPECT_THROW(io::read_msms(dir / "nan.vert"), FormatError);
  EXPECT_THROW(io::read_msms(dir / "absent.vert"), FileError);
}

// ---------------------------------------------------------------------------------------------
// OFF and OBJ

TEST(MeshIoOffObj, ReadsHandWrittenTetrahedra) {
  TempDir dir;
  write_text(dir / "tet.off",
             "OFF\n# a tetrahedron\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
             "3 0 2 1\n3 0 1 3 255 0 0\n3 0 3 2\n3 1 2 3  # last\n");
  const Surface off = io::read_off(dir / "tet.off");
  EXPECT_EQ(off.n_vertices(), 4u);
  EXPECT_EQ(off.n_faces(), 4u);
  EXPECT_NEAR(measure_surface(off).volume, 1.0 / 6.0, 1e-15);

  // OBJ: v/vt/vn corner forms, a negative (relative) index, ignored statements.
  write_text(dir / "tet.obj",
             "# tetrahedron\nmtllib none.mtl\no tet\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1 1.0\n"
             "vn 0 0 1\nvt 0 0\ns off\nf 1/1/1 3/1/1 2/1/1\nf 1//1 2//1 4//1\nf 1/1 4/1 3/1\n"
             "f -3 -2 -1\n");
  const Surface obj = io::read_obj(dir / "tet.obj");
  EXPECT_EQ(obj.n_vertices(), 4u);
  EXPECT_EQ(obj.n_faces(), 4u);
  EXPECT_EQ(obj.faces(), off.faces());
  EXPECT_EQ(obj.positions(), off.positions());

  // Quads are split into fans: a cube of 6 quads gives 12 triangles.
  write_text(dir / "cube.obj",
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
             "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  const Surface cube = io::read_obj(dir / "cube.obj");
  EXPECT_EQ(cube.n_faces(), 12u);
  EXPECT_NEAR(measure_surface(cube).volume, 1.0, 1e-15);
  EXPECT_EQ(measure_surface(cube).euler_characteristic, 2);
  write_text(dir / "cube.off",
             "OFF 8 6 12\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
             "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n");
  EXPECT_EQ(io::read_off(dir / "cube.off").faces(), cube.faces());
}

TEST(MeshIoOffObj, WriteThenReadGivesTheSamePositions) {
  TempDir dir;
  const Surface s = tetrahedron();
  io::write_off(s, dir / "t.off");
  io::write_obj(s, dir / "t.obj");
  const Surface off = io::read_off(dir / "t.off");
  const Surface obj = io::read_obj(dir / "t.obj");
  EXPECT_TRUE(same_bits(off.positions(), s.positions()));
  EXPECT_TRUE(same_bits(obj.positions(), s.positions()));
  EXPECT_EQ(off.faces(), s.faces());
  EXPECT_EQ(obj.faces(), s.faces());
  EXPECT_EQ(read_bytes(dir / "t.off").substr(0, 10), "OFF\n4 4 0\n");
}

TEST(MeshIoOffObj, MalformedFilesGiveFormatErrors) {
  TempDir dir;
  auto off_error = [&](const std::string& text) -> std::string {
    write_text(dir / "bad.off", text);
    try {
      io::read_off(dir / "bad.off");
    } catch (const FormatError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(off_error("OFF\n1000000000 1 0\n0 0 0\n").find("bad.off:2: the header claims"),
            std::string::npos);
  EXPECT_NE(off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")
                .find("bad.off:6: expected a vertex index (an integer in 0..2), found '3'"),
            std::string::npos);
  EXPECT_NE(off_error("OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n")
                .find("bad.off:4: expected a finite coordinate, found 'inf'"),
            std::string::npos);
  EXPECT_NE(off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n5 0 1 2\n").find("polygon size"),
            std::string::npos);
  EXPECT_NE(off_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n")
                .find("bad.off:7: expected the end of the file"),
            std::string::npos);
  EXPECT_NE(off_error("PLY\n").find("bad.off:1: expected 'OFF'"), std::string::npos);

  auto obj_error = [&](const std::string& text) -> std::string {
    write_text(dir / "bad.obj", text);
    try {
      io::read_obj(dir / "bad.obj");
    } catch (const FormatError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
                .find("bad.obj:4: expected a vertex number in 1..3 or -3..-1"),
            std::string::npos);
  EXPECT_NE(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").find("found 0"), std::string::npos);
  EXPECT_NE(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n").find("bad.obj:4:"),
            std::string::npos);
  EXPECT_NE(obj_error("v 0 0\n").find("bad.obj:1: expected 'v x y z"), std::string::npos);
  EXPECT_NE(obj_error("v 0 0 nan\n").find("bad.obj:1: expected a finite coordinate"),
            std::string::npos);
  EXPECT_NE(obj_error("v 0 0 0\nv 1 0 0\nf 1 2\n").find("at least 3 corners"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Dispatch

TEST(MeshIoDispatch, ReadMeshChoosesTheReaderByExtension) {
  EXPECT_TRUE(io::is_mesh_file("a/b.ply"));
  EXPECT_TRUE(io::is_mesh_file("X.VERT"));
  EXPECT_TRUE(io::is_mesh_file("x.face"));
  EXPECT_TRUE(io::is_mesh_file("x.Off"));
  EXPECT_TRUE(io::is_mesh_file("x.obj"));
  EXPECT_TRUE(io::is_mesh_file("x.stl"));
  EXPECT_FALSE(io::is_mesh_file("x.xyz"));
  EXPECT_FALSE(io::is_mesh_file("ply"));
  EXPECT_FALSE(io::is_mesh_file("x.pdb"));

  TempDir dir;
  Surface s = tetrahedron();
  s.set_property("esp", Eigen::Vector4d(1, 2, 3, 4));
  io::write_mesh(s, dir / "t.ply");
  io::write_mesh(s, dir / "t.off");
  io::write_mesh(s, dir / "t.OBJ");
  EXPECT_EQ(read_bytes(dir / "t.ply").substr(0, 36), "ply\nformat binary_little_endian 1.0\n");
  expect_identical(s, io::read_mesh(dir / "t.ply"));
  EXPECT_TRUE(same_bits(io::read_mesh(dir / "t.off").positions(), s.positions()));
  EXPECT_TRUE(same_bits(io::read_mesh(dir / "t.OBJ").positions(), s.positions()));
  EXPECT_FALSE(io::read_mesh(dir / "t.off").has_property("esp"));

  write_text(dir / "t.vert", "0 0 1 0 0 1\n1 0 0 1 0 0\n0 1 0 0 1 0\n");
  write_text(dir / "t.face", "1 2 3\n");
  EXPECT_EQ(io::read_mesh(dir / "t.face").n_faces(), 1u);
  EXPECT_EQ(io::read_mesh(dir / "t.vert").n_vertices(), 3u);

  write_text(dir / "t.abc", "solid t\n");
  try {
    io::read_mesh(dir / "t.abc");
    FAIL() << "expected FormatError";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("found '.abc'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(io::write_mesh(s, dir / "t.xyz"), FormatError);
  EXPECT_FALSE(fs::exists(dir / "t.xyz"));
  EXPECT_THROW(io::write_mesh(s, dir / "t.vert"), FormatError);
  EXPECT_THROW(io::read_mesh(dir / "absent.ply"), FileError);
}

}  // namespace
}  // namespace surfcomp::mesh
