// surfcomp patch-map --methods: each method's map of a patch as an OBJ whose texture coordinates
// lie in the unit square, the harmonic one cpI.obj's own, and the figure of the maps side by
// side, on a nearly flat bump where the maps with linear precision are near-exact and those
// with uniform or 1/length springs are not.
// A run that cannot write every file leaves no folder behind.
#include "analytic_meshes.hpp"
#include "program_run.hpp"
#include "test_data.hpp"

#include "surfcomp/harmonic/map_distortion.hpp"

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

using test::ProgramRun;

/// A patch file as the OBJ reader of a mesh-processing program takes it.
struct ObjFile {
  Eigen::MatrixX3d v;
  Eigen::MatrixX2d vt;
  Eigen::MatrixX3i f;  ///< 0-based; the texture index of each corner is its vertex index
};

ObjFile read_obj(const fs::path& path) {
  std::ifstream in(path);
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector2d> vt;
  std::vector<Eigen::Vector3i> f;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string kind;
    words >> kind;
    if (kind == "v") {
      Eigen::Vector3d p;
      words >> p.x() >> p.y() >> p.z();
      v.push_back(p);
    } else if (kind == "vt") {
      Eigen::Vector2d t;
      words >> t.x() >> t.y();
      vt.push_back(t);
    } else if (kind == "f") {
      Eigen::Vector3i face;
      for (int k = 0; k < 3; ++k) {
        std::string corner;
        words >> corner;
        const std::size_t slash = corner.find('/');
        EXPECT_EQ(corner.substr(0, slash), corner.substr(slash + 1)) << path;
        face(k) = std::stoi(corner.substr(0, slash)) - 1;
      }
      f.push_back(face);
    }
  }
  ObjFile out;
  out.v.resize(static_cast<Eigen::Index>(v.size()), 3);
  out.vt.resize(static_cast<Eigen::Index>(vt.size()), 2);
  out.f.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) out.v.row(static_cast<Eigen::Index>(i)) = v[i];
  for (std::size_t i = 0; i < vt.size(); ++i) out.vt.row(static_cast<Eigen::Index>(i)) = vt[i];
  for (std::size_t i = 0; i < f.size(); ++i) out.f.row(static_cast<Eigen::Index>(i)) = f[i];
  return out;
}

/// A disk of radius 12 A (24 rings, test::disk) raised into a bump z = 0.4 exp(-r^2 / 25): its
/// top, vertex 0, is the one peak of curvature; within the default patch radius (5 A) the
/// surface leans at most 4 degrees, so the patch is nearly flat, as an OFF file.
void write_bump_off(const fs::path& path) {
  const mesh::Surface disk = test::disk(12.0, 24);
  const Eigen::MatrixX3d p = disk.positions();
  const Eigen::MatrixX3i f = disk.faces();
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << p.rows() << " " << f.rows() << " 0\n";
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    const double r2 = p(v, 0) * p(v, 0) + p(v, 1) * p(v, 1);
    out << p(v, 0) << " " << p(v, 1) << " " << 0.4 * std::exp(-r2 / 25.0) << "\n";
  }
  for (Eigen::Index t = 0; t < f.rows(); ++t)
    out << "3 " << f(t, 0) << " " << f(t, 1) << " " << f(t, 2) << "\n";
}

class CliPatchMap : public ::testing::Test {
 protected:
  static ProgramRun run(const std::string& arguments, const std::string& prefix = "") {
    return test::run_program(arguments, {"", prefix});
  }
  fs::path scratch(const std::string& name) const { return dir_ / name; }

 private:
  const test::TempDir dir_;
};

TEST_F(CliPatchMap, EveryMethodsMapIsAnObjAndAColumnOfTheFigure) {
  const fs::path off = scratch("bump.off"), maps = scratch("maps");
  write_bump_off(off);
  const ProgramRun r =
      run("patch-map " + off.string() + " --unit 1 --cp 0 --methods all -o " + maps.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(maps / "patch_maps.json");
  const nlohmann::json document = nlohmann::json::parse(in);
  const nlohmann::json& point = document["points"].at(0);
  ASSERT_EQ(point["vertex"], 0) << "cp 0 is not the bump's top";
  ASSERT_EQ(point["status"], "ok");
  const std::vector<std::string> listed = point["files"];
  const auto is_listed = [&](const std::string& name) {
    return std::find(listed.begin(), listed.end(), name) != listed.end();
  };

  const ObjFile harmonic_map = read_obj(maps / "cp0.obj");
  ASSERT_GT(harmonic_map.v.rows(), 100);
  std::map<std::string, double> angle_mean;  // from each OBJ, degrees
  const std::vector<std::string> names = {
      "harmonic", "tutte", "mean-value", "discrete-conformal", "discrete-authalic", "lscm", "arap"};
  ASSERT_EQ(point["methods"].size(), names.size());
  for (std::size_t m = 0; m < names.size(); ++m) {
    const nlohmann::json& method = point["methods"][m];
    SCOPED_TRACE(names[m]);
    ASSERT_EQ(method["method"], names[m]);
    const std::string file = "cp0_" + names[m] + ".obj";
    if (method.contains("failure")) {
      EXPECT_FALSE(method.contains("file"));
      EXPECT_FALSE(fs::exists(maps / file));
      continue;
    }
    ASSERT_EQ(method["file"], file);
    EXPECT_TRUE(is_listed(file));
    ASSERT_TRUE(fs::exists(maps / file));
    const ObjFile obj = read_obj(maps / file);
    ASSERT_EQ(obj.vt.rows(), obj.v.rows());
    EXPECT_EQ(obj.v, harmonic_map.v);
    EXPECT_EQ(obj.f, harmonic_map.f);
    EXPECT_GE(obj.vt.minCoeff(), 0.0);
    EXPECT_LE(obj.vt.maxCoeff(), 1.0);
    if (names[m] == "harmonic") {
      EXPECT_EQ(obj.vt, harmonic_map.vt);
    }
    if (names[m] == "lscm" || names[m] == "arap") {
      // Fitted into the unit square by one factor: the longer side spans it, both centred.
      const Eigen::RowVector2d lo = obj.vt.colwise().minCoeff(), hi = obj.vt.colwise().maxCoeff();
      EXPECT_NEAR((hi - lo).maxCoeff(), 1.0, 1e-12);
      EXPECT_NEAR((lo + hi).x() / 2.0, 0.5, 1e-12);
      EXPECT_NEAR((lo + hi).y() / 2.0, 0.5, 1e-12);
    }
    const harmonic::MapDistortion d =
        harmonic::map_distortion(obj.v, obj.f, (2.0 * obj.vt.array() - 1.0).matrix());
    // Scaling keeps angles: the file's map has the distortion the table reports.
    EXPECT_NEAR(d.angle_mean_degrees, double(method["angle_mean_degrees"]), 1e-9);
    angle_mean[names[m]] = d.angle_mean_degrees;
    std::cout << names[m] << ": angle mean " << d.angle_mean_degrees << " deg\n";
  }
  // On a nearly flat patch every map whose weights reproduce a flat map (linear precision:
  // mean-value, cotangent, authalic) or that keeps angles where it can (the free-border maps) is
  // near-exact, here on a border that is a regular polygon; the seed's 1/length springs and
  // Tutte's uniform ones are not. Measured: at most 0.02 degrees against 7.4 (harmonic) and 9.3
  // (tutte).
  for (const char* name :
       {"mean-value", "discrete-conformal", "discrete-authalic", "lscm", "arap"}) {
    ASSERT_TRUE(angle_mean.count(name)) << name << " failed";
    EXPECT_LT(angle_mean[name], 0.1) << name;
  }
  EXPECT_GT(angle_mean["harmonic"], 3.0);
  EXPECT_GT(angle_mean["tutte"], 3.0);

  // The figure: a column of 240 pixels per method, two rows of panels and 84 pixels of titles
  // and colour bar.
  EXPECT_TRUE(is_listed("cp0_methods.png"));
  const auto [width, height] = test::png_size(maps / "cp0_methods.png");
  EXPECT_EQ(width, names.size() * 240);
  EXPECT_EQ(height, 2u * 240 + 84);
}

TEST_F(CliPatchMap, ARunWithoutThePngModuleLeavesNoFolder) {
  // Without the PNG module no PNG can be drawn: the files written before the first one stay in
  // the staging folder, which goes, with the folder the run made.
  const fs::path off = scratch("bump.off"), maps = scratch("maps"), empty = scratch("no_modules");
  write_bump_off(off);
  fs::create_directory(empty);
  const ProgramRun r =
      run("patch-map " + off.string() + " --unit 1 --cp 0 --methods all -o " + maps.string(),
          "SURFCOMP_MODULE_DIR=" + empty.string() + " ");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("libsurfcomp_png.so"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(maps));
}

}  // namespace
}  // namespace surfcomp
