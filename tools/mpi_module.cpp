// libsurfcomp_mpi.so: the MPI calls of the distributed screen and library build (mpi_module.hpp)
// over Open MPI.
#include "mpi_module.hpp"

#include <mpi.h>

namespace surfcomp::tools {
namespace {

void init(int* rank, int* ranks) {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, ranks);
}

void gather_doubles(const double* local, int count, double* all, const int* counts,
                    const int* displacements) {
  MPI_Gatherv(local, count, MPI_DOUBLE, all, counts, displacements, MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

void broadcast_uint64(std::uint64_t* values, int count) {
  MPI_Bcast(values, count, MPI_UINT64_T, 0, MPI_COMM_WORLD);
}

void abort_job(int status) { MPI_Abort(MPI_COMM_WORLD, status); }

void finalize() { MPI_Finalize(); }

}  // namespace
}  // namespace surfcomp::tools

extern "C" __attribute__((visibility("default")))
const surfcomp::tools::MpiModule surfcomp_mpi_module_1 = {
    &surfcomp::tools::init, &surfcomp::tools::gather_doubles, &surfcomp::tools::broadcast_uint64,
    &surfcomp::tools::abort_job, &surfcomp::tools::finalize};
