// The check every mesh reader applies to the surface it has read (private to the readers).
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <string>

namespace surfcomp::mesh::io::detail {

/// Checks what `file` gave: every vertex position finite and within
/// surfcomp::io::max_coordinate_magnitude, every normal component and every vertex property
/// value finite. Throws FormatError naming `file`, the vertex (0-based) and, for a property,
/// its name ("x.ply: vertex 12 has a non-finite property 'charge' (nan)").
void check_read_surface(const Surface& surface, const std::string& file);

}  // namespace surfcomp::mesh::io::detail
