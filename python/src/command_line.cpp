// `python3 -m surfcomp ...`: the surfcomp command line run in-process (tools/cli.cpp), the same
// subcommands, options, messages and exit statuses as the program. An extension of its own, so
// that the library module (_surfcomp) does not link the command line.
#include "command.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace py = pybind11;

PYBIND11_MODULE(_command_line, m) {
  m.doc() = "The surfcomp command line, for `python3 -m surfcomp`.";
  m.def(
      "run_command_line",
      [](const std::vector<std::string>& args) {
        py::gil_scoped_release release;
        return surfcomp::tools::run_command_line(args);
      },
      py::arg("args"));
}
