// Internal to the screening module (not installed): the stages of a screen and the ranking of
// what they leave, which the screen engine (screen_engine.cpp) strings together for one process
// or several. The public entry points are screen.hpp's.
#pragma once

#include "surfcomp/screening/screen.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace surfcomp::screening {

/// options.match with the mode the query asks for: MatchMode::binding_sites for a site query.
matching::MatchOptions query_match_options(const ScreenQuery& query, const ScreenOptions& options);

/// Stage 3 of one entry: the full match of the query with the entry's molecule, rebuilt (see
/// ScreenOptions::read, surface; a site's structure described at its site, matched as binding
/// sites, its surface that of the atoms within the site's margin, as molsurf::build_site_surface
/// builds it); the top alignment's overlay score and transform. An entry
/// without any alignment scores 0 with the identity. Throws what reading the molecule,
/// building its surface or matching throws.
HitScore full_score(const ScreenQuery& query, const LibraryEntry& entry,
                    const ScreenOptions& options = {});

/// One molecule's score against one query after stage 2, for a fused ranking.
struct MoleculeScore {
  std::size_t entry = 0;  ///< its best conformer
  double score = 0.0;     ///< what ranks it (ranking_score: ScreenQuery::shape_weight)
};

/// A molecule's scores against every query after stage 2.
struct MoleculeScores {
  std::size_t molecule = 0;           ///< its first entry
  std::vector<MoleculeScore> scores;  ///< one per query, in query order
};

/// What stages 1 and 2 leave of one query over a range of molecules.
struct QueryScores {
  /// Each molecule's best conformer (stage 2, or stage 1 with refine 0): a molecule's entries
  /// get their fast scores, its `refine` best by fast score (ties to the lower index) their
  /// refined scores where those are not lower, and its best entry (ties to the lower index)
  /// stands for it. Only the kept_molecules() best molecules, best first (ties to the lower
  /// entry); for a query ranked by another value (ScreenQuery::shape_weight above 0), the
  /// options.candidates best by score first, then the others by that value. The scores are
  /// overlay scores.
  std::vector<Hit> best;
};

/// The molecules stages 1 and 2 keep per query: every one when options.top is 0, else
/// max(options.top, options.candidates).
std::size_t kept_molecules(const ScreenOptions& options);

/// The molecules stages 1 and 2 keep by fused score for a ranking of `queries` queries: every
/// one when options.top is 0, else options.top + queries * options.candidates. Stage 3 changes
/// the scores of at most queries * options.candidates molecules, so the options.top best after
/// it are among these and the candidates.
std::size_t fused_molecules(const ScreenOptions& options, std::size_t queries);

/// Stages 1 and 2 of some molecules against every query.
struct StreamedScores {
  std::vector<QueryScores> queries;  ///< one per query, in query order
  /// With several queries, what their fused ranking needs (fuse_scores): the fused_molecules()
  /// best molecules by their scores fused (options.fusion; ties to the lower molecule) and every
  /// molecule of a query's `best`, each once, in library order. Empty for one query.
  std::vector<MoleculeScores> molecules;
  double stage1_seconds = 0.0;  ///< wall-clock, summed over the blocks
  double stage2_seconds = 0.0;
};

/// Stages 1 and 2 (see the file comment) of the molecules of entries [begin, end) against every
/// query, streamed: a block of whole molecules at a time is read once, its entries fast-scored
/// against every query and each molecule's best refined, then released (Library::release).
/// `begin` and `end` begin molecules (molecule_start_at). Progress (options.progress) is
/// reported as stage 1 over the range's entries. Throws InputError when an entry is not of the
/// queries' kind (as check_library_kind words it) or the queries are of two kinds (sites and
/// molecules, or ranked by different shape weights: agree_on_chemistry), FormatError
/// for a damaged entry.
StreamedScores score_molecules(const std::vector<const ScreenQuery*>& queries,
                               const Library& library, std::size_t begin, std::size_t end,
                               const ScreenOptions& options = {});

/// The kept_molecules() best of several ranges' lists of one query (QueryScores::best), in
/// its order, ties to the lower entry: what one range of all the molecules would have kept.
std::vector<Hit> merge_best(const std::vector<std::vector<Hit>>& parts,
                            const ScreenOptions& options, double shape_weight);

/// The result rows: first the `full.size()` candidates (the first molecules of `best`, their
/// stage-3 scores in `full`) by their stage-3 score, then the other molecules of `best` in
/// their order, each scored by `shape_weight` times its shape term plus 1 - shape_weight times
/// its score (ScreenQuery::shape_weight); at most `top` rows (0: all).
/// Ties go to the lower entry index.
std::vector<Hit> rank_hits(const std::vector<Hit>& best, const std::vector<HitScore>& full,
                           std::size_t top, double shape_weight);

/// The fused ranking of `molecules`: each one's final score against each query (its score in
/// `molecules`, or its stage-3 score where its best conformer for that query is a stage-3 row of
/// the query's `ranked` hits) fused by `fusion` (max: the highest, mean: the mean over the
/// queries), best first, ties to the lower molecule; at most `top` rows (0: all). For the
/// ranking of a whole screen, `molecules` holds StreamedScores::molecules (of one range, or of
/// several ranges together) and `ranked` each query's every stage-3 row, also those past its
/// table's `--top` (rank_and_fuse). Throws InputError when a molecule has not one score per
/// query.
std::vector<FusedHit> fuse_scores(const std::vector<MoleculeScores>& molecules,
                                  const std::vector<std::vector<Hit>>& ranked, Fusion fusion,
                                  std::size_t top);

/// The rows and fused ranking of a screen from what its stages left: `best` each query's
/// best molecules after stage 2 (merge_best of its ranges), `full` the stage-3 scores of each
/// query's first min(options.candidates, its best) molecules, query after query, `molecules`
/// the ranges' StreamedScores::molecules, `shape_weight` the queries' ScreenQuery::shape_weight.
/// Each query's rows are rank_hits(best, its scores, options.top, shape_weight); the fused ranking
/// (several queries) is fuse_scores with every stage-3 score. Times are left 0. Throws
/// InputError when `full` is short.
MultiScreenResult rank_and_fuse(const std::vector<std::vector<Hit>>& best,
                                const std::vector<HitScore>& full,
                                const std::vector<MoleculeScores>& molecules,
                                const ScreenOptions& options, double shape_weight);

/// What ranks a hit: its score, its shape term, or a weighted mean of the two
/// (ScreenQuery::shape_weight).
inline double ranking_score(const HitScore& score, double shape_weight) {
  return shape_weight * score.shape + (1.0 - shape_weight) * score.score;
}

/// Ranks hits: the higher ranking_score first, ties to the lower entry.
inline bool better_hit(const Hit& x, const Hit& y, double shape_weight = 0.0) {
  const double a = ranking_score(x.score, shape_weight), b = ranking_score(y.score, shape_weight);
  if (a != b) return a > b;
  return x.entry < y.entry;
}

/// The `capacity` best items added (every one when capacity is 0) by `Better`, a strict order,
/// as a heap whose top is the worst kept.
template <class Item, class Better>
class BestItems {
 public:
  explicit BestItems(std::size_t capacity, Better better = {})
      : capacity_(capacity), better_(better) {}
  void add(Item item) {
    if (capacity_ > 0 && heap_.size() == capacity_) {
      if (!better_(item, heap_.front())) return;
      std::pop_heap(heap_.begin(), heap_.end(), better_);
      heap_.back() = std::move(item);
    } else {
      heap_.push_back(std::move(item));
    }
    std::push_heap(heap_.begin(), heap_.end(), better_);
  }
  /// The items kept, best first.
  std::vector<Item> sorted() const {
    std::vector<Item> items = heap_;
    std::sort(items.begin(), items.end(), better_);
    return items;
  }

 private:
  std::size_t capacity_;
  Better better_;
  std::vector<Item> heap_;
};

/// A molecule's best hit against one query and, with several queries, its scores against all.
struct KeptHit {
  Hit hit;
  MoleculeScores all;
};

inline const Hit& hit_of(const Hit& hit) { return hit; }
inline const Hit& hit_of(const KeptHit& kept) { return kept.hit; }

/// better_hit of items that are or hold hits.
struct BetterHit {
  double shape_weight = 0.0;
  template <class Item>
  bool operator()(const Item& x, const Item& y) const {
    return better_hit(hit_of(x), hit_of(y), shape_weight);
  }
};

/// A query's best molecules (QueryScores::best) of those added, each once: the
/// kept_molecules() best by score, and for a query ranked by another value (a shape weight
/// above 0) the first options.candidates of them followed by the others best by that value.
template <class Item>
class KeptMolecules {
 public:
  KeptMolecules(const ScreenOptions& options, double shape_weight)
      : candidates_(options.candidates),
        capacity_(kept_molecules(options)),
        by_score_(capacity_, BetterHit{0.0}) {
    if (shape_weight != 0.0) by_rank_.emplace(capacity_, BetterHit{shape_weight});
  }
  void add(const Item& item) {
    by_score_.add(item);
    if (by_rank_) by_rank_->add(item);
  }
  std::vector<Item> sorted() const {
    std::vector<Item> items = by_score_.sorted();
    if (!by_rank_) return items;
    items.resize(std::min(candidates_, items.size()));
    std::set<std::size_t> candidates;
    for (const Item& item : items) candidates.insert(hit_of(item).entry);
    for (Item& item : by_rank_->sorted()) {
      if (capacity_ > 0 && items.size() == capacity_) break;
      if (candidates.count(hit_of(item).entry) == 0) items.push_back(std::move(item));
    }
    return items;
  }

 private:
  std::size_t candidates_;
  std::size_t capacity_;
  BestItems<Item, BetterHit> by_score_;
  std::optional<BestItems<Item, BetterHit>> by_rank_;
};

/// A molecule's scores fused by `fusion` (fuse_scores), and the query that scores it highest
/// (ties to the first).
inline std::pair<double, std::size_t> fused_score(const std::vector<MoleculeScore>& scores,
                                                  Fusion fusion) {
  double sum = 0.0;
  std::size_t best = 0;
  for (std::size_t q = 0; q < scores.size(); ++q) {
    sum += scores[q].score;
    if (scores[q].score > scores[best].score) best = q;
  }
  const double fused =
      fusion == Fusion::max ? scores[best].score : sum / static_cast<double>(scores.size());
  return {fused, best};
}

/// A molecule by its fused score: the higher first, ties to the lower molecule.
struct FusedMolecule {
  double score = 0.0;
  MoleculeScores all;
};
struct BetterFused {
  bool operator()(const FusedMolecule& x, const FusedMolecule& y) const {
    if (x.score != y.score) return x.score > y.score;
    return x.all.molecule < y.all.molecule;
  }
};

/// score(i) for i in [0, count), in parallel into slots, reporting progress as `stage`.
template <class Score>
std::vector<HitScore> score_in_parallel(std::size_t count, int stage, const ScreenOptions& options,
                                        const Score& score) {
  std::vector<HitScore> scores(count);
  const auto total = static_cast<std::int64_t>(count);
  std::atomic<std::int64_t> done{0};
  tbb::parallel_for(std::size_t{0}, count, [&](std::size_t i) {
    scores[i] = score(i);
    if (options.progress) options.progress(stage, ++done, total);
  });
  if (options.progress) options.progress(stage, total, total);
  return scores;
}

}  // namespace surfcomp::screening
