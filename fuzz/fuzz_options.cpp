// libFuzzer harness: the command-line option parsing the subcommands share (tools/options.cpp),
// over the library's option tables they add (tools/*_settings.hpp): describe (hsi-build,
// patch-map), match (match, report) and screen, with the surface options and the options with a
// former name. The input is the argument list, one
// argument per line (or NUL-separated).
#include "describe_settings.hpp"
#include "match_settings.hpp"
#include "options.hpp"
#include "screen_settings.hpp"

#include "surfcomp/core/error.hpp"

#include <boost/program_options.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace {

std::vector<std::string> split_arguments(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args(1);
  for (std::size_t i = 0; i < size; ++i) {
    const char c = static_cast<char>(data[i]);
    if (c == '\n' || c == '\0') {
      args.emplace_back();
    } else {
      args.back() += c;
    }
  }
  if (args.back().empty()) args.pop_back();
  return args;
}

/// Parses `args` with one of the subcommands' own option sets, chosen by the first argument's
/// length: describe (hsi-build, patch-map), match (match, report, the Python module's match) or
/// screen, each with the surface options where the subcommand has them.
void parse(std::vector<std::string> args) {
  namespace po = boost::program_options;
  using namespace surfcomp::tools;
  const std::size_t set = args.empty() ? 0 : args.front().size() % 3;
  std::string output;
  po::options_description described("options");
  described.add_options()("help,h", "print this help")("output,o", po::value(&output), "output");
  if (set == 0) {
    add_describe_options(described);
  } else if (set == 1) {
    add_match_options(described);
  } else {
    add_screen_options(described);
  }
  po::variables_map vm;
  if (!parse_command_line(args, described, 2, "usage: fuzz_options", vm)) return;
  if (set == 0) {
    describe_options_from(vm);
  } else if (set == 1) {
    match_options_from(vm);
  } else {
    screen_options_from(vm);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    parse(split_arguments(data, size));
  } catch (const boost::program_options::error&) {  // a command-line syntax error: exit 2
  } catch (const surfcomp::OptionError&) {          // an option outside its domain: exit 2
  }  // anything else (another surfcomp::Error would exit 1 or 3) is a finding
  return 0;
}
