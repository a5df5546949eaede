#include "mpi_loader.hpp"

#include "surfcomp/core/loadable_module.hpp"

namespace surfcomp::tools {

const MpiModule& mpi() {
  static const MpiModule& module =
      *static_cast<const MpiModule*>(module_symbol(kMpiModuleFile, kMpiModuleSymbol));
  return module;
}

}  // namespace surfcomp::tools
