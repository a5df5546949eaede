// surfcomp surf-build: molecule or mesh in, SES with per-vertex properties out.
#include "command.hpp"

#include <boost/program_options.hpp>

#include <iostream>

namespace surfcomp::tools {

int surf_build(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  po::options_description options("surfcomp surf-build INPUT -o OUT.ply [options]");
  options.add_options()("help,h", "print this help");
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(options).run(), vm);
  if (vm.count("help")) {
    std::cout << options << "\n";
    return 0;
  }
  po::notify(vm);
  return 0;
}

}  // namespace surfcomp::tools
