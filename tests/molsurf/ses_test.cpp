#include "surfcomp/molsurf/ses.hpp"
#include "atom_balls.hpp"
#include "surface_components.hpp"
#include "surfcomp/core/elements.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/remesh.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace surfcomp::molsurf {
namespace {

using test::Atoms;
using test::make_atoms;
using test::read_pdb_heavy_atoms;
using test::two_atom_ses;
using test::TwoAtomSes;
using test::union_area;

/// para-cresol, heavy atoms only, placed by hand in the xy plane (ring C-C 1.39 A, C-O 1.36 A,
/// C-CH3 1.51 A): a compact 8-atom fragment.
Atoms cresol() {
  std::vector<Eigen::Vector3d> centers;
  std::vector<double> radii;
  for (int k = 0; k < 6; ++k) {
    const double angle = M_PI / 3.0 * k;
    centers.emplace_back(1.39 * std::cos(angle), 1.39 * std::sin(angle), 0.0);
    radii.push_back(1.70);
  }
  centers.emplace_back(1.39 + 1.36, 0.0, 0.0);
  radii.push_back(1.52);
  centers.emplace_back(-1.39 - 1.51, 0.0, 0.0);
  radii.push_back(1.70);
  return make_atoms(centers, radii);
}

double vertex_density(const mesh::Surface& surface) {
  return static_cast<double>(surface.n_vertices()) / mesh::measure_surface(surface).area;
}

/// The fraction of triangles whose normal points against their vertices' normals (folds).
double folded_fraction(const mesh::Surface& surface) {
  const Eigen::MatrixX3d p = surface.positions();
  const Eigen::MatrixX3i f = surface.faces();
  const Eigen::MatrixX3d n = surface.normals();
  int folded = 0;
  for (Eigen::Index t = 0; t < f.rows(); ++t) {
    const Eigen::Vector3d a = p.row(f(t, 0)), b = p.row(f(t, 1)), c = p.row(f(t, 2));
    const Eigen::Vector3d average = n.row(f(t, 0)) + n.row(f(t, 1)) + n.row(f(t, 2));
    if ((b - a).cross(c - a).dot(average) <= 0.0) ++folded;
  }
  return static_cast<double>(folded) / static_cast<double>(f.rows());
}

TEST(EdgeLength, EquilateralMeshDensity) {
  // V / area = 2 / (sqrt(3) L^2) for an equilateral mesh with F = 2V.
  const double length = mesh::edge_length_for_density(2.5);
  EXPECT_NEAR(2.0 / (std::sqrt(3.0) * length * length), 2.5, 1e-12);
  EXPECT_NEAR(length, 0.6796, 1e-4);
  EXPECT_THROW(mesh::edge_length_for_density(0.0), OptionError);
}

TEST(Ses, OneAtomIsItsVanDerWaalsSphere) {
  const double r = 1.7;
  const double area = 4.0 * M_PI * r * r;
  const double volume = 4.0 / 3.0 * M_PI * r * r * r;
  const Atoms atom = make_atoms({Eigen::Vector3d(0.3, -0.2, 0.1)}, {r});
  const SesOptions options;
  const mesh::Surface ses = build_ses(atom.centers, atom.radii, options);
  ASSERT_NO_THROW(mesh::require_closed_manifold(ses));
  const mesh::SurfaceMeasures m = mesh::measure_surface(ses);
  std::cout << "one atom: " << ses.n_vertices() << " vertices, area " << m.area << " (exact "
            << area << "), volume " << m.volume << " (exact " << volume << "), density "
            << vertex_density(ses) << " per A^2\n";
  EXPECT_NEAR(m.area, area, 0.01 * area);
  EXPECT_NEAR(m.volume, volume, 0.01 * volume);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_NEAR(vertex_density(ses), options.vertex_density, 0.3 * options.vertex_density);
  // Normals are radial; vertices sit just outside the sphere by the chord compensation
  // H L^2 / 8 = 0.68^2 / (8 * 1.7) = 0.034 A for an equilateral mesh.
  const Eigen::MatrixX3d p = ses.positions();
  const Eigen::MatrixX3d n = ses.normals();
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    const Eigen::Vector3d radial = p.row(v) - atom.centers.row(0);
    ASSERT_GT(radial.normalized().dot(n.row(v)), 1.0 - 1e-12);
    ASSERT_GT(radial.norm() - r, 0.0);
    ASSERT_LT(radial.norm() - r, 0.07);
  }
}

TEST(Ses, WithoutChordCompensationVerticesLieOnTheSurface) {
  const double r = 1.7;
  const Atoms atom = make_atoms({Eigen::Vector3d(0.3, -0.2, 0.1)}, {r});
  SesOptions options;
  options.compensate_chords = false;
  const mesh::Surface ses = build_ses(atom.centers, atom.radii, options);
  const Eigen::MatrixX3d p = ses.positions();
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    ASSERT_NEAR((p.row(v) - atom.centers.row(0)).norm(), r, 1e-12);
  }
  // The inscribed polyhedron loses area: about 3 % at 2.5 vertices per A^2 (see SesOptions).
  const double ratio = mesh::measure_surface(ses).area / (4.0 * M_PI * r * r);
  std::cout << "one atom, vertices on the sphere: area ratio " << ratio << "\n";
  EXPECT_GT(ratio, 0.95);
  EXPECT_LT(ratio, 0.985);
}

TEST(Ses, ZeroProbeGivesTheVanDerWaalsSurface) {
  // Two atoms 2.5 A apart: the union of two balls, area 2 pi r1^2 (1 + x1 / r1) +
  // 2 pi r2^2 (1 + x2 / r2) with x1, x2 the distances from the centres to the intersection plane.
  const double r1 = 1.7, r2 = 1.5, d = 2.5;
  const double x1 = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
  const double x2 = d - x1;
  const double area =
      2.0 * M_PI * r1 * r1 * (1.0 + x1 / r1) + 2.0 * M_PI * r2 * r2 * (1.0 + x2 / r2);
  SesOptions options;
  options.probe_radius = 0.0;
  const Atoms atoms = make_atoms({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(d, 0, 0)}, {r1, r2});
  const mesh::SurfaceMeasures m =
      mesh::measure_surface(build_ses(atoms.centers, atoms.radii, options));
  std::cout << "van der Waals surface of two atoms: area " << m.area << " (exact " << area << ")\n";
  EXPECT_NEAR(m.area, area, 0.02 * area);
  EXPECT_EQ(m.euler_characteristic, 2);
}

TEST(Sas, OneAtomIsTheProbeGrownSphere) {
  const double r = 1.7;
  const SesOptions options;
  const double big = r + options.probe_radius;
  const Atoms atom = make_atoms({Eigen::Vector3d(0, 0, 0)}, {r});
  const mesh::Surface sas = build_sas(atom.centers, atom.radii, options);
  const mesh::SurfaceMeasures m = mesh::measure_surface(sas);
  std::cout << "SAS one atom: area " << m.area << " (exact " << 4 * M_PI * big * big << ")\n";
  EXPECT_NEAR(m.area, 4.0 * M_PI * big * big, 0.01 * 4.0 * M_PI * big * big);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_GT(m.volume, 0.0);
}

TEST(Sas, TwoAtomsAreTwoSphereCaps) {
  // The union of spheres R1 = 3.1 and R2 = 2.9 with centres 2.5 A apart: caps beyond the
  // intersection plane at x1 = (d^2 + R1^2 - R2^2) / (2 d) from centre 1.
  const double big1 = 1.7 + 1.4, big2 = 1.5 + 1.4, d = 2.5;
  const double x1 = (d * d + big1 * big1 - big2 * big2) / (2.0 * d);
  const double area = 2.0 * M_PI * big1 * big1 * (1.0 + x1 / big1) +
                      2.0 * M_PI * big2 * big2 * (1.0 + (d - x1) / big2);
  const Atoms atoms = make_atoms({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, d, 0)}, {1.7, 1.5});
  const mesh::SurfaceMeasures m = mesh::measure_surface(build_sas(atoms.centers, atoms.radii));
  std::cout << "SAS two atoms: area " << m.area << " (exact " << area << ")\n";
  EXPECT_NEAR(m.area, area, 0.01 * area);
  EXPECT_EQ(m.euler_characteristic, 2);
}

TEST(Sas, CreasedClusterMatchesShrakeRupley) {
  // Five atoms about 3 A apart (a branched cluster): their probe-grown spheres (2.6-3.2 A)
  // meet at deep, sharp concave creases and at triple points. Triangles chording across the
  // creases lost 1.5 % of the area (before the mesh followed the creases; now +0.2 %).
  const Atoms atoms = make_atoms({Eigen::Vector3d(0.1, 0.2, -0.3), Eigen::Vector3d(3.0, 0.5, -0.2),
                                  Eigen::Vector3d(4.2, 3.2, 0.1), Eigen::Vector3d(4.4, -2.1, 1.2),
                                  Eigen::Vector3d(1.9, 2.6, 1.9)},
                                 {1.7, 1.55, 1.52, 1.8, 1.2});
  const SesOptions options;
  const double exact = union_area(atoms, options.probe_radius, 400000);
  const mesh::Surface sas = build_sas(atoms.centers, atoms.radii, options);
  const mesh::SurfaceMeasures m = mesh::measure_surface(sas);
  std::cout << "SAS creased cluster: area " << m.area << " (Shrake-Rupley " << exact << ", "
            << 100.0 * (m.area - exact) / exact << " %), " << sas.n_vertices()
            << " vertices, density " << vertex_density(sas) << "\n";
  EXPECT_NEAR(m.area, exact, 0.005 * exact);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_NO_THROW(mesh::require_closed_manifold(sas));
  EXPECT_NEAR(vertex_density(sas), options.vertex_density, 0.3 * options.vertex_density);
  // Every vertex lies on the SAS: on the outermost of the spheres through it, up to the chord
  // compensation (at most ~0.05 A outward for these radii).
  const Eigen::MatrixX3d p = sas.positions();
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    double depth = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < atoms.centers.rows(); ++i) {
      depth = std::min(
          depth, (p.row(v) - atoms.centers.row(i)).norm() - atoms.radii(i) - options.probe_radius);
    }
    ASSERT_GT(depth, -1e-9) << "vertex " << v;
    ASSERT_LT(depth, 0.05) << "vertex " << v;
  }
}

void expect_two_atom_area(double r1, double r2, double d, double tolerance) {
  const SesOptions options;
  const TwoAtomSes exact = two_atom_ses(r1, r2, d, options.probe_radius);
  ASSERT_GT(exact.h, options.probe_radius) << "the torus self-intersects; formula invalid";
  ASSERT_GT(exact.contact1_margin, 0.0);
  ASSERT_GT(exact.contact2_margin, 0.0);
  // An oblique axis, so the grid is not aligned with the molecule.
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 0.4, -0.7).normalized();
  const Eigen::Vector3d c1(0.1, 0.2, 0.3);
  const Atoms atoms = make_atoms({c1, c1 + d * axis}, {r1, r2});
  const mesh::Surface ses = build_ses(atoms.centers, atoms.radii, options);
  const mesh::SurfaceMeasures m = mesh::measure_surface(ses);
  std::cout << "two atoms r " << r1 << ", " << r2 << " at " << d << " A: area " << m.area
            << " (analytic " << exact.area << ", h " << exact.h << "), " << ses.n_vertices()
            << " vertices\n";
  EXPECT_NEAR(m.area, exact.area, tolerance * exact.area);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_NO_THROW(mesh::require_closed_manifold(ses));
}

TEST(Ses, TwoOverlappingAtomsMatchCapsPlusTorus) { expect_two_atom_area(1.7, 1.5, 2.5, 0.02); }

TEST(Ses, TwoSeparateAtomsBridgedByTheProbe) {
  // 0.5 A apart: the probe (diameter 2.8 A) cannot pass between them.
  expect_two_atom_area(1.5, 1.5, 3.5, 0.02);
}

TEST(Ses, RigidMotionKeepsAreaAndVolume) {
  const Atoms atoms = cresol();
  const unsigned seed = 20240611;
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
  const Eigen::Vector3d t(10.0 * normal(rng), 10.0 * normal(rng), 10.0 * normal(rng));
  Atoms moved = atoms;
  for (Eigen::Index i = 0; i < moved.centers.rows(); ++i) {
    moved.centers.row(i) = (q * atoms.centers.row(i).transpose() + t).transpose();
  }
  const mesh::SurfaceMeasures a = mesh::measure_surface(build_ses(atoms.centers, atoms.radii));
  const mesh::SurfaceMeasures b = mesh::measure_surface(build_ses(moved.centers, moved.radii));
  std::cout << "cresol (seed " << seed << "): area " << a.area << " -> " << b.area << ", volume "
            << a.volume << " -> " << b.volume << "\n";
  EXPECT_NEAR(b.area, a.area, 0.005 * a.area);
  EXPECT_NEAR(b.volume, a.volume, 0.005 * a.volume);
}

TEST(Ses, MultiAtomFragmentIsASphereTopologically) {
  const Atoms atoms = cresol();
  const mesh::Surface ses = build_ses(atoms.centers, atoms.radii);
  ASSERT_NO_THROW(mesh::require_closed_manifold(ses));
  const mesh::SurfaceMeasures m = mesh::measure_surface(ses);
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_GT(m.volume, 0.0);
  // The SES encloses the van der Waals volume: at least the largest atom's sphere.
  EXPECT_GT(m.volume, 4.0 / 3.0 * M_PI * std::pow(1.7, 3));
  EXPECT_EQ(folded_fraction(ses), 0.0);
  // The grid mesh itself (no remeshing) is closed and encloses the same volume.
  SesOptions raw;
  raw.remesh = false;
  const mesh::Surface grid_mesh = build_ses(atoms.centers, atoms.radii, raw);
  ASSERT_NO_THROW(mesh::require_closed_manifold(grid_mesh));
  const mesh::SurfaceMeasures g = mesh::measure_surface(grid_mesh);
  EXPECT_EQ(g.euler_characteristic, 2);
  EXPECT_NEAR(g.volume, m.volume, 0.01 * m.volume);
  EXPECT_NEAR(g.area, m.area, 0.01 * m.area);
}

TEST(Ses, CavitiesAreDroppedOrKept) {
  // 240 carbon atoms on a sphere of radius 5 A (Fibonacci points, about 1.1 A apart) enclose a
  // void of radius 5 - 1.7 = 3.3 A where the probe fits but which it cannot reach.
  std::vector<Eigen::Vector3d> centers;
  const int n = 240;
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double phi = M_PI * (3.0 - std::sqrt(5.0)) * i;
    const double s = std::sqrt(1.0 - z * z);
    centers.emplace_back(5.0 * s * std::cos(phi), 5.0 * s * std::sin(phi), 5.0 * z);
  }
  const Atoms shell = make_atoms(centers, std::vector<double>(n, 1.7));
  const mesh::SurfaceMeasures outer = mesh::measure_surface(build_ses(shell.centers, shell.radii));
  SesOptions keep;
  keep.keep_cavities = true;
  const mesh::Surface both = build_ses(shell.centers, shell.radii, keep);
  const mesh::SurfaceMeasures m = mesh::measure_surface(both);
  const double cavity = outer.volume - m.volume;
  // Probe centres fit where every atom is >= 1.7 + 1.4 = 3.1 A away: out to radius
  // 5 - 3.1 = 1.9 below an atom and a little further (< 0.1 A) in the gaps between atoms, so
  // the cavity (the union of those probe balls) lies between the balls of radius 3.3 and 3.4.
  const double void_ball = 4.0 / 3.0 * M_PI * std::pow(3.3, 3);
  const double void_bound = 4.0 / 3.0 * M_PI * std::pow(3.4, 3);
  std::cout << "shell: outer chi " << outer.euler_characteristic << " volume " << outer.volume
            << "; with cavity chi " << m.euler_characteristic << ", cavity volume " << cavity
            << " (between " << void_ball << " and " << void_bound << ")\n";
  EXPECT_EQ(outer.euler_characteristic, 2);
  EXPECT_EQ(m.euler_characteristic, 4);  // two spheres
  EXPECT_GT(cavity, 0.99 * void_ball);
  EXPECT_LT(cavity, void_bound);
  EXPECT_NO_THROW(mesh::require_closed_manifold(both));
}

TEST(Ses, NeckThinnerThanAVoxelLeavesNoFragment) {
  // Two carbon atoms whose expanded spheres (1.7 + 1.4 A) meet in a circle of radius
  // h = 1.4 + 0.1 A: the probe just fails to pass between them, and the SES joins them by a
  // neck of radius h - 1.4 = 0.1 A at their midpoint. The grid (0.68 A) cannot hold the neck:
  // with the midpoint on a grid node and the axis oblique to the grid, only that node falls
  // inside it, and the mesh gets a one-voxel component with no atom in it (as in the Kahraman
  // sites 1DV2, 1E8X, 1NAZ, 1PP9, 1QLA): the grid's 8-vertex box around the node, kept out of
  // the remeshing and projected onto the neck, so it holds less than the neck does over a
  // voxel, pi 0.1^2 0.68 = 0.021 A^3.
  const double r = 1.7, neck = 0.1;
  const SesOptions defaults;
  const double h = defaults.probe_radius + neck;
  const double half = std::sqrt(std::pow(r + defaults.probe_radius, 2) - h * h);
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 1.0, 1.0).normalized();
  const Atoms atoms = make_atoms({-half * axis, half * axis}, {r, r});
  const double ball = 4.0 / 3.0 * M_PI * std::pow(r, 3);

  SesOptions keep_all;
  keep_all.min_component_volume_fraction = 0.0;
  const auto all = test::surface_components(build_ses(atoms.centers, atoms.radii, keep_all));
  ASSERT_EQ(all.size(), 3u) << "the grid no longer leaves a fragment of the neck here";
  const auto fragment = std::min_element(all.begin(), all.end(), [](const auto& a, const auto& b) {
    return std::abs(a.volume) < std::abs(b.volume);
  });
  std::cout << "neck fragment: " << fragment->vertices << " vertices, volume " << fragment->volume
            << " A^3\n";
  EXPECT_LT(std::abs(fragment->volume),
            M_PI * neck * neck * ses_voxel_size(atoms.centers, atoms.radii, defaults));
  EXPECT_LT(fragment->vertices, 9);

  // By default the fragment is dropped: two components, each enclosing its atom's ball.
  const mesh::Surface ses = build_ses(atoms.centers, atoms.radii);
  const auto kept = test::surface_components(ses);
  ASSERT_EQ(kept.size(), 2u);
  for (const auto& c : kept) {
    EXPECT_GT(c.volume, 0.99 * ball);
    EXPECT_LT(c.volume, 1.05 * ball);
  }
  EXPECT_EQ(mesh::measure_surface(ses).euler_characteristic, 4);
  EXPECT_NO_THROW(mesh::require_closed_manifold(ses));
}

TEST(Ses, DeterministicAcrossRunsAndThreadCounts) {
  const Atoms atoms = cresol();
  const mesh::Surface first = build_ses(atoms.centers, atoms.radii);
  const mesh::Surface second = build_ses(atoms.centers, atoms.radii);
  mesh::Surface serial;
  {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    serial = build_ses(atoms.centers, atoms.radii);
  }
  EXPECT_TRUE(first.positions() == second.positions());
  EXPECT_TRUE(first.faces() == second.faces());
  EXPECT_TRUE(first.positions() == serial.positions());
  EXPECT_TRUE(first.faces() == serial.faces());
  // The SAS crease splits and collapses run after a parallel projection.
  const mesh::Surface sas = build_sas(atoms.centers, atoms.radii);
  mesh::Surface sas_serial;
  {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    sas_serial = build_sas(atoms.centers, atoms.radii);
  }
  EXPECT_TRUE(sas.positions() == sas_serial.positions());
  EXPECT_TRUE(sas.faces() == sas_serial.faces());
}

TEST(Ses, InvalidInputsThrow) {
  const Atoms one = make_atoms({Eigen::Vector3d(0, 0, 0)}, {1.7});
  const Eigen::MatrixX3d none(0, 3);
  EXPECT_THROW(build_ses(none, Eigen::VectorXd(0)), InputError);
  EXPECT_THROW(build_ses(one.centers, Eigen::VectorXd::Constant(2, 1.7)), InputError);
  Atoms bad = one;
  bad.radii(0) = 0.0;
  EXPECT_THROW(build_ses(bad.centers, bad.radii), InputError);
  bad = one;
  bad.centers(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(build_sas(bad.centers, bad.radii), InputError);
  bad = one;
  bad.radii(0) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(build_ses(bad.centers, bad.radii), InputError);
  SesOptions options;
  options.probe_radius = -1.0;
  EXPECT_THROW(build_ses(one.centers, one.radii, options), OptionError);
  options = SesOptions{};
  options.voxel_size = 3.0;  // the sphere 1.7 + 1.4 spans ~1 voxel
  EXPECT_THROW(build_ses(one.centers, one.radii, options), OptionError);
  for (const double density : {0.0, 0.049, 20.5, std::numeric_limits<double>::quiet_NaN()}) {
    options = SesOptions{};
    options.vertex_density = density;
    EXPECT_THROW(build_ses(one.centers, one.radii, options), OptionError) << density;
  }
  options = SesOptions{};
  options.vertex_density = max_vertex_density;  // the largest accepted: a 1.7 A atom builds
  EXPECT_GT(build_ses(one.centers, one.radii, options).n_vertices(), 500u);
  for (const double fraction : {-0.1, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    options = SesOptions{};
    options.min_component_volume_fraction = fraction;
    EXPECT_THROW(build_ses(one.centers, one.radii, options), OptionError) << fraction;
  }
}

/// The region of one ball.
SesRegion ball(const Eigen::Vector3d& center, double radius) {
  SesRegion region;
  region.centers = center.transpose();
  region.radii = Eigen::VectorXd::Constant(1, radius);
  return region;
}

// One atom (its SES is its van der Waals sphere) cut to a ball that holds part of it: a lens,
// closed by the ball's sphere, with the two caps' analytic area and volume; every vertex on one
// sphere with its radial normal, or on the circle where they meet.
TEST(SesRegion, OneAtomCutByABallIsALens) {
  const double r = 4.0, rho = 3.5, d = 3.0;  // atom at the origin, the ball's centre at (d, 0, 0)
  const Eigen::Vector3d ball_center(d, 0.0, 0.0);
  const Atoms atom = make_atoms({Eigen::Vector3d::Zero()}, {r});
  const mesh::Surface lens = build_ses(atom.centers, atom.radii, ball(ball_center, rho));
  ASSERT_NO_THROW(mesh::require_closed_manifold(lens));
  // The spheres meet in the plane x = a; the atom's cap beyond it, the ball's cap before it.
  const double a = (d * d + r * r - rho * rho) / (2.0 * d);
  const double atom_cap = r - a, ball_cap = rho - (d - a);
  const double area = 2.0 * M_PI * (r * atom_cap + rho * ball_cap);
  const auto cap_volume = [](double radius, double h) {
    return M_PI * h * h * (3.0 * radius - h) / 3.0;
  };
  const double volume = cap_volume(r, atom_cap) + cap_volume(rho, ball_cap);
  const mesh::SurfaceMeasures m = mesh::measure_surface(lens);
  std::cout << "lens: " << lens.n_vertices() << " vertices, area " << m.area << " (exact " << area
            << "), volume " << m.volume << " (exact " << volume << ")\n";
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_NEAR(m.area, area, 0.015 * area);
  EXPECT_NEAR(m.volume, volume, 0.015 * volume);
  const Eigen::MatrixX3d p = lens.positions();
  const Eigen::MatrixX3d n = lens.normals();
  int on_atom = 0, on_ball = 0;
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    const Eigen::Vector3d x = p.row(v).transpose();
    const Eigen::Vector3d normal = n.row(v).transpose();
    const double from_atom = x.norm() - r, from_ball = (x - ball_center).norm() - rho;
    if (std::abs(x.x() - a) < 0.5) continue;  // near the seam: on both, or between
    // Off the seam the chord compensation (H L^2 / 8 < 0.03 A) alone moves a vertex.
    if (x.x() > a) {
      ++on_atom;
      EXPECT_LT(std::abs(from_atom), 0.03) << v;
      EXPECT_GT(x.normalized().dot(normal), 1.0 - 1e-9) << v;
    } else {
      ++on_ball;
      EXPECT_LT(std::abs(from_ball), 0.03) << v;
      EXPECT_GT((x - ball_center).normalized().dot(normal), 1.0 - 1e-9) << v;
    }
  }
  EXPECT_GT(on_atom, 50);
  EXPECT_GT(on_ball, 50);
  mesh::Surface serial;
  {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    serial = build_ses(atom.centers, atom.radii, ball(ball_center, rho));
  }
  EXPECT_TRUE(lens.positions() == serial.positions());
  EXPECT_TRUE(lens.faces() == serial.faces());
}

// One atom cut to two overlapping balls whose spheres meet inside it: every vertex lies on the
// boundary of atom ∩ (ball A ∪ ball B), whose signed field is max(|x| - r, min over the balls),
// none on a ball's sphere where the other ball buries it.
TEST(SesRegion, TwoBallsMeetingInsideTheAtomCutItAlongTheirUnion) {
  const double r = 6.0;
  const Atoms atom = make_atoms({Eigen::Vector3d::Zero()}, {r});
  SesRegion two;
  two.centers = Eigen::MatrixX3d(2, 3);
  two.centers << -3.5, 0.0, 5.0, 3.5, 0.0, 5.0;
  two.radii = Eigen::Vector2d(4.0, 4.0);
  const mesh::Surface cut = build_ses(atom.centers, atom.radii, two);
  ASSERT_NO_THROW(mesh::require_closed_manifold(cut));
  EXPECT_EQ(mesh::measure_surface(cut).euler_characteristic, 2);
  const Eigen::MatrixX3d p = cut.positions();
  double worst = 0.0;
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    const Eigen::Vector3d x = p.row(v).transpose();
    const double balls = std::min((x - two.centers.row(0).transpose()).norm() - two.radii(0),
                                  (x - two.centers.row(1).transpose()).norm() - two.radii(1));
    worst = std::max(worst, std::abs(std::max(x.norm() - r, balls)));
  }
  std::cout << "two balls: " << cut.n_vertices() << " vertices, farthest from the boundary "
            << worst << " A\n";
  EXPECT_LT(worst, 0.03);  // the chord compensation, H L^2 / 8 < 0.015 A, and the seams
}

// A region that holds the whole molecule, with room for the grid, changes nothing.
TEST(SesRegion, ARegionHoldingTheMoleculeChangesNothing) {
  const Atoms atoms = cresol();
  const mesh::Surface whole = build_ses(atoms.centers, atoms.radii);
  SesRegion two;
  two.centers = Eigen::MatrixX3d(2, 3);
  two.centers << -4.0, 0.0, 0.0, 4.0, 0.0, 0.0;
  two.radii = Eigen::Vector2d(9.0, 9.0);
  const mesh::Surface inside = build_ses(atoms.centers, atoms.radii, two);
  EXPECT_TRUE(whole.positions() == inside.positions());
  EXPECT_TRUE(whole.faces() == inside.faces());
  EXPECT_TRUE(whole.normals() == inside.normals());
}

TEST(SesRegion, BadRegionsAreRefused) {
  const Atoms one = make_atoms({Eigen::Vector3d(0, 0, 0)}, {1.7});
  SesRegion empty;
  empty.centers = Eigen::MatrixX3d(0, 3);
  SesRegion mismatch = ball(Eigen::Vector3d::Zero(), 3.0);
  mismatch.radii = Eigen::Vector2d(3.0, 3.0);
  SesRegion nan_centre = ball(Eigen::Vector3d(std::nan(""), 0.0, 0.0), 3.0);
  SesRegion zero_radius = ball(Eigen::Vector3d::Zero(), 0.0);
  SesRegion far_away = ball(Eigen::Vector3d(100.0, 0.0, 0.0), 3.0);  // holds none of the surface
  for (const SesRegion* region : {&empty, &mismatch, &nan_centre, &zero_radius, &far_away}) {
    try {
      (void)build_ses(one.centers, one.radii, *region, {}, "one.pdb");
      ADD_FAILURE() << "expected InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("one.pdb: ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find("region"), std::string::npos) << e.what();
    }
  }
}

TEST(Ses, ThermolysinLigand) {
  SURFCOMP_SHARED_OR_SKIP(path, "thermolysin/ligands-common-frame/1THL_ligand.pdb");
  const Atoms atoms = read_pdb_heavy_atoms(path);
  ASSERT_EQ(atoms.radii.size(), 35);
  const auto start = std::chrono::steady_clock::now();
  const mesh::Surface ses = build_ses(atoms.centers, atoms.radii);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const mesh::SurfaceMeasures m = mesh::measure_surface(ses);
  std::cout << "1THL ligand (" << atoms.radii.size() << " atoms): " << ses.n_vertices()
            << " vertices, area " << m.area << " A^2, volume " << m.volume << " A^3, chi "
            << m.euler_characteristic << ", " << seconds << " s\n";
  EXPECT_NO_THROW(mesh::require_closed_manifold(ses));
  EXPECT_GT(m.volume, 0.0);
  EXPECT_NEAR(vertex_density(ses), 2.5, 0.3 * 2.5);
  EXPECT_EQ(folded_fraction(ses), 0.0);
}

TEST(Ses, AllThermolysinStructuresGiveClosedSurfaces) {
  for (const std::string name :
       {"ligands-common-frame/1THL_ligand.pdb", "ligands-common-frame/1TLP_ligand.pdb",
        "ligands-common-frame/1TMN_ligand.pdb", "ligands-common-frame/3TMN_ligand.pdb",
        "ligands-common-frame/4TMN_ligand.pdb", "1THL.pdb"}) {
    SURFCOMP_SHARED_OR_SKIP(path, "thermolysin/" + name);
    const Atoms atoms = read_pdb_heavy_atoms(path);
    const auto start = std::chrono::steady_clock::now();
    const mesh::Surface ses = build_ses(atoms.centers, atoms.radii);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const mesh::SurfaceMeasures m = mesh::measure_surface(ses);
    std::cout << name << " (" << atoms.radii.size() << " atoms): " << ses.n_vertices()
              << " vertices, area " << m.area << ", chi " << m.euler_characteristic << ", "
              << seconds << " s\n";
    EXPECT_NO_THROW(mesh::require_closed_manifold(ses)) << name;
    EXPECT_GT(m.volume, 0.0) << name;
    EXPECT_NEAR(vertex_density(ses), 2.5, 0.3 * 2.5) << name;
    EXPECT_LT(folded_fraction(ses), 1e-3) << name;
  }
}

TEST(Ses, Protein4we2) {
  SURFCOMP_FETCHED_OR_SKIP(path, "edtsurf/4we2.pdb");
  const Atoms atoms = read_pdb_heavy_atoms(path);
  const auto start = std::chrono::steady_clock::now();
  const mesh::Surface ses = build_ses(atoms.centers, atoms.radii);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const mesh::SurfaceMeasures m = mesh::measure_surface(ses);
  std::cout << "4we2 (" << atoms.radii.size() << " atoms): " << ses.n_vertices()
            << " vertices, area " << m.area << " A^2, volume " << m.volume << " A^3, chi "
            << m.euler_characteristic << ", " << seconds << " s\n";
  EXPECT_NO_THROW(mesh::require_closed_manifold(ses));
  EXPECT_GT(m.volume, 0.0);
  EXPECT_NEAR(vertex_density(ses), 2.5, 0.3 * 2.5);
  std::cout << "4we2 folded triangles: " << folded_fraction(ses) << "\n";
  EXPECT_LT(folded_fraction(ses), 1e-3);
}

}  // namespace
}  // namespace surfcomp::molsurf
