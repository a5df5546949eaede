// Repair of real meshes (CGAL Polygon Mesh Processing): duplicate vertices merged, degenerate
// and duplicate faces removed, non-manifold vertices split, borders stitched, faces oriented
// outward, the largest component kept. `--repair` on the command line, repair=True in Python.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace surfcomp::mesh {

/// What repair_triangles and repair_mesh_file changed, in counts.
struct RepairReport {
  std::size_t merged_vertices = 0;     ///< duplicate points merged, unused points dropped
  std::size_t removed_faces = 0;       ///< degenerate or duplicate faces removed
  std::size_t split_vertices = 0;      ///< copies made of non-manifold vertices
  std::size_t stitched_edges = 0;      ///< pairs of border edges stitched into one edge
  std::size_t dropped_components = 0;  ///< components other than the largest, removed
  bool reoriented = false;             ///< a closed mesh turned inside out, faces flipped
  /// The changes as one line ("merged or dropped 12 duplicate or unused vertices, removed 3
  /// degenerate or duplicate faces"), or "nothing to repair".
  std::string summary() const;
};

/// The note a front end prints for a repaired input: "SOURCE: repaired: <summary>".
std::string repair_note(const std::string& source, const RepairReport& report);

/// A repaired mesh and what the repair changed.
struct RepairedMesh {
  Surface surface;  ///< 2-manifold triangles, no vertex properties, named `source`
  RepairReport report;
};

/// Repairs a triangle soup (#V by 3 positions, #F by 3 0-based indices) with CGAL's Polygon
/// Mesh Processing: repair_polygon_soup (duplicate points merged, degenerate and duplicate
/// faces removed, unused points dropped), orient_polygon_soup (non-manifold vertices split so that
/// the faces can be oriented consistently), stitch_borders, remove_degenerate_faces (zero-area
/// triangles), keep_largest_connected_components, and a closed result turned outward. Throws
/// InputError naming `source` for an index out of range, a non-finite coordinate, or nothing left.
RepairedMesh repair_triangles(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                              const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                              const std::string& source);

/// Reads the geometry of a mesh file (io::mesh_extensions(io::MeshUse::repair): .ply .stl .off
/// .obj; polygons triangulated; vertex properties are not kept) as a soup (STL with
/// io::read_stl's reader, the others with CGAL's) and repairs it (repair_triangles).
/// Throws InputError naming the file when it cannot be read as one, holds more than
/// `max_vertices` points, or has another extension; FormatError ("FILE: vertex I has coordinate
/// ...") for a coordinate beyond surfcomp::io::max_coordinate_magnitude or not finite, and for a
/// malformed STL file.
RepairedMesh repair_mesh_file(const std::filesystem::path& path, std::size_t max_vertices);

}  // namespace surfcomp::mesh
