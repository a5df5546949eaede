// Reading and writing any supported mesh file, chosen by its extension (io/formats.hpp).
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace surfcomp::mesh::io {

/// True if `path` has an extension read_mesh reads: mesh_extensions(MeshUse::read), letter
/// case ignored. Looks at the name only, not at the file.
bool is_mesh_file(const std::filesystem::path& path);

/// Reads `path` with the reader of its format (find_mesh_format: read_ply, read_stl, read_off,
/// read_obj, read_msms), then tidies what real meshes bring along:
/// - vertices that no triangle uses are dropped, with their normals and properties (the
///   others keep their order); note "FILE: dropped N unused vertices";
/// - zero-area triangles (area <= 1e-12 times the squared diagonal of the bounding box,
///   collinear corners included) are kept, and noted: "FILE: N zero-area triangles (faces
///   i, j, ..., counted from 0); --repair removes them".
/// Each note is one line appended to `notes` (when not null), for the front end to print.
/// Throws FormatError for an extension no reader has (naming the ones there are), and whatever
/// the reader throws.
Surface read_mesh(const std::filesystem::path& path, std::vector<std::string>* notes);

/// read_mesh(path, notes) with the notes discarded.
Surface read_mesh(const std::filesystem::path& path);

/// Writes `s` to `path` with the writer of its format: .ply (binary little-endian), .off or
/// .obj (mesh_extensions(MeshUse::write)), atomically. Throws FormatError for any other
/// extension, and whatever the writer throws.
void write_mesh(const Surface& s, const std::filesystem::path& path);

}  // namespace surfcomp::mesh::io
