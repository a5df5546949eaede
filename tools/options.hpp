// Small helpers shared by the subcommands: option parsing (which also accepts the former names of
// renamed options), option checks and the summary clock.
#pragma once

#include "surfcomp/core/error.hpp"

#include <boost/program_options.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace surfcomp::tools {

/// Parses `args` with `options` (plus one or more positional INPUT arguments under "input").
/// The former name of a renamed option (the table in options.cpp) still sets it, hidden from
/// --help, with one line "note: --OLD is deprecated; use --NEW" on stderr. Returns false when
/// --help was asked (the help text is already printed). Throws boost::program_options::error (a
/// command-line syntax error) for an unknown option or a bad value, and for an option given
/// under both its former and its new name.
bool parse_command_line(const std::vector<std::string>& args,
                        const boost::program_options::options_description& options, int max_inputs,
                        const char* usage, boost::program_options::variables_map& vm);

/// Throws OptionError "--name: value V is outside [lo, hi]" unless lo <= value <= hi and finite.
void require_in_range(const char* name, double value, double lo, double hi);

/// Throws OptionError "--name: value V is outside (0, hi]" unless 0 < value <= hi and finite.
void require_positive(const char* name, double value, double hi);

/// Throws OptionError unless `value` is one of `allowed`.
void require_one_of(const char* name, const std::string& value,
                    const std::vector<std::string>& allowed);

}  // namespace surfcomp::tools
