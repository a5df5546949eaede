// libFuzzer harness: the command-line option parsing the subcommands share (tools/options.cpp
// and tools/surface_input.cpp), over an option table like hsi-build's: its own options, the
// surface options, and options with a former name. The input is the argument list, one
// argument per line (or NUL-separated).
#include "options.hpp"
#include "surface_input.hpp"

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

void parse(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  using namespace surfcomp::tools;
  std::string output;
  double radius = 0.0;
  int rings = 0;
  int sectors = 0;
  int threads = 0;
  std::string weights;
  SurfaceInput input;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "output file")
      ("critical-point-radius", po::value(&radius)->default_value(1.5), "A")
      ("image-rings", po::value(&rings)->default_value(16), "rings")
      ("image-sectors", po::value(&sectors)->default_value(64), "sectors")
      ("weights", po::value(&weights)->default_value("inverse-length"), "weights")
      ("threads", po::value(&threads)->default_value(0), "threads")
      ("ascii", po::bool_switch(), "ascii");
  // clang-format on
  add_surface_options(described, input);
  po::variables_map vm;
  if (!parse_command_line(args, described, 2, "usage: fuzz_options", vm)) return;
  finish_surface_options(input);
  require_in_range("critical-point-radius", radius, 1e-3, 100.0);
  require_in_range("image-rings", rings, 1, 1024);
  require_in_range("image-sectors", sectors, 1, 4096);
  require_in_range("threads", threads, 0, 1024);
  require_one_of("weights", weights, {"inverse-length", "uniform", "cotangent", "mean-value"});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    parse(split_arguments(data, size));
  } catch (const boost::program_options::error&) {  // a command-line syntax error: exit 2
  } catch (const surfcomp::Error&) {                // an option check: exit 1
  }
  return 0;
}
