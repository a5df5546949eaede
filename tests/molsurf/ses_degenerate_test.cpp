// Degenerate but valid SES inputs: a zero probe (the van der Waals surface, whose re-entrant
// patches shrink to creases and corners) and atoms repeated at one position.
#include "atom_balls.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/ses.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

namespace surfcomp::molsurf {
namespace {

using test::Atoms;
using test::make_atoms;

SesOptions zero_probe() {
  SesOptions options;
  options.probe_radius = 0.0;
  return options;
}

TEST(SesZeroProbe, OneAtomIsItsSphere) {
  const double r = 1.7;
  SesOptions options = zero_probe();
  options.compensate_chords = false;
  const Atoms atom = make_atoms({Eigen::Vector3d(0.5, -1.0, 2.0)}, {r});
  const mesh::Surface ses = build_ses(atom.centers, atom.radii, options);
  const Eigen::MatrixX3d p = ses.positions();
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    ASSERT_NEAR((p.row(v) - atom.centers.row(0)).norm(), r, 1e-12);
  }
  EXPECT_EQ(mesh::measure_surface(ses).euler_characteristic, 2);
}

TEST(SesZeroProbe, ClustersHaveFiniteVerticesAndTheUnionArea) {
  // Three and four mutually overlapping atoms: their van der Waals surface has creases (two
  // spheres meet) and corners (three meet), where the re-entrant curvature -1/probe of a
  // positive probe is unbounded; no vertex may become non-finite there.
  const std::vector<Atoms> clusters = {
      make_atoms({{0, 0, 0}, {1.5, 0, 0}, {0.7, 1.3, 0}}, {1.7, 1.5, 1.6}),
      make_atoms({{0, 0, 0}, {1.5, 0, 0}, {0.7, 1.3, 0}, {0.7, 0.5, 1.3}}, {1.7, 1.5, 1.6, 1.2}),
  };
  for (const Atoms& atoms : clusters) {
    const mesh::Surface ses = build_ses(atoms.centers, atoms.radii, zero_probe());
    ASSERT_TRUE(ses.positions().allFinite());
    const mesh::SurfaceMeasures m = mesh::measure_surface(ses);
    const double exact = test::union_area(atoms, 0.0, 200000);
    std::cout << atoms.centers.rows() << " atoms, zero probe: area " << m.area << " (union "
              << exact << ")\n";
    EXPECT_EQ(m.euler_characteristic, 2);
    EXPECT_NEAR(m.area, exact, 0.01 * exact);
  }
}

TEST(SesCoincidentAtoms, RepeatedAtomsGiveTheSurfaceOfOne) {
  const Eigen::Vector3d c(1.0, 2.0, -0.5);
  const double r = 1.7;
  const Atoms one = make_atoms({c}, {r});
  for (const double probe : {1.4, 0.0}) {
    SesOptions options;
    options.probe_radius = probe;
    const mesh::Surface reference = build_ses(one.centers, one.radii, options);
    for (const int copies : {2, 3}) {
      const Atoms repeated =
          make_atoms(std::vector<Eigen::Vector3d>(static_cast<std::size_t>(copies), c),
                     std::vector<double>(static_cast<std::size_t>(copies), r));
      const mesh::Surface ses = build_ses(repeated.centers, repeated.radii, options);
      EXPECT_EQ(ses.positions(), reference.positions()) << copies << " copies, probe " << probe;
      EXPECT_EQ(ses.faces(), reference.faces()) << copies << " copies, probe " << probe;
    }
  }
}

TEST(SesCoincidentAtoms, ARepeatedAtomInAMoleculeChangesNothing) {
  const Atoms atoms = make_atoms({{0, 0, 0}, {1.5, 0, 0}, {0.7, 1.3, 0}}, {1.7, 1.5, 1.6});
  const Atoms repeated =
      make_atoms({{0, 0, 0}, {1.5, 0, 0}, {0.7, 1.3, 0}, {1.5, 0, 0}}, {1.7, 1.5, 1.6, 1.5});
  const mesh::Surface reference = build_ses(atoms.centers, atoms.radii);
  const mesh::Surface ses = build_ses(repeated.centers, repeated.radii);
  EXPECT_EQ(ses.positions(), reference.positions());
  EXPECT_EQ(ses.faces(), reference.faces());
  // A coincident atom of another radius is a different ball: the smaller lies inside.
  const Atoms nested = make_atoms({{0, 0, 0}, {0, 0, 0}}, {1.7, 1.2});
  const mesh::SurfaceMeasures m = mesh::measure_surface(build_sas(nested.centers, nested.radii));
  const double big = 1.7 + SesOptions{}.probe_radius;
  EXPECT_NEAR(m.area, 4.0 * M_PI * big * big, 0.01 * 4.0 * M_PI * big * big);
}

}  // namespace
}  // namespace surfcomp::molsurf
