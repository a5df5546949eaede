// Makes a small .hsi seed for fuzz_hsi from a mesh file: the surface's curvature properties,
// then critical points, patches, maps and 4 x 8 images (scripts/fuzz.sh runs it on
// seeds/off/bumpy_sphere.off).
// usage: make_hsi_seed MESH OUT.hsi
#include "surfcomp/core/error.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_hsi_seed MESH OUT.hsi\n");
    return 2;
  }
  try {
    surfcomp::mesh::Surface surface = surfcomp::mesh::io::read_mesh(argv[1]);
    surfcomp::molsurf::assign_surface_properties(surface, nullptr);
    surfcomp::harmonic::DescriptorOptions options;
    options.image.rings = 4;
    options.image.sectors = 8;
    const auto descriptors = surfcomp::harmonic::describe_surface(std::move(surface), options);
    surfcomp::harmonic::io::write_hsi(descriptors, argv[2]);
    std::printf("%s: %zu critical points\n", argv[2], descriptors.critical_points.size());
  } catch (const surfcomp::Error& e) {
    std::fprintf(stderr, "make_hsi_seed: %s\n", e.what());
    return 1;
  }
  return 0;
}
