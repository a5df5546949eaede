#include "surfcomp/molsurf/load_surface.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/mesh/io/formats.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"

namespace surfcomp::molsurf {

std::string surface_input_formats() {
  return "molecule: " + io::molecule_extensions(io::MoleculeUse::molecule) +
         "; mesh: " + mesh::io::mesh_extensions(mesh::io::MeshUse::read);
}

void check_surface_input(const std::filesystem::path& path, const SurfaceInputOptions& options) {
  if (mesh::io::is_mesh_file(path)) {
    if (!options.read.ligand.empty())
      throw OptionError(options::named("ligand") + " applies to a molecule INPUT, not a mesh");
    if (options.read.min_plddt > 0.0 && options.molecule_file.empty())
      throw OptionError(options::named("min_plddt") +
                        " applies to a PDB or mmCIF structure INPUT, not a mesh");
    if (options.unit > 0.0 && !options.molecule_file.empty())
      throw OptionError(options::named("unit") + " applies to general meshes; " + path.string() +
                        " is in A (a mesh with " + options::named("molecule") + ")");
  } else if (surfcomp::io::is_molecule_file(path)) {
    if (!options.read.ligand.empty()) {
      try {
        parse_ligand_selector(options.read.ligand);
      } catch (const OptionError& error) {
        throw OptionError(options::named("ligand") + " " + error.what());
      }
    }
    if (!options.molecule_file.empty())
      throw OptionError(options::named("molecule") + " applies to a mesh INPUT");
    if (options.repair) throw OptionError(options::named("repair") + " applies to a mesh INPUT");
    if (options.unit > 0.0)
      throw OptionError(options::named("unit") + " applies to general meshes; " + path.string() +
                        " is in A (a molecule)");
  } else {
    throw InputError(path.string() + ": unknown input format (" + surface_input_formats() + ")");
  }
}

void check_vertex_limit(const mesh::Surface& surface, const SurfaceInputOptions& options) {
  const auto limit = static_cast<std::size_t>(options.surface.ses.max_vertices);
  if (surface.n_vertices() > limit) {
    throw InputError(surface.source() + ": " + std::to_string(surface.n_vertices()) +
                     " vertices, more than " + options::named("max_vertices") + " " +
                     std::to_string(limit));
  }
}

LoadedSurface read_mesh_input(const std::filesystem::path& path,
                              const SurfaceInputOptions& options) {
  LoadedSurface loaded;
  if (options.repair) {
    mesh::RepairedMesh repaired =
        mesh::repair_mesh_file(path, static_cast<std::size_t>(options.surface.ses.max_vertices));
    loaded.surface = std::move(repaired.surface);
    loaded.repair = repaired.report;
    loaded.notes.push_back(mesh::repair_note(path.string(), repaired.report));
  } else {
    loaded.surface = mesh::io::read_mesh(path, &loaded.notes);
    check_vertex_limit(loaded.surface, options);
  }
  return loaded;
}

void assign_general_mesh_curvature(mesh::Surface& surface, double unit,
                                   mesh::CurvatureOptions curvature) {
  if (!surface.has_normals()) surface.compute_normals();
  curvature.radius = mesh::general_mesh_curvature_radius;
  mesh::Surface in_units = surface;
  if (unit != 1.0) mesh::scale_surface(in_units, 1.0 / unit);
  const mesh::PrincipalCurvatures k = mesh::principal_curvatures(in_units, curvature);
  surface.set_property(mesh::property::cc1, k.cc1 / unit);
  surface.set_property(mesh::property::cc2, k.cc2 / unit);
  surface.set_property(mesh::property::shape_index, k.shape_index);
  surface.set_property(mesh::property::curvedness, k.curvedness / unit);
}

namespace {

/// `loaded`'s mesh given its properties: a molecular one's (is_molecular_mesh of `extension`,
/// or a --molecule's potentials) over options.surface.curvature in A, a general one's in its
/// length unit.
void complete_mesh(LoadedSurface& loaded, const std::string& extension,
                   const SurfaceInputOptions& options) {
  const std::string& name = loaded.surface.source();
  if (!options.molecule_file.empty() || mesh::is_molecular_mesh(loaded.surface, extension)) {
    if (options.unit > 0.0) {
      throw OptionError(options::named("unit") + " applies to general meshes; " + name +
                        " is in A (a mesh with ESP and LP, or an MSMS surface)");
    }
    if (!options.molecule_file.empty())
      loaded.molecule = surfcomp::io::read_molecule(options.molecule_file, options.read);
    assign_surface_properties(loaded.surface, loaded.molecule ? &*loaded.molecule : nullptr,
                              options.surface);
    return;
  }
  loaded.general_mesh = true;
  loaded.unit = mesh::general_mesh_unit({&loaded.surface}, options.scale, options.unit, name);
  assign_general_mesh_curvature(loaded.surface, loaded.unit.value, options.surface.curvature);
}

}  // namespace

LoadedSurface load_mesh_surface(mesh::Surface surface, const SurfaceInputOptions& options) {
  check_vertex_limit(surface, options);
  LoadedSurface loaded;
  loaded.surface = std::move(surface);
  complete_mesh(loaded, "", options);
  return loaded;
}

LoadedSurface load_surface(const std::filesystem::path& path, const SurfaceInputOptions& options) {
  check_surface_input(path, options);
  LoadedSurface loaded;
  if (mesh::io::is_mesh_file(path)) {
    loaded = read_mesh_input(path, options);
    complete_mesh(loaded, surfcomp::io::lowercase_extension(path), options);
  } else {
    loaded.molecule = surfcomp::io::read_molecule(path, options.read);
    loaded.surface = build_molecular_surface(*loaded.molecule, options.surface);
  }
  return loaded;
}

}  // namespace surfcomp::molsurf
