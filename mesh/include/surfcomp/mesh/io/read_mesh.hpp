// Reading and writing any supported mesh file, chosen by its extension.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <filesystem>

namespace surfcomp::mesh::io {

/// True if `path` has a mesh extension read_mesh knows: .ply, .vert, .face, .off or .obj
/// (letter case ignored). Looks at the name only, not at the file.
bool is_mesh_file(const std::filesystem::path& path);

/// Reads `path` with read_ply, read_msms (.vert or .face), read_off or read_obj according to
/// its extension (letter case ignored). Throws FormatError for any other extension, and
/// whatever the reader throws.
Surface read_mesh(const std::filesystem::path& path);

/// Writes `s` to `path` according to its extension: .ply (binary little-endian), .off or .obj,
/// atomically. Throws FormatError for any other extension (MSMS files are not written), and
/// whatever the writer throws.
void write_mesh(const Surface& s, const std::filesystem::path& path);

}  // namespace surfcomp::mesh::io
