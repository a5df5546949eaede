// The limits every reader applies to its input (core/io/input_file.hpp): only regular files of
// bounded size are read, read coordinates are finite and of plausible magnitude, per-vertex
// properties are finite, .hsi contents are validated after the checksum, and a molecule file
// is read as asked (one record chosen, no ligand selection on SDF). Each refusal is a
// surfcomp::Error subclass naming the file and the problem.
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/binary_stream.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <sys/stat.h>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

/// Expects `call` to throw exactly an `E` (or subclass) whose message holds every `part`.
template <class E>
void expect_error(const std::function<void()>& call, const std::vector<std::string>& parts) {
  try {
    call();
    ADD_FAILURE() << "no exception; expected one mentioning '" << parts.front() << "'";
  } catch (const E& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
  }
}

// ---- special files ---------------------------------------------------------------------------

TEST(ReadInputFile, ReadsARegularFileWhole) {
  const TempDir dir;
  const std::string content("a\0b\nline two", 12);
  EXPECT_EQ(io::read_input_file(dir.write("x.txt", content)), content);
  EXPECT_EQ(io::read_input_file(dir.write("empty.txt", "")), "");
}

TEST(ReadInputFile, RefusesMissingFilesDirectoriesFifosAndDevices) {
  const TempDir dir;
  expect_error<FileError>([&] { io::read_input_file(dir / "missing.ply"); },
                          {"missing.ply", "no such file"});
  fs::create_directory(dir / "x.hsi");
  expect_error<FileError>([&] { io::read_input_file(dir / "x.hsi"); },
                          {"x.hsi", "not a regular file"});
  ASSERT_EQ(::mkfifo((dir / "fifo.ply").c_str(), 0600), 0);
  // Opening a FIFO without a writer must not block: the test would hang here otherwise.
  expect_error<FileError>([&] { io::read_input_file(dir / "fifo.ply"); },
                          {"fifo.ply", "not a regular file"});
  expect_error<FileError>([&] { io::read_input_file("/dev/zero"); },
                          {"/dev/zero", "not a regular file"});
}

TEST(ReadInputFile, EveryReaderRefusesSpecialFiles) {
  const TempDir dir;
  for (const std::string name :
       {"a.ply", "a.off", "a.obj", "a.vert", "a.hsi", "a.sdf", "a.mol2", "a.pdb", "a.pqr"}) {
    SCOPED_TRACE(name);
    const fs::path directory = dir / ("dir_" + name);
    const fs::path fifo = dir / ("fifo_" + name);
    fs::create_directory(directory);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const fs::path& path : {directory, fifo}) {
      const auto read = [&] {
        if (mesh::io::is_mesh_file(path)) {
          mesh::io::read_mesh(path);
        } else if (harmonic::io::is_hsi_file(path)) {
          harmonic::io::read_hsi(path);
        } else {
          io::read_molecule(path);
        }
      };
      expect_error<FileError>(read, {path.filename().string(), "not a regular file"});
    }
  }
}

// ---- coordinates and properties --------------------------------------------------------------

std::string tetrahedron_ply(const std::string& property, const std::string& value,
                            const std::string& z) {
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
         "property float z\nproperty float " +
         property +
         "\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0 0.1\n10 0 0 0.2\n0 10 0 " +
         value + "\n0 0 " + z + " 0.3\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
}

TEST(ReadCoordinates, ValidMeshesReadAsWritten) {
  const TempDir dir;
  const mesh::Surface s =
      mesh::io::read_mesh(dir.write("t.ply", tetrahedron_ply("esp", "2", "10")));
  EXPECT_EQ(s.n_vertices(), 4u);
  EXPECT_DOUBLE_EQ(s.property("esp", 2), 2.0);
  EXPECT_DOUBLE_EQ(s.positions()(3, 2), 10.0);
}

TEST(ReadCoordinates, NonFiniteVertexPropertiesAreRefusedNamingPropertyAndVertex) {
  const TempDir dir;
  for (const std::string property : {"charge", "esp"}) {
    for (const std::string value : {"nan", "inf", "-inf"}) {
      const fs::path path = dir.write(property + ".ply", tetrahedron_ply(property, value, "10"));
      expect_error<FormatError>([&] { mesh::io::read_mesh(path); },
                                {path.string(), "vertex 2", "property '" + property + "'"});
    }
  }
}

TEST(ReadCoordinates, HugeMeshCoordinatesAreRefused) {
  const TempDir dir;
  const fs::path ply = dir.write("big.ply", tetrahedron_ply("charge", "0.5", "1e30"));
  expect_error<FormatError>([&] { mesh::io::read_mesh(ply); },
                            {ply.string(), "vertex 3", "z = 1e+30", "1e+06"});
  const std::string faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const fs::path off = dir.write("big.off", "OFF\n4 4 0\n0 0 0\n10 0 0\n0 -2e6 0\n0 0 1\n" + faces);
  expect_error<FormatError>([&] { mesh::io::read_mesh(off); }, {off.string(), "vertex 2", "y ="});
  const fs::path obj = dir.write(
      "big.obj", "v 0 0 0\nv 1e7 0 0\nv 0 10 0\nv 0 0 10\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  expect_error<FormatError>([&] { mesh::io::read_mesh(obj); }, {obj.string(), "vertex 1", "x ="});
  // At the limit itself the coordinate is accepted.
  EXPECT_NO_THROW(mesh::io::read_mesh(dir.write("edge.ply", tetrahedron_ply("c", "0", "1e6"))));
}

constexpr const char* kPqr =
    "ATOM      1  C1  LIG     1       0.000   0.000   0.000  0.1000 1.7000\n"
    "ATOM      2  O1  LIG     1       1.200   0.000   0.000 -0.1000 1.5200\n"
    "ATOM      3  N1  LIG     1       0.000   1.300   Z      0.0000 1.5500\n";

std::string pqr_with_z(const std::string& z) {
  std::string text = kPqr;
  text.replace(text.find(" Z "), 3, " " + z + " ");
  return text;
}

TEST(ReadCoordinates, HugePqrCoordinatesAreRefusedNamingLineAndAtom) {
  const TempDir dir;
  const fs::path path = dir.write("z.pqr", pqr_with_z("1e30"));
  expect_error<FormatError>([&] { io::read_molecule(path); },
                            {path.string() + ":3:", "atom 'N1'", "z = 1e+30"});
  const Molecule ok = io::read_molecule(dir.write("ok.pqr", pqr_with_z("0.5")));
  ASSERT_EQ(ok.atoms.size(), 3u);
  EXPECT_DOUBLE_EQ(ok.atoms[2].position.z(), 0.5);
}

TEST(ReadCharges, AbsurdPqrChargesAreRefusedNamingLineAndAtom) {
  const TempDir dir;
  const auto with_charge = [](const std::string& q) {  // atom O1's charge, 7 columns
    std::string text = pqr_with_z("0.5");
    text.replace(text.find("-0.1000"), 7, q);
    return text;
  };
  const fs::path path = dir.write("q.pqr", with_charge("   1e30"));
  expect_error<FormatError>([&] { io::read_molecule(path); },
                            {path.string() + ":2:", "atom 'O1'", "charge 1e+30 e", "10 e"});
  const Molecule ok = io::read_molecule(dir.write("ok.pqr", with_charge("-9.5000")));
  EXPECT_DOUBLE_EQ(ok.atoms[1].charge, -9.5);
}

TEST(ReadRadii, AbsurdPqrRadiiAreRefusedNamingLineAndAtom) {
  const TempDir dir;
  const auto with_radius = [](const std::string& r) {  // atom O1's radius, 6 columns
    std::string text = pqr_with_z("0.5");
    text.replace(text.find("1.5200"), 6, r);
    return text;
  };
  const fs::path path = dir.write("r.pqr", with_radius("  1e30"));
  expect_error<FormatError>([&] { io::read_molecule(path); },
                            {path.string() + ":2:", "atom 'O1'", "radius 1e+30 A", "100 A"});
  expect_error<FormatError>([&] { io::read_molecule(dir.write("z.pqr", with_radius("0.0000"))); },
                            {":2:", "atom 'O1'", "not positive"});
  const Molecule ok = io::read_molecule(dir.write("ok.pqr", with_radius("99.000")));
  EXPECT_DOUBLE_EQ(ok.atoms[1].radius, 99.0);
}

/// Ethanol in MOL2 with its own charges; the oxygen's charge is Q.
constexpr const char* kMol2 =
    "@<TRIPOS>MOLECULE\n"
    "ethanol\n"
    " 3 2 0 0 0\n"
    "SMALL\n"
    "USER_CHARGES\n"
    "\n"
    "@<TRIPOS>ATOM\n"
    "      1 C1          0.0000    0.0000    0.0000 C.3     1  EOH1       -0.1000\n"
    "      2 C2          1.5200    0.0000    0.0000 C.3     1  EOH1        0.3000\n"
    "      3 O           2.0300    1.3400    0.0000 O.3     1  EOH1       Q\n"
    "@<TRIPOS>BOND\n"
    "     1     1     2    1\n"
    "     2     2     3    1\n";

TEST(ReadCharges, AbsurdMol2ChargesAreRefusedNamingLineAndAtom) {
  const TempDir dir;
  const auto with_charge = [](const std::string& q) {
    std::string text = kMol2;
    text.replace(text.find(" Q\n"), 3, " " + q + "\n");
    return text;
  };
  const fs::path path = dir.write("q.mol2", with_charge("-1e30"));
  expect_error<FormatError>([&] { io::read_molecule(path); },
                            {path.string() + ":10:", "atom 3 (O)", "charge -1e+30 e"});
  const Molecule ok = io::read_molecule(dir.write("ok.mol2", with_charge("-0.2000")));
  const auto oxygen = std::find_if(ok.atoms.begin(), ok.atoms.end(),
                                   [](const Atom& atom) { return atom.element == "O"; });
  ASSERT_NE(oxygen, ok.atoms.end());
  EXPECT_DOUBLE_EQ(oxygen->charge, -0.2);
}

/// Ethanol as two PDB HETATM records plus one, with standard columns.
constexpr const char* kPdb =
    "HETATM    1  C1  EOH A   1       0.000   0.000   0.000  1.00  0.00           C\n"
    "HETATM    2  C2  EOH A   1       1.520   0.000   0.000  1.00  0.00           C\n"
    "HETATM    3  O   EOH A   1       2.030   1.340   0.000  1.00  0.00           O\n"
    "END\n";

TEST(ReadCoordinates, PdbRecordsWithoutTheirCoordinatesAreRefused) {
  const TempDir dir;
  const Molecule whole = io::read_molecule(dir.write("ok.pdb", kPdb));
  ASSERT_EQ(whole.atoms.size(), 3u);
  EXPECT_DOUBLE_EQ(whole.atoms[2].position.y(), 1.34);

  std::string cut = kPdb;  // the third record cut inside its y column
  const std::size_t third = cut.find("HETATM    3");
  cut.erase(third + 40, cut.find('\n', third) - third - 40);
  const fs::path cut_path = dir.write("cut.pdb", cut);
  expect_error<FormatError>([&] { io::read_molecule(cut_path); },
                            {cut_path.string() + ":3:", "y coordinate", "columns 39-46"});

  std::string blank = kPdb;  // the third record with blank z columns
  blank.replace(third + 46, 8, std::string(8, ' '));
  const fs::path blank_path = dir.write("blank.pdb", blank);
  expect_error<FormatError>([&] { io::read_molecule(blank_path); },
                            {blank_path.string() + ":3:", "z coordinate", "missing"});
}

// ---- records and ligand selection ------------------------------------------------------------

std::string methanol_sdf(const std::string& name, double x) {
  char line[128];
  std::snprintf(line, sizeof line,
                "%10.4f    0.0000    0.0000 C   0  0  0  0  0  0  0  0  0  0  0  0\n", x);
  return name + "\n  test\n\n  2  1  0  0  0  0  0  0  0  0999 V2000\n" + line +
         "    1.4300    0.0000    0.0000 O   0  0  0  0  0  0  0  0  0  0  0  0\n"
         "  1  2  1  0\nM  END\n$$$$\n";
}

TEST(ReadRecords, MultiRecordSdfNeedsARecordAndReadsTheOneAsked) {
  const TempDir dir;
  const fs::path two =
      dir.write("two.sdf", methanol_sdf("first", 0.0) + methanol_sdf("second", -1.0));
  expect_error<InputError>([&] { io::read_molecule(two); },
                           {two.string(), "2 molecules", "with record N"});
  io::MoleculeReadOptions options;
  options.record = 2;
  const Molecule second = io::read_molecule(two, options);
  EXPECT_EQ(second.title, "second");
  EXPECT_DOUBLE_EQ(second.atoms[0].position.x(), -1.0);
  options.record = 1;
  EXPECT_EQ(io::read_molecule(two, options).title, "first");
  options.record = 3;
  expect_error<InputError>([&] { io::read_molecule(two, options); },
                           {two.string(), "record 3", "holds 2"});

  // A single-record file reads the same with or without record 1.
  const fs::path one = dir.write("one.sdf", methanol_sdf("only", 0.0));
  EXPECT_EQ(io::read_molecule(one).title, "only");
  options.record = 1;
  EXPECT_EQ(io::read_molecule(one, options).title, "only");
  options.record = 2;
  expect_error<InputError>([&] { io::read_molecule(one, options); }, {one.string(), "record 2"});
  expect_error<InputError>([&] { io::read_molecule(dir.write("one.pdb", kPdb), options); },
                           {"one.pdb", "record 2"});
}

TEST(ReadRecords, RdkitRefusalsAreSaidInAChemistsWords) {
  const TempDir dir;
  const std::string good = methanol_sdf("m", 0.0);
  const auto edited = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const std::pair<std::string, std::string> cases[] = {
      {edited("  1  2  1  0\n", "  1  7  1  0\n"),
       "a bond names an atom number beyond the molecule's atom count"},
      {edited("  1  2  1  0\n", "  2  2  1  0\n"), "a bond joins an atom to itself"},
      {edited(" O   0", " Xx  0"), "'Xx' is not an element symbol"},
      {edited("  2  1  0  0", "\n  2  1  0  0"),
       "line 4: the counts line (atom and bond counts) is missing or short"},
      // A triple bond to the oxygen.
      {edited("  1  2  1  0\n", "  1  2  3  0\n"), "atom 2 (O) has valence 3, more than O allows"},
  };
  int k = 0;
  for (const auto& [text, expected] : cases) {
    const fs::path path = dir.write("bad" + std::to_string(++k) + ".sdf", text);
    expect_error<FormatError>([&] { io::read_molecule(path); }, {path.string(), expected});
  }
}

TEST(ReadRecords, LigandSelectionOnSdfIsRefused) {
  const TempDir dir;
  const fs::path sdf = dir.write("l.sdf", methanol_sdf("l", 0.0));
  io::MoleculeReadOptions options;
  options.ligand = "ATP";
  expect_error<OptionError>([&] { io::read_molecule(sdf, options); },
                            {sdf.string(), "ligand ATP", "PDB or PQR"});
}

// ---- .hsi contents ---------------------------------------------------------------------------

/// A description of a tetrahedron with one critical point (no patch): the smallest valid .hsi.
/// Its vertex 0 sits at x = 777.25 and the point at x = 555.5, so that tests can find them.
std::vector<std::uint8_t> small_hsi(const std::string& image_property = "shape_index") {
  Eigen::MatrixX3d positions(4, 3);
  positions << 777.25, 0, 0, 10, 0, 0, 0, 10, 0, 0, 0, 10;
  Eigen::MatrixX3i faces(4, 3);
  faces << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  harmonic::SurfaceDescriptors d;
  d.surface = mesh::Surface::from_arrays(positions, faces, "t");
  d.surface.set_property("shape_index", Eigen::VectorXd::Zero(4));
  d.options.image_property = image_property;
  harmonic::CriticalPointDescriptor cp;
  cp.point.vertex = 0;
  cp.point.position = Eigen::Vector3d(555.5, 0, 0);
  cp.point.esp = cp.point.lp = std::numeric_limits<double>::quiet_NaN();  // no esp, lp
  cp.status = harmonic::PatchStatus::skipped;
  d.critical_points.push_back(cp);
  return harmonic::io::encode_hsi(d);
}

constexpr std::size_t kPayload = 32;  // the .hsi header's size

std::size_t offset_of(const std::vector<std::uint8_t>& bytes, double value) {
  std::uint8_t pattern[8];
  std::memcpy(pattern, &value, 8);  // little-endian hosts, as the writer's encoding
  const auto at = std::search(bytes.begin(), bytes.end(), pattern, pattern + 8);
  EXPECT_NE(at, bytes.end());
  return static_cast<std::size_t>(at - bytes.begin());
}

template <class T>
void put(std::vector<std::uint8_t>& bytes, std::size_t offset, T value) {
  std::memcpy(bytes.data() + offset, &value, sizeof value);
}

/// Writes the checksum of the (edited) payload into the header, as a crafted file would.
fs::path seal(const TempDir& dir, const std::string& name, std::vector<std::uint8_t> bytes) {
  put(bytes, 24, io::fnv1a64(bytes.data() + kPayload, bytes.size() - kPayload));
  return dir.write(name, std::string(bytes.begin(), bytes.end()));
}

TEST(ReadHsi, TheSmallDescriptionReadsBack) {
  const TempDir dir;
  const harmonic::SurfaceDescriptors d = harmonic::io::read_hsi(seal(dir, "ok.hsi", small_hsi()));
  EXPECT_EQ(d.surface.n_vertices(), 4u);
  ASSERT_EQ(d.critical_points.size(), 1u);
  EXPECT_DOUBLE_EQ(d.critical_points[0].point.position.x(), 555.5);
  EXPECT_TRUE(std::isnan(d.critical_points[0].point.esp));
}

TEST(ReadHsi, CraftedContentsAreRefusedNamingTheFile) {
  const TempDir dir;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    std::string name;
    std::function<void(std::vector<std::uint8_t>&)> edit;
    std::string problem;
  };
  const std::vector<Case> cases = {
      {"nan_rcp.hsi", [&](auto& b) { put(b, kPayload, nan); }, "r_cp nan"},
      {"zero_rcp.hsi", [&](auto& b) { put(b, kPayload, 0.0); }, "r_cp 0"},
      {"nan_patch.hsi", [&](auto& b) { put(b, kPayload + 17, nan); }, "patch radius"},
      {"huge_grid.hsi",
       [&](auto& b) {
         put(b, kPayload + 35, std::int32_t{1} << 30);
         put(b, kPayload + 39, std::int32_t{1} << 30);
       },
       "image grid of 1073741824 rings"},
      {"huge_vertices.hsi",
       [&](auto& b) { put(b, offset_of(b, 777.25) - 16, std::uint64_t{1} << 40); },
       "larger than the file"},
      {"huge_points.hsi",
       [&](auto& b) {
         // the point count sits right before the point: type (1), vertex (4), then x
         put(b, offset_of(b, 555.5) - 5 - 8, std::uint64_t{1} << 40);
       },
       "critical points cannot fit"},
      {"nan_point.hsi", [&](auto& b) { put(b, offset_of(b, 555.5), nan); },
       "critical point at vertex 0 has a non-finite coordinate"},
      {"far_point.hsi", [&](auto& b) { put(b, offset_of(b, 555.5), 1e30); },
       "critical point at vertex 0 has coordinate x = 1e+30"},
      {"nan_vertex.hsi", [&](auto& b) { put(b, offset_of(b, 777.25), -nan); },
       "stored vertex 0 has a non-finite coordinate"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    std::vector<std::uint8_t> bytes = small_hsi();
    c.edit(bytes);
    const fs::path path = seal(dir, c.name, bytes);
    expect_error<FormatError>([&] { harmonic::io::read_hsi(path); }, {path.string(), c.problem});
  }
  // Images of a property the stored surface does not carry.
  const fs::path absent = seal(dir, "absent_property.hsi", small_hsi("curvedness"));
  expect_error<FormatError>(
      [&] { harmonic::io::read_hsi(absent); },
      {absent.string(), "images are of property 'curvedness'", "surface does not carry"});
}

}  // namespace
}  // namespace surfcomp
