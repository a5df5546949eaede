// A surface from a file, as every subcommand, the Python module and a screen load one: the SES of
// a molecule with its ESP, LP and curvature (build_molecular_surface), or a mesh with its
// curvature and, given a molecule, the molecule's ESP and LP (assign_surface_properties).
#pragma once

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/mesh/molecular_surface.hpp"
#include "surfcomp/mesh/repair.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <filesystem>
#include <optional>
#include <string>

namespace surfcomp::mesh {

struct SurfaceInputOptions {
  MolecularSurfaceOptions surface;  ///< probe 1.4 A, 2.5 vertices/A^2, ESP eps 1, LP exp(-d)
  io::MoleculeReadOptions read;     ///< charges from the file, the whole structure, record 0
  /// A mesh input: the molecule file whose ESP and LP are mapped onto the mesh; default none.
  /// Refused for a molecule input.
  std::string molecule_file;
  /// Default false. A mesh input is repaired first (repair_mesh_file: its geometry only, vertex
  /// properties not kept). Refused for a molecule input.
  bool repair = false;
};

/// The user's options of SurfaceInputOptions: --probe-radius --density --voxel --charges --eps
/// --eps-distance-dependent --lp-kernel --ligand --record --molecule --max-atoms
/// --max-grid-cells --max-vertices, with their ranges.
const options::Table<SurfaceInputOptions>& surface_input_option_table();

/// A surface and the molecule it was built from (or whose properties it carries), if any.
struct LoadedSurface {
  Surface surface;
  std::optional<Molecule> molecule;
  std::optional<RepairReport> repair;  ///< what SurfaceInputOptions::repair changed
};

/// Extensions load_surface reads, for messages.
inline constexpr const char* surface_input_formats =
    "molecule: .sdf .mol .mol2 .pdb .ent .cif .mmcif .cif.gz .pqr; mesh: .ply .vert .face .off "
    ".obj";

/// Checks from the name alone, before any work, that `path` is a molecule or a mesh
/// (InputError naming it and the formats) and that the options apply to it (OptionError:
/// read.ligand on a mesh, molecule_file on a molecule).
void check_surface_input(const std::filesystem::path& path, const SurfaceInputOptions& options);

/// The mesh file `path` as it is (io::read_mesh) or, with options.repair, repaired
/// (repair_mesh_file, bounded by options.surface.ses.max_vertices; LoadedSurface::repair says
/// what changed): its geometry, without the curvature and potentials load_surface adds.
LoadedSurface read_mesh_input(const std::filesystem::path& path,
                              const SurfaceInputOptions& options);

/// The SES of the molecule file `path` (io::read_molecule with options.read), or the mesh file
/// `path` with its properties. Throws as check_surface_input, the readers and the surface
/// construction.
LoadedSurface load_surface(const std::filesystem::path& path,
                           const SurfaceInputOptions& options = {});

}  // namespace surfcomp::mesh
