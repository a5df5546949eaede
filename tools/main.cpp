// surfcomp: compare molecular surfaces. One program, one subcommand per job (tools/cli.cpp).
#include "command.hpp"

#include <string>
#include <vector>

int main(int argc, char** argv) {
  return surfcomp::tools::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}
