// The screen over the ranks of an MPI job (see screen_mpi.hpp): MPI as the transport of the
// screen engine (screening::screen_queries with an Exchange), its calls made through the MPI
// module (mpi_module.hpp).
#include "screen_mpi.hpp"

#include "mpi_loader.hpp"
#include "surfcomp/core/error.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <string>
#include <vector>

namespace surfcomp::tools {
namespace {

/// Every rank's `local` doubles gathered on rank 0 in rank order (their counts gathered first).
std::vector<double> gather_any(const std::vector<double>& local, int rank, int ranks) {
  const std::vector<double> count{static_cast<double>(local.size())};
  std::vector<int> ones(static_cast<std::size_t>(ranks), 1), at(static_cast<std::size_t>(ranks));
  for (int r = 0; r < ranks; ++r) at[static_cast<std::size_t>(r)] = r;
  std::vector<double> counts(rank == 0 ? static_cast<std::size_t>(ranks) : 0);
  mpi().gather_doubles(count.data(), 1, counts.data(), ones.data(), at.data());
  std::vector<int> sizes(static_cast<std::size_t>(ranks)), displacements(sizes.size());
  int total = 0;
  double sum = 0.0;  // MPI counts and offsets are ints
  for (std::size_t r = 0; r < counts.size(); ++r) {
    sum += counts[r];
    if (sum > std::numeric_limits<int>::max()) {
      throw InputError("the processes' results (" +
                       std::to_string(static_cast<std::uint64_t>(sum)) +
                       " numbers and more) are too large for one MPI gather: give --top N");
    }
    sizes[r] = static_cast<int>(counts[r]);
    displacements[r] = total;
    total += sizes[r];
  }
  std::vector<double> all(rank == 0 ? static_cast<std::size_t>(total) : 0);
  mpi().gather_doubles(local.data(), static_cast<int>(local.size()), all.data(), sizes.data(),
                       displacements.data());
  return all;
}

/// The ranks of MPI_COMM_WORLD as the screen's processes.
class MpiExchange final : public screening::Exchange {
 public:
  MpiExchange(int rank, int ranks) : rank_(rank), ranks_(ranks) {}
  int process() const override { return rank_; }
  int processes() const override { return ranks_; }
  std::vector<double> gather(const std::vector<double>& local) override {
    return gather_any(local, rank_, ranks_);
  }
  std::vector<std::uint64_t> broadcast(std::vector<std::uint64_t> values) override {
    std::uint64_t k = values.size();
    mpi().broadcast_uint64(&k, 1);
    values.resize(k);
    mpi().broadcast_uint64(values.data(), static_cast<int>(k));
    return values;
  }

 private:
  int rank_, ranks_;
};

/// `work` on this rank's exchange between MPI's start and end; an error on a rank printed, as
/// `command`'s, and the job aborted.
template <class Result, class Work>
Result on_ranks(const char* command, const Work& work) {
  int rank = 0, ranks = 1;
  mpi().init(&rank, &ranks);
  Result result;
  result.root = rank == 0;
  result.ranks = ranks;
  try {
    MpiExchange exchange(rank, ranks);
    work(exchange, result);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "surfcomp %s: rank %d: error: %s\n", command, rank, e.what());
    mpi().abort(1);
  }
  mpi().finalize();
  return result;
}

}  // namespace

bool launched_by_mpi() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"}) {
    if (std::getenv(variable) == nullptr) continue;
    try {
      mpi();
    } catch (const FileError& e) {
      throw InputError(std::string("run by an MPI launcher, which needs the MPI module: ") +
                       e.what());
    }
    return true;
  }
  return false;
}

DistributedScreen screen_distributed(const std::vector<const screening::ScreenQuery*>& queries,
                                     const screening::Library& library,
                                     const screening::ScreenOptions& options) {
  return on_ranks<DistributedScreen>(
      "screen", [&](screening::Exchange& exchange, DistributedScreen& out) {
        out.result = screening::screen_queries(queries, library, options, exchange);
      });
}

DistributedMatrix matrix_distributed(const std::vector<std::filesystem::path>& set,
                                     const std::vector<std::filesystem::path>& against,
                                     const screening::MatrixOptions& options) {
  return on_ranks<DistributedMatrix>(
      "matrix", [&](screening::Exchange& exchange, DistributedMatrix& out) {
        out.matrix = screening::similarity_matrix(set, against, options, exchange);
      });
}

}  // namespace surfcomp::tools
