// The association graph and its four filters (method §5.1-5.5) on hand-built cases
// with known outcomes, a surface against a moved copy of itself, and the 1THL vs 4TMN reference
// trace (method §5.7).
#include "surfcomp/matching/association_graph.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/harmonic/disk_map.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/cliques.hpp"
#include "surfcomp/mesh/patch.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include "analytic_meshes.hpp"
#include "test_data.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>

namespace surfcomp {
namespace {

using matching::PointPair;
using mesh::CriticalPointType;
using Edges = std::vector<std::pair<int, int>>;

constexpr double kPi = 3.14159265358979323846;

harmonic::CriticalPointDescriptor point_at(CriticalPointType type,
                                           const Eigen::Vector3d& position) {
  harmonic::CriticalPointDescriptor cp;
  cp.point.type = type;
  cp.point.position = position;
  return cp;
}

PointPair node(int a, int b) {
  PointPair p;
  p.a = a;
  p.b = b;
  return p;
}

std::vector<std::pair<int, int>> pairs_of(const std::vector<PointPair>& nodes) {
  std::vector<std::pair<int, int>> out;
  for (const PointPair& p : nodes) out.emplace_back(p.a, p.b);
  return out;
}

TEST(AssociationGraph, InitialPairsAreSameTypePairsAndTheCompleteEdgeCountExcludesSharedPoints) {
  harmonic::SurfaceDescriptors a, b;
  for (const auto type :
       {CriticalPointType::peak, CriticalPointType::valley, CriticalPointType::peak,
        CriticalPointType::peak, CriticalPointType::valley}) {
    a.critical_points.push_back(point_at(type, Eigen::Vector3d::Zero()));
  }
  for (const auto type :
       {CriticalPointType::valley, CriticalPointType::peak, CriticalPointType::peak}) {
    b.critical_points.push_back(point_at(type, Eigen::Vector3d::Zero()));
  }
  const auto nodes = matching::initial_pairs(a, b);
  const std::vector<std::pair<int, int>> expected = {{0, 1}, {0, 2}, {1, 0}, {2, 1},
                                                     {2, 2}, {3, 1}, {3, 2}, {4, 0}};
  EXPECT_EQ(pairs_of(nodes), expected);
  // C(8, 2) = 28 minus pairs sharing A's points (peaks 0, 2, 3 twice each: 3) and B's points
  // (valley 0 twice: 1; peaks 1, 2 three times each: 6) = 18; brute force agrees.
  EXPECT_EQ(matching::count_complete_edges(nodes), 18u);
  std::size_t brute = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (std::size_t j = i + 1; j < nodes.size(); ++j)
      brute += nodes[i].a != nodes[j].a && nodes[i].b != nodes[j].b;
  }
  EXPECT_EQ(brute, 18u);

  const std::vector<bool> a_allowed = {false, true, true, true, false};
  const std::vector<bool> b_allowed = {true, true, false};
  const std::vector<std::pair<int, int>> restricted = {{1, 0}, {2, 1}, {3, 1}};
  EXPECT_EQ(pairs_of(matching::initial_pairs(a, b, &a_allowed, &b_allowed)), restricted);
  const std::vector<bool> wrong_size = {true};
  EXPECT_THROW(matching::initial_pairs(a, b, &wrong_size), InputError);
}

// Vertex properties alternating -1, +1 on a 42-vertex sphere (mean 0, sd 1): the critical
// points' disc averages are their own z-scores.
harmonic::SurfaceDescriptors with_properties(const std::vector<std::pair<double, double>>& esp_lp) {
  harmonic::SurfaceDescriptors d;
  d.surface = test::icosphere(3.0, 2);
  const auto n = static_cast<Eigen::Index>(d.surface.n_vertices());
  Eigen::VectorXd alternating(n);
  for (Eigen::Index i = 0; i < n; ++i) alternating[i] = i % 2 == 0 ? -1.0 : 1.0;
  d.surface.set_property(mesh::property::esp, alternating);
  d.surface.set_property(mesh::property::lp, alternating);
  for (const auto& [esp, lp] : esp_lp) {
    auto cp = point_at(CriticalPointType::peak, Eigen::Vector3d::Zero());
    cp.point.esp = esp;
    cp.point.lp = lp;
    d.critical_points.push_back(cp);
  }
  return d;
}

TEST(AssociationGraph, FuzzyFilterKeepsPairsSimilarInBothPropertiesAndSkipsMissingOnes) {
  const auto a = with_properties({{0.0, 0.0}});
  auto b = with_properties({{0.5, 0.0}, {0.1, 0.0}, {0.0, 1.0}, {0.0, -0.2}});
  // Similarities: B0 esp 1/3 (out), B1 esp 0.9/1.1 (in), B2 lp 0 (out), B3 lp 0.8/1.2 (in).
  const auto kept = matching::fuzzy_filter(matching::initial_pairs(a, b), a, b, 0.5);
  const std::vector<std::pair<int, int>> expected = {{0, 1}, {0, 3}};
  ASSERT_EQ(pairs_of(kept), expected);
  EXPECT_NEAR(kept[0].fuzzy_esp, 0.9 / 1.1, 1e-12);
  EXPECT_DOUBLE_EQ(kept[0].fuzzy_lp, 1.0);
  EXPECT_NEAR(kept[1].fuzzy_lp, 0.8 / 1.2, 1e-12);
  // A threshold of 0.7 drops B3 (lp 0.667) and keeps B1 (esp 0.818).
  EXPECT_EQ(matching::fuzzy_filter(matching::initial_pairs(a, b), a, b, 0.7).size(), 1u);
  // Without esp on B, esp does not filter: B0 comes back, B2 stays out on lp.
  b.surface.remove_property(mesh::property::esp);
  const auto no_esp = matching::fuzzy_filter(matching::initial_pairs(a, b), a, b, 0.5);
  const std::vector<std::pair<int, int>> expected_no_esp = {{0, 0}, {0, 1}, {0, 3}};
  ASSERT_EQ(pairs_of(no_esp), expected_no_esp);
  EXPECT_TRUE(std::isnan(no_esp[0].fuzzy_esp));
  EXPECT_THROW(matching::fuzzy_filter({node(0, 4)}, a, b, 0.5), InputError);
}

// A fully valid polar image whose value at ring r, sector s is f(r, angle of s).
harmonic::ShapeImage polar_image(double (*f)(int ring, double radians), int shift_sectors = 0) {
  harmonic::ShapeImage image;
  image.rings = 16;
  image.sectors = 180;
  const int n = 16 * 180;
  image.values.resize(n);
  image.valid.assign(static_cast<std::size_t>(n), 1);
  image.face = Eigen::VectorXi::Zero(n);
  image.barycentric = Eigen::MatrixX3d::Zero(n, 3);
  for (int ring = 0; ring < 16; ++ring) {
    for (int s = 0; s < 180; ++s) {
      const int source = ((s - shift_sectors) % 180 + 180) % 180;
      image.values(ring * 180 + s) = f(ring, source * 2.0 * kPi / 180.0);
    }
  }
  return image;
}

double one_lobe(int ring, double t) { return (ring + 1) * std::cos(t) + 0.3 * std::sin(2 * t); }
double three_lobes(int ring, double t) { return (ring + 1) * std::cos(3 * t); }

TEST(AssociationGraph, ImageFilterKeepsCorrelatedImagesWithTheirAngleAndDropsPointsWithoutImages) {
  harmonic::SurfaceDescriptors a, b;
  a.critical_points.push_back(point_at(CriticalPointType::peak, Eigen::Vector3d::Zero()));
  a.critical_points[0].image = polar_image(one_lobe);
  for (int k = 0; k < 3; ++k)
    b.critical_points.push_back(point_at(CriticalPointType::peak, Eigen::Vector3d::Zero()));
  b.critical_points[0].image = polar_image(one_lobe, 10);  // a rotated by 20 degrees
  b.critical_points[1].image = polar_image(three_lobes);   // orthogonal harmonics
  b.critical_points[2].image = polar_image(one_lobe);
  b.critical_points[2].status = harmonic::PatchStatus::map_failed;

  const auto matched = matching::with_image_matches(matching::initial_pairs(a, b), a, b);
  ASSERT_EQ(matched.size(), 3u);
  EXPECT_NEAR(matched[0].image_correlation, 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(matched[0].image_angle_degrees, 20.0);
  EXPECT_EQ(matched[0].image_shift, 10);
  EXPECT_LT(matched[1].image_correlation, 0.35);
  EXPECT_DOUBLE_EQ(matched[2].image_correlation, -1.0);

  const auto kept = matching::image_filter(matching::initial_pairs(a, b), a, b, 0.5);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].b, 0);
  EXPECT_DOUBLE_EQ(kept[0].image_angle_degrees, 20.0);
  // A point without an image never passes, even at the lowest threshold.
  EXPECT_EQ(matching::image_filter(matching::initial_pairs(a, b), a, b, -1.0).size(), 2u);
}

TEST(AssociationGraph, DistanceFilterGivesTheExactEdgeSet) {
  harmonic::SurfaceDescriptors a, b;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 0, 0),
                                   Eigen::Vector3d(0, 4, 0), Eigen::Vector3d(1, 0, 0)}) {
    a.critical_points.push_back(point_at(CriticalPointType::peak, p));
  }
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 3.5, 0), Eigen::Vector3d(5, 0, 0)}) {
    b.critical_points.push_back(point_at(CriticalPointType::peak, p));
  }
  const std::vector<PointPair> nodes = {node(0, 0), node(1, 1), node(2, 2), node(3, 1), node(1, 0)};
  // d_A / d_B: 0-1 3 / 3.5; 0-2 4 / 5; 1-2 5 / 6.10; 2-3 4.12 / 6.10 (off by 1.98); 2-4 5 / 5;
  // 3-4 2 / 3.5 (off by exactly 1.5, d_A exactly d_min); 0-3 d_A 1 < d_min; 0-4, 1-3, 1-4 share
  // a point.
  EXPECT_EQ(matching::distance_filter(nodes, a, b, 1.5, 2.0),
            (Edges{{0, 1}, {0, 2}, {1, 2}, {2, 4}, {3, 4}}));
  EXPECT_EQ(matching::distance_filter(nodes, a, b, 1.0, 2.0), (Edges{{0, 1}, {0, 2}, {2, 4}}));
  EXPECT_EQ(matching::distance_filter(nodes, a, b, 1.5, 3.2), (Edges{{0, 2}, {1, 2}, {2, 4}}));
  // Zero tolerance: only equal distances.
  EXPECT_EQ(matching::distance_filter(nodes, a, b, 0.0, 0.0), (Edges{{2, 4}}));
  EXPECT_THROW(matching::distance_filter(nodes, a, b, -1.0, 2.0), OptionError);
  EXPECT_THROW(matching::distance_filter({node(4, 0)}, a, b, 1.5, 2.0), InputError);
}

// On a flat disk the harmonic map of a round patch is close to a similarity, so the bearing
// towards a point is its planar direction from the centre, offset by where the map put the
// first border vertex.
TEST(AssociationGraph, BearingOnAFlatPatchIsThePlanarDirection) {
  const mesh::Surface disk = test::disk(10.0, 20);
  const Eigen::MatrixX3d positions = disk.positions();
  int centre = 0;
  positions.rowwise().squaredNorm().minCoeff(&centre);
  harmonic::CriticalPointDescriptor from;
  from.point.vertex = centre;
  from.patch = mesh::extract_patch(
      disk, centre, mesh::PatchOptions{5.0, 0.05, mesh::GeodesicMethod::fast_marching});
  from.map = harmonic::harmonic_disk_map(from.patch.positions, from.patch.faces,
                                         from.patch.outer_boundary);
  const Eigen::Vector3d first = from.patch.positions.row(from.patch.outer_boundary[0]);
  const double offset = -std::atan2(first.y(), first.x()) * 180.0 / kPi;  // map puts it at 0
  double worst = 0.0;
  for (int k = 0; k < 12; ++k) {
    const double phi = 30.0 * k + 7.0;
    for (const double radius : {3.0, 8.0}) {  // inside the patch, and beyond its border
      mesh::CriticalPoint to;
      to.position = Eigen::Vector3d(radius * std::cos(phi * kPi / 180),
                                    radius * std::sin(phi * kPi / 180), 0);
      Eigen::Index nearest = 0;
      (positions.rowwise() - to.position.transpose()).rowwise().squaredNorm().minCoeff(&nearest);
      to.vertex = radius < 5.0 ? static_cast<int>(nearest) : -1;
      const double bearing = matching::patch_bearing_degrees(from, to);
      worst = std::max(worst, matching::angular_difference_degrees(bearing, phi + offset));
    }
  }
  // Border vertices are about 6 degrees apart at the 5 A border of this mesh, so the nearest
  // one is up to 3 degrees off; the map's distortion of a polygonal patch adds a few more.
  std::printf("[ bearing  ] flat disk: worst error %.2f degrees over 24 directions\n", worst);
  EXPECT_LT(worst, 8.0);
  mesh::CriticalPoint itself;
  itself.vertex = centre;
  EXPECT_THROW(matching::patch_bearing_degrees(from, itself), InputError);
  from.status = harmonic::PatchStatus::empty;
  EXPECT_THROW(matching::patch_bearing_degrees(from, itself), InputError);
}

TEST(AssociationGraph, AngularDifferenceWrapsIntoZeroTo180) {
  EXPECT_DOUBLE_EQ(matching::angular_difference_degrees(10, 350), 20);
  EXPECT_DOUBLE_EQ(matching::angular_difference_degrees(-30, 30), 60);
  EXPECT_DOUBLE_EQ(matching::angular_difference_degrees(0, 180), 180);
  EXPECT_DOUBLE_EQ(matching::angular_difference_degrees(725, 0), 5);
}

const char* kLigands = "thermolysin/ligands-common-frame/";

harmonic::SurfaceDescriptors ligand(const std::filesystem::path& file) {
  return harmonic::describe_surface(molsurf::build_molecular_surface(io::read_molecule(file)));
}

// The surface moved rigidly, with each patch's harmonic map then rotated by its own angle
// theta_i (as another border starting vertex would) and its image rebuilt: the true pair (i, i)
// must be found at angle theta_i, and the overlap filter must undo theta_i to keep its edges.
harmonic::SurfaceDescriptors moved_copy_with_rotated_maps(const harmonic::SurfaceDescriptors& d,
                                                          std::vector<double>& thetas) {
  std::mt19937 rng(11u);
  std::normal_distribution<double> gauss;
  const Eigen::Matrix3d rotation =
      Eigen::Quaterniond(gauss(rng), gauss(rng), gauss(rng), gauss(rng))
          .normalized()
          .toRotationMatrix();
  const Eigen::Vector3d shift(-7.0, 25.0, 3.0);
  harmonic::SurfaceDescriptors moved = d;
  mesh::transform_surface(moved.surface, rotation, shift);
  const Eigen::VectorXd shape = d.surface.property(d.options.image_property);
  thetas.clear();
  for (std::size_t i = 0; i < moved.critical_points.size(); ++i) {
    auto& cp = moved.critical_points[i];
    cp.point.position = rotation * cp.point.position + shift;
    cp.point.normal = rotation * cp.point.normal;
    cp.patch.positions = (cp.patch.positions * rotation.transpose()).rowwise() + shift.transpose();
    const double theta = static_cast<double>((i * 38) % 180) * 2.0;  // a multiple of 2 degrees
    thetas.push_back(theta);
    if (cp.status != harmonic::PatchStatus::ok) continue;
    const Eigen::Matrix2d turn = Eigen::Rotation2Dd(theta * kPi / 180.0).toRotationMatrix();
    cp.map.uv = cp.map.uv * turn.transpose();
    Eigen::VectorXd values(static_cast<Eigen::Index>(cp.patch.surface_vertex.size()));
    for (std::size_t v = 0; v < cp.patch.surface_vertex.size(); ++v)
      values[static_cast<Eigen::Index>(v)] = shape[cp.patch.surface_vertex[v]];
    cp.image = harmonic::harmonic_shape_image(cp.map.uv, cp.patch.faces, values, d.options.image);
  }
  return moved;
}

TEST(AssociationGraph, IdentityPairsOfAMovedCopySurviveEveryFilterAndFormOneClique) {
  SURFCOMP_SHARED_OR_SKIP(file, std::string(kLigands) + "1THL_ligand.sdf");
  const auto a = ligand(file);
  std::vector<double> thetas;
  const auto b = moved_copy_with_rotated_maps(a, thetas);
  const auto graph = matching::build_association_graph(a, b);
  std::vector<int> identity;  // node index of (i, i) for every imaged point
  std::size_t imaged = 0;
  for (std::size_t i = 0; i < a.critical_points.size(); ++i) {
    if (a.critical_points[i].status != harmonic::PatchStatus::ok) continue;
    ++imaged;
    for (std::size_t k = 0; k < graph.nodes.size(); ++k) {
      const PointPair& p = graph.nodes[k];
      if (p.a == static_cast<int>(i) && p.b == static_cast<int>(i)) {
        identity.push_back(static_cast<int>(k));
        EXPECT_NEAR(p.image_correlation, 1.0, 1e-6) << i;
        EXPECT_NEAR(matching::angular_difference_degrees(p.image_angle_degrees, thetas[i]), 0.0,
                    1e-9)
            << i;
      }
    }
  }
  EXPECT_EQ(identity.size(), imaged);
  // Every two identity nodes whose points are at least d_min apart are joined after the
  // overlap filter.
  const std::set<std::pair<int, int>> edges(graph.edges.begin(), graph.edges.end());
  std::size_t expected_edges = 0, missing = 0;
  for (std::size_t x = 0; x < identity.size(); ++x) {
    for (std::size_t y = x + 1; y < identity.size(); ++y) {
      const PointPair& p = graph.nodes[static_cast<std::size_t>(identity[x])];
      const PointPair& q = graph.nodes[static_cast<std::size_t>(identity[y])];
      const double d = (a.critical_points[static_cast<std::size_t>(p.a)].point.position -
                        a.critical_points[static_cast<std::size_t>(q.a)].point.position)
                           .norm();
      if (d < 2.0) continue;
      ++expected_edges;
      missing += edges.count({identity[x], identity[y]}) == 0;
    }
  }
  std::printf(
      "[ identity ] %zu identity nodes, %zu identity edges expected, %zu missing; graph %zu nodes "
      "%zu edges\n",
      identity.size(), expected_edges, missing, graph.nodes.size(), graph.edges.size());
  EXPECT_EQ(missing, 0u);
  EXPECT_GT(expected_edges, 100u);
  // With d_min 0 every two identity nodes are joined, and they form one maximal clique.
  matching::GraphOptions no_min_distance;
  no_min_distance.min_distance = 0.0;
  const auto close_graph = matching::build_association_graph(a, b, no_min_distance);
  std::vector<int> close_identity;
  for (std::size_t k = 0; k < close_graph.nodes.size(); ++k) {
    if (close_graph.nodes[k].a == close_graph.nodes[k].b)
      close_identity.push_back(static_cast<int>(k));
  }
  EXPECT_EQ(close_identity.size(), imaged);
  const auto cliques = matching::maximal_cliques(close_graph, 2);
  EXPECT_NE(std::find(cliques.begin(), cliques.end(), close_identity), cliques.end());
  std::printf(
      "[ identity ] d_min 0: %zu maximal cliques, all %zu identity nodes in one: %s\n",
      cliques.size(), close_identity.size(),
      std::find(cliques.begin(), cliques.end(), close_identity) != cliques.end() ? "yes" : "no");

  // The angles matter: the overlap filter drops every identity edge when both nodes' angles
  // are off by 90 degrees, and keeps it when one node's angle is still right.
  auto wrong = graph.nodes;
  for (PointPair& p : wrong) p.image_angle_degrees += 90.0;
  Edges identity_edges;
  for (const auto& e : graph.edges) {
    if (std::find(identity.begin(), identity.end(), e.first) != identity.end() &&
        std::find(identity.begin(), identity.end(), e.second) != identity.end()) {
      identity_edges.push_back(e);
    }
  }
  EXPECT_TRUE(matching::overlap_filter(wrong, identity_edges, a, b, 30.0).empty());
  auto half_wrong = graph.nodes;
  half_wrong[static_cast<std::size_t>(identity[0])].image_angle_degrees += 90.0;
  EXPECT_EQ(matching::overlap_filter(half_wrong, identity_edges, a, b, 30.0), identity_edges);
}

TEST(AssociationGraph, ThermolysinLigandsTraceBesideTheThesis) {
  SURFCOMP_SHARED_OR_SKIP(file_a, std::string(kLigands) + "1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(file_b, std::string(kLigands) + "4TMN_ligand.sdf");
  const auto a = ligand(file_a);
  const auto b = ligand(file_b);
  const auto ca = harmonic::count_descriptors(a);
  const auto cb = harmonic::count_descriptors(b);

  const auto first = matching::build_association_graph(a, b);
  const auto graph = matching::build_association_graph(a, b);
  const auto cliques = matching::maximal_cliques(graph, 2);

  const std::size_t thesis[5][2] = {{553, 274841}, {162, 17982}, {63, 1260}, {63, 359}, {60, 93}};
  std::printf("[ trace    ] 1THL (%zu+%zu CPs) vs 4TMN (%zu+%zu CPs)\n", ca.peaks, ca.valleys,
              cb.peaks, cb.valleys);
  std::printf("[ trace    ] %-16s %8s %10s   %8s %10s\n", "stage", "nodes", "edges", "thesis",
              "edges");
  ASSERT_EQ(graph.trace.size(), 5u);
  for (std::size_t s = 0; s < graph.trace.size(); ++s) {
    const auto& t = graph.trace[s];
    std::printf("[ trace    ] %-16s %8zu %10zu   %8zu %10zu\n", t.stage.c_str(), t.nodes, t.edges,
                thesis[s][0], thesis[s][1]);
  }
  std::map<std::size_t, int> sizes;
  for (const auto& c : cliques) ++sizes[c.size()];
  std::printf("[ cliques  ] %zu maximal cliques (size:count", cliques.size());
  for (const auto& [size, count] : sizes) std::printf(" %zu:%d", size, count);
  std::printf(")\n");

  // Deterministic: a second run gives the same nodes, angles and edges.
  ASSERT_EQ(first.nodes.size(), graph.nodes.size());
  for (std::size_t k = 0; k < graph.nodes.size(); ++k) {
    EXPECT_EQ(first.nodes[k].a, graph.nodes[k].a);
    EXPECT_EQ(first.nodes[k].b, graph.nodes[k].b);
    EXPECT_EQ(first.nodes[k].image_correlation, graph.nodes[k].image_correlation);
    EXPECT_EQ(first.nodes[k].image_shift, graph.nodes[k].image_shift);
  }
  EXPECT_EQ(first.edges, graph.edges);
  // In the common frame, how many surviving nodes are true pairs (points within 2 A)?
  std::vector<bool> true_node(graph.nodes.size());
  std::size_t n_true = 0;
  for (std::size_t k = 0; k < graph.nodes.size(); ++k) {
    const PointPair& p = graph.nodes[k];
    true_node[k] = (a.critical_points[static_cast<std::size_t>(p.a)].point.position -
                    b.critical_points[static_cast<std::size_t>(p.b)].point.position)
                       .norm() < 2.0;
    n_true += true_node[k];
  }
  std::size_t largest_true_clique = 0;
  for (const auto& c : cliques) {
    if (std::all_of(c.begin(), c.end(),
                    [&](int v) { return true_node[static_cast<std::size_t>(v)]; })) {
      largest_true_clique = std::max(largest_true_clique, c.size());
    }
  }
  std::printf(
      "[ truth    ] %zu of %zu final nodes are true pairs (< 2 A apart in the common frame); "
      "largest all-true clique %zu\n",
      n_true, graph.nodes.size(), largest_true_clique);
  EXPECT_GE(n_true, 5u);
  EXPECT_GE(largest_true_clique, 3u);

  EXPECT_EQ(graph.trace[0].nodes, ca.peaks * cb.peaks + ca.valleys * cb.valleys);
  for (std::size_t s = 1; s < graph.trace.size(); ++s) {
    EXPECT_LE(graph.trace[s].nodes, graph.trace[s - 1].nodes) << graph.trace[s].stage;
    EXPECT_LE(graph.trace[s].edges, graph.trace[s - 1].edges) << graph.trace[s].stage;
  }
  EXPECT_EQ(graph.trace.back().nodes, graph.nodes.size());
  EXPECT_EQ(graph.trace.back().edges, graph.edges.size());
  // Each stage removes a sizeable share, as in the reference trace of method §5.7 (553 -> 63 nodes,
  // 359 -> 93 edges).
  EXPECT_LT(graph.trace[2].nodes, graph.trace[0].nodes / 2);
  EXPECT_LT(graph.trace[4].edges, graph.trace[3].edges);
  EXPECT_GT(graph.edges.size(), 10u);
  for (const auto& c : cliques) {
    EXPECT_GE(c.size(), 2u);
    EXPECT_TRUE(std::is_sorted(c.begin(), c.end()));
  }
  EXPECT_TRUE(std::is_sorted(cliques.begin(), cliques.end()));

  // The two ligands are in one frame: pairs whose points lie within 1.5 A of each other are
  // true. Their image correlations beside all others' decide the default R.
  auto all = matching::with_image_matches(matching::initial_pairs(a, b), a, b);
  std::vector<double> true_r, other_r;
  for (const PointPair& p : all) {
    if (a.critical_points[static_cast<std::size_t>(p.a)].status != harmonic::PatchStatus::ok ||
        b.critical_points[static_cast<std::size_t>(p.b)].status != harmonic::PatchStatus::ok)
      continue;
    const double d = (a.critical_points[static_cast<std::size_t>(p.a)].point.position -
                      b.critical_points[static_cast<std::size_t>(p.b)].point.position)
                         .norm();
    (d < 1.5 ? true_r : other_r).push_back(p.image_correlation);
  }
  auto quantile = [](std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
  };
  ASSERT_GE(true_r.size(), 5u);
  std::printf(
      "[ image R  ] true pairs (%zu): q10 %.3f median %.3f q90 %.3f; others (%zu): q10 %.3f median "
      "%.3f q90 %.3f\n",
      true_r.size(), quantile(true_r, 0.1), quantile(true_r, 0.5), quantile(true_r, 0.9),
      other_r.size(), quantile(other_r, 0.1), quantile(other_r, 0.5), quantile(other_r, 0.9));
  std::size_t true_kept = 0;
  for (const double r : true_r) true_kept += r >= matching::GraphOptions{}.image_threshold;
  std::printf("[ image R  ] default R %.2f keeps %zu of %zu true pairs\n",
              matching::GraphOptions{}.image_threshold, true_kept, true_r.size());
  EXPECT_GT(quantile(true_r, 0.5), quantile(other_r, 0.5));
}

}  // namespace
}  // namespace surfcomp
