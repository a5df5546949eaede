// `surfcomp library build` of meshes and `surfcomp screen` of a mesh against them, as a user runs
// them: a moved half of one of CGAL's meshes finds its whole first, with the motion that puts the
// whole onto it; the table does not depend on --threads; molecules and meshes do not mix, a
// library of meshes exports no molecules, and the options of molecule screens and a query no
// mesh can be matched with are refused, each with one line.
#include "mesh_cut.hpp"
#include "program_run.hpp"
#include "test_data.hpp"

#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

/// The rows of a CSV table without quoted fields, each by its header's column names.
std::vector<std::map<std::string, std::string>> csv_rows(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) fields.push_back(cell);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    if (header.empty()) {
      header = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < header.size() && k < fields.size(); ++k) row[header[k]] = fields[k];
    rows.push_back(row);
  }
  return rows;
}

class ShapeScreen : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : {"cow", "knot", "elephant", "femur"}) {
      const std::string relative = std::string("cgal/meshes/") + name + ".off";
      const auto path = test::fetched_dataset(relative);
      if (!path) SURFCOMP_DATA_ABSENT(test::fetched_absent_message(relative));
      meshes_.push_back(*path);
    }
    folder_ = fs::temp_directory_path() / ("surfcomp_shape_screen_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    std::string inputs;
    for (const fs::path& path : meshes_) inputs += path.string() + " ";
    const test::ProgramRun build =
        test::run_program("library build " + inputs + "-o " + (folder_ / "meshes.sclib").string());
    ASSERT_EQ(build.status, 0) << build.err;
    // The query: the half of the cow below a plane, moved.
    const mesh::Surface cow = mesh::io::read_mesh(meshes_.front());
    mesh::Surface half = test::cut(cow, Eigen::Vector3d(0.2, 1.0, -0.4).normalized());
    motion_.linear() =
        Eigen::AngleAxisd(1.3, Eigen::Vector3d(0.6, 0.2, -0.7).normalized()).matrix();
    motion_.translation() = Eigen::Vector3d(0.4, -1.1, 2.5);
    Eigen::MatrixX3d moved = half.positions();
    for (Eigen::Index i = 0; i < moved.rows(); ++i)
      moved.row(i) = (motion_ * Eigen::Vector3d(moved.row(i).transpose())).transpose();
    mesh::io::write_mesh(mesh::Surface::from_arrays(moved, half.faces(), "half cow"),
                         folder_ / "scan.ply");
    const Eigen::MatrixX3d v = cow.positions();
    diagonal_ = (v.colwise().maxCoeff() - v.colwise().minCoeff()).norm();
    cow_points_ = v;
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }

  std::vector<fs::path> meshes_;
  fs::path folder_;
  Eigen::Isometry3d motion_ = Eigen::Isometry3d::Identity();
  double diagonal_ = 0.0;
  Eigen::MatrixX3d cow_points_;
};

TEST_F(ShapeScreen, AHalfFindsItsWholeFirstWithTheMotionThatPutsItThere) {
  const fs::path hits = folder_ / "hits.csv";
  const test::ProgramRun run =
      test::run_program("screen " + (folder_ / "scan.ply").string() + " " +
                        (folder_ / "meshes.sclib").string() + " -o " + hits.string() + " --top 0");
  ASSERT_EQ(run.status, 0) << run.err;
  const auto rows = csv_rows(test::file_bytes(hits));
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].at("name"), "cow");
  // A half lies wholly on its whole, but for the tolerance's edge: 0.9 and more when measured.
  EXPECT_GT(std::stod(rows[0].at("score")), 0.9);
  // ... and covers about half of it.
  EXPECT_NEAR(std::stod(rows[0].at("entry_coverage")), 0.5, 0.15);
  for (std::size_t r = 1; r < rows.size(); ++r) {
    EXPECT_LT(std::stod(rows[r].at("score")), std::stod(rows[0].at("score")) - 0.2)
        << rows[r].at("name");
    EXPECT_TRUE(rows[r].at("note").empty()) << rows[r].at("note");
  }
  // t moves the whole into the scan's frame: the motion the scan was made with.
  Eigen::Matrix4d t;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c)
      t(r, c) = std::stod(rows[0].at("t" + std::to_string(r) + std::to_string(c)));
  }
  double sum = 0.0;
  for (Eigen::Index i = 0; i < cow_points_.rows(); ++i) {
    const Eigen::Vector3d x = cow_points_.row(i).transpose();
    const Eigen::Vector3d found = t.topLeftCorner<3, 3>() * x + t.topRightCorner<3, 1>();
    sum += (found - motion_ * x).squaredNorm();
  }
  EXPECT_LT(std::sqrt(sum / static_cast<double>(cow_points_.rows())), 0.01 * diagonal_);
}

TEST_F(ShapeScreen, TheTableDoesNotDependOnTheThreads) {
  std::string tables[2];
  for (int threads : {1, 2}) {
    const fs::path hits = folder_ / ("hits" + std::to_string(threads) + ".csv");
    const test::ProgramRun run = test::run_program(
        "screen " + (folder_ / "scan.ply").string() + " " + (folder_ / "meshes.sclib").string() +
        " -o " + hits.string() + " --top 2 --threads " + std::to_string(threads));
    ASSERT_EQ(run.status, 0) << run.err;
    tables[threads - 1] = test::file_bytes(hits);
  }
  EXPECT_EQ(tables[0], tables[1]);
  EXPECT_EQ(csv_rows(tables[0]).size(), 2u);
}

TEST_F(ShapeScreen, AQueryWiderThanEveryMeshIsMatchedWithNone) {
  // The cow three times over: no mesh of the library can hold it as a part.
  mesh::Surface big = mesh::io::read_mesh(meshes_.front());
  mesh::scale_surface(big, 3.0);
  mesh::io::write_mesh(big, folder_ / "big.off");
  const fs::path hits = folder_ / "big.csv";
  const test::ProgramRun run =
      test::run_program("screen " + (folder_ / "big.off").string() + " " +
                        (folder_ / "meshes.sclib").string() + " -o " + hits.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto rows = csv_rows(test::file_bytes(hits));
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& row : rows) {
    EXPECT_EQ(std::stod(row.at("score")), 0.0);
    EXPECT_NE(row.at("note").find("not matched: the query's extent"), std::string::npos)
        << row.at("note");
  }
  EXPECT_NE(run.out.find("4 not matched"), std::string::npos) << run.out;
}

/// The one line a refused run writes, and that it wrote no table.
void expect_refused(const std::string& arguments, const std::string& wanted,
                    const fs::path& table) {
  const test::ProgramRun run = test::run_program(arguments);
  EXPECT_NE(run.status, 0) << arguments;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_NE(run.err.find(wanted), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(table)) << arguments;
}

TEST_F(ShapeScreen, MoleculesAndMeshesDoNotMixAndMoleculeOptionsAreRefused) {
  SURFCOMP_SHARED_OR_SKIP(ligand, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  const std::string library = (folder_ / "meshes.sclib").string();
  const fs::path table = folder_ / "refused.csv";
  const std::string scan = (folder_ / "scan.ply").string();
  expect_refused("screen " + ligand.string() + " " + library + " -o " + table.string(),
                 "a library of meshes", table);
  expect_refused("screen " + scan + " " + library + " -o " + table.string() + " --refine 3",
                 "--refine applies to molecule and site queries", table);
  expect_refused("screen " + scan + " " + scan + " " + library + " -o " + table.string(),
                 "a library of meshes: its query is one mesh", table);
  // A query that no entry can be matched with (one triangle has no curvature to fit) stops the
  // screen with the reason, rather than a table of failed pairs.
  {
    std::ofstream triangle(folder_ / "triangle.off");
    triangle << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  }
  expect_refused("screen " + (folder_ / "triangle.off").string() + " " + library + " -o " +
                     table.string() + " --unit 0.1",
                 "fewer than 3 other vertices", table);
  const fs::path exported = folder_ / "meshes.sdf";
  expect_refused("library export " + library + " -o " + exported.string(),
                 "a library of meshes has no molecules to export", exported);
  const test::ProgramRun info = test::run_program("library info " + library);
  EXPECT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find("4 entries, 4 meshes"), std::string::npos) << info.out;
  const fs::path mixed = folder_ / "mixed.sclib";
  expect_refused(
      "library build " + meshes_.front().string() + " " + ligand.string() + " -o " + mixed.string(),
      "molecules or meshes, not both", mixed);
  // A molecule library refuses a mesh query.
  const fs::path molecules = folder_ / "molecules.sclib";
  ASSERT_EQ(
      test::run_program("library build " + ligand.string() + " -o " + molecules.string()).status,
      0);
  // A mesh with ESP and LP (a molecule's surface) is a query of a molecule library, as before.
  const fs::path surface = folder_ / "ligand.ply";
  ASSERT_EQ(test::run_program("surf-build " + ligand.string() + " -o " + surface.string()).status,
            0);
  const test::ProgramRun molecular = test::run_program(
      "screen " + surface.string() + " " + molecules.string() + " -o " + table.string());
  EXPECT_EQ(molecular.status, 0) << molecular.err;
  EXPECT_TRUE(fs::exists(table));
}

}  // namespace
}  // namespace surfcomp
