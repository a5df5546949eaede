// Internal to the molsurf module (not installed): the zero isosurface of a sparse grid as a closed,
// 2-manifold triangle mesh (dual marching cubes), the mesher of build_ses and build_sas.
#pragma once

#include "sparse_grid.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>

namespace surfcomp::molsurf::detail {

/// Triangles before they become a Surface.
struct TriangleSoup {
  Eigen::MatrixX3d positions;  ///< #V by 3, A
  Eigen::MatrixX3i faces;      ///< #F by 3, counter-clockwise seen from outside
};

/// The marching-cubes surface of one cell: which of the cell's 12 edges it crosses and how the
/// crossings join into closed loops, one surface patch (one mesh vertex) per loop. An ambiguous
/// face (inside and outside corners alternating around it) joins its inside corners: its two
/// segments cut off the outside corners. Each loop bounds one disk inside the cell, so two loops
/// never join through the cell's interior.
/// Corner c of the cell lies at offset (c & 1, (c >> 1) & 1, c >> 2). Edge 4a + u + 2v runs along
/// axis a from the corner with offset 0 along a, u along axis (a + 1) % 3 and v along
/// (a + 2) % 3. Face 2a + s is the face at offset s along axis a.
struct CellTopology {
  std::array<int, 12> loop{};  ///< loop of each edge's crossing, -1 for no crossing
  int loops = 0;               ///< number of loops (patches)
  /// Bit f set: face f has four crossings (an ambiguous face) and both of its segments belong
  /// to one loop.
  std::uint8_t one_loop_faces = 0;
  /// The cell's only ambiguous face when it has two or three inside corners and one ambiguous
  /// face; -1 otherwise (see dual_marching_cubes).
  int lone_ambiguous_face = -1;
};

/// The loops of a cell whose corner c is inside (value < 0) iff bit c of `inside` is set: an
/// entry of the 256-case table, which is generated at compile time from the corner signs.
CellTopology cell_topology(std::uint8_t inside);

/// The zero isosurface of `grid` (a node is inside iff its value < 0), node (i, j, k) at
/// (i, j, k) * spacing A, by dual marching cubes (Nielson 2004):
/// each cell gets one vertex per loop of its marching-cubes surface (cell_topology), at the mean
/// of the loop's edge crossings (linear interpolation along each edge), and each grid edge
/// whose ends differ in sign gets the quad of the four loops around it, split along its shorter
/// diagonal. An ambiguous face joins its inside corners (CellTopology), so that a wall of the
/// solid thinner than a voxel stays whole rather than getting a hole, except where it is the only
/// ambiguous face of both cells sharing it and each has two or three inside corners: there both
/// cells take the loops of their complement pattern, which separate the face's inside corners
/// (OpenVDB's rule), and a lone bridge thinner than a voxel is cut. The rule reads the signs of
/// the two cells only, so they agree. It also keeps the mesh 2-manifold: a face whose two
/// segments lie in one loop of a cell is that cell's only ambiguous face with two or three inside
/// corners, so where both cells would put both segments in one loop (and their two loops would
/// share two mesh edges), the face is cut instead.
/// Returns a closed, 2-manifold triangle mesh wound counter-clockwise seen from outside (the
/// positive side), with vertices sorted by coordinates and faces by indices (each face starts
/// at its smallest index); empty when no edge changes sign.
TriangleSoup dual_marching_cubes(const SparseGrid& grid, double spacing);

}  // namespace surfcomp::molsurf::detail
