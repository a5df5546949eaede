// The patch files of surfcomp patch-map as a mesh-processing program reads them: OpenMesh's OBJ
// reader (the reader MeshLab-like tools share the format with) takes the patch with one texture
// coordinate per vertex equal to the map, and our PLY reader takes u, v and the properties back.
#include "analytic_meshes.hpp"
#include "program_run.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "surfcomp/report/patch_files.hpp"
#include "test_data.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <gtest/gtest.h>

#include <filesystem>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;
using ObjMesh = OpenMesh::TriMesh_ArrayKernelT<>;

harmonic::CriticalPointDescriptor a_described_point(mesh::Surface& surface) {
  surface = test::ellipsoid(6.0, 4.0, 3.0, 24);
  molsurf::assign_surface_properties(surface, nullptr);
  harmonic::SurfaceDescriptors d = harmonic::describe_surface(surface);
  for (auto& cp : d.critical_points)
    if (cp.status == harmonic::PatchStatus::ok) return cp;
  ADD_FAILURE() << "no critical point with a patch";
  return {};
}

TEST(PatchFiles, OpenMeshReadsTheObjWithTheMapAsTextureCoordinates) {
  mesh::Surface surface;
  const harmonic::CriticalPointDescriptor cp = a_described_point(surface);
  const test::TempDir dir;
  const fs::path obj = dir / "patch.obj";
  report::write_patch_obj(cp.patch, cp.map, obj);

  ObjMesh read;
  read.request_vertex_texcoords2D();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexTexCoord;
  ASSERT_TRUE(OpenMesh::IO::read_mesh(read, obj.string(), options));
  ASSERT_TRUE(options.check(OpenMesh::IO::Options::VertexTexCoord));
  ASSERT_EQ(static_cast<Eigen::Index>(read.n_vertices()), cp.patch.positions.rows());
  ASSERT_EQ(static_cast<Eigen::Index>(read.n_faces()), cp.patch.faces.rows());
  double worst_position = 0.0, worst_uv = 0.0;
  for (const auto v : read.vertices()) {
    const auto i = static_cast<Eigen::Index>(v.idx());
    const auto p = read.point(v);
    const auto t = read.texcoord2D(v);
    for (int k = 0; k < 3; ++k)
      worst_position = std::max(worst_position, std::abs(p[k] - cp.patch.positions(i, k)));
    // OpenMesh keeps floats: the map within float precision.
    worst_uv = std::max(worst_uv, std::abs(2.0 * t[0] - 1.0 - cp.map.uv(i, 0)));
    worst_uv = std::max(worst_uv, std::abs(2.0 * t[1] - 1.0 - cp.map.uv(i, 1)));
  }
  EXPECT_LT(worst_position, 1e-5);
  EXPECT_LT(worst_uv, 1e-6);
  for (const auto f : read.faces()) {
    int k = 0;
    for (const auto v : read.fv_range(f)) EXPECT_EQ(v.idx(), cp.patch.faces(f.idx(), k++));
  }
}

TEST(PatchFiles, ThePlyCarriesTheMapAndTheSurfaceProperties) {
  mesh::Surface surface;
  const harmonic::CriticalPointDescriptor cp = a_described_point(surface);
  const test::TempDir dir;
  const fs::path ply = dir / "patch.ply";
  report::write_patch_ply(surface, cp.patch, cp.map, ply);
  const mesh::Surface read = mesh::io::read_ply(ply);
  ASSERT_EQ(static_cast<Eigen::Index>(read.n_vertices()), cp.patch.positions.rows());
  EXPECT_EQ(read.property("u"), cp.map.uv.col(0));
  EXPECT_EQ(read.property("v"), cp.map.uv.col(1));
  EXPECT_EQ(read.property("distance"), cp.patch.distance);
  const Eigen::VectorXd shape = surface.property(mesh::property::shape_index);
  const Eigen::VectorXd patch_shape = read.property(mesh::property::shape_index);
  for (std::size_t v = 0; v < cp.patch.surface_vertex.size(); ++v)
    EXPECT_EQ(patch_shape(static_cast<Eigen::Index>(v)), shape(cp.patch.surface_vertex[v]));
}

TEST(PatchFiles, BadImagesAndRangesAreRefused) {
  harmonic::ShapeImage image;
  image.rings = 2;
  image.sectors = 3;
  image.values = Eigen::VectorXd::Zero(5);  // not 6
  image.valid.assign(5, 1);
  const test::TempDir dir;
  EXPECT_THROW(report::write_image_grid_png(image, dir / "g.png"), InputError);
  image.values = Eigen::VectorXd::Zero(6);
  image.valid.assign(6, 1);
  EXPECT_THROW(report::write_image_grid_png(image, dir / "g.png", 1.0, 1.0), OptionError);
  report::ImagePngOptions options;
  options.diameter = 10;
  EXPECT_THROW(report::write_image_png(image, dir / "p.png", options), OptionError);
  EXPECT_FALSE(fs::exists(dir / "g.png"));
  EXPECT_FALSE(fs::exists(dir / "p.png"));
  // The diverging scale's ends and middle.
  EXPECT_EQ(report::diverging_colour(0.0, -1.0, 1.0), (std::array<std::uint8_t, 3>{255, 255, 255}));
  EXPECT_EQ(report::diverging_colour(5.0, -1.0, 1.0), (std::array<std::uint8_t, 3>{178, 24, 43}));
  EXPECT_EQ(report::diverging_colour(-1.0, -1.0, 1.0), (std::array<std::uint8_t, 3>{33, 102, 172}));
}

TEST(PatchFiles, AFreeBorderMapIsFittedIntoTheDisksSquareKeepingItsShape) {
  Eigen::MatrixX2d uv(3, 2);
  uv << 2, 1, 6, 1, 2, 3;  // a box 4 by 2 centred at (4, 2)
  const Eigen::MatrixX2d fitted = report::fit_to_disk_square(uv);
  Eigen::MatrixX2d expected(3, 2);
  expected << -1, -0.5, 1, -0.5, -1, 0.5;
  EXPECT_LT((fitted - expected).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_THROW(report::fit_to_disk_square(Eigen::MatrixX2d(0, 2)), InputError);
  EXPECT_THROW(report::fit_to_disk_square(Eigen::MatrixX2d::Ones(3, 2)), InputError);
  uv(1, 0) = std::nan("");
  EXPECT_THROW(report::fit_to_disk_square(uv), InputError);
}

TEST(PatchFiles, TheMethodsFigureHasAColumnPerMapAndRefusesBadMaps) {
  mesh::Surface surface;
  const harmonic::CriticalPointDescriptor cp = a_described_point(surface);
  const test::TempDir dir;
  const fs::path png = dir / "methods.png";
  report::MethodsPngOptions options;
  options.panel = 96;
  report::write_methods_png(cp.patch, {{"harmonic", cp.map.uv}, {"arap", {}}}, png, options);
  const auto [width, height] = test::png_size(png);
  EXPECT_EQ(width, 2u * 96);        // two columns, the failed one among them
  EXPECT_EQ(height, 2u * 96 + 84);  // two rows, the titles and the colour bar

  const fs::path refused = dir / "refused.png";
  const Eigen::MatrixX2d short_map = cp.map.uv.topRows(3);
  EXPECT_THROW(report::write_methods_png(cp.patch, {{"tutte", short_map}}, refused), InputError);
  EXPECT_THROW(report::write_methods_png(cp.patch, {}, refused), InputError);
  options.panel = 10;
  EXPECT_THROW(report::write_methods_png(cp.patch, {{"harmonic", cp.map.uv}}, refused, options),
               OptionError);
  options.panel = 96;
  options.angle_top_degrees = 0.0;
  EXPECT_THROW(report::write_methods_png(cp.patch, {{"harmonic", cp.map.uv}}, refused, options),
               OptionError);
  EXPECT_FALSE(fs::exists(refused));
}

}  // namespace
}  // namespace surfcomp
