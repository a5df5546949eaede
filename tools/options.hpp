// Small helpers shared by the subcommands: option parsing (which also accepts the former names of
// renamed options), option checks and the summary clock.
#pragma once

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_table.hpp"

#include <boost/program_options.hpp>

#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
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

/// `usage` with its one "%s" replaced by the input formats a surface is read from
/// (molsurf::surface_input_formats), so that help texts list them from the one registry.
std::string with_formats(const char* usage);

/// An option value stored in `*target`, with default `fallback`. --help shows a floating-point
/// default in its shortest exact form (1.4, not 1.3999999999999999).
template <class T>
boost::program_options::typed_value<T>* defaulted(T* target, const T& fallback) {
  auto* value = boost::program_options::value(target);
  if constexpr (std::is_floating_point_v<T>) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, fallback).ptr;
    return value->default_value(fallback, std::string(text, end));
  } else {
    return value->default_value(fallback);
  }
}

/// defaulted(target, *target): the value `*target` holds is the default.
template <class T>
boost::program_options::typed_value<T>* defaulted(T* target) {
  return defaulted(target, *target);
}

/// Adds the option of `spec` to `described`: its help line (options::help_line) and, unless it
/// is optional, `fallback` as its default. A flag is a switch; spheres repeat.
void add_table_option(boost::program_options::options_description& described,
                      const options::Spec& spec, const options::Value& fallback);

/// The value of the option of `spec` as given on the command line (options::parse, naming
/// "--NAME" in errors); none when it was not given.
std::optional<options::Value> given_value(const options::Spec& spec,
                                          const boost::program_options::variables_map& vm);

/// Adds every option of `table`, with its default as `defaults` holds it.
template <class Settings>
void add_table_options(boost::program_options::options_description& described,
                       const options::Table<Settings>& table, const Settings& defaults = {}) {
  for (const options::Option<Settings>& option : table) {
    add_table_option(described, option.spec, option.get(defaults));
  }
}

/// Sets in `settings` every option of `table` given on the command line.
template <class Settings>
void apply_table_options(const options::Table<Settings>& table,
                         const boost::program_options::variables_map& vm, Settings& settings) {
  for (const options::Option<Settings>& option : table) {
    if (const std::optional<options::Value> value = given_value(option.spec, vm))
      option.set(settings, *value);
  }
}

/// Adds --threads (options::threads_option) for a subcommand whose other options are its own.
void add_threads_option(boost::program_options::options_description& described);

/// The --threads given on the command line (checked), else 0: all cores.
int threads_from(const boost::program_options::variables_map& vm);

/// Throws OptionError "--name: value V is outside [lo, hi]" unless lo <= value <= hi and finite.
void require_in_range(const char* name, double value, double lo, double hi);

}  // namespace surfcomp::tools
