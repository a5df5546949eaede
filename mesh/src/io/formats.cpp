#include "surfcomp/mesh/io/formats.hpp"

#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/mesh/io/msms.hpp"
#include "surfcomp/mesh/io/obj.hpp"
#include "surfcomp/mesh/io/off.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/mesh/io/stl.hpp"

namespace surfcomp::mesh::io {

const std::vector<MeshFormat>& mesh_formats() {
  using Path = std::filesystem::path;
  static const std::vector<MeshFormat> formats{
      {".ply", "PLY (Stanford; faces or triangle strips, with vertex properties)",
       [](const Path& path) { return read_ply(path); },
       [](const Surface& s, const Path& path) {
         write_ply(s, path, PlyFormat::binary_little_endian);
       },
       true},
      {".stl", "STL (binary or ASCII triangles)", [](const Path& path) { return read_stl(path); },
       nullptr, true},
      {".off", "OFF (Object File Format)", &read_off, &write_off, true},
      {".obj", "Wavefront OBJ", &read_obj, &write_obj, true},
      {".vert", "MSMS vertices (read with X.face)", &read_msms, nullptr, false},
      {".face", "MSMS faces (read with X.vert)", &read_msms, nullptr, false},
  };
  return formats;
}

const MeshFormat* find_mesh_format(const std::filesystem::path& path) {
  const std::string extension = surfcomp::io::lowercase_extension(path);
  for (const MeshFormat& format : mesh_formats()) {
    if (format.extension == extension) return &format;
  }
  return nullptr;
}

std::string mesh_extensions(MeshUse use) {
  std::string text;
  for (const MeshFormat& format : mesh_formats()) {
    const bool serves = use == MeshUse::read    ? format.read != nullptr
                        : use == MeshUse::write ? format.write != nullptr
                                                : format.repairable;
    if (!serves) continue;
    if (!text.empty()) text += ' ';
    text += format.extension;
  }
  return text;
}

}  // namespace surfcomp::mesh::io
