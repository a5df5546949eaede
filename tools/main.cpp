// surfcomp: compare molecular surfaces. One program, one subcommand per job (tools/cli.cpp).
#include "command.hpp"
#include "surfcomp/core/io/atomic_file.hpp"

#include <string>
#include <vector>

int main(int argc, char** argv) {
  surfcomp::io::remove_temporary_files_on_signals();
  return surfcomp::tools::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}
