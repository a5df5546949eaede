// The screen split over the ranks of an MPI job (tools/screen_mpi.cpp, built when MPI is found):
// the one place of the program that calls MPI, through the MPI module it loads (mpi_module.hpp).
#pragma once

#include "surfcomp/screening/screen.hpp"

#include <vector>

namespace surfcomp::tools {

/// Whether this build has the MPI path and this process was started by an MPI launcher
/// (mpirun/mpiexec of Open MPI, or any PMI/PMIx launch), as its environment says. When it was,
/// also loads the MPI module, so that a missing module stops the run before its work: throws
/// InputError naming the module and the folders tried when it cannot be loaded.
bool launched_by_mpi();

/// The result of a screen split over the ranks.
struct DistributedScreen {
  bool root = true;  ///< rank 0: the one that writes the outputs
  int ranks = 1;
  screening::ScreenResult result;  ///< hits on rank 0 only; stage times as rank 0 saw them
};

/// screening::screen over the ranks of MPI_COMM_WORLD: each rank scores a contiguous slice of
/// the entries (stage 1), rank 0 gathers the scores and picks the conformers to refine, each
/// refined (stage 2) by the rank whose slice holds it and gathered again, then the candidates,
/// whose full matches (stage 3) are dealt out round-robin and gathered, and rank 0 ranks the
/// hits: the same hits as one process. Initialises and finalises MPI; an error on one rank aborts
/// the job after printing it. Every rank must give the same query, library and options.
DistributedScreen screen_distributed(const screening::ScreenQuery& query,
                                     const screening::Library& library,
                                     const screening::ScreenOptions& options);

}  // namespace surfcomp::tools
