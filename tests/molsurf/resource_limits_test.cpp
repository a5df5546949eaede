// Resource limits: inputs and options whose cost would be unbounded are refused up front, with
// a message giving the estimate, the limit and the option that raises it; the progress of the
// potentials is reported without changing their values.
#include "atom_balls.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "surfcomp/molsurf/potentials.hpp"
#include "surfcomp/molsurf/ses.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace surfcomp {
namespace {

using test::Atoms;

/// Three overlapping atoms, the last of radius `last_radius`.
Atoms three_atoms(double last_radius = 1.6) {
  Atoms atoms;
  atoms.centers.resize(3, 3);
  atoms.centers << 0, 0, 0, 1.5, 0, 0, 0.7, 1.3, 0;
  atoms.radii.resize(3);
  atoms.radii << 1.7, 1.5, last_radius;
  return atoms;
}

/// Runs `build` and returns the message of the exception E it must throw. The refusals are
/// the estimates' (their messages state the estimate and the limit), which come before any
/// grid or mesh is allocated.
template <class E, class F>
std::string refusal(F build) {
  std::string message;
  try {
    build();
    ADD_FAILURE() << "not refused";
  } catch (const E& e) {
    message = e.what();
  }
  return message;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(SesLimits, AHugeRadiusIsRefusedByTheGridLimit) {
  const Atoms atoms = three_atoms(1000.0);
  const std::string message =
      refusal<InputError>([&] { molsurf::build_ses(atoms.centers, atoms.radii); });
  EXPECT_TRUE(contains(message, "max_grid_cells")) << message;
  EXPECT_TRUE(contains(message, "limit is 2e+08")) << message;
}

TEST(SesLimits, AFineVoxelIsRefusedByTheGridLimit) {
  const Atoms atoms = three_atoms();
  molsurf::SesOptions options;
  options.voxel_size = 0.01;
  const std::string message =
      refusal<InputError>([&] { molsurf::build_ses(atoms.centers, atoms.radii, options); });
  EXPECT_TRUE(contains(message, "max_grid_cells")) << message;
  // The automatic voxel needs a few thousand cells for three atoms.
  options.voxel_size = 0.0;
  options.max_grid_cells = 10.0;
  EXPECT_THROW(molsurf::build_ses(atoms.centers, atoms.radii, options), InputError);
}

TEST(SesLimits, VoxelsAndRadiiBelowTheGridResolutionAreRefused) {
  const Atoms atoms = three_atoms();
  molsurf::SesOptions options;
  options.voxel_size = 1e-6;
  EXPECT_THROW(molsurf::build_ses(atoms.centers, atoms.radii, options), OptionError);
  const Atoms tiny = three_atoms(1e-6);
  const std::string message =
      refusal<InputError>([&] { molsurf::build_ses(tiny.centers, tiny.radii); });
  EXPECT_TRUE(contains(message, "atom 3 has radius 1e-06 A")) << message;
  // The smallest accepted radius passes this check and meets the grid limit instead.
  const Atoms smallest = three_atoms(2.0 * molsurf::min_voxel_size);
  const std::string limit =
      refusal<InputError>([&] { molsurf::build_ses(smallest.centers, smallest.radii); });
  EXPECT_TRUE(contains(limit, "cells of 0.001 A")) << limit;
}

TEST(SesLimits, CentresBeyondTheGridRangeAreRefused) {
  Atoms atoms = three_atoms();
  atoms.centers(1, 2) = 1e30;
  const std::string message =
      refusal<InputError>([&] { molsurf::build_ses(atoms.centers, atoms.radii); });
  EXPECT_TRUE(contains(message, "atom 2 lies 1e+30 A from the origin")) << message;
}

TEST(SesLimits, AtomAndVertexLimits) {
  const Atoms atoms = three_atoms();
  molsurf::SesOptions options;
  options.max_atoms = 2;
  std::string message =
      refusal<InputError>([&] { molsurf::build_ses(atoms.centers, atoms.radii, options); });
  EXPECT_TRUE(contains(message, "3 atoms; the limit is 2 (raise it with max_atoms")) << message;
  options.max_atoms = 3;
  options.max_vertices = 50;
  message = refusal<InputError>([&] { molsurf::build_sas(atoms.centers, atoms.radii, options); });
  EXPECT_TRUE(contains(message, "max_vertices")) << message;
  // The estimate is the grid mesh's area times the density: the result stays near it.
  options.max_vertices = molsurf::SesOptions{}.max_vertices;
  const mesh::Surface ses = molsurf::build_ses(atoms.centers, atoms.radii, options);
  options.max_vertices = static_cast<std::int64_t>(1.5 * static_cast<double>(ses.n_vertices()));
  EXPECT_NO_THROW(molsurf::build_ses(atoms.centers, atoms.radii, options));
  options.max_vertices = 0;
  EXPECT_THROW(molsurf::build_ses(atoms.centers, atoms.radii, options), OptionError);
}

Molecule three_atom_molecule() {
  const Atoms atoms = three_atoms();
  Molecule molecule;
  molecule.source = "three.pqr";
  const std::vector<std::string> elements = {"C", "N", "O"};
  for (Eigen::Index i = 0; i < 3; ++i) {
    Atom atom;
    atom.element = elements[static_cast<std::size_t>(i)];
    atom.name = atom.element;
    atom.position = atoms.centers.row(i).transpose();
    atom.radius = atoms.radii(i);
    atom.charge = 0.3 - 0.2 * static_cast<double>(i);
    atom.lipophilicity = 0.1 * static_cast<double>(i);
    molecule.atoms.push_back(atom);
  }
  return molecule;
}

TEST(ImageLimits, TheImagesAreEstimatedBeforeTheyAreBuilt) {
  const mesh::Surface surface = molsurf::build_molecular_surface(three_atom_molecule());
  harmonic::ImageOptions grid;
  EXPECT_DOUBLE_EQ(harmonic::image_bytes(grid, 10), 10.0 * 16 * 180 * 37);
  // Less than one image of the default grid: refused if the surface has a critical point.
  harmonic::DescriptorOptions options;
  options.max_image_bytes = static_cast<std::int64_t>(harmonic::image_bytes(grid, 1)) - 1;
  const std::string message =
      refusal<InputError>([&] { harmonic::describe_surface(surface, options); });
  EXPECT_TRUE(contains(message, "three.pqr: ")) << message;
  EXPECT_TRUE(contains(message, "16 rings x 180 sectors")) << message;
  EXPECT_TRUE(contains(message, "max_image_bytes")) << message;
  options = harmonic::DescriptorOptions{};
  options.max_image_bytes = 0;
  EXPECT_THROW(harmonic::describe_surface(surface, options), OptionError);
  options.max_image_bytes = 1;
  // Only the points to describe count: none selected, nothing to refuse.
  EXPECT_NO_THROW(harmonic::describe_surface(surface, options,
                                             [](const mesh::CriticalPoint&) { return false; }));
}

TEST(PotentialProgress, ReportsUpToTheTotalAndLeavesTheValuesUnchanged) {
  const Molecule molecule = three_atom_molecule();
  Eigen::MatrixX3d points(5000, 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    points.row(i) << 0.01 * static_cast<double>(i), 3.0, -1.0;
  }
  molsurf::EspOptions esp;
  const Eigen::VectorXd plain = molsurf::electrostatic_potential(points, molecule, esp);
  std::vector<std::int64_t> reported;
  std::int64_t total = 0;
  esp.progress = [&](std::int64_t done, std::int64_t all) {
    reported.push_back(done);
    total = all;
  };
  const Eigen::VectorXd watched = molsurf::electrostatic_potential(points, molecule, esp);
  EXPECT_EQ(watched, plain);
  ASSERT_FALSE(reported.empty());
  EXPECT_EQ(total, points.rows());
  EXPECT_EQ(reported.back(), points.rows());
  EXPECT_LE(reported.size(), 101U);
  for (std::size_t k = 1; k < reported.size(); ++k) EXPECT_GT(reported[k], reported[k - 1]);

  molsurf::LpOptions lp;
  int calls = 0;
  lp.progress = [&](std::int64_t, std::int64_t) { ++calls; };
  EXPECT_EQ(molsurf::lipophilic_potential(points, molecule, lp),
            molsurf::lipophilic_potential(points, molecule));
  EXPECT_GT(calls, 0);
}

}  // namespace
}  // namespace surfcomp
