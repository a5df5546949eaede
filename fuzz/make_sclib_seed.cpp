// Makes a small screening library as fuzz_sclib's seed, with one entry of each kind the format
// holds: a molecule (MDL text, surface sample, heteroatoms), a binding site (PDB text, spheres)
// and an entry made from a .hsi file (its described surface as .hsi bytes). The samples come
// from a mesh with its curvature properties and zero ESP and LP (scripts/fuzz.sh runs it on
// seeds/off/bumpy_sphere.off).
// usage: make_sclib_seed MESH OUT.sclib
#include "surfcomp/core/error.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "surfcomp/screening/library.hpp"

#include <cstdio>
#include <vector>

namespace {

constexpr const char* kWater =
    "water\n  seed\n\n  3  2  0  0  0  0  0  0  0  0999 V2000\n"
    "    0.0000    0.0000    0.0000 O   0  0  0  0  0  0  0  0  0  0  0  0\n"
    "    0.9572    0.0000    0.0000 H   0  0  0  0  0  0  0  0  0  0  0  0\n"
    "   -0.2400    0.9266    0.0000 H   0  0  0  0  0  0  0  0  0  0  0  0\n"
    "  1  2  1  0\n  1  3  1  0\nM  END\n";

constexpr const char* kSite =
    "ATOM      1  N   ALA A   1       0.000   0.000   0.000  1.00  0.00           N\n"
    "ATOM      2  CA  ALA A   1       1.458   0.000   0.000  1.00  0.00           C\nEND\n";

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_sclib_seed MESH OUT.sclib\n");
    return 2;
  }
  namespace sc = surfcomp;
  try {
    sc::mesh::Surface surface = sc::mesh::io::read_mesh(argv[1]);
    sc::molsurf::assign_surface_properties(surface, nullptr);
    const auto n = static_cast<Eigen::Index>(surface.n_vertices());
    surface.set_property(sc::mesh::property::esp, Eigen::VectorXd::Zero(n));
    surface.set_property(sc::mesh::property::lp, Eigen::VectorXd::Zero(n));
    const sc::matching::SurfaceSample sample = sc::matching::sample_surface(surface, 1.5);

    std::vector<sc::screening::LibraryEntry> entries(3);
    sc::screening::LibraryEntry& molecule = entries[0];
    molecule.info = {"water", "seed.sdf", 1, 0, 1, 0};
    molecule.molecule.text = kWater;
    molecule.sample = sample;
    molecule.atoms.elements = {"O"};
    molecule.atoms.points = Eigen::Matrix3Xd::Zero(3, 1);

    sc::screening::LibraryEntry& site = entries[1];
    site.info = {"site", "seed.txt", 1, 0, 2, 1};
    site.molecule.format = sc::io::RecordFormat::structure;
    site.molecule.text = kSite;
    site.sample = sample;
    site.site = {{Eigen::Vector3d(0.7, 0.0, 0.0), 4.0}};

    sc::harmonic::DescriptorOptions options;
    options.image.rings = 4;
    options.image.sectors = 8;
    sc::harmonic::SurfaceDescriptors described = sc::harmonic::describe_surface(surface, options);
    described.critical_points.clear();
    sc::screening::LibraryEntry& from_hsi = entries[2];
    from_hsi.info = {"described", "seed.hsi", 1, 0, 0, 0};
    from_hsi.molecule.text = kWater;
    from_hsi.sample = sample;
    from_hsi.surface = sc::harmonic::io::encode_hsi(described);

    sc::screening::write_library(argv[2], entries, "seed");
    std::printf("%s: %zu entries\n", argv[2], entries.size());
  } catch (const sc::Error& e) {
    std::fprintf(stderr, "make_sclib_seed: %s\n", e.what());
    return 1;
  }
  return 0;
}
