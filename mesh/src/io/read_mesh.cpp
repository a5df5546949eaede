#include "surfcomp/mesh/io/read_mesh.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/mesh/io/msms.hpp"
#include "surfcomp/mesh/io/obj.hpp"
#include "surfcomp/mesh/io/off.hpp"
#include "surfcomp/mesh/io/ply.hpp"

namespace surfcomp::mesh::io {

bool is_mesh_file(const std::filesystem::path& path) {
  const std::string ext = surfcomp::io::lowercase_extension(path);
  return ext == ".ply" || ext == ".vert" || ext == ".face" || ext == ".off" || ext == ".obj";
}

Surface read_mesh(const std::filesystem::path& path) {
  const std::string ext = surfcomp::io::lowercase_extension(path);
  if (ext == ".ply") return read_ply(path);
  if (ext == ".vert" || ext == ".face") return read_msms(path);
  if (ext == ".off") return read_off(path);
  if (ext == ".obj") return read_obj(path);
  throw FormatError(path.string(),
                    "expected a mesh extension (.ply, .vert, .face, .off or "
                    ".obj), found '" +
                        path.extension().string() + "'");
}

void write_mesh(const Surface& s, const std::filesystem::path& path) {
  const std::string ext = surfcomp::io::lowercase_extension(path);
  if (ext == ".ply") return write_ply(s, path, PlyFormat::binary_little_endian);
  if (ext == ".off") return write_off(s, path);
  if (ext == ".obj") return write_obj(s, path);
  throw FormatError(path.string(),
                    "expected an extension surfcomp writes (.ply, .off or .obj), "
                    "found '" +
                        path.extension().string() + "'");
}

}  // namespace surfcomp::mesh::io
