// The triangles of an STL file with their corners welded, shared by read_stl and --repair
// (repair_mesh_file). Private to the mesh module.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace surfcomp::mesh::io::detail {

/// Welded STL triangles: every distinct corner once, in order of first appearance.
struct StlSoup {
  std::vector<double> positions;  ///< 3 per vertex (x y z), A, float32 values
  std::vector<int> triangles;     ///< 3 per triangle, 0-based, in the file's order
};

/// The triangles of the STL file whose whole content is `data`; `name` names it in messages.
/// Throws FormatError as read_stl does for a malformed file (coordinate magnitudes are not
/// checked here).
StlSoup read_stl_soup(std::string_view data, const std::string& name);

}  // namespace surfcomp::mesh::io::detail
