// The rows of a screen from what its stages left: the ranges' best molecules merged, the
// candidates ranked by their full matches, and the fused ranking of several queries.
#include "surfcomp/screening/screen.hpp"

#include "screen_stages.hpp"

#include "surfcomp/core/error.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::screening {

std::vector<Hit> merge_best(const std::vector<std::vector<Hit>>& parts,
                            const ScreenOptions& options, double shape_weight) {
  KeptMolecules<Hit> kept(options, shape_weight);
  for (const std::vector<Hit>& part : parts) {
    for (const Hit& hit : part) kept.add(hit);
  }
  return kept.sorted();
}

std::vector<Hit> rank_hits(const std::vector<Hit>& best, const std::vector<HitScore>& full,
                           std::size_t top, double shape_weight) {
  const std::size_t k = std::min(full.size(), best.size());
  std::vector<Hit> hits;
  for (std::size_t i = 0; i < best.size(); ++i) {
    hits.push_back(i < k ? Hit{best[i].entry, 3, full[i], best[i].fast_score} : best[i]);
    hits.back().score.score = ranking_score(hits.back().score, shape_weight);
  }
  std::sort(hits.begin(), hits.begin() + static_cast<std::ptrdiff_t>(k), BetterHit{});
  if (top > 0 && hits.size() > top) hits.resize(top);
  return hits;
}

std::vector<FusedHit> fuse_scores(const std::vector<MoleculeScores>& molecules,
                                  const std::vector<std::vector<Hit>>& ranked, Fusion fusion,
                                  std::size_t top) {
  if (ranked.empty()) throw InputError("fusion: no query");
  // Each query's stage-3 scores by the entry they are of.
  std::vector<std::map<std::size_t, double>> final_scores(ranked.size());
  for (std::size_t q = 0; q < ranked.size(); ++q) {
    for (const Hit& hit : ranked[q]) {
      if (hit.stage == 3) final_scores[q][hit.entry] = hit.score.score;
    }
  }
  std::vector<FusedMolecule> rows;
  for (const MoleculeScores& molecule : molecules) {
    if (molecule.scores.size() != ranked.size()) {
      throw InputError("fusion: molecule " + std::to_string(molecule.molecule + 1) + " has " +
                       std::to_string(molecule.scores.size()) + " scores for " +
                       std::to_string(ranked.size()) + " queries");
    }
    FusedMolecule row{0.0, molecule};
    for (std::size_t q = 0; q < ranked.size(); ++q) {
      MoleculeScore& s = row.all.scores[q];
      const auto full = final_scores[q].find(s.entry);
      if (full != final_scores[q].end()) s.score = full->second;
    }
    row.score = fused_score(row.all.scores, fusion).first;
    rows.push_back(std::move(row));
  }
  std::sort(rows.begin(), rows.end(), BetterFused());
  if (top > 0 && rows.size() > top) rows.resize(top);
  std::vector<FusedHit> fused;
  for (const FusedMolecule& row : rows) {
    FusedHit hit;
    hit.query = fused_score(row.all.scores, fusion).second;
    hit.entry = row.all.scores[hit.query].entry;
    hit.score = row.score;
    for (const MoleculeScore& s : row.all.scores) hit.scores.push_back(s.score);
    fused.push_back(std::move(hit));
  }
  return fused;
}

MultiScreenResult rank_and_fuse(const std::vector<std::vector<Hit>>& best,
                                const std::vector<HitScore>& full,
                                const std::vector<MoleculeScores>& molecules,
                                const ScreenOptions& options, double shape_weight) {
  MultiScreenResult result;
  std::vector<std::vector<Hit>> rows;  // each query's every row: its every stage-3 score
  for (std::size_t q = 0, at = 0; q < best.size(); ++q) {
    const std::size_t k = std::min(options.candidates, best[q].size());
    if (at + k > full.size()) throw InputError("fusion: fewer stage-3 scores than candidates");
    const std::vector<HitScore> mine(full.begin() + static_cast<std::ptrdiff_t>(at),
                                     full.begin() + static_cast<std::ptrdiff_t>(at + k));
    at += k;
    rows.push_back(rank_hits(best[q], mine, 0, shape_weight));
    const std::size_t shown =
        options.top == 0 ? rows.back().size() : std::min(options.top, rows.back().size());
    result.hits.emplace_back(rows.back().begin(),
                             rows.back().begin() + static_cast<std::ptrdiff_t>(shown));
  }
  if (best.size() > 1) result.fused = fuse_scores(molecules, rows, options.fusion, options.top);
  return result;
}

}  // namespace surfcomp::screening
