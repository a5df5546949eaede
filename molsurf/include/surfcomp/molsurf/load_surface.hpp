// A surface from a file, as every subcommand, the Python module and a screen load one: the SES of
// a molecule with its ESP, LP and curvature (build_molecular_surface), or a mesh with its
// curvature and, given a molecule, the molecule's ESP and LP (assign_surface_properties).
#pragma once

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/mesh/length_unit.hpp"
#include "surfcomp/mesh/repair.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace surfcomp::molsurf {

struct SurfaceInputOptions {
  MolecularSurfaceOptions surface;  ///< probe 1.4 A, 2.5 vertices/A^2, ESP eps 1, LP exp(-d)
  io::MoleculeReadOptions read;     ///< charges from the file, the whole structure, record 0
  /// A mesh input: the molecule file whose ESP and LP are mapped onto the mesh; default none.
  /// Refused for a molecule input.
  std::string molecule_file;
  /// Default false. A mesh input is repaired first (repair_mesh_file: its geometry only, vertex
  /// properties not kept). Refused for a molecule input.
  bool repair = false;
  /// Default auto. How a general mesh's length unit is chosen when `unit` is 0 (LengthScale).
  mesh::LengthScale scale = mesh::LengthScale::automatic;
  /// Default 0: from `scale`. A general mesh's length, in its coordinates, that every length
  /// option (curvature, critical point and patch radii, a match's distances and overlay) counts
  /// as 1 A. OptionError for an input in A (a molecule, a mesh with ESP and LP or --molecule,
  /// an MSMS mesh). Finite, > 0 when given.
  double unit = 0.0;
};

/// The user's options of SurfaceInputOptions: --probe-radius --density --voxel --charges --eps
/// --eps-distance-dependent --lp-kernel --ligand --record --molecule --repair --scale --unit
/// --max-atoms --max-grid-cells --max-vertices, with their ranges.
const options::Table<SurfaceInputOptions>& surface_input_option_table();

/// A surface and the molecule it was built from (or whose properties it carries), if any.
struct LoadedSurface {
  mesh::Surface surface;  ///< in the input's coordinates, its curvature in 1/(their length)
  std::optional<Molecule> molecule;
  std::optional<mesh::RepairReport> repair;  ///< what SurfaceInputOptions::repair changed
  /// True for a general mesh (not in A: no molecule, no ESP and LP, not MSMS); its lengths are
  /// in its own coordinates' units.
  bool general_mesh = false;
  /// The length unit the surface's curvature was fitted at (1 for an input in A).
  mesh::LengthUnit unit;
  /// What a reader may want to know, one line each (unused vertices dropped, degenerate
  /// triangles, the repair).
  std::vector<std::string> notes;
};

/// Extensions load_surface reads, for messages: "molecule: .sdf ...; mesh: .ply .stl ...".
std::string surface_input_formats();

/// Checks from the name alone, before any work, that `path` is a molecule or a mesh
/// (InputError naming it and the formats) and that the options apply to it (OptionError:
/// read.ligand on a mesh, molecule_file on a molecule).
void check_surface_input(const std::filesystem::path& path, const SurfaceInputOptions& options);

/// The mesh file `path` as it is (io::read_mesh) or, with options.repair, repaired
/// (repair_mesh_file; LoadedSurface::repair says what changed), held to
/// options.surface.ses.max_vertices (check_vertex_limit): its geometry, without the curvature
/// and potentials load_surface adds.
LoadedSurface read_mesh_input(const std::filesystem::path& path,
                              const SurfaceInputOptions& options);

/// Throws InputError naming the surface's source when it has more vertices than
/// options.surface.ses.max_vertices (--max-vertices), the limit a surface built is held to:
/// every step after reading a mesh is linear or worse in its vertices. read_mesh_input and
/// load_mesh_surface check it; a caller holding a mesh of its own calls it.
void check_vertex_limit(const mesh::Surface& surface, const SurfaceInputOptions& options);

/// The curvature properties (cc1, cc2, shape_index, curvedness) of a general mesh, fitted over
/// general_mesh_curvature_radius units on its copy in `unit` (the other curvature options from
/// `curvature`) and given back per length of its own coordinates. Normals are computed if absent.
void assign_general_mesh_curvature(mesh::Surface& surface, double unit,
                                   mesh::CurvatureOptions curvature);

/// A mesh made elsewhere (from arrays, say) given the properties load_surface gives a mesh
/// file's: with ESP and LP (or options.molecule_file's potentials) it is in A, else a general
/// mesh described in its length unit. Throws as check_vertex_limit, assign_surface_properties
/// and general_mesh_unit; OptionError for options.unit on a mesh in A.
LoadedSurface load_mesh_surface(mesh::Surface surface, const SurfaceInputOptions& options = {});

/// The SES of the molecule file `path` (io::read_molecule with options.read), or the mesh file
/// `path` with its properties: a molecular mesh's curvature over options.surface.curvature in A,
/// a general mesh's in its length unit (general_mesh_unit of options.scale and options.unit;
/// assign_general_mesh_curvature). Throws as check_surface_input, the readers and the surface
/// construction; OptionError for options.unit on an input in A.
LoadedSurface load_surface(const std::filesystem::path& path,
                           const SurfaceInputOptions& options = {});

}  // namespace surfcomp::molsurf
