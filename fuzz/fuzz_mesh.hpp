// What the mesh-reader harnesses (fuzz_ply, fuzz_msms, fuzz_off, fuzz_obj) check after a read.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace surfcomp::fuzz {

/// Aborts (a finding) when a surface read without error breaks the readers' promises: finite
/// positions and normals, every face index a vertex.
inline void check_surface(const mesh::Surface& surface) {
  const Eigen::MatrixX3i faces = surface.faces();
  const auto n = static_cast<int>(surface.n_vertices());
  const bool finite =
      surface.positions().allFinite() && (!surface.has_normals() || surface.normals().allFinite());
  const bool indices_valid = faces.size() == 0 || (faces.minCoeff() >= 0 && faces.maxCoeff() < n);
  if (!finite || !indices_valid) {
    std::fprintf(stderr, "a mesh reader returned %s without an error\n",
                 finite ? "a face index out of range" : "a non-finite position or normal");
    std::abort();
  }
}

}  // namespace surfcomp::fuzz
