// The options of `surfcomp screen` that say how a query is screened (not what is written), as
// the library defines them (screening::screen_option_table).
#pragma once

#include "surfcomp/screening/screen.hpp"

#include <boost/program_options.hpp>

namespace surfcomp::tools {

/// Adds --top --refine --refine-starts --candidates --record --site-ligand --site-sphere
/// --site-radius --site-margin --threads, and a mesh query's --repair --scale --unit.
void add_screen_options(boost::program_options::options_description& described);

/// The screen options given on the command line (checked), with progress lines for the query's
/// description and, verbose, the steps' log.
screening::QueryScreenOptions screen_options_from(const boost::program_options::variables_map& vm);

}  // namespace surfcomp::tools
