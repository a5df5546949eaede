// General meshes (no ESP, no LP, any length unit): shape-only matching of a cut, moved copy
// onto its original, the length unit taken from the meshes, and patches that reach a border.
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/mesh/repair.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/mesh/topology.hpp"
#include "surfcomp/molsurf/load_surface.hpp"

#include "surfcomp/core/error.hpp"

#include "mesh_cut.hpp"
#include "test_data.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

namespace surfcomp {
namespace {

double diagonal(const mesh::Surface& s) {
  const Eigen::MatrixX3d v = s.positions();
  return (v.colwise().maxCoeff() - v.colwise().minCoeff()).norm();
}

/// RMSE over `truth` (the copy's vertices in the original's frame) of transform(motion(x)) - x.
double motion_error(const Eigen::MatrixX3d& truth, const Eigen::Isometry3d& motion,
                    const Eigen::Matrix4d& transform) {
  double sum = 0.0;
  for (Eigen::Index i = 0; i < truth.rows(); ++i) {
    const Eigen::Vector3d x = truth.row(i).transpose();
    const Eigen::Vector3d back =
        transform.topLeftCorner<3, 3>() * (motion * x) + transform.topRightCorner<3, 1>();
    sum += (back - x).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(truth.rows()));
}

TEST(MeshMatch, PatchesThatReachABorderAreNotImaged) {
  SURFCOMP_FETCHED_OR_SKIP(path, "cgal/meshes/elephant.off");
  const mesh::Surface full = mesh::io::read_mesh(path);
  mesh::Surface copy = test::cut(full, Eigen::Vector3d(1, 0.3, 0.2).normalized());
  mesh::scale_surface(copy, 1.0 / 0.03);  // the elephant is 1 unit long; patches of 5 A
  matching::MatchInputOptions options;
  matching::MatchInput input;
  input.surface = copy;
  const matching::PreparedInput prepared = matching::prepare_input(input, options);
  const std::vector<bool> border = mesh::border_vertices(prepared.descriptors.surface);
  int at_border = 0, imaged = 0;
  for (const auto& cp : prepared.descriptors.critical_points) {
    const auto& patch = cp.patch;
    const bool touches = std::any_of(patch.surface_vertex.begin(), patch.surface_vertex.end(),
                                     [&](int v) { return border[static_cast<std::size_t>(v)]; });
    if (cp.status == harmonic::PatchStatus::ok) {
      ++imaged;
      EXPECT_FALSE(touches) << "critical point at vertex " << cp.point.vertex;
      EXPECT_EQ(std::count(patch.outer_boundary.begin(), patch.outer_boundary.end(), patch.center),
                0);
    }
    if (cp.status == harmonic::PatchStatus::at_border) ++at_border;
  }
  EXPECT_GT(at_border, 0);
  EXPECT_GT(imaged, 10);
}

TEST(MeshMatch, ACutMovedCopyIsRecoveredWhateverTheLengthUnit) {
  SURFCOMP_FETCHED_OR_SKIP(path, "cgal/meshes/elephant.off");
  const mesh::Surface original = mesh::io::read_mesh(path);
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = Eigen::AngleAxisd(2.0, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).matrix();
  motion.translation() = Eigen::Vector3d(0.4, -0.2, 0.3);
  std::vector<matching::InputMatch> matches;
  for (const double scale : {1.0, 1000.0}) {
    mesh::Surface full = original;
    mesh::scale_surface(full, scale);
    mesh::Surface copy = test::cut(full, Eigen::Vector3d(1, 0.3, 0.2).normalized());
    const Eigen::MatrixX3d truth = copy.positions();
    mesh::transform_surface(copy, motion.linear(), motion.translation() * scale);
    matching::MatchInput reference, probe;
    reference.surface = full;
    probe.surface = copy;
    matches.push_back(matching::match_inputs(reference, probe));
    const matching::InputMatch& m = matches.back();
    EXPECT_TRUE(m.shape_only);
    EXPECT_EQ(m.unit_from, "auto");
    ASSERT_FALSE(m.result.alignments.empty());
    Eigen::Isometry3d scaled_motion = motion;
    scaled_motion.translation() *= scale;
    EXPECT_LT(motion_error(truth, scaled_motion, m.result.alignments.front().transform),
              0.02 * diagonal(full))
        << "scale " << scale;
  }
  // The same match at both scales: the unit follows the mesh, the answer is only rescaled.
  EXPECT_NEAR(matches[1].unit / matches[0].unit, 1000.0, 1e-9);
  const Eigen::Matrix4d& a = matches[0].result.alignments.front().transform;
  const Eigen::Matrix4d& b = matches[1].result.alignments.front().transform;
  EXPECT_LT((a.topLeftCorner<3, 3>() - b.topLeftCorner<3, 3>()).norm(), 1e-3);
  EXPECT_LT((a.topRightCorner<3, 1>() * 1000.0 - b.topRightCorner<3, 1>()).norm(),
            1e-3 * 1000.0 * diagonal(original));
}

TEST(MeshMatch, ACutCopyLiesWhollyOnItsOriginalAndIcpMakesItsPoseExact) {
  SURFCOMP_FETCHED_OR_SKIP(path, "cgal/meshes/elephant.off");
  SURFCOMP_FETCHED_OR_SKIP(other_path, "cgal/meshes/cow.off");
  const mesh::Surface full = mesh::io::read_mesh(path);
  mesh::Surface copy = test::cut(full, Eigen::Vector3d(1, 0.3, 0.2).normalized());
  const double area_fraction = mesh::measure_surface(copy).area / mesh::measure_surface(full).area;
  const Eigen::MatrixX3d truth = copy.positions();
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = Eigen::AngleAxisd(2.0, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).matrix();
  motion.translation() = Eigen::Vector3d(0.4, -0.2, 0.3);
  mesh::transform_surface(copy, motion.linear(), motion.translation());
  matching::MatchInput reference, probe;
  reference.surface = full;
  probe.surface = copy;
  matching::MatchInputOptions options;
  options.match.icp_top = 1;
  const matching::InputMatch m = matching::match_inputs(reference, probe, options);
  ASSERT_FALSE(m.result.alignments.empty());
  const matching::Alignment& top = m.result.alignments.front();
  EXPECT_EQ(top.repeat_of, 0);
  EXPECT_TRUE(top.icp);
  // The cut is a piece of the original: all of it lies on it, and it covers its share and the
  // band within the distance (one unit) beyond its cut edge.
  EXPECT_GT(top.coverage.score, 0.99);
  EXPECT_EQ(top.coverage.score, top.coverage.probe);
  EXPECT_GT(top.coverage.reference, area_fraction - 0.01);
  EXPECT_LT(top.coverage.reference, area_fraction + 0.06);
  // ICP on the exact geometry leaves the pose at the precision of the meshes' coordinates.
  EXPECT_LT(motion_error(truth, motion, top.transform), 1e-4 * diagonal(full));
  // Repeats point at a better distinct pose.
  std::size_t distinct = 0;
  for (const matching::Alignment& a : m.result.alignments) {
    if (a.repeat_of == 0) {
      ++distinct;
      continue;
    }
    ASSERT_LT(a.repeat_of, a.rank);
    EXPECT_EQ(m.result.alignments[static_cast<std::size_t>(a.repeat_of - 1)].repeat_of, 0);
  }
  EXPECT_LT(distinct, m.result.alignments.size());

  // The same cut on another shape of the same size lies on it far less.
  mesh::Surface other = mesh::io::read_mesh(other_path);
  mesh::scale_surface(other, diagonal(full) / diagonal(other));
  reference.surface = other;
  const matching::InputMatch wrong = matching::match_inputs(reference, probe, options);
  ASSERT_FALSE(wrong.result.alignments.empty());
  EXPECT_LT(wrong.result.alignments.front().coverage.score, 0.8)
      << wrong.result.alignments.front().coverage.score;
}

TEST(MeshMatch, CurvatureFittedAtThePairsUnitIsKeptAndAtAnotherFittedAgain) {
  SURFCOMP_FETCHED_OR_SKIP(path, "cgal/meshes/elephant.off");
  const mesh::Surface full = mesh::io::read_mesh(path);
  mesh::Surface copy = test::cut(full, Eigen::Vector3d(1, 0.3, 0.2).normalized());
  mesh::transform_surface(copy, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.2, 0.1, 0.0));
  // The whole with the curvature a mesh library stores: fitted at its own (automatic) unit.
  const molsurf::LoadedSurface fitted = molsurf::load_mesh_surface(full);
  matching::MatchInput plain, stored, probe;
  plain.surface = full;
  stored.surface = fitted.surface;
  stored.curvature_unit = fitted.unit.value;
  probe.surface = copy;
  const auto top = [](const matching::InputMatch& m) {
    EXPECT_FALSE(m.result.alignments.empty());
    return m.result.alignments.empty() ? Eigen::Matrix4d::Identity().eval()
                                       : m.result.alignments.front().transform;
  };
  const auto peaks = [](const matching::InputMatch& m) {
    std::vector<int> at;
    for (const auto& point : m.reference.descriptors.critical_points)
      at.push_back(point.point.vertex);
    return at;
  };
  // The pair's unit is the whole's (the larger): the stored curvature is the one a fit gives
  // (but for rounding), and so is the match.
  const matching::InputMatch a = matching::match_inputs(plain, probe);
  const matching::InputMatch b = matching::match_inputs(stored, probe);
  ASSERT_EQ(a.unit, fitted.unit.value);
  EXPECT_EQ(peaks(a), peaks(b));
  EXPECT_LT((top(a) - top(b)).norm(), 1e-9);
  // A curvature that is not the fit's shows which one the match used: kept at its unit...
  matching::MatchInput altered = stored;
  const Eigen::VectorXd height = full.positions().col(1);
  for (const char* name : {mesh::property::cc1, mesh::property::cc2})
    altered.surface->set_property(name, height);
  EXPECT_NE(peaks(matching::match_inputs(altered, probe)), peaks(a));
  // ... and fitted again in another unit: the plain match in that unit.
  matching::MatchInputOptions other;
  other.input.unit = 2.0 * fitted.unit.value;
  const matching::InputMatch c = matching::match_inputs(plain, probe, other);
  const matching::InputMatch d = matching::match_inputs(altered, probe, other);
  EXPECT_EQ(peaks(c), peaks(d));
  EXPECT_LT((top(c) - top(d)).norm(), 1e-9);
}

TEST(MeshRepair, ATriangleSoupBecomesTheMeshItCameFrom) {
  SURFCOMP_FETCHED_OR_SKIP(path, "cgal/meshes/elephant.off");
  const mesh::Surface original = mesh::io::read_mesh(path);
  const Eigen::MatrixX3d v = original.positions();
  const Eigen::MatrixX3i f = original.faces();
  // As an STL file holds it: three vertices of its own per triangle, and five triangles twice.
  const Eigen::Index n = f.rows();
  Eigen::MatrixX3d soup(3 * n, 3);
  Eigen::MatrixX3i faces(n + 5, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      soup.row(3 * i + c) = v.row(f(i, c));
      faces(i, c) = static_cast<int>(3 * i + c);
    }
  }
  faces.bottomRows(5) = faces.topRows(5);
  EXPECT_THROW(mesh::Surface::from_arrays(soup, faces, "soup"), TopologyError);
  const mesh::RepairedMesh repaired = mesh::repair_triangles(soup, faces, "soup");
  EXPECT_EQ(repaired.report.merged_vertices, static_cast<std::size_t>(3 * n - v.rows()));
  EXPECT_EQ(repaired.report.removed_faces, 5u);
  EXPECT_EQ(repaired.report.dropped_components, 0u);
  EXPECT_FALSE(repaired.report.reoriented);
  EXPECT_EQ(repaired.surface.n_vertices(), original.n_vertices());
  EXPECT_EQ(repaired.surface.n_faces(), original.n_faces());
  const mesh::SurfaceMeasures before = mesh::measure_surface(original);
  const mesh::SurfaceMeasures after = mesh::measure_surface(repaired.surface);
  EXPECT_EQ(after.boundary_edges, 0u);
  EXPECT_EQ(after.euler_characteristic, before.euler_characteristic);
  EXPECT_NEAR(after.area, before.area, 1e-12 * before.area);
  EXPECT_NEAR(after.volume, before.volume, 1e-9 * std::abs(before.volume));
  EXPECT_EQ(repaired.report.summary(),
            "merged or dropped " + std::to_string(3 * n - v.rows()) +
                " duplicate or unused vertices, removed 5 degenerate or duplicate faces");
}

TEST(MeshRepair, AnInsideOutMeshWithAStrayPieceIsTurnedAndTrimmed) {
  SURFCOMP_FETCHED_OR_SKIP(path, "cgal/meshes/elephant.off");
  const mesh::Surface original = mesh::io::read_mesh(path);
  Eigen::MatrixX3d v(original.n_vertices() + 3, 3);
  v.topRows(static_cast<Eigen::Index>(original.n_vertices())) = original.positions();
  const Eigen::Index s = static_cast<Eigen::Index>(original.n_vertices());
  v.bottomRows(3) << 5, 5, 5, 6, 5, 5, 5, 6, 5;  // a lone triangle far away
  Eigen::MatrixX3i f(original.n_faces() + 1, 3);
  const Eigen::MatrixX3i faces = original.faces();
  f.topRows(faces.rows()) = faces.rowwise().reverse();  // every face turned inside out
  f.bottomRows(1) << static_cast<int>(s), static_cast<int>(s + 1), static_cast<int>(s + 2);
  const mesh::RepairedMesh repaired = mesh::repair_triangles(v, f, "inside out");
  EXPECT_TRUE(repaired.report.reoriented);
  EXPECT_EQ(repaired.report.dropped_components, 1u);
  EXPECT_EQ(repaired.surface.n_faces(), original.n_faces());
  EXPECT_NEAR(mesh::measure_surface(repaired.surface).volume,
              mesh::measure_surface(original).volume, 1e-9);
  EXPECT_GT(mesh::measure_surface(repaired.surface).volume, 0.0);
}

TEST(MeshMatch, AnExplicitUnitIsForGeneralMeshesOnly) {
  SURFCOMP_FETCHED_OR_SKIP(path, "cgal/meshes/elephant.off");
  SURFCOMP_FETCHED_OR_SKIP(ligand, "rdkit-data/4i23_1C9.pdb");
  matching::MatchInput mesh_side, molecule_side;
  mesh_side.path = path;
  molecule_side.path = ligand;
  matching::MatchInputOptions options;
  options.input.unit = 0.03;
  try {
    matching::match_inputs(molecule_side, mesh_side, options);
    ADD_FAILURE() << "a molecule with --unit was matched";
  } catch (const OptionError& e) {
    EXPECT_EQ(std::string(e.what()),
              "unit applies to general meshes; " + ligand.string() + " is in A (a molecule)");
  }
  // Two general meshes take it: the unit is the one given, the answer in their coordinates.
  const matching::InputMatch m = matching::match_inputs(mesh_side, mesh_side, options);
  EXPECT_EQ(m.unit, 0.03);
  EXPECT_EQ(m.unit_from, "given");
  ASSERT_FALSE(m.result.alignments.empty());
  // The clique search stops at its budget on this pair, so the best pose is a refined clique
  // fit, not the exact identity the principal-axes start gives at the automatic unit.
  EXPECT_LT((m.result.alignments.front().transform - Eigen::Matrix4d::Identity()).norm(), 2e-3);
}

using test::error_of;

TEST(MeshRepair, BrokenMeshesAreRefusedInOneLineThatNamesRepair) {
  SURFCOMP_FETCHED_OR_SKIP(path, "cgal/meshes/elephant.off");
  const mesh::Surface elephant = mesh::io::read_mesh(path);
  const Eigen::MatrixX3d v = elephant.positions();
  const Eigen::MatrixX3i f = elephant.faces();
  struct Broken {
    const char* name;
    Eigen::MatrixX3d positions;
    Eigen::MatrixX3i faces;
    Eigen::Index faces_repaired;  ///< after repair_triangles; 0: nothing is left
  };
  std::vector<Broken> cases;
  Eigen::MatrixX3i twice(f.rows() + 1, 3);  // a face given twice: a complex edge
  twice << f, f.row(0);
  cases.push_back({"duplicate face", v, twice, f.rows()});
  Eigen::MatrixX3d lone(v.rows() + 1, 3);  // a vertex in no face: no normal
  lone << v, Eigen::RowVector3d(9, 9, 9);
  cases.push_back({"isolated vertex", lone, f, f.rows()});
  Eigen::MatrixX3i repeated = f;  // a face that names one vertex twice
  repeated(0, 1) = repeated(0, 0);
  cases.push_back({"repeated vertex", v, repeated, f.rows() - 1});
  Eigen::MatrixX3d flat = Eigen::MatrixX3d::Zero(v.rows(), 3);  // every vertex at one point
  cases.push_back({"collapsed", flat, f, 0});
  const std::regex function_name("[a-z]+_[a-z_]+: ");
  for (const Broken& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string message = error_of([&] {
      matching::MatchInput reference, probe;
      reference.surface = mesh::Surface::from_arrays(c.positions, c.faces, "broken.off");
      probe.surface = elephant;
      matching::match_inputs(reference, probe);
    });
    EXPECT_EQ(message.rfind("broken.off: ", 0), 0u) << message;
    EXPECT_TRUE(message.find("; repair ") != std::string::npos ||
                message.find("(repair ") != std::string::npos)
        << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_FALSE(std::regex_search(message, function_name)) << message;
    // Repaired: the elephant again (less the degenerate face), or refused with nothing left.
    const std::string repaired = error_of([&] {
      const mesh::RepairedMesh r = mesh::repair_triangles(c.positions, c.faces, "broken.off");
      EXPECT_EQ(static_cast<Eigen::Index>(r.surface.n_faces()), c.faces_repaired);
    });
    if (c.faces_repaired == 0) {
      EXPECT_EQ(repaired, "broken.off: no face is left after the repair");
    } else {
      EXPECT_EQ(repaired, "");
    }
  }
}

}  // namespace
}  // namespace surfcomp
