// The screen and the matrix split over the ranks of an MPI job (tools/screen_mpi.cpp, built when
// MPI is found): the one place of the program that calls MPI, through the MPI module it loads
// (mpi_module.hpp).
#pragma once

#include "surfcomp/screening/matrix.hpp"
#include "surfcomp/screening/screen.hpp"

#include <filesystem>

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
  screening::MultiScreenResult result;  ///< hits on rank 0 only; stage times as rank 0 saw them
};

/// screening::screen_queries over the ranks of MPI_COMM_WORLD (its Exchange overload: the same
/// rows as one process, on rank 0). Initialises and finalises MPI; an error on one rank aborts
/// the job after printing it. Every rank must give the same queries, library and options.
DistributedScreen screen_distributed(const std::vector<const screening::ScreenQuery*>& queries,
                                     const screening::Library& library,
                                     const screening::ScreenOptions& options);

/// The result of a matrix split over the ranks.
struct DistributedMatrix {
  bool root = true;  ///< rank 0: the one that writes the outputs
  int ranks = 1;
  screening::SimilarityMatrix matrix;  ///< its cells on rank 0 only
};

/// screening::similarity_matrix over the ranks of MPI_COMM_WORLD (its Exchange overload: the
/// same matrix as one process, on rank 0). Initialises and finalises MPI; an error on one rank
/// aborts the job after printing it. Every rank must give the same sets and options.
DistributedMatrix matrix_distributed(const std::vector<std::filesystem::path>& set,
                                     const std::vector<std::filesystem::path>& against,
                                     const screening::MatrixOptions& options);

}  // namespace surfcomp::tools
