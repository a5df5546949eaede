// The options of `surfcomp hsi-build` that say how a surface is described (critical points,
// patches, harmonic maps, images), as the library defines them
// (matching::describe_option_table): shared by hsi-build and patch-map.
#pragma once

#include "surfcomp/matching/match_inputs.hpp"

#include <boost/program_options.hpp>

#include <cstdint>
#include <functional>

namespace surfcomp::tools {

/// Adds the surface options and --critical-point-radius --patch-radius --image-rings
/// --image-sectors --weights --max-image-bytes --threads.
void add_describe_options(boost::program_options::options_description& described);

/// The description options given on the command line (checked), with progress lines.
matching::MatchInputOptions describe_options_from(const boost::program_options::variables_map& vm);

/// A progress line for describing critical points (console::ProgressLine), or none.
std::function<void(std::int64_t, std::int64_t)> describe_progress();

}  // namespace surfcomp::tools
