// The check every mesh reader applies to the surface it has read (private to the readers).
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <cstddef>
#include <string>

namespace surfcomp::mesh::io::detail {

/// Checks what `file` gave: every vertex position finite and within
/// surfcomp::io::max_coordinate_magnitude, every normal component and every vertex property
/// value finite. Throws FormatError naming `file`, the vertex (0-based) and, for a property,
/// its name ("x.ply: vertex 12 has a non-finite property 'charge' (nan)").
void check_read_surface(const Surface& surface, const std::string& file);

/// Checks that `file` gave triangles: throws FormatError "FILE: a point cloud (N vertices, no
/// faces); surfcomp needs a triangle mesh: ..." when it gave vertices and no triangle, and
/// "FILE: no vertices and no faces; ..." when it gave neither.
void check_has_triangles(std::size_t n_vertices, std::size_t n_triangles, const std::string& file);

}  // namespace surfcomp::mesh::io::detail
