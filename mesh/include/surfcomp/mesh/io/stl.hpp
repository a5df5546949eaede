// STL (stereolithography) triangles, binary or ASCII: a triangle soup welded into a mesh.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <filesystem>
#include <istream>
#include <string>

namespace surfcomp::mesh::io {

/// Reads an STL file, binary or ASCII.
/// - Binary: an 80-byte header, a little-endian uint32 triangle count M, then M records of 50
///   bytes (normal and three corners as float32 x y z, a uint16 attribute). The file must be
///   exactly 84 + 50 M bytes long. A file is binary when its size says so, even if its header
///   starts with "solid" as many binary writers make it.
/// - ASCII: `solid [name]`, then `facet normal nx ny nz` / `outer loop` / three
///   `vertex x y z` / `endloop` / `endfacet` per triangle, then `endsolid [name]`; several
///   solids may follow one another. Keywords are matched in any letter case; coordinates are
///   rounded to float32, as the binary form stores them.
/// STL has no shared vertices: corners with exactly equal float32 coordinates (+0 and -0 equal)
/// are welded into one vertex, numbered in order of first appearance, so that the triangles
/// keep the file's order. The stored facet normals are ignored (Surface normals are left unset);
/// position_type() is float32.
/// Throws FileError if the file cannot be read; FormatError naming the file for a binary file
/// whose size disagrees with its count ("cut short: expected N bytes for M triangles, found
/// K"), a non-finite corner, or a file without triangles, and naming the line for a malformed
/// ASCII statement; FormatError from detail checks for a coordinate beyond
/// surfcomp::io::max_coordinate_magnitude; TopologyError (naming --repair) when the welded
/// triangles repeat a vertex or do not form a manifold mesh.
Surface read_stl(const std::filesystem::path& path);

/// As read_stl(path), from a stream (read to its end); `name` stands for the file in messages
/// and becomes Surface::source().
Surface read_stl(std::istream& in, const std::string& name);

}  // namespace surfcomp::mesh::io
