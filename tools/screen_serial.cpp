// The program's MPI entry points when it is built without MPI: never launched by MPI.
#include "screen_mpi.hpp"

#include "surfcomp/core/error.hpp"

namespace surfcomp::tools {

bool launched_by_mpi() { return false; }

DistributedScreen screen_distributed(const std::vector<const screening::ScreenQuery*>& /*queries*/,
                                     const screening::Library& /*library*/,
                                     const screening::ScreenOptions& /*options*/) {
  throw InputError("this surfcomp was built without MPI");
}

DistributedMatrix matrix_distributed(const std::vector<std::filesystem::path>& /*set*/,
                                     const std::vector<std::filesystem::path>& /*against*/,
                                     const screening::MatrixOptions& /*options*/) {
  throw InputError("this surfcomp was built without MPI");
}

}  // namespace surfcomp::tools
