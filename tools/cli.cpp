// The surfcomp command line: one subcommand per job, dispatched by name (the program's main and
// `python3 -m surfcomp` run it).
#include "command.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"

#include <boost/program_options/errors.hpp>

#include <array>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

namespace {

using surfcomp::tools::Command;

constexpr std::array kCommands{
    Command{"surf-build", "molecule or mesh -> SES with ESP, LP and curvature (PLY)",
            &surfcomp::tools::surf_build},
    Command{"cp-detect", "surface -> shape critical points (JSON; PDB/PLY for viewing)",
            &surfcomp::tools::cp_detect},
    Command{"hsi-build", "surface -> critical points, patches, harmonic maps and images (.hsi)",
            &surfcomp::tools::hsi_build},
    Command{"match", "REF PROBE -> ranked rigid alignments of PROBE onto REF (JSON)",
            &surfcomp::tools::match},
    Command{"dock",
            "LIGAND RECEPTOR -> poses of LIGAND in RECEPTOR's pocket by complementarity (SDF)",
            &surfcomp::tools::dock},
    Command{"matrix",
            "SET... -> every pair of its molecules matched once: a similarity matrix (CSV)",
            &surfcomp::tools::matrix},
    Command{"library", "build | info | export: screening libraries of conformers (.sclib)",
            &surfcomp::tools::library},
    Command{"screen", "QUERY LIB -> the library's molecules ranked by similarity (CSV)",
            &surfcomp::tools::screen},
    Command{"report", "REF PROBE -> a match as an HTML page to look at (3D viewer, tables)",
            &surfcomp::tools::report},
    Command{"pockets", "structure -> its pockets, found without a ligand (JSON; PDB for viewing)",
            &surfcomp::tools::pockets},
    Command{"patch-map", "surface -> each critical point's patch and harmonic map (OBJ, PLY, PNG)",
            &surfcomp::tools::patch_map},
};

void print_usage(std::ostream& out) {
  out << "usage: surfcomp COMMAND [options]   (surfcomp COMMAND --help for its options)\n\n"
         "Compares molecular surfaces by critical points, harmonic shape images and cliques.\n\n"
         "commands:\n";
  for (const auto& command : kCommands) {
    out << "  " << command.name << std::string(14 - std::strlen(command.name), ' ')
        << command.summary << "\n";
  }
  out << "\n  --version     print the version\n";
}

}  // namespace

namespace surfcomp::tools {

int run_command_line(const std::vector<std::string>& args) {
  // The options library messages name, as the command line spells them, for the whole run.
  const surfcomp::options::ScopedSpelling spelling(&surfcomp::options::command_line_spelling);
  if (args.empty()) {
    print_usage(std::cerr);
    return 2;
  }
  const std::string& name = args.front();
  if (name == "--help" || name == "-h" || name == "help") {
    print_usage(std::cout);
    return 0;
  }
  if (name == "--version") {
    std::cout << "surfcomp " << SURFCOMP_VERSION << "\n";
    return 0;
  }
  for (const auto& command : kCommands) {
    if (name != command.name) continue;
    try {
      return command.run(std::vector<std::string>(args.begin() + 1, args.end()));
    } catch (const boost::program_options::error& e) {
      std::cerr << "surfcomp " << name << ": " << e.what() << " (see --help)\n";
      return 2;
    } catch (const surfcomp::OptionError& e) {  // a command line that cannot run as given
      std::cerr << "surfcomp " << name << ": error: " << e.what() << "\n";
      return 2;
    } catch (const surfcomp::Error& e) {
      std::cerr << "surfcomp " << name << ": error: " << e.what() << "\n";
      return 1;
    } catch (const std::bad_alloc&) {
      std::cerr << "surfcomp " << name << ": error: out of memory\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "surfcomp " << name << ": internal error: " << e.what() << "\n";
      return 3;
    }
  }
  std::cerr << "surfcomp: unknown command '" << name << "' (see surfcomp --help)\n";
  return 2;
}

}  // namespace surfcomp::tools
