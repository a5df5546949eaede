// The options of `surfcomp screen` that say how a query is screened (not what is written),
// parsed into the library's options: shared by the screen subcommand and the Python module's
// screen().
#pragma once

#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/screening/screen.hpp"

#include <boost/program_options.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace surfcomp::tools {

struct ScreenSettings {
  // Read as doubles: a negative value is refused, not wrapped.
  double top = 100, refine = static_cast<double>(screening::ScreenOptions{}.refine),
         candidates = static_cast<double>(screening::ScreenOptions{}.candidates),
         refine_starts = static_cast<double>(screening::ScreenOptions{}.refine_starts);
  std::size_t record = 0;
  std::string site_ligand;
  std::vector<std::string> site_spheres;
  matching::BindingSiteOptions site;
  int threads = 0;
  /// Set by finish_screen_options.
  screening::ScreenOptions options;
  std::vector<matching::SiteSphere> spheres;
};

/// Adds --top --refine --refine-starts --candidates --record --site-ligand --site-sphere
/// --site-radius
/// --site-margin
/// --threads, bound to `settings`.
void add_screen_options(boost::program_options::options_description& options,
                        ScreenSettings& settings);

/// Checks the parsed values (OptionError naming the option) and completes `settings`.
void finish_screen_options(ScreenSettings& settings);

/// Whether the settings ask for a binding-site query (a site ligand or spheres).
bool is_site_query(const ScreenSettings& settings);

/// `query` with the settings' site, and the options its description is built with
/// (matching::prepare_input): the record, the site's sphere radius and margin.
matching::MatchInput screen_query_input(matching::MatchInput query, const ScreenSettings& settings);
matching::MatchInputOptions screen_query_options(const ScreenSettings& settings);

}  // namespace surfcomp::tools
