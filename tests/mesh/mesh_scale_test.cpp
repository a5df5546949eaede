// A general mesh is described in a length unit of its own (mesh/length_unit.hpp), so that the
// same shape gives the same critical points, patches and images at any scale, whichever front
// end describes it; and its curvature's cost stays bounded whatever the radius.
#include "analytic_meshes.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/mesh/curvature.hpp"
#include "surfcomp/mesh/length_unit.hpp"
#include "surfcomp/molsurf/load_surface.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace surfcomp {
namespace {

/// A closed blob with bumps and dents (peaks and valleys), `size` across about 2: the unit
/// icosphere with its radius modulated by smooth waves.
mesh::Surface blob(double size, int frequency = 24) {
  test::MeshArrays m = test::unit_icosphere_arrays(frequency);
  for (Eigen::Index i = 0; i < m.positions.rows(); ++i) {
    const Eigen::Vector3d p = m.positions.row(i);
    // No symmetry: two vertices never tie on curvature.
    const double r = 1.0 + 0.18 * std::sin(3.0 * p.x() + 0.4) * std::cos(2.0 * p.y() - 0.3) +
                     0.12 * std::cos(4.0 * p.z() + 1.3 * p.x() + 0.2 * p.y());
    m.positions.row(i) = size * r * p.transpose();
  }
  return mesh::Surface::from_arrays(m.positions, m.faces, "blob");
}

std::vector<int> vertices_of(const std::vector<mesh::CriticalPoint>& points) {
  std::vector<int> out;
  for (const auto& p : points) out.push_back(p.vertex);
  return out;
}

TEST(MeshScale, TheAutomaticUnitIsATwelfthOfTheRmsRadius) {
  // Triangle centroids of a fine sphere lie at r cos(small angle): the RMS radius is r to 0.1 %.
  const mesh::Surface sphere = test::icosphere(7.0, 30);
  EXPECT_NEAR(mesh::rms_radius(sphere), 7.0, 7e-3);
  const mesh::LengthUnit unit =
      mesh::general_mesh_unit({&sphere}, mesh::LengthScale::automatic, 0.0, "sphere");
  EXPECT_EQ(unit.from, "auto");
  EXPECT_NEAR(unit.value, 7.0 / 12.0, 1e-3);
  EXPECT_EQ(mesh::general_mesh_unit({&sphere}, mesh::LengthScale::none, 0.0, "s").value, 1.0);
  const mesh::LengthUnit given =
      mesh::general_mesh_unit({&sphere}, mesh::LengthScale::automatic, 0.25, "s");
  EXPECT_EQ(given.value, 0.25);
  EXPECT_EQ(given.from, "given");
}

TEST(MeshScale, TheSameMeshGivesTheSameCriticalPointsAtAnyScale) {
  std::vector<int> reference;
  double reference_cc1 = 0.0;
  for (const double size : {0.01, 1.0, 100.0}) {
    SCOPED_TRACE("size " + std::to_string(size));
    const molsurf::LoadedSurface loaded = molsurf::load_mesh_surface(blob(size));
    EXPECT_TRUE(loaded.general_mesh);
    EXPECT_NEAR(loaded.unit.value / size, mesh::rms_radius(blob(1.0)) / 12.0, 1e-9);
    const std::vector<mesh::CriticalPoint> points =
        mesh::detect_critical_points_in_unit(loaded.surface, loaded.unit.value);
    ASSERT_GE(points.size(), 4u);
    const std::vector<int> vertices = vertices_of(points);
    if (reference.empty()) {
      reference = vertices;
      reference_cc1 = points.front().cc1 * size;
    }
    EXPECT_EQ(vertices, reference);
    // Positions in the mesh's coordinates, curvature per its length.
    const Eigen::Vector3d expected = loaded.surface.positions().row(points.front().vertex);
    EXPECT_TRUE(points.front().position.isApprox(expected, 1e-12));
    EXPECT_NEAR(points.front().cc1 * size, reference_cc1, 1e-9 * std::abs(reference_cc1));
  }
}

TEST(MeshScale, DescribeAndDetectFindTheSamePointsAndImagesAtAnyScale) {
  const harmonic::SurfaceDescriptors* first = nullptr;
  std::vector<harmonic::SurfaceDescriptors> described;
  for (const double size : {0.01, 100.0}) {
    SCOPED_TRACE("size " + std::to_string(size));
    matching::MatchInput input;
    input.surface = blob(size);
    const matching::PreparedInput prepared = matching::prepare_input(input, {});
    EXPECT_EQ(prepared.unit.from, "auto");
    EXPECT_NEAR(prepared.descriptors.length_unit, prepared.unit.value, 0.0);
    // The critical points are cp-detect's (load_surface, then detect in the unit).
    const molsurf::LoadedSurface loaded = molsurf::load_mesh_surface(blob(size));
    const auto detected = mesh::detect_critical_points_in_unit(loaded.surface, loaded.unit.value);
    std::vector<int> described_vertices;
    for (const auto& cp : prepared.descriptors.critical_points)
      described_vertices.push_back(cp.point.vertex);
    EXPECT_EQ(described_vertices, vertices_of(detected));
    // The description is in the mesh's coordinates: its surface is the input's.
    EXPECT_TRUE(prepared.descriptors.surface.positions().isApprox(blob(size).positions(), 1e-12));
    described.push_back(prepared.descriptors);
  }
  first = &described.front();
  const harmonic::SurfaceDescriptors& second = described.back();
  ASSERT_EQ(first->critical_points.size(), second.critical_points.size());
  int imaged = 0;
  for (std::size_t k = 0; k < first->critical_points.size(); ++k) {
    const auto& a = first->critical_points[k];
    const auto& b = second.critical_points[k];
    ASSERT_EQ(a.status, b.status);
    if (a.status != harmonic::PatchStatus::ok) continue;
    ++imaged;
    EXPECT_EQ(a.patch.surface_vertex, b.patch.surface_vertex);
    EXPECT_LT((a.image.values - b.image.values).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_NEAR(a.patch.distance.maxCoeff() * 1e4, b.patch.distance.maxCoeff(), 1e-6);
  }
  EXPECT_GT(imaged, 2);
}

TEST(MeshScale, AStoredDescriptionKeepsItsUnitAndMatchesItsMesh) {
  matching::MatchInput input;
  input.surface = blob(0.05);
  const matching::PreparedInput prepared = matching::prepare_input(input, {});
  const double unit = prepared.unit.value;
  const harmonic::SurfaceDescriptors read =
      harmonic::io::decode_hsi(harmonic::io::encode_hsi(prepared.descriptors), "blob.hsi");
  EXPECT_EQ(read.length_unit, unit);
  EXPECT_EQ(harmonic::io::encode_hsi(read), harmonic::io::encode_hsi(prepared.descriptors));

  // Matched against the mesh it came from, the stored unit is the pair's, the mesh is described
  // as the stored side was (the same critical points), and the best pose puts the mesh back
  // onto itself, in its own coordinates (about 0.06 in radius).
  matching::MatchInput stored;
  stored.descriptors = read;
  const matching::InputMatch m = matching::match_inputs(stored, input, {});
  EXPECT_EQ(m.unit, unit);
  EXPECT_EQ(m.unit_from, "stored");
  ASSERT_EQ(m.probe.descriptors.critical_points.size(), read.critical_points.size());
  for (std::size_t k = 0; k < read.critical_points.size(); ++k) {
    EXPECT_EQ(m.probe.descriptors.critical_points[k].point.vertex,
              read.critical_points[k].point.vertex);
  }
  ASSERT_FALSE(m.result.alignments.empty());
  const matching::Alignment& best = m.result.alignments.front();
  EXPECT_GT(best.overlay.score, 0.999);
  const Eigen::MatrixX3d v = blob(0.05).positions();
  double worst = 0.0;
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    const Eigen::Vector3d p = v.row(i).transpose();
    const Eigen::Vector3d moved =
        best.transform.topLeftCorner<3, 3>() * p + best.transform.topRightCorner<3, 1>();
    worst = std::max(worst, (moved - p).norm());
  }
  EXPECT_LT(worst, 1e-6 * 0.05);

  // Matched with a molecule, it is refused: its radii count in its unit, not in A.
  matching::MatchInput sphere_in_angstrom;
  sphere_in_angstrom.surface = test::icosphere(3.0, 8);
  Eigen::VectorXd zeros =
      Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sphere_in_angstrom.surface->n_vertices()));
  sphere_in_angstrom.surface->set_property(mesh::property::esp, zeros);
  sphere_in_angstrom.surface->set_property(mesh::property::lp, zeros);
  EXPECT_THROW(matching::match_inputs(stored, sphere_in_angstrom, {}), InputError);

  // A description in A is still written as version 2.
  matching::MatchInput sphere;
  sphere.surface = test::icosphere(3.0, 8);
  matching::MatchInputOptions in_angstrom;
  in_angstrom.input.scale = mesh::LengthScale::none;
  const std::vector<std::uint8_t> bytes =
      harmonic::io::encode_hsi(matching::prepare_input(sphere, in_angstrom).descriptors);
  EXPECT_EQ(bytes[8], 2);
}

TEST(MeshScale, AFineSphereInTinyCoordinatesGetsItsCurvatureAtABoundedCost) {
  // 0.01 across and 10,242 vertices, taken as A (--scale none): the 3 A curvature radius covers
  // the whole sphere, and each fit stops growing at 4 x CurvatureOptions::max_points = 4096
  // vertices (40 % of the sphere), sampled down to 1024.
  const double radius = 0.005;
  molsurf::SurfaceInputOptions options;
  options.scale = mesh::LengthScale::none;
  const molsurf::LoadedSurface loaded =
      molsurf::load_mesh_surface(test::icosphere(radius, 32), options);
  EXPECT_EQ(loaded.unit.value, 1.0);
  const Eigen::VectorXd cc1 = loaded.surface.property(mesh::property::cc1);
  const Eigen::VectorXd cc2 = loaded.surface.property(mesh::property::cc2);
  // A height quadric over 40 % of a sphere is biased, not lost: every vertex is convex with
  // the sphere's curvature to 3 %.
  EXPECT_NEAR(cc1.minCoeff(), -1.0 / radius, 0.03 / radius);
  EXPECT_NEAR(cc1.maxCoeff(), -1.0 / radius, 0.03 / radius);
  EXPECT_NEAR(cc2.maxCoeff(), -1.0 / radius, 0.03 / radius);
  // Where the 3 A neighbourhood holds fewer than 4096 vertices nothing is sampled: a sphere of
  // 3 A gets its curvature to 0.1 %.
  const molsurf::LoadedSurface coarse =
      molsurf::load_mesh_surface(test::icosphere(3.0, 16), options);
  EXPECT_NEAR(coarse.surface.property(mesh::property::cc1).maxCoeff(), -1.0 / 3.0, 1e-3 / 3.0);

  mesh::CurvatureOptions bad;
  bad.max_points = 5;
  EXPECT_THROW(mesh::principal_curvatures(test::icosphere(1.0, 4), bad), OptionError);
}

TEST(MeshScale, AUnitIsRefusedForAnInputInAngstrom) {
  mesh::Surface with_chemistry = test::icosphere(3.0, 8);
  const Eigen::VectorXd zeros =
      Eigen::VectorXd::Zero(static_cast<Eigen::Index>(with_chemistry.n_vertices()));
  with_chemistry.set_property(mesh::property::esp, zeros);
  with_chemistry.set_property(mesh::property::lp, zeros);
  molsurf::SurfaceInputOptions options;
  options.unit = 0.5;
  EXPECT_THROW(molsurf::load_mesh_surface(with_chemistry, options), OptionError);
  // Without the unit it is in A: its curvature is the sphere's in A.
  const molsurf::LoadedSurface loaded = molsurf::load_mesh_surface(with_chemistry);
  EXPECT_FALSE(loaded.general_mesh);
  EXPECT_NEAR(loaded.surface.property(mesh::property::cc1).mean(), -1.0 / 3.0, 1e-3);
}

}  // namespace
}  // namespace surfcomp
