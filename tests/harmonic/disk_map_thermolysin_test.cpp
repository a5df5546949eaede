// Harmonic disk maps of real patches: the critical-point patches of the 1THL ligand's SES
// (method §3-4) mapped by harmonic_disk_map and by CGAL's parameterizers must agree for
// every weight kind, and the maps with positive weights must not fold.
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/harmonic/cgal_reference.hpp"
#include "surfcomp/harmonic/disk_map.hpp"
#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/mesh/patch.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace surfcomp::harmonic {
namespace {

TEST(DiskMapThermolysinTest, CriticalPointPatchesOf1thlAgreeWithCgalAndDoNotFold) {
  SURFCOMP_SHARED_OR_SKIP(file, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  const mesh::Surface surface = molsurf::build_molecular_surface(io::read_molecule(file));
  const std::vector<mesh::CriticalPoint> critical_points = mesh::detect_critical_points(surface);
  ASSERT_GE(critical_points.size(), 6u);
  // Every fourth critical point, peaks and valleys alike: a spread over the whole ligand.
  int mapped = 0;
  for (std::size_t c = 0; c < critical_points.size(); c += 4) {
    const mesh::Patch patch = mesh::extract_patch(surface, critical_points[c].vertex);
    if (patch.genus != 0) continue;  // a tunnel: not a disk, the harmonic map does not apply
    ++mapped;
    for (const SpringWeights weights : {SpringWeights::inverse_length, SpringWeights::uniform,
                                        SpringWeights::cotangent, SpringWeights::mean_value}) {
      SCOPED_TRACE("critical point " + std::to_string(c) + ", " + to_string(weights));
      const DiskMap ours =
          harmonic_disk_map(patch.positions, patch.faces, patch.outer_boundary, {weights});
      const DiskMap cgal =
          cgal_disk_map(patch.positions, patch.faces, patch.outer_boundary, {weights});
      const double distance = (ours.uv - cgal.uv).rowwise().norm().maxCoeff();
      const int flipped = count_flipped_triangles(ours.uv, patch.faces);
      std::cout << "1THL critical point " << c << " (vertex " << critical_points[c].vertex << ", "
                << patch.positions.rows() << " vertices, " << patch.holes.size() << " holes), "
                << to_string(weights) << ": max |ours - CGAL| = " << distance
                << ", flipped triangles " << flipped << "\n";
      EXPECT_LE(distance, 1e-6);
      if (weights != SpringWeights::cotangent) {
        EXPECT_EQ(flipped, 0);
      }
      for (const int v : patch.outer_boundary) EXPECT_NEAR(ours.uv.row(v).norm(), 1.0, 1e-12);
    }
  }
  EXPECT_GE(mapped, 2);
}

}  // namespace
}  // namespace surfcomp::harmonic
