// The screen over the ranks of an MPI job (see screen_mpi.hpp), its MPI calls made through the
// MPI module (mpi_module.hpp). Scores travel as doubles, so rank 0 ranks exactly the numbers one
// process would have computed.
#include "screen_mpi.hpp"

#include "mpi_module.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/loadable_module.hpp"
#include "surfcomp/core/stopwatch.hpp"

#include <tbb/parallel_for.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

namespace surfcomp::tools {
namespace {

constexpr int kDoubles = 20;  // score, shape, chem, atoms, then the 16 transform numbers

/// The MPI module, loaded on the first call; throws FileError when it cannot be loaded.
const MpiModule& mpi() {
  static const MpiModule& module =
      *static_cast<const MpiModule*>(module_symbol(kMpiModuleFile, kMpiModuleSymbol));
  return module;
}

void pack(const screening::HitScore& s, double* out) {
  out[0] = s.score;
  out[1] = s.shape;
  out[2] = s.chem;
  out[3] = s.atoms;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out[4 + 4 * r + c] = s.transform(r, c);
  }
}

screening::HitScore unpack(const double* in) {
  screening::HitScore s;
  s.score = in[0];
  s.shape = in[1];
  s.chem = in[2];
  s.atoms = in[3];
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) s.transform(r, c) = in[4 + 4 * r + c];
  }
  return s;
}

/// Gathers every rank's packed scores on rank 0, in rank order; `counts` (scores per rank) is
/// known to every rank.
std::vector<double> gather(const std::vector<double>& local, const std::vector<int>& counts,
                           int rank) {
  std::vector<int> sizes(counts.size()), displacements(counts.size());
  int total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    sizes[r] = counts[r] * kDoubles;
    displacements[r] = total;
    total += sizes[r];
  }
  std::vector<double> all(rank == 0 ? static_cast<std::size_t>(total) : 0);
  mpi().gather_doubles(local.data(), static_cast<int>(local.size()), all.data(), sizes.data(),
                       displacements.data());
  return all;
}

/// Rank 0's list `chosen`, sent to every rank.
std::vector<std::uint64_t> broadcast(std::vector<std::uint64_t> chosen) {
  std::uint64_t k = chosen.size();
  mpi().broadcast_uint64(&k, 1);
  chosen.resize(k);
  mpi().broadcast_uint64(chosen.data(), static_cast<int>(k));
  return chosen;
}

/// score(i) for every item i, on the rank owner[i] (in parallel there), gathered on rank 0 in
/// item order; empty on the other ranks. Every rank passes the same owners.
template <class Score>
std::vector<screening::HitScore> deal_out(const std::vector<int>& owner, int rank, int ranks,
                                          const Score& score) {
  std::vector<std::size_t> mine;
  std::vector<int> counts(static_cast<std::size_t>(ranks), 0);
  for (std::size_t i = 0; i < owner.size(); ++i) {
    ++counts[static_cast<std::size_t>(owner[i])];
    if (owner[i] == rank) mine.push_back(i);
  }
  std::vector<double> packed(mine.size() * kDoubles);
  tbb::parallel_for(std::size_t{0}, mine.size(),
                    [&](std::size_t j) { pack(score(mine[j]), &packed[j * kDoubles]); });
  const std::vector<double> all = gather(packed, counts, rank);
  std::vector<screening::HitScore> scores;
  if (rank != 0) return scores;
  scores.resize(owner.size());
  std::size_t at = 0;
  for (int r = 0; r < ranks; ++r) {
    for (std::size_t i = 0; i < owner.size(); ++i) {
      if (owner[i] == r) scores[i] = unpack(&all[kDoubles * at++]);
    }
  }
  return scores;
}

DistributedScreen run(const screening::ScreenQuery& query, const screening::Library& library,
                      const screening::ScreenOptions& options, int rank, int ranks) {
  matching::validate(screening::query_match_options(query, options));
  screening::check_library_kind(library,
                                !query.site.empty());  // on every rank, before any collective
  const Stopwatch clock;
  const std::size_t n = library.size();
  const auto slice_begin = [&](int r) {
    return n * static_cast<std::size_t>(r) / static_cast<std::size_t>(ranks);
  };
  // Stage 1: a contiguous slice per rank.
  const std::vector<screening::HitScore> mine =
      screening::fast_scores(query, library, slice_begin(rank), slice_begin(rank + 1), options);
  std::vector<double> packed(mine.size() * kDoubles);
  for (std::size_t i = 0; i < mine.size(); ++i) pack(mine[i], &packed[i * kDoubles]);
  std::vector<int> counts(static_cast<std::size_t>(ranks));
  for (int r = 0; r < ranks; ++r)
    counts[static_cast<std::size_t>(r)] = static_cast<int>(slice_begin(r + 1) - slice_begin(r));
  const std::vector<double> all = gather(packed, counts, rank);

  // Stage 2: rank 0 picks the conformers to refine and tells the others.
  std::vector<screening::HitScore> fast;
  std::vector<std::uint64_t> to_refine;
  if (rank == 0) {
    for (std::size_t e = 0; e < n; ++e) fast.push_back(unpack(&all[e * kDoubles]));
    for (const std::size_t e : screening::entries_to_refine(library, fast, options.refine))
      to_refine.push_back(e);
  }
  const double stage1_seconds = clock.elapsed_s();
  to_refine = broadcast(std::move(to_refine));
  // Each conformer is refined by the rank whose slice holds it: a rank reads only its slice.
  std::vector<int> slice_of(to_refine.size());
  for (std::size_t i = 0, r = 0; i < to_refine.size(); ++i) {
    while (to_refine[i] >= slice_begin(static_cast<int>(r) + 1)) ++r;
    slice_of[i] = static_cast<int>(r);
  }
  const std::vector<screening::HitScore> refined =
      deal_out(slice_of, rank, ranks, [&](std::size_t i) {
        return screening::refined_score(query, library.entry(to_refine[i]), options);
      });

  // Stage 3: rank 0 picks the candidates and tells the others.
  std::vector<screening::EntryScore> scores;
  std::vector<std::size_t> best;
  std::vector<std::uint64_t> chosen;
  if (rank == 0) {
    scores = screening::merge_refined(
        fast, std::vector<std::size_t>(to_refine.begin(), to_refine.end()), refined);
    best = screening::best_entry_per_molecule(library, scores);
    for (std::size_t i = 0; i < best.size() && i < options.candidates; ++i)
      chosen.push_back(best[i]);
  }
  const double stage2_seconds = clock.elapsed_s() - stage1_seconds;
  chosen = broadcast(std::move(chosen));
  // The candidates, few and costly, go round-robin.
  std::vector<int> round_robin(chosen.size());
  for (std::size_t i = 0; i < chosen.size(); ++i)
    round_robin[i] = static_cast<int>(i % static_cast<std::size_t>(ranks));
  const std::vector<screening::HitScore> full =
      deal_out(round_robin, rank, ranks, [&](std::size_t i) {
        return screening::full_score(query, library.entry(chosen[i]), options);
      });

  DistributedScreen result;
  result.root = rank == 0;
  result.ranks = ranks;
  result.result.stage1_seconds = stage1_seconds;
  result.result.stage2_seconds = stage2_seconds;
  result.result.stage3_seconds = clock.elapsed_s() - stage1_seconds - stage2_seconds;
  if (rank == 0) result.result.hits = screening::rank_hits(best, scores, full, options.top);
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

DistributedScreen screen_distributed(const screening::ScreenQuery& query,
                                     const screening::Library& library,
                                     const screening::ScreenOptions& options) {
  int rank = 0, ranks = 1;
  mpi().init(&rank, &ranks);
  DistributedScreen result;
  try {
    result = run(query, library, options, rank, ranks);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "surfcomp screen: rank %d: error: %s\n", rank, e.what());
    mpi().abort(1);
  }
  mpi().finalize();
  return result;
}

}  // namespace surfcomp::tools
