// The surface options shared by the subcommands that start from a molecule or a mesh
// (surf-build, cp-detect, hsi-build), as the library defines them
// (molsurf::surface_input_option_table).
#pragma once

#include "surfcomp/molsurf/load_surface.hpp"

#include <boost/program_options.hpp>

#include <filesystem>

namespace surfcomp::tools {

/// Adds the surface options: --probe-radius --density --voxel --charges --eps
/// --eps-distance-dependent --lp-kernel --ligand --record --molecule and the limits.
void add_surface_options(boost::program_options::options_description& described);

/// The surface options given on the command line (checked), with progress lines for the ESP and
/// LP sums.
molsurf::SurfaceInputOptions surface_options_from(const boost::program_options::variables_map& vm);

/// molsurf::load_surface of `path`, with its notes (what --repair changed, what the reader
/// dropped or found) printed.
molsurf::LoadedSurface load_noted(const std::filesystem::path& path,
                                  const molsurf::SurfaceInputOptions& options);

/// Progress lines for the ESP and LP sums and the curvature fits of `surface`
/// (console::ProgressLine), when shown.
void show_surface_progress(molsurf::MolecularSurfaceOptions& surface);

}  // namespace surfcomp::tools
