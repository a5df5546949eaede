// The surface options shared by the subcommands that start from a molecule or a mesh
// (surf-build, cp-detect, hsi-build): parsed into the library's options, then one call loads
// or builds the surface with its properties.
#pragma once

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/mesh/molecular_surface.hpp"

#include <boost/program_options.hpp>

#include <filesystem>
#include <optional>
#include <string>

namespace surfcomp::tools {

struct SurfaceInput {
  mesh::MolecularSurfaceOptions surface;
  io::MoleculeReadOptions read;
  std::string charges = "file";
  std::string lp_kernel = "fauchere";
  std::string molecule_file;  ///< mesh INPUT: the molecule whose ESP and LP to map on it
};

/// Adds --probe-radius --density --voxel --charges --eps --eps-distance-dependent --lp-kernel
/// --ligand --molecule, bound to `input`.
void add_surface_options(boost::program_options::options_description& options, SurfaceInput& input);

/// Checks the values parsed into `input` and completes its library options (OptionError).
void finish_surface_options(SurfaceInput& input);

struct LoadedSurface {
  mesh::Surface surface;
  std::optional<Molecule> molecule;  ///< the molecule read (INPUT or --molecule), if any
};

/// Checks, from the names alone and before any work, that `path` is a molecule or a mesh
/// (InputError) and that the options given apply to it (OptionError: --ligand on a mesh,
/// --molecule on a molecule).
void check_surface_input(const std::filesystem::path& path, const SurfaceInput& input);

/// Builds the SES of a molecule file, or reads a mesh file and assigns its properties.
/// Throws as check_surface_input, and as the readers and the surface construction.
LoadedSurface load_surface(const std::filesystem::path& path, const SurfaceInput& input);

/// Extensions accepted as INPUT, for messages.
inline constexpr const char* kInputFormats =
    "molecule: .sdf .mol .mol2 .pdb .ent .pqr; mesh: .ply .vert .face .off .obj";

}  // namespace surfcomp::tools
