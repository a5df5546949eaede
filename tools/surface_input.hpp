// The surface options shared by the subcommands that start from a molecule or a mesh
// (surf-build, cp-detect, hsi-build): parsed into the library's options, then one call loads
// or builds the surface with its properties.
#pragma once

#include "surfcomp/mesh/load_surface.hpp"

#include <boost/program_options.hpp>

#include <string>

namespace surfcomp::tools {

/// The surface options of the command line: the library's, and the names of the charge model
/// and LP kernel as given (finish_surface_options sets the library's from them).
struct SurfaceInput : mesh::SurfaceInputOptions {
  std::string charges = "file";
  std::string lp_kernel = "fauchere";
};

/// Adds --probe-radius --density --voxel --charges --eps --eps-distance-dependent --lp-kernel
/// --ligand --molecule, bound to `input`.
void add_surface_options(boost::program_options::options_description& options, SurfaceInput& input);

/// Checks the values parsed into `input` and completes its library options (OptionError).
void finish_surface_options(SurfaceInput& input);

}  // namespace surfcomp::tools
