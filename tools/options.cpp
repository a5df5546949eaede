#include "options.hpp"

#include "surfcomp/molsurf/load_surface.hpp"

#include "console.hpp"

#include <iostream>
#include <sstream>

namespace surfcomp::tools {
namespace {

/// A renamed option: its former name and its name now.
struct Renamed {
  const char* old_name;
  const char* new_name;
};

/// Every option renamed so far (each takes a value: the former name is registered as one). A
/// subcommand accepts the former names of the options it has.
constexpr Renamed kRenamed[] = {
    {"fuzzy", "fuzzy-threshold"},                        // match
    {"hsi-r", "image-threshold"},                        // match
    {"axes-starts", "principal-axes-starts"},            // match
    {"site-axes-starts", "site-principal-axes-starts"},  // match
    {"grid-rings", "image-rings"},                       // hsi-build
    {"grid-sectors", "image-sectors"},                   // hsi-build
    {"radius", "critical-point-radius"},                 // cp-detect, hsi-build
    {"probe", "probe-radius"},                           // every subcommand that builds a surface
};

}  // namespace

bool parse_command_line(const std::vector<std::string>& args,
                        const boost::program_options::options_description& options, int max_inputs,
                        const char* usage, boost::program_options::variables_map& vm) {
  namespace po = boost::program_options;
  po::options_description general("general options");
  general.add_options()("quiet,q", po::bool_switch(), "print only errors and warnings")(
      "verbose,v", po::bool_switch(), "also print each step as it ends, with the time");
  po::options_description all;
  all.add(options);
  all.add(general);
  all.add_options()("input", po::value<std::vector<std::string>>(), "input files");
  std::vector<Renamed> renamed;
  for (const Renamed& r : kRenamed) {
    if (options.find_nothrow(r.new_name, false) && !options.find_nothrow(r.old_name, false)) {
      // The former name only has to take a value in the parser: its occurrences are renamed
      // before store(), which converts the value as the new option's.
      all.add_options()(r.old_name, po::value<std::string>(), "");
      renamed.push_back(r);
    }
  }
  po::positional_options_description positional;
  positional.add("input", max_inputs);
  po::parsed_options parsed =
      po::command_line_parser(args).options(all).positional(positional).run();
  std::vector<Renamed> used;
  for (const Renamed& r : renamed) {
    bool old_given = false, new_given = false;
    for (auto& option : parsed.options) {
      if (option.string_key == r.old_name) {
        option.string_key = r.new_name;
        old_given = true;
      } else if (option.string_key == r.new_name) {
        new_given = true;
      }
    }
    if (old_given && new_given) {
      throw po::error(std::string("--") + r.old_name + " is the former name of --" + r.new_name +
                      "; give --" + r.new_name + " only");
    }
    if (old_given) used.push_back(r);
  }
  po::store(parsed, vm);
  if (vm.count("help")) {
    std::cout << usage << "\n" << options << "\n" << general << "\n";
    return false;
  }
  po::notify(vm);
  if (vm["quiet"].as<bool>() && vm["verbose"].as<bool>())
    throw po::error("--quiet and --verbose cannot be combined");
  console::set_level(vm["quiet"].as<bool>()     ? console::Level::quiet
                     : vm["verbose"].as<bool>() ? console::Level::verbose
                                                : console::Level::normal);
  for (const Renamed& r : used)
    console::note(std::string("--") + r.old_name + " is deprecated; use --" + r.new_name);
  return true;
}

void add_table_option(boost::program_options::options_description& described,
                      const options::Spec& spec, const options::Value& fallback) {
  namespace po = boost::program_options;
  const std::string help = options::help_line(spec);
  if (spec.kind == options::Kind::flag) {
    described.add_options()(spec.name.c_str(), po::bool_switch(), help.c_str());
  } else if (spec.kind == options::Kind::spheres) {
    described.add_options()(spec.name.c_str(), po::value<std::vector<std::string>>()->composing(),
                            help.c_str());
  } else if (spec.optional) {
    described.add_options()(spec.name.c_str(), po::value<std::string>(), help.c_str());
  } else {
    const std::string text = options::format(fallback);
    described.add_options()(spec.name.c_str(), po::value<std::string>()->default_value(text),
                            help.c_str());
  }
}

std::optional<options::Value> given_value(const options::Spec& spec,
                                          const boost::program_options::variables_map& vm) {
  const auto found = vm.find(spec.name);
  if (found == vm.end() || found->second.defaulted()) return std::nullopt;
  const std::string shown = "--" + spec.name;
  if (spec.kind == options::Kind::flag) {
    if (!found->second.as<bool>()) return std::nullopt;
    return options::Value(true);
  }
  if (spec.kind == options::Kind::spheres) {
    std::vector<options::Sphere> spheres;
    for (const std::string& text : found->second.as<std::vector<std::string>>()) {
      const auto one = std::get<std::vector<options::Sphere>>(options::parse(spec, text, shown));
      spheres.insert(spheres.end(), one.begin(), one.end());
    }
    return options::Value(std::move(spheres));
  }
  return options::parse(spec, found->second.as<std::string>(), shown);
}

namespace {

const options::Table<int>& threads_table() {
  static const options::Table<int> table = {
      options::threads_option<int>([](auto& threads) -> auto& { return threads; })};
  return table;
}

}  // namespace

void add_threads_option(boost::program_options::options_description& described) {
  add_table_options(described, threads_table());
}

int threads_from(const boost::program_options::variables_map& vm) {
  int threads = 0;
  apply_table_options(threads_table(), vm, threads);
  return threads;
}

std::string with_formats(const char* usage) {
  std::string text = usage;
  const std::size_t at = text.find("%s");
  if (at != std::string::npos) text.replace(at, 2, molsurf::surface_input_formats());
  return text;
}

void require_in_range(const char* name, double value, double lo, double hi) {
  if (!(std::isfinite(value) && value >= lo && value <= hi)) {
    std::ostringstream message;
    message << "--" << name << ": value " << value << " is outside [" << lo << ", " << hi << "]";
    throw OptionError(message.str());
  }
}

}  // namespace surfcomp::tools
