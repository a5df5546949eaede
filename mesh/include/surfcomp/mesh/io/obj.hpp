// Wavefront OBJ geometry: `v` and `f` lines, nothing else.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <filesystem>

namespace surfcomp::mesh::io {

/// Reads the geometry of an OBJ file: `v x y z [w | r g b]` lines (A; w and colours ignored)
/// and `f` lines whose corners are `a`, `a/b`, `a//c` or `a/b/c` with 1-based vertex numbers
/// (negative numbers count back from the last vertex read so far). A polygon with more than
/// three corners is split into a fan of triangles (a1, ak, ak+1); fewer than three is an error.
/// Every other statement (vn, vt, g, o, s, usemtl, mtllib, l, p...) and '#' comments are
/// ignored.
/// Throws FileError if the file cannot be read; FormatError ("FILE: a point cloud (N vertices,
/// no faces); ...") for vertices without faces, and ("file:line: expected ..., found ...") for a
/// malformed v or f line, a non-finite coordinate or a vertex number out of range; TopologyError
/// from Surface::from_arrays for a non-manifold mesh.
Surface read_obj(const std::filesystem::path& path);

/// Writes positions (shortest text that reads back to the same double) and triangles of `s`
/// as OBJ `v` and `f` lines, atomically (io::write_file_atomically). Throws FileError if
/// writing fails.
void write_obj(const Surface& s, const std::filesystem::path& path);

}  // namespace surfcomp::mesh::io
