// Adjacency queries on a Surface: the one-ring of a vertex and the connected components.
// Vertex and face indices are those of Surface::positions() and Surface::faces().
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <vector>

namespace surfcomp::mesh {

/// The vertices that share an edge with `vertex`, each once, counter-clockwise around it seen
/// from outside (the side the faces' counter-clockwise order points to). At a boundary vertex
/// the list runs across the surface from one boundary neighbour to the other; where several fans
/// of triangles meet at the vertex it runs fan by fan; a vertex in no triangle has none. Throws
/// InputError (naming surface.source()) for a vertex out of range.
std::vector<int> one_ring_vertices(const Surface& surface, int vertex);

/// The faces that hold `vertex`, each once, in the order of one_ring_vertices: where the
/// triangles at the vertex form one fan, face i is the triangle of `vertex` and ring vertices i
/// and i + 1 (cyclically unless the vertex is on the boundary). Throws InputError for a vertex
/// out of range.
std::vector<int> one_ring_faces(const Surface& surface, int vertex);

/// The connected components of a surface: two vertices are in one component when a path of
/// edges joins them; a vertex in no triangle is a component of its own.
struct SurfaceComponents {
  int count = 0;               ///< number of components; 0 for an empty surface
  std::vector<int> component;  ///< #V: each vertex's component, 0..count-1, numbered in the
                               ///< order of their lowest vertex index
};
SurfaceComponents connected_components(const Surface& surface);

/// One flag per vertex: true for a vertex on the surface's own border (an edge of one
/// triangle only), as on a cut or partial mesh; all false for a closed surface.
std::vector<bool> border_vertices(const Surface& surface);

}  // namespace surfcomp::mesh
