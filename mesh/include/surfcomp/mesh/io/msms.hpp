// MSMS surface files: X.vert (vertices with normals) and X.face (1-based triangles).
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <filesystem>

namespace surfcomp::mesh::io {

/// Reads the MSMS pair X.vert / X.face; `path` may name either file or the base X.
/// - .vert lines: `x y z nx ny nz [face_number sphere_index type]` (A; the normals become the
///   Surface normals, position_type and normal_type stay float64).
/// - .face lines: `v1 v2 v3 [type sphere]`, 1-based vertex numbers.
/// Either file may start with MSMS's header: comment lines beginning with '#' followed by one
/// count line (`count n_spheres density probe_radius`); the count must then equal the number of
/// data lines. Blank lines are skipped.
/// Throws FileError if a file cannot be read; FormatError for an X.face without faces ("a
/// point cloud"), or ("file:line: expected ..., found ...") for a malformed line, a non-finite
/// coordinate or normal, a vertex number outside 1..#V, or a header count that disagrees with the
/// data; TopologyError from Surface::from_arrays for faces that do not form a manifold mesh.
Surface read_msms(const std::filesystem::path& path);

}  // namespace surfcomp::mesh::io
