#include "surfcomp/matching/cliques.hpp"

#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"

#include <algorithm>
#include <bitset>
#include <deque>
#include <string>

namespace surfcomp::matching {
namespace {

using Word = std::uint64_t;
constexpr int kWordBits = 64;

int popcount(Word w) { return static_cast<int>(std::bitset<kWordBits>(w).count()); }
int lowest_bit(Word w) { return __builtin_ctzll(w); }

/// Bron-Kerbosch with Tomita's pivot over bitsets of the m nodes with an edge (renumbered
/// 0..m-1 in increasing node order). A set is m_words_ words; each call works on the word range
/// [lo, hi) outside which its P and X are empty, so sparse graphs pay for their neighbourhoods
/// rather than for m.
class Search {
 public:
  Search(const std::vector<int>& original, const std::vector<std::pair<int, int>>& edges,
         const std::vector<int>& compact, const CliqueOptions& options,
         std::vector<std::vector<int>>& cliques)
      : original_(original),
        options_(options),
        cliques_(cliques),
        m_(static_cast<int>(original.size())),
        words_((original.size() + kWordBits - 1) / kWordBits),
        adjacency_(original.size() * words_, 0) {
    for (const auto& [i, j] : edges) {
      const auto u = static_cast<std::size_t>(compact[static_cast<std::size_t>(i)]);
      const auto v = static_cast<std::size_t>(compact[static_cast<std::size_t>(j)]);
      adjacency_[u * words_ + v / kWordBits] |= Word{1} << (v % kWordBits);
      adjacency_[v * words_ + u / kWordBits] |= Word{1} << (u % kWordBits);
    }
  }

  /// Runs the search from P = all nodes, X = {}; false when it stopped at a budget.
  bool run() {
    if (m_ == 0) return true;
    Level& top = level(0);
    std::fill(top.p.begin(), top.p.end(), 0);
    std::fill(top.x.begin(), top.x.end(), 0);
    for (int v = 0; v < m_; ++v) top.p[static_cast<std::size_t>(v) / kWordBits] |= bit(v);
    expand(0, 0, words_);
    return !stopped_;
  }

  std::int64_t work() const { return work_; }

 private:
  /// P, X and the branch nodes of one recursion depth.
  struct Level {
    std::vector<Word> p, x;
    std::vector<int> branches;
  };

  static Word bit(int v) { return Word{1} << (v % kWordBits); }
  const Word* row(int v) const { return &adjacency_[static_cast<std::size_t>(v) * words_]; }

  Level& level(std::size_t depth) {
    while (levels_.size() <= depth) {
      levels_.push_back(Level{std::vector<Word>(words_, 0), std::vector<Word>(words_, 0), {}});
    }
    return levels_[depth];
  }

  bool spend(std::size_t words) {
    work_ += static_cast<std::int64_t>(words);
    if (work_ > options_.max_work) stopped_ = true;
    return !stopped_;
  }

  void report() {
    if (cliques_.size() >= options_.max_cliques) {
      stopped_ = true;
      return;
    }
    std::vector<int> clique;
    clique.reserve(r_.size());
    for (const int v : r_) clique.push_back(original_[static_cast<std::size_t>(v)]);
    std::sort(clique.begin(), clique.end());
    cliques_.push_back(std::move(clique));
  }

  /// Extends the clique r_ by the candidates P of level `depth`, X being the nodes already
  /// tried; both are empty outside the words [lo, hi).
  void expand(std::size_t depth, std::size_t lo, std::size_t hi) {
    level(depth + 1);
    Level& here = levels_[depth];
    Level& child = levels_[depth + 1];
    const std::size_t given = hi - lo;
    while (lo < hi && (here.p[lo] | here.x[lo]) == 0) ++lo;
    while (hi > lo && (here.p[hi - 1] | here.x[hi - 1]) == 0) --hi;
    int n_p = 0;
    for (std::size_t w = lo; w < hi; ++w) n_p += popcount(here.p[w]);
    if (!spend(given + (hi - lo))) return;
    if (n_p == 0) {
      if (lo == hi && static_cast<int>(r_.size()) >= options_.min_size) report();
      return;
    }
    if (static_cast<int>(r_.size()) + n_p < options_.min_size) return;

    // The pivot: the node of P u X with the most neighbours in P, ties to the lowest index.
    int pivot = -1, best = -1;
    for (std::size_t w = lo; w < hi; ++w) {
      for (Word bits = here.p[w] | here.x[w]; bits != 0; bits &= bits - 1) {
        const int u = static_cast<int>(w) * kWordBits + lowest_bit(bits);
        const Word* nu = row(u);
        int count = 0;
        for (std::size_t k = lo; k < hi; ++k) count += popcount(here.p[k] & nu[k]);
        if (!spend(hi - lo)) return;
        if (count > best) {
          best = count;
          pivot = u;
        }
      }
    }
    // Branch on P minus the pivot's neighbours, in increasing order.
    const Word* np = row(pivot);
    here.branches.clear();
    for (std::size_t w = lo; w < hi; ++w) {
      for (Word bits = here.p[w] & ~np[w]; bits != 0; bits &= bits - 1)
        here.branches.push_back(static_cast<int>(w) * kWordBits + lowest_bit(bits));
    }
    for (std::size_t b = 0; b < here.branches.size(); ++b) {
      const int v = here.branches[b];
      const Word* nv = row(v);
      for (std::size_t k = lo; k < hi; ++k) {
        child.p[k] = here.p[k] & nv[k];
        child.x[k] = here.x[k] & nv[k];
      }
      if (!spend(2 * (hi - lo))) return;
      r_.push_back(v);
      expand(depth + 1, lo, hi);
      r_.pop_back();
      if (stopped_) return;
      here.p[static_cast<std::size_t>(v) / kWordBits] &= ~bit(v);
      here.x[static_cast<std::size_t>(v) / kWordBits] |= bit(v);
    }
  }

  const std::vector<int>& original_;
  const CliqueOptions& options_;
  std::vector<std::vector<int>>& cliques_;
  int m_;
  std::size_t words_;
  std::vector<Word> adjacency_;  ///< m rows of words_ words
  std::deque<Level> levels_;     ///< per recursion depth (a deque: growing keeps references)
  std::vector<int> r_;           ///< the clique being extended
  std::int64_t work_ = 0;
  bool stopped_ = false;
};

}  // namespace

CliqueResult maximal_cliques(const AssociationGraph& g, const CliqueOptions& options) {
  detail::check_clique_options(options, {"maximal_cliques", ""});
  const std::size_t n = g.nodes.size();
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    const auto [i, j] = g.edges[e];
    if (i < 0 || j < 0 || static_cast<std::size_t>(i) >= n || static_cast<std::size_t>(j) >= n ||
        i == j) {
      throw InputError("clique search: edge " + std::to_string(e) + " joins nodes " +
                       std::to_string(i) + " and " + std::to_string(j) +
                       ", expected two distinct indices in [0, " + std::to_string(n) + ")");
    }
  }
  // Only nodes with an edge enter the search (an isolated node is its own maximal clique),
  // numbered in increasing node order.
  std::vector<int> compact(n, -1);
  for (const auto& [i, j] : g.edges) {
    compact[static_cast<std::size_t>(i)] = 0;
    compact[static_cast<std::size_t>(j)] = 0;
  }
  CliqueResult result;
  std::vector<int> original;
  for (std::size_t v = 0; v < n; ++v) {
    if (compact[v] == 0) {
      compact[v] = static_cast<int>(original.size());
      original.push_back(static_cast<int>(v));
    } else if (options.min_size <= 1) {
      if (result.cliques.size() >= options.max_cliques) {
        result.complete = false;
        break;
      }
      result.cliques.push_back({static_cast<int>(v)});
    }
  }
  if (result.complete) {
    Search search(original, g.edges, compact, options, result.cliques);
    result.complete = search.run();
    result.work = search.work();
  }
  std::sort(result.cliques.begin(), result.cliques.end());
  return result;
}

std::vector<std::vector<int>> maximal_cliques(const AssociationGraph& g, int min_size) {
  CliqueOptions options;
  options.min_size = min_size;
  CliqueResult result = maximal_cliques(g, options);
  if (!result.complete) {
    throw InputError("clique search: the search stopped after " + std::to_string(result.work) +
                     " units of work and " + std::to_string(result.cliques.size()) + " cliques (" +
                     options::named("max_clique_work") + ", " + options::named("max_cliques") +
                     "); the list would be "
                     "incomplete");
  }
  return std::move(result.cliques);
}

}  // namespace surfcomp::matching
