#include "options.hpp"

#include <iostream>
#include <sstream>

namespace surfcomp::tools {

bool parse_command_line(const std::vector<std::string>& args,
                        const boost::program_options::options_description& options, int max_inputs,
                        const char* usage, boost::program_options::variables_map& vm) {
  namespace po = boost::program_options;
  po::options_description all;
  all.add(options);
  all.add_options()("input", po::value<std::vector<std::string>>(), "input files");
  po::positional_options_description positional;
  positional.add("input", max_inputs);
  po::store(po::command_line_parser(args).options(all).positional(positional).run(), vm);
  if (vm.count("help")) {
    std::cout << usage << "\n" << options << "\n";
    return false;
  }
  po::notify(vm);
  return true;
}

void require_in_range(const char* name, double value, double lo, double hi) {
  if (!(std::isfinite(value) && value >= lo && value <= hi)) {
    std::ostringstream message;
    message << "--" << name << ": value " << value << " is outside [" << lo << ", " << hi << "]";
    throw OptionError(message.str());
  }
}

void require_one_of(const char* name, const std::string& value,
                    const std::vector<std::string>& allowed) {
  for (const auto& a : allowed) {
    if (value == a) return;
  }
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : "|") + a;
  throw OptionError(std::string("--") + name + ": '" + value + "' is not one of " + list);
}

}  // namespace surfcomp::tools
