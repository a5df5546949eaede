// The MPI module (mpi_module.hpp) as the program's MPI paths reach it: loaded on first use, so
// that only a run started by an MPI launcher maps Open MPI's libraries.
#pragma once

#include "mpi_module.hpp"

namespace surfcomp::tools {

/// The MPI module, loaded on the first call (module_symbol); throws FileError naming the module
/// and the folders tried when it cannot be loaded.
const MpiModule& mpi();

}  // namespace surfcomp::tools
