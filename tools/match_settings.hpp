// The options of `surfcomp match` that say how two inputs are compared (not what is written),
// parsed into the library's options: shared by the match and report subcommands and the Python
// module, whose keyword arguments are these options.
#pragma once

#include "surface_input.hpp"

#include "surfcomp/matching/match_inputs.hpp"

#include <boost/program_options.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace surfcomp::tools {

struct MatchSettings {
  SurfaceInput input;
  harmonic::DescriptorOptions descriptors;
  matching::BindingSiteOptions site;
  matching::MatchOptions match;
  std::string ranking = "rank";
  std::string site_ligand, ref_site_ligand, probe_site_ligand;
  std::vector<std::string> site_spheres, ref_site_spheres, probe_site_spheres;
  // Read as signed integers, so that a negative value is refused rather than wrapped.
  std::int64_t max_clique_work = matching::MatchOptions{}.max_clique_work;
  std::int64_t max_cliques = static_cast<std::int64_t>(matching::MatchOptions{}.max_cliques);
  std::int64_t max_graph_nodes = static_cast<std::int64_t>(matching::GraphOptions{}.max_nodes);
  /// Set by finish_match_options: each side's spheres, and the option that named its ligand.
  std::vector<matching::SiteSphere> ref_spheres, probe_spheres;
  const char* ref_site_option = "--site-ligand";
  const char* probe_site_option = "--site-ligand";
};

/// Adds the surface options (add_surface_options) and the match's own: the association graph,
/// clique budget, ranking, overlay, sites, --patch-radius and --max-image-bytes, bound to
/// `settings`.
void add_match_options(boost::program_options::options_description& options,
                       MatchSettings& settings);

/// Checks the parsed values (OptionError naming the option) and completes `settings`: the
/// surface options, the ranking scheme, the limits, the site spheres, the site margin's
/// default (at least the patch radius + 8 A), and matching::validate.
void finish_match_options(MatchSettings& settings, const boost::program_options::variables_map& vm);

/// The library's options for matching::match_inputs.
matching::MatchInputOptions match_input_options(const MatchSettings& settings);

/// `input` with REF's (`reference`) or PROBE's site from `settings`: its ligand and spheres.
matching::MatchInput with_site(matching::MatchInput input, const MatchSettings& settings,
                               bool reference);

/// REF and PROBE as files.
struct PairInputs {
  matching::MatchInput reference, probe;
};

/// REF and PROBE read from these files with their sites (with_site), checked before any work
/// (matching::check_match_input, naming the site options as they were given).
PairInputs pair_inputs(const std::filesystem::path& reference, const std::filesystem::path& probe,
                       const MatchSettings& settings);

/// The site sphere of a --site-sphere value; OptionError for anything but x,y,z,r with r > 0.
matching::SiteSphere parse_sphere_option(const std::string& text);

}  // namespace surfcomp::tools
