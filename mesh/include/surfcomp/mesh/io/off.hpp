// OFF (Object File Format) geometry: positions and polygons, nothing else.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <filesystem>

namespace surfcomp::mesh::io {

/// Reads an OFF file: the keyword "OFF" (alone or followed by the counts on the same line),
/// `#V #F #E`, #V lines `x y z` (A), #F lines `n i1 ... in [colour...]` with 0-based indices.
/// A polygon with n > 3 is split into a fan of triangles (i1, ik, ik+1); n < 3 is an error.
/// '#' starts a comment; blank lines are skipped; nothing but comments may follow the faces.
/// Throws FileError if the file cannot be read; FormatError ("FILE: a point cloud (N vertices,
/// no faces); ...") for vertices without faces, and ("file:line: expected ..., found ...") for a
/// malformed line, counts the file cannot hold, a non-finite coordinate or an index out of range;
/// TopologyError from Surface::from_arrays for a non-manifold mesh.
Surface read_off(const std::filesystem::path& path);

/// Writes positions (shortest text that reads back to the same double) and triangles of `s`
/// as OFF, atomically (io::write_file_atomically). Throws FileError if writing fails.
void write_off(const Surface& s, const std::filesystem::path& path);

}  // namespace surfcomp::mesh::io
