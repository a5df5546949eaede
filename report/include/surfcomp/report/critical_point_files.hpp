// The shape critical points of a surface as files: a JSON document (every field of each point),
// PDB HETATM records and a PLY point cloud for viewing. `surfcomp cp-detect` and the Python
// module write them with these functions.
#pragma once

#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace surfcomp::report {

/// The critical points of one input and how they were found.
struct CriticalPointSet {
  std::string input;                        ///< the input's name (a path)
  mesh::CriticalPointOptions options;       ///< r_cp and the property disc radius used
  std::size_t surface_vertices = 0;         ///< vertices of the surface they lie on
  std::vector<mesh::CriticalPoint> points;  ///< in detection order (their indices)
  /// The length of the input's coordinates that the radii count as 1 A (a general mesh's
  /// length unit); written as parameters.length_unit when not 1.
  double length_unit = 1.0;
};

/// The JSON document, indented by two spaces, ending with a newline: input, parameters (radius,
/// disc_radius, in A or in units of length_unit), surface_vertices, peaks, valleys and
/// critical_points (index, type, vertex, position, normal, cc1, cc2, shape_index, curvedness, esp,
/// lp).
std::string critical_points_json(const CriticalPointSet& set);

/// HETATM records, one per point (name PK or VL, residue CPK or CVL, B-factor = cc1), then END.
void write_critical_points_pdb(const std::vector<mesh::CriticalPoint>& points, std::ostream& out);

/// The points as a surface without faces: positions, normals, a `type` property (0 peak,
/// 1 valley, uint8) and cc1, for a PLY point cloud.
mesh::Surface critical_points_cloud(const std::vector<mesh::CriticalPoint>& points);

/// Writes `set` to `path` in the format its extension names: .json, .pdb or .ply (ASCII).
/// Atomic: nothing is left at `path` when writing fails (FileError). InputError for another
/// extension.
void write_critical_points(const std::filesystem::path& path, const CriticalPointSet& set);

}  // namespace surfcomp::report
