#include "surfcomp/report/aligned_probe.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/mesh/io/ply.hpp"

namespace surfcomp::report {

std::vector<std::string> aligned_probe_formats(const std::filesystem::path& probe_path) {
  if (!io::is_molecule_file(probe_path)) return {".ply"};
  const io::MoleculeFormat* format = io::find_molecule_format(probe_path);
  if (format->kind == io::MoleculeFileKind::mdl || format->kind == io::MoleculeFileKind::mol2) {
    return {".sdf", ".pdb", ".ply"};
  }
  return {".pdb", ".ply"};
}

void write_aligned_probe(const std::filesystem::path& output,
                         const std::filesystem::path& probe_path, std::size_t record,
                         const matching::PreparedInput& probe, const Eigen::Matrix4d& transform) {
  const Eigen::Matrix3d rotation = transform.topLeftCorner<3, 3>();
  const Eigen::Vector3d translation = transform.topRightCorner<3, 1>();
  const std::string extension = io::lowercase_extension(output);
  if (extension == ".ply") {
    mesh::Surface moved = probe.descriptors.surface;
    mesh::transform_surface(moved, rotation, translation);
    mesh::io::write_ply(moved, output);
  } else if (extension == ".sdf") {
    const std::string block = io::moved_mol_block(probe_path, rotation, translation, record);
    io::write_file_atomically(output, [&](std::ostream& out) { out << block; });
  } else {
    Molecule moved = *probe.molecule;
    transform_molecule(moved, rotation, translation);
    io::write_file_atomically(output, [&](std::ostream& out) { io::write_pdb(moved, out); });
  }
}

}  // namespace surfcomp::report
