// Simplification of a surface for display (the HTML report draws at most a vertex budget per
// surface): OpenMesh's Decimater with the quadric error metric (Garland & Heckbert 1997), by
// halfedge collapses only, so that every vertex kept is a vertex of the input with its own
// position, normal and properties.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <cstddef>
#include <vector>

namespace surfcomp::mesh {

/// A simplified surface and where its vertices come from.
struct DecimatedSurface {
  Surface surface;
  /// One per vertex of `surface`: its index in the input surface.
  std::vector<int> original;
};

/// `surface` with at most `max_vertices` vertices: unchanged when it has no more; otherwise
/// collapsed in order of least quadric error until it has max_vertices, or until no collapse
/// keeps the mesh a 2-manifold (then it keeps more). Properties, their stored types, normals
/// and the source follow the vertices. Throws OptionError when max_vertices < 4.
DecimatedSurface decimate(const Surface& surface, std::size_t max_vertices);

}  // namespace surfcomp::mesh
