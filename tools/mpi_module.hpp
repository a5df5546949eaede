// The interface between the program and its MPI module, libsurfcomp_mpi.so (mpi_module.cpp): the
// MPI calls of the distributed screen (screen_mpi.cpp) and library build (library.cpp), as plain
// functions. The module alone links Open MPI, and the program loads it (mpi_loader.hpp) only when
// an MPI launcher started it, so that no other run maps and initialises Open MPI's libraries
// (docs/decisions.md#loadable-modules).
#pragma once

#include <cstdint>

namespace surfcomp::tools {

/// The module file and its one exported symbol, a `const MpiModule`.
constexpr const char* kMpiModuleFile = "libsurfcomp_mpi.so";
constexpr const char* kMpiModuleSymbol = "surfcomp_mpi_module_1";

/// The MPI calls, all over MPI_COMM_WORLD with rank 0 as the root. An MPI error aborts the job
/// (MPI's default error handler), so none returns a status.
struct MpiModule {
  /// MPI_Init_thread asking for MPI_THREAD_FUNNELED; then this process's rank and the number of
  /// ranks.
  void (*init)(int* rank, int* ranks);
  /// MPI_Gatherv of `count` doubles from every rank into `all` on rank 0, rank r's at
  /// `displacements[r]`, `counts[r]` of them (both read on rank 0 only).
  void (*gather_doubles)(const double* local, int count, double* all, const int* counts,
                         const int* displacements);
  /// MPI_Bcast of `count` unsigned 64-bit integers from rank 0.
  void (*broadcast_uint64)(std::uint64_t* values, int count);
  /// MPI_Abort with exit status `status`.
  void (*abort)(int status);
  /// MPI_Finalize.
  void (*finalize)();
};

}  // namespace surfcomp::tools
