// Maximal cliques (method §6) on small graphs with known answers and against brute
// force on random graphs (bench/cliques_bench.cpp times them at the association graph's sizes).
#include "surfcomp/matching/cliques.hpp"
#include "surfcomp/core/error.hpp"

#include "random_graphs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace surfcomp {
namespace {

using Cliques = std::vector<std::vector<int>>;

using test::graph_of;
using test::random_edges;

TEST(Cliques, SmallGraphsGiveTheirKnownMaximalCliques) {
  // Two triangles sharing vertex 2.
  EXPECT_EQ(
      matching::maximal_cliques(graph_of(5, {{0, 1}, {1, 2}, {0, 2}, {2, 3}, {3, 4}, {2, 4}})),
      (Cliques{{0, 1, 2}, {2, 3, 4}}));
  // K4 minus the edge 0-1.
  EXPECT_EQ(matching::maximal_cliques(graph_of(4, {{0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}})),
            (Cliques{{0, 2, 3}, {1, 2, 3}}));
  // K4, edges given in any order and direction.
  EXPECT_EQ(
      matching::maximal_cliques(graph_of(4, {{3, 2}, {0, 1}, {2, 0}, {1, 3}, {0, 3}, {2, 1}})),
      (Cliques{{0, 1, 2, 3}}));
  // A path and an isolated vertex: the isolated vertex only with min_size 1.
  const auto path = graph_of(4, {{0, 1}, {1, 2}});
  EXPECT_EQ(matching::maximal_cliques(path), (Cliques{{0, 1}, {1, 2}}));
  EXPECT_EQ(matching::maximal_cliques(path, 1), (Cliques{{0, 1}, {1, 2}, {3}}));
  EXPECT_TRUE(matching::maximal_cliques(path, 3).empty());
  // A square with one diagonal and a pendant: min_size 3 keeps the two triangles only.
  const auto square = graph_of(5, {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}, {3, 4}});
  EXPECT_EQ(matching::maximal_cliques(square), (Cliques{{0, 1, 2}, {0, 2, 3}, {3, 4}}));
  EXPECT_EQ(matching::maximal_cliques(square, 3), (Cliques{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_TRUE(matching::maximal_cliques(graph_of(0, {})).empty());
  EXPECT_THROW(matching::maximal_cliques(graph_of(3, {{0, 3}})), InputError);
  EXPECT_THROW(matching::maximal_cliques(graph_of(3, {{1, 1}})), InputError);
  EXPECT_THROW(matching::maximal_cliques(path, 0), OptionError);
}

// Brute force: every vertex subset that is a clique and cannot be extended.
Cliques brute_force_maximal_cliques(int n, const std::vector<std::vector<bool>>& adjacent,
                                    int min_size) {
  Cliques out;
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    std::vector<int> members;
    for (int v = 0; v < n; ++v)
      if (mask & (1u << v)) members.push_back(v);
    bool clique = true;
    for (std::size_t x = 0; x < members.size() && clique; ++x)
      for (std::size_t y = x + 1; y < members.size() && clique; ++y)
        clique =
            adjacent[static_cast<std::size_t>(members[x])][static_cast<std::size_t>(members[y])];
    if (!clique) continue;
    bool maximal = true;
    for (int v = 0; v < n && maximal; ++v) {
      if (mask & (1u << v)) continue;
      bool joins_all = true;
      for (const int m : members)
        joins_all = joins_all && adjacent[static_cast<std::size_t>(v)][static_cast<std::size_t>(m)];
      maximal = !joins_all;
    }
    if (maximal && static_cast<int>(members.size()) >= min_size) out.push_back(members);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Cliques, RandomGraphsAgreeWithBruteForce) {
  std::mt19937 rng(2024u);
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 6 + trial % 8;
    const double p = 0.2 + 0.05 * (trial % 10);
    std::vector<std::vector<bool>> adjacent;
    const auto edges = random_edges(n, p, rng, &adjacent);
    for (const int min_size : {1, 2, 3}) {
      EXPECT_EQ(matching::maximal_cliques(graph_of(n, edges), min_size),
                brute_force_maximal_cliques(n, adjacent, min_size))
          << "trial " << trial << " min_size " << min_size;
    }
  }
}

}  // namespace
}  // namespace surfcomp
