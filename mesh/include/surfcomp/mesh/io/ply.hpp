// PLY (Stanford polygon format) reading and writing: ascii and binary of both endiannesses, with
// every scalar vertex property kept as a named Surface property in its stored type.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <filesystem>
#include <istream>
#include <ostream>
#include <string>

namespace surfcomp::mesh::io {

/// Encoding of the data section of a PLY file.
enum class PlyFormat { ascii, binary_little_endian, binary_big_endian };

/// Reads a PLY file.
/// - Vertex element: scalar properties x, y, z (any numeric type) are the positions (A); nx, ny,
///   nz, when all three are present, become the normals (set_normals); every other scalar
///   vertex property becomes a named Surface property with its file type recorded
///   (property_type), so that write_ply reproduces it. List properties on vertices are skipped.
///   The storage types of x, y, z (and of nx, ny, nz) become position_type (normal_type) when
///   the three agree, float64 otherwise.
/// - Face element ("face"): the list property vertex_indices (or vertex_index), any integer
///   count and index types, 0-based. A polygon with more than three vertices is split into a
///   fan of triangles (v0, vk, vk+1); fewer than three vertices is a FormatError. Other face
///   properties are skipped.
/// - Triangle strip element ("tristrips", alone or beside "face"): the list property
///   vertex_indices (or vertex_index), RPly's convention: -1 ends one strip and starts the
///   next; in a strip s0 s1 s2 s3 ... triangle j is (sj, sj+1, sj+2) for even j and
///   (sj+1, sj, sj+2) for odd j, and a triangle that repeats a vertex is skipped. Strip
///   triangles follow the face triangles when the face element comes first, and precede them
///   otherwise (file order).
/// - Every other element (edges, materials...) is skipped, in ascii and binary. comment and
///   obj_info lines are ignored. ascii data is read one element item per line (blank lines are
///   skipped). A float property written as text is rounded to float, as its binary form would.
/// Throws FileError if the file cannot be read; FormatError ("file:line: expected ..., found
/// ...", line 0 for binary data, which names the byte offset instead) for a point cloud
/// (vertices and no triangle: "FILE: a point cloud (N vertices, no faces); ..."), a malformed
/// header, an element count the remaining bytes cannot hold, truncated data, an unparsable or
/// out-of-range value, a non-finite position or normal, or a vertex index out of range;
/// TopologyError from Surface::from_arrays for faces that do not form a manifold mesh.
Surface read_ply(const std::filesystem::path& path);

/// As read_ply(path), from a stream (read to its end); `name` stands for the file in messages
/// and becomes Surface::source().
Surface read_ply(std::istream& in, const std::string& name);

/// Writes `s` as PLY: header "comment surfcomp", x y z in position_type(), nx ny nz in
/// normal_type() when has_normals(), then every property in property_names() order in its
/// property_type(), and faces as "property list uchar int vertex_indices". Binary output
/// reproduces every value bit for bit; ascii output prints the shortest text that reads back to
/// the same value in its type (so ascii round trips are exact too).
/// Throws InputError if a property name is empty, contains whitespace or repeats x, y, z (nx,
/// ny, nz when normals are written), or a value does not fit its storage type (an integer type
/// given a fraction or an out-of-range value, float32 given a finite value beyond its range);
/// FileError if the stream fails.
void write_ply(const Surface& s, std::ostream& out,
               PlyFormat format = PlyFormat::binary_little_endian);

/// As write_ply(s, out, format) into `path`, atomically (io::write_file_atomically): on any
/// error the file at `path` is left untouched.
void write_ply(const Surface& s, const std::filesystem::path& path,
               PlyFormat format = PlyFormat::binary_little_endian);

}  // namespace surfcomp::mesh::io
