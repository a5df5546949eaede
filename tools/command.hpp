// The subcommand interface of the surfcomp program: each subcommand is one thin file in tools/
// that parses options into the library's Options struct, calls it, writes and reports.
#pragma once

#include <string>
#include <vector>

namespace surfcomp::tools {

/// Runs one subcommand with its arguments (without the program and subcommand names).
/// Returns the exit status; library errors propagate as surfcomp::Error.
using CommandFunction = int (*)(const std::vector<std::string>& args);

struct Command {
  const char* name;
  const char* summary;
  CommandFunction run;
};

/// Runs the subcommand named by args[0] with the rest of `args` (the program's own name not
/// included), or prints the usage for --help and the version for --version. Turns a
/// surfcomp::Error into one line on stderr: returns 0 on success, 1 for bad input, 2 for a
/// command line that cannot run as given, 3 for an internal error.
int run_command_line(const std::vector<std::string>& args);

int surf_build(const std::vector<std::string>& args);
int cp_detect(const std::vector<std::string>& args);
int hsi_build(const std::vector<std::string>& args);
int match(const std::vector<std::string>& args);
int dock(const std::vector<std::string>& args);
int matrix(const std::vector<std::string>& args);
int library(const std::vector<std::string>& args);
int screen(const std::vector<std::string>& args);
int report(const std::vector<std::string>& args);
int patch_map(const std::vector<std::string>& args);
int pockets(const std::vector<std::string>& args);

}  // namespace surfcomp::tools
