// The screen engine: stages 1 and 2 on this process's slice of the library, the best molecules
// gathered, the candidates' full matches dealt out and gathered, and the hits ranked, over the
// processes of an Exchange; one process is the Exchange of one. Scores travel as doubles, so
// process 0 ranks exactly the numbers one process would have computed.
#include "surfcomp/screening/screen.hpp"

#include "screen_stages.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/stopwatch.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace surfcomp::screening {
namespace {

constexpr std::size_t kScoreDoubles = 20;  // score, shape, chem, atoms, the 16 transform numbers

void pack(const HitScore& s, double* out) {
  out[0] = s.score;
  out[1] = s.shape;
  out[2] = s.chem;
  out[3] = s.atoms;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out[4 + 4 * r + c] = s.transform(r, c);
  }
}

HitScore unpack(const double* in) {
  HitScore s;
  s.score = in[0];
  s.shape = in[1];
  s.chem = in[2];
  s.atoms = in[3];
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) s.transform(r, c) = in[4 + 4 * r + c];
  }
  return s;
}

/// A hit as doubles: the entry, the stage, the fast score, then the score (pack).
constexpr std::size_t kHitDoubles = 3 + kScoreDoubles;

void pack_hit(const Hit& hit, double* out) {
  out[0] = static_cast<double>(hit.entry);
  out[1] = hit.stage;
  out[2] = hit.fast_score;
  pack(hit.score, out + 3);
}

Hit unpack_hit(const double* in) {
  return {static_cast<std::size_t>(in[0]), static_cast<int>(in[1]), unpack(in + 3), in[2]};
}

/// The entry where process p's slice begins: about library.size() * p / processes, at the start
/// of a molecule.
std::size_t slice_begin(const Library& library, int p, int processes) {
  return molecule_start_at(
      library, library.size() * static_cast<std::size_t>(p) / static_cast<std::size_t>(processes));
}

/// Each query's best molecules of every process's slice, merged on process 0 (empty elsewhere).
std::vector<std::vector<Hit>> gather_best(const StreamedScores& mine, const ScreenOptions& options,
                                          double shape_weight, Exchange& exchange) {
  std::vector<std::vector<Hit>> best(mine.queries.size());
  for (std::size_t q = 0; q < mine.queries.size(); ++q) {
    const std::vector<Hit>& local = mine.queries[q].best;
    std::vector<double> packed(local.size() * kHitDoubles);
    for (std::size_t i = 0; i < local.size(); ++i) pack_hit(local[i], &packed[i * kHitDoubles]);
    const std::vector<double> gathered = exchange.gather(packed);
    std::vector<Hit> hits;
    for (std::size_t at = 0; at < gathered.size(); at += kHitDoubles)
      hits.push_back(unpack_hit(&gathered[at]));
    if (exchange.process() == 0) best[q] = merge_best({hits}, options, shape_weight);
  }
  return best;
}

/// Every process's molecules that a fused ranking may need (StreamedScores::molecules), on
/// process 0 in process order, each as its first entry then each query's entry and score.
std::vector<MoleculeScores> gather_molecules(const StreamedScores& mine, std::size_t queries,
                                             Exchange& exchange) {
  std::vector<double> local;
  for (const MoleculeScores& m : mine.molecules) {
    local.push_back(static_cast<double>(m.molecule));
    for (const MoleculeScore& s : m.scores) {
      local.push_back(static_cast<double>(s.entry));
      local.push_back(s.score);
    }
  }
  const std::vector<double> every = exchange.gather(local);
  std::vector<MoleculeScores> molecules;
  for (std::size_t at = 0; at < every.size(); at += 1 + 2 * queries) {
    MoleculeScores m{static_cast<std::size_t>(every[at]), {}};
    for (std::size_t q = 0; q < queries; ++q)
      m.scores.push_back({static_cast<std::size_t>(every[at + 1 + 2 * q]), every[at + 2 + 2 * q]});
    molecules.push_back(std::move(m));
  }
  return molecules;
}

/// Stage 3: process 0 picks each query's first options.candidates best molecules; the (query,
/// entry) pairs are dealt out round-robin, scored in parallel on their process and gathered on
/// process 0 in pick order (empty elsewhere).
std::vector<HitScore> full_scores(const std::vector<const ScreenQuery*>& queries,
                                  const Library& library, const ScreenOptions& options,
                                  const std::vector<std::vector<Hit>>& best, Exchange& exchange) {
  std::vector<std::uint64_t> chosen;  // (query, entry) pairs
  if (exchange.process() == 0) {
    for (std::size_t q = 0; q < best.size(); ++q) {
      for (std::size_t i = 0; i < best[q].size() && i < options.candidates; ++i) {
        chosen.push_back(q);
        chosen.push_back(best[q][i].entry);
      }
    }
  }
  chosen = exchange.broadcast(std::move(chosen));
  const auto processes = static_cast<std::size_t>(exchange.processes());
  std::vector<std::size_t> mine;
  for (std::size_t i = static_cast<std::size_t>(exchange.process()); i < chosen.size() / 2;
       i += processes)
    mine.push_back(i);
  const std::vector<HitScore> scores =
      score_in_parallel(mine.size(), 3, options, [&](std::size_t j) {
        const std::size_t i = mine[j];
        return full_score(*queries[chosen[2 * i]], library.entry(chosen[2 * i + 1]), options);
      });
  std::vector<double> packed(scores.size() * kScoreDoubles);
  for (std::size_t j = 0; j < scores.size(); ++j) pack(scores[j], &packed[j * kScoreDoubles]);
  const std::vector<double> all = exchange.gather(packed);
  std::vector<HitScore> full;
  if (exchange.process() != 0) return full;
  // Process p sent the items p, p + processes, ...: put each back at its place.
  full.resize(chosen.size() / 2);
  std::size_t at = 0;
  for (std::size_t p = 0; p < processes; ++p) {
    for (std::size_t i = p; i < full.size(); i += processes)
      full[i] = unpack(&all[kScoreDoubles * at++]);
  }
  return full;
}

}  // namespace

MultiScreenResult screen_queries(const std::vector<const ScreenQuery*>& queries,
                                 const Library& library, const ScreenOptions& options,
                                 Exchange& exchange) {
  if (queries.empty()) throw InputError("screen: no query");
  matching::validate(query_match_options(*queries.front(), options));
  const Stopwatch clock;
  const int p = exchange.process(), processes = exchange.processes();
  const StreamedScores mine = score_molecules(queries, library, slice_begin(library, p, processes),
                                              slice_begin(library, p + 1, processes), options);
  const double shape_weight = queries.front()->shape_weight;
  const std::vector<std::vector<Hit>> best = gather_best(mine, options, shape_weight, exchange);
  std::vector<MoleculeScores> molecules;
  if (queries.size() > 1) molecules = gather_molecules(mine, queries.size(), exchange);
  const double stages12_seconds = clock.elapsed_s();
  const std::vector<HitScore> full = full_scores(queries, library, options, best, exchange);

  MultiScreenResult result;
  // Stages 1 and 2 with the gathers, split in the proportion of this process's own times.
  const double own = mine.stage1_seconds + mine.stage2_seconds;
  const double share = own > 0 ? mine.stage1_seconds / own : 1.0;
  result.stage1_seconds = stages12_seconds * share;
  result.stage2_seconds = stages12_seconds - result.stage1_seconds;
  result.stage3_seconds = clock.elapsed_s() - stages12_seconds;
  if (p != 0) return result;
  MultiScreenResult ranked = rank_and_fuse(best, full, molecules, options, shape_weight);
  result.hits = std::move(ranked.hits);
  result.fused = std::move(ranked.fused);
  return result;
}

MultiScreenResult screen_queries(const std::vector<const ScreenQuery*>& queries,
                                 const Library& library, const ScreenOptions& options) {
  SingleProcess one;
  return screen_queries(queries, library, options, one);
}

ScreenResult screen(const ScreenQuery& query, const Library& library,
                    const ScreenOptions& options) {
  MultiScreenResult multi = screen_queries({&query}, library, options);
  ScreenResult result;
  result.hits = std::move(multi.hits.front());
  result.stage1_seconds = multi.stage1_seconds;
  result.stage2_seconds = multi.stage2_seconds;
  result.stage3_seconds = multi.stage3_seconds;
  return result;
}

}  // namespace surfcomp::screening
