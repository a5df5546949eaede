// The screen over the ranks of an MPI job (see screen_mpi.hpp), its MPI calls made through the
// MPI module (mpi_module.hpp). Scores travel as doubles, so rank 0 ranks exactly the numbers one
// process would have computed.
#include "screen_mpi.hpp"

#include "mpi_loader.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/stopwatch.hpp"

#include <tbb/parallel_for.h>

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

constexpr int kDoubles = 20;  // score, shape, chem, atoms, then the 16 transform numbers

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
  for (std::size_t i = 0; i < owner.size(); ++i) {
    if (owner[i] == rank) mine.push_back(i);
  }
  std::vector<double> packed(mine.size() * kDoubles);
  tbb::parallel_for(std::size_t{0}, mine.size(),
                    [&](std::size_t j) { pack(score(mine[j]), &packed[j * kDoubles]); });
  const std::vector<double> all = gather_any(packed, rank, ranks);
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

/// A hit as doubles: the entry, the stage, the fast score, then the score (pack).
constexpr int kHitDoubles = 3 + kDoubles;

void pack_hit(const screening::Hit& hit, double* out) {
  out[0] = static_cast<double>(hit.entry);
  out[1] = hit.stage;
  out[2] = hit.fast_score;
  pack(hit.score, out + 3);
}

screening::Hit unpack_hit(const double* in) {
  return {static_cast<std::size_t>(in[0]), static_cast<int>(in[1]), unpack(in + 3), in[2]};
}

DistributedScreen run(const std::vector<const screening::ScreenQuery*>& queries,
                      const screening::Library& library, const screening::ScreenOptions& options,
                      int rank, int ranks) {
  matching::validate(screening::query_match_options(*queries.front(), options));
  const Stopwatch clock;
  const std::size_t q_count = queries.size();
  // Stages 1 and 2: a slice of whole molecules per rank, about n / ranks entries each.
  const auto slice_begin = [&](int r) {
    return screening::molecule_start_at(
        library, library.size() * static_cast<std::size_t>(r) / static_cast<std::size_t>(ranks));
  };
  const screening::StreamedScores mine = screening::score_molecules(
      queries, library, slice_begin(rank), slice_begin(rank + 1), options);
  std::vector<std::vector<screening::Hit>> best(q_count);
  for (std::size_t q = 0; q < q_count; ++q) {
    const screening::QueryScores& local = mine.queries[q];
    std::vector<double> packed(local.best.size() * kHitDoubles);
    for (std::size_t i = 0; i < local.best.size(); ++i)
      pack_hit(local.best[i], &packed[i * kHitDoubles]);
    const std::vector<double> gathered = gather_any(packed, rank, ranks);
    std::vector<screening::Hit> hits;
    for (std::size_t at = 0; at < gathered.size(); at += kHitDoubles)
      hits.push_back(unpack_hit(&gathered[at]));
    if (rank == 0) best[q] = screening::merge_best({hits}, options, queries.front()->shape_weight);
  }
  // For the fused ranking, each rank's molecules that it may need (bounded lists), as the
  // molecule then each query's entry and score.
  std::vector<screening::MoleculeScores> molecules;
  if (q_count > 1) {
    std::vector<double> local;
    for (const screening::MoleculeScores& m : mine.molecules) {
      local.push_back(static_cast<double>(m.molecule));
      for (const screening::MoleculeScore& s : m.scores) {
        local.push_back(static_cast<double>(s.entry));
        local.push_back(s.score);
      }
    }
    const std::vector<double> every = gather_any(local, rank, ranks);
    for (std::size_t at = 0; at < every.size(); at += 1 + 2 * q_count) {
      screening::MoleculeScores m{static_cast<std::size_t>(every[at]), {}};
      for (std::size_t q = 0; q < q_count; ++q) {
        m.scores.push_back(
            {static_cast<std::size_t>(every[at + 1 + 2 * q]), every[at + 2 + 2 * q]});
      }
      molecules.push_back(std::move(m));
    }
  }
  const double stages12_seconds = clock.elapsed_s();

  // Stage 3: rank 0 picks each query's candidates and deals them out round-robin.
  std::vector<std::uint64_t> chosen;  // (query, entry) pairs
  if (rank == 0) {
    for (std::size_t q = 0; q < q_count; ++q) {
      for (std::size_t i = 0; i < best[q].size() && i < options.candidates; ++i) {
        chosen.push_back(q);
        chosen.push_back(best[q][i].entry);
      }
    }
  }
  chosen = broadcast(std::move(chosen));
  std::vector<int> round_robin(chosen.size() / 2);
  for (std::size_t i = 0; i < round_robin.size(); ++i)
    round_robin[i] = static_cast<int>(i % static_cast<std::size_t>(ranks));
  const std::vector<screening::HitScore> full =
      deal_out(round_robin, rank, ranks, [&](std::size_t i) {
        return screening::full_score(*queries[chosen[2 * i]], library.entry(chosen[2 * i + 1]),
                                     options);
      });

  DistributedScreen result;
  result.root = rank == 0;
  result.ranks = ranks;
  // The stage times as rank 0 saw them: its own stages 1 and 2, in proportion, with the gathers.
  const double own = mine.stage1_seconds + mine.stage2_seconds;
  const double share = own > 0 ? mine.stage1_seconds / own : 1.0;
  result.result.stage1_seconds = stages12_seconds * share;
  result.result.stage2_seconds = stages12_seconds - result.result.stage1_seconds;
  result.result.stage3_seconds = clock.elapsed_s() - stages12_seconds;
  if (rank != 0) return result;
  screening::MultiScreenResult ranked =
      screening::rank_and_fuse(best, full, molecules, options, queries.front()->shape_weight);
  result.result.hits = std::move(ranked.hits);
  result.result.fused = std::move(ranked.fused);
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
  int rank = 0, ranks = 1;
  mpi().init(&rank, &ranks);
  DistributedScreen result;
  try {
    result = run(queries, library, options, rank, ranks);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "surfcomp screen: rank %d: error: %s\n", rank, e.what());
    mpi().abort(1);
  }
  mpi().finalize();
  return result;
}

}  // namespace surfcomp::tools
