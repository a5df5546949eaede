// The mesh file formats surfcomp knows, in one table: what reads and writes each extension and
// whether --repair reads it. is_mesh_file, read_mesh, write_mesh, repair_mesh_file and every
// "expected one of ..." message are derived from it.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace surfcomp::mesh::io {

/// One mesh file format, known by its extension.
struct MeshFormat {
  std::string_view extension;  ///< lowercase, with the dot (".ply")
  std::string_view name;       ///< what the format is, for help texts ("PLY (Stanford)")
  /// Reads a file of this format; null when surfcomp does not read it.
  Surface (*read)(const std::filesystem::path& path);
  /// Writes a surface in this format, atomically; null when surfcomp does not write it.
  void (*write)(const Surface& surface, const std::filesystem::path& path);
  /// True when repair_mesh_file (--repair) reads it as a polygon soup.
  bool repairable;
};

/// Every mesh format, in the order messages list them: .ply .stl .off .obj .vert .face.
const std::vector<MeshFormat>& mesh_formats();

/// The format of `path` by its extension (letter case ignored), or null for an extension no
/// format has. Looks at the name only, not at the file.
const MeshFormat* find_mesh_format(const std::filesystem::path& path);

/// What a caller wants to do with a mesh file.
enum class MeshUse { read, write, repair };

/// The extensions of the formats that serve `use`, in mesh_formats() order, separated by
/// spaces: ".ply .stl .off .obj .vert .face" for MeshUse::read, ".ply .off .obj" for write,
/// ".ply .stl .off .obj" for repair. For help texts and "expected one of ..." messages.
std::string mesh_extensions(MeshUse use);

}  // namespace surfcomp::mesh::io
