// The options of `surfcomp match` that say how two inputs are compared (not what is written), as
// the library defines them (matching::pair_match_option_table): shared by the match and report
// subcommands.
#pragma once

#include "surfcomp/matching/match_inputs.hpp"

#include <boost/program_options.hpp>

#include <filesystem>

namespace surfcomp::tools {

/// Adds the options of a pair match: the surface options, the association graph, clique budget,
/// ranking, overlay, sites, --patch-radius, --max-image-bytes and --threads.
void add_match_options(boost::program_options::options_description& described);

/// The match options given on the command line (checked), with progress lines and, verbose, the
/// steps' log.
matching::PairMatchOptions match_options_from(const boost::program_options::variables_map& vm);

/// REF and PROBE as files.
struct PairInputs {
  matching::MatchInput reference, probe;
};

/// REF and PROBE read from these files with their sites (matching::with_site), checked before
/// any work (matching::check_match_input, naming the site options as they were given).
PairInputs pair_inputs(const std::filesystem::path& reference, const std::filesystem::path& probe,
                       const matching::PairMatchOptions& options);

}  // namespace surfcomp::tools
