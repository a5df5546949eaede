// build_ses with SesMethod::distance_transform: its vertices against the exact SES (analytic for
// one and two atoms, the exact field of sas_geometry for a protein), its topology, and its
// determinism.
#include "atom_balls.hpp"
#include "sas_geometry.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/ses.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace surfcomp::molsurf {
namespace {

using test::Atoms;
using test::make_atoms;

SesOptions transform_options() {
  SesOptions options;
  options.method = SesMethod::distance_transform;
  return options;
}

/// The region of one ball.
SesRegion one_ball(const Eigen::Vector3d& center, double radius) {
  SesRegion region;
  region.centers = center.transpose();
  region.radii = Eigen::VectorXd::Constant(1, radius);
  return region;
}

/// |exact SES value| at each vertex: the distance to the exact surface, to first order.
struct Deviation {
  double mean = 0.0;
  double max = 0.0;
};

Deviation ses_deviation(const mesh::Surface& surface, const Atoms& atoms, double probe) {
  const detail::SasGeometry sas(atoms.centers, atoms.radii, probe);
  detail::SasGeometry::Candidates candidates;
  Deviation out;
  const Eigen::MatrixX3d p = surface.positions();
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    const Eigen::Vector3d x = p.row(v).transpose();
    const double clamp = 5.0;
    sas.gather(x, 0.0, probe + clamp, candidates);
    const double d = std::abs(sas.ses_value(x, clamp, candidates));
    out.mean += d;
    out.max = std::max(out.max, d);
  }
  out.mean /= static_cast<double>(p.rows());
  return out;
}

TEST(SesDistanceTransform, OneAtomIsItsVanDerWaalsSphere) {
  const double r = 1.7;
  const Atoms atom = make_atoms({Eigen::Vector3d(0.3, -0.2, 0.1)}, {r});
  const mesh::Surface ses = build_ses(atom.centers, atom.radii, transform_options());
  ASSERT_NO_THROW(mesh::require_closed_manifold(ses));
  const mesh::SurfaceMeasures m = mesh::measure_surface(ses);
  EXPECT_EQ(m.euler_characteristic, 2);
  const Eigen::MatrixX3d p = ses.positions();
  const Eigen::MatrixX3d n = ses.normals();
  double worst = 0.0, worst_normal = 1.0;
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    const Eigen::Vector3d radial = p.row(v) - atom.centers.row(0);
    worst = std::max(worst, std::abs(radial.norm() - r));
    worst_normal = std::min(worst_normal, radial.normalized().dot(n.row(v)));
  }
  const double area = 4.0 * M_PI * r * r;
  std::cout << "one atom, distance transform: " << ses.n_vertices() << " vertices, area " << m.area
            << " (exact " << area << "), largest |r - " << r << "| " << worst
            << " A, smallest normal . radial " << worst_normal << "\n";
  EXPECT_LT(worst, 0.07);
  EXPECT_GT(worst_normal, 0.96);
  EXPECT_NEAR(m.area, area, 0.03 * area);  // chord triangles, no compensation
}

TEST(SesDistanceTransform, TwoAtomsFollowTheTorus) {
  const double r1 = 1.7, r2 = 1.5, d = 2.5, probe = 1.4;
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 0.4, -0.7).normalized();
  const Eigen::Vector3d c1(0.1, 0.2, 0.3);
  const Atoms atoms = make_atoms({c1, c1 + d * axis}, {r1, r2});
  const mesh::Surface ses = build_ses(atoms.centers, atoms.radii, transform_options());
  ASSERT_NO_THROW(mesh::require_closed_manifold(ses));
  const mesh::SurfaceMeasures m = mesh::measure_surface(ses);
  const double exact = test::two_atom_ses(r1, r2, d, probe).area;
  const Deviation off = ses_deviation(ses, atoms, probe);
  std::cout << "two atoms, distance transform: area " << m.area << " (analytic " << exact
            << "), |SES value| at the vertices mean " << off.mean << " max " << off.max << " A\n";
  EXPECT_EQ(m.euler_characteristic, 2);
  EXPECT_NEAR(m.area, exact, 0.03 * exact);
  EXPECT_LT(off.mean, 0.035);
  EXPECT_LT(off.max, 0.18);
}

TEST(SesDistanceTransform, ZeroProbeGivesTheVanDerWaalsSurface) {
  SesOptions options = transform_options();
  options.probe_radius = 0.0;
  const Atoms atoms =
      make_atoms({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2.0, 0.3, 0)}, {1.7, 1.5});
  const mesh::Surface ses = build_ses(atoms.centers, atoms.radii, options);
  ASSERT_NO_THROW(mesh::require_closed_manifold(ses));
  const Deviation off = ses_deviation(ses, atoms, 0.0);
  std::cout << "van der Waals surface, distance transform: |value| mean " << off.mean << " max "
            << off.max << " A\n";
  EXPECT_LT(off.mean, 0.02);
  EXPECT_LT(off.max, 0.2);
}

TEST(SesDistanceTransform, DeterministicAndARegionHoldingTheMoleculeChangesNothing) {
  const Atoms atoms = make_atoms(
      {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.4, 0.2, 0), Eigen::Vector3d(2.1, 1.4, 0.3),
       Eigen::Vector3d(3.5, 1.5, -0.2), Eigen::Vector3d(4.3, 0.3, 0.1)},
      {1.7, 1.7, 1.52, 1.7, 1.55});
  const mesh::Surface first = build_ses(atoms.centers, atoms.radii, transform_options());
  mesh::Surface serial;
  {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    serial = build_ses(atoms.centers, atoms.radii, transform_options());
  }
  EXPECT_TRUE(first.positions() == serial.positions());
  EXPECT_TRUE(first.faces() == serial.faces());
  const SesRegion big = one_ball(Eigen::Vector3d(2.0, 0.5, 0.0), 12.0);
  const mesh::Surface inside = build_ses(atoms.centers, atoms.radii, big, transform_options());
  EXPECT_TRUE(first.positions() == inside.positions());
  EXPECT_TRUE(first.faces() == inside.faces());
}

TEST(SesDistanceTransform, ARegionReadsTheProbesReachBeyondIt) {
  // A probe of 12 voxels: the field inside the region depends on the outside of U up to a probe
  // radius beyond the region's box, which the dense box must hold.
  SesOptions options = transform_options();
  options.probe_radius = 3.0;
  options.voxel_size = 0.25;
  const Atoms atoms =
      make_atoms({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3.6, 0.4, 0)}, {1.7, 1.5});
  const SesRegion holding = one_ball(Eigen::Vector3d(1.8, 0.2, 0.0), 4.5);
  const mesh::Surface whole = build_ses(atoms.centers, atoms.radii, options);
  const mesh::Surface inside = build_ses(atoms.centers, atoms.radii, holding, options);
  EXPECT_TRUE(whole.positions() == inside.positions());
  EXPECT_TRUE(whole.faces() == inside.faces());
  const SesRegion far = one_ball(Eigen::Vector3d(1e12, 0.0, 0.0), 1.0);
  EXPECT_THROW(build_ses(atoms.centers, atoms.radii, far, options), InputError);
}

TEST(SesDistanceTransform, ARegionCutsTheSurface) {
  // One atom cut by a ball through its centre: the lens of the sphere and the ball.
  const Atoms atom = make_atoms({Eigen::Vector3d(0, 0, 0)}, {1.7});
  const SesRegion half = one_ball(Eigen::Vector3d(3.0, 0.0, 0.0), 3.0);
  const mesh::Surface lens = build_ses(atom.centers, atom.radii, half, transform_options());
  ASSERT_NO_THROW(mesh::require_closed_manifold(lens));
  const Eigen::MatrixX3d p = lens.positions();
  double worst = 0.0;
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    const Eigen::Vector3d x = p.row(v).transpose();
    const double on_atom = std::abs(x.norm() - 1.7);
    const double on_ball = std::abs((x - Eigen::Vector3d(3, 0, 0)).norm() - 3.0);
    worst = std::max(worst, std::min(on_atom, on_ball));
  }
  std::cout << "lens, distance transform: " << lens.n_vertices() << " vertices, farthest " << worst
            << " A from both spheres\n";
  EXPECT_LT(worst, 0.12);
}

TEST(SesDistanceTransform, ADenseBoxOverTheLimitIsRefusedFirst) {
  // Two atoms 170 A apart along a diagonal: the sparse grid is small, the dense box about 4.6e6
  // nodes of 0.68 A.
  const Atoms atoms =
      make_atoms({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(100.0, 100.0, 100.0)}, {1.7, 1.7});
  SesOptions options = transform_options();
  options.max_grid_cells = 1e6;
  try {
    build_ses(atoms.centers, atoms.radii, options, "far.pdb");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("far.pdb: the distance transform's grid would span"),
              std::string::npos)
        << e.what();
  }
  options.method = SesMethod::exact;
  EXPECT_NO_THROW(build_ses(atoms.centers, atoms.radii, options, "far.pdb"));
}

TEST(SesDistanceTransform, Protein4we2NearTheExactSurface) {
  SURFCOMP_FETCHED_OR_SKIP(path, "edtsurf/4we2.pdb");
  const Atoms atoms = test::read_pdb_heavy_atoms(path);
  const mesh::Surface exact = build_ses(atoms.centers, atoms.radii);
  const mesh::Surface fast = build_ses(atoms.centers, atoms.radii, transform_options());
  ASSERT_NO_THROW(mesh::require_closed_manifold(fast));
  const mesh::SurfaceMeasures e = mesh::measure_surface(exact);
  const mesh::SurfaceMeasures f = mesh::measure_surface(fast);
  const Deviation off = ses_deviation(fast, atoms, 1.4);
  std::cout << "4we2: exact area " << e.area << " volume " << e.volume << "; distance transform "
            << f.area << ", " << f.volume << "; |SES value| at its vertices mean " << off.mean
            << " max " << off.max << " A\n";
  // The grid misses the crevices of U's outside thinner than a voxel, where the probe's centre
  // fits: the surface bridges them (more volume, less area), as EDTSurf's does.
  EXPECT_NEAR(f.volume, e.volume, 0.07 * e.volume);
  EXPECT_NEAR(f.area, e.area, 0.13 * e.area);
  EXPECT_LT(off.mean, 0.18);
}

}  // namespace
}  // namespace surfcomp::molsurf
