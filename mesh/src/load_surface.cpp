#include "surfcomp/mesh/load_surface.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"

namespace surfcomp::mesh {

void check_surface_input(const std::filesystem::path& path, const SurfaceInputOptions& options) {
  if (io::is_mesh_file(path)) {
    if (!options.read.ligand.empty())
      throw OptionError("--ligand applies to a molecule INPUT, not a mesh");
    if (options.read.min_plddt > 0.0 && options.molecule_file.empty())
      throw OptionError("--min-plddt applies to a PDB or mmCIF structure INPUT, not a mesh");
  } else if (surfcomp::io::is_molecule_file(path)) {
    if (!options.molecule_file.empty()) throw OptionError("--molecule applies to a mesh INPUT");
    if (options.repair) throw OptionError("--repair applies to a mesh INPUT");
  } else {
    throw InputError(path.string() + ": unknown input format (" + surface_input_formats + ")");
  }
}

LoadedSurface read_mesh_input(const std::filesystem::path& path,
                              const SurfaceInputOptions& options) {
  LoadedSurface loaded;
  if (options.repair) {
    RepairedMesh repaired =
        repair_mesh_file(path, static_cast<std::size_t>(options.surface.ses.max_vertices));
    loaded.surface = std::move(repaired.surface);
    loaded.repair = repaired.report;
  } else {
    loaded.surface = io::read_mesh(path);
  }
  return loaded;
}

LoadedSurface load_surface(const std::filesystem::path& path, const SurfaceInputOptions& options) {
  check_surface_input(path, options);
  LoadedSurface loaded;
  if (io::is_mesh_file(path)) {
    loaded = read_mesh_input(path, options);
    if (!options.molecule_file.empty())
      loaded.molecule = surfcomp::io::read_molecule(options.molecule_file, options.read);
    assign_surface_properties(loaded.surface, loaded.molecule ? &*loaded.molecule : nullptr,
                              options.surface);
  } else {
    loaded.molecule = surfcomp::io::read_molecule(path, options.read);
    loaded.surface = build_molecular_surface(*loaded.molecule, options.surface);
  }
  return loaded;
}

}  // namespace surfcomp::mesh
