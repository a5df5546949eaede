// The bounded maximal-clique search (cliques.hpp): with room enough it returns exactly the set
// Boost.Graph's Bron-Kerbosch returns; stopped by a budget it returns a subset of true maximal
// cliques, the same one on every run, growing with the budget; its work is deterministic.
#include "surfcomp/core/error.hpp"
#include "surfcomp/matching/cliques.hpp"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/bron_kerbosch_all_cliques.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

namespace surfcomp {
namespace {

using Cliques = std::vector<std::vector<int>>;

matching::AssociationGraph graph_of(int n, const std::vector<std::pair<int, int>>& edges) {
  matching::AssociationGraph g;
  g.nodes.resize(static_cast<std::size_t>(n));
  g.edges = edges;
  return g;
}

std::vector<std::pair<int, int>> random_edges(int n, double p, std::mt19937& rng) {
  std::bernoulli_distribution coin(p);
  std::vector<std::pair<int, int>> edges;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (coin(rng)) edges.emplace_back(i, j);
    }
  }
  return edges;
}

/// Boost.Graph's maximal cliques of at least min_size nodes (min_size >= 2), each sorted, the
/// list sorted: the reference the search replaced.
Cliques boost_maximal_cliques(int n, const std::vector<std::pair<int, int>>& edges, int min_size) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
  Graph graph(static_cast<std::size_t>(n));
  for (const auto& [i, j] : edges)
    boost::add_edge(static_cast<std::size_t>(i), static_cast<std::size_t>(j), graph);
  struct Collector {
    Cliques* out;
    void clique(const std::deque<std::size_t>& members, const Graph&) const {
      std::vector<int> sorted(members.begin(), members.end());
      std::sort(sorted.begin(), sorted.end());
      out->push_back(std::move(sorted));
    }
  };
  Cliques out;
  boost::bron_kerbosch_all_cliques(graph, Collector{&out}, static_cast<std::size_t>(min_size));
  std::sort(out.begin(), out.end());
  return out;
}

bool is_maximal_clique(const std::vector<int>& clique, int n,
                       const std::vector<std::pair<int, int>>& edges) {
  std::set<std::pair<int, int>> adjacent;
  for (const auto& [i, j] : edges) {
    adjacent.emplace(i, j);
    adjacent.emplace(j, i);
  }
  for (std::size_t x = 0; x < clique.size(); ++x) {
    for (std::size_t y = x + 1; y < clique.size(); ++y) {
      if (!adjacent.count({clique[x], clique[y]})) return false;
    }
  }
  for (int v = 0; v < n; ++v) {
    if (std::all_of(clique.begin(), clique.end(), [&](int c) {
          return adjacent.count({v, c}) > 0;
        })) {
      return false;  // v extends it (v is not a member: no self-loops)
    }
  }
  return true;
}

/// The Moon-Moser graph on 3k nodes: complete k-partite with parts {3i, 3i+1, 3i+2}; its maximal
/// cliques are the 3^k choices of one node per part, the most any graph of 3k nodes has.
std::vector<std::pair<int, int>> moon_moser_edges(int k) {
  std::vector<std::pair<int, int>> edges;
  for (int i = 0; i < 3 * k; ++i) {
    for (int j = i + 1; j < 3 * k; ++j) {
      if (i / 3 != j / 3) edges.emplace_back(i, j);
    }
  }
  return edges;
}

TEST(CliqueBudget, CompleteSearchesGiveBoostsCliquesOnRandomGraphs) {
  std::mt19937 rng(20240611u);
  int trial = 0;
  for (const int n : {12, 40, 90}) {
    for (const double p : {0.05, 0.2, 0.5, 0.8}) {
      if (n == 90 && p > 0.5) continue;  // Boost alone would take seconds
      const auto edges = random_edges(n, p, rng);
      for (const int min_size : {2, 3, 5}) {
        const matching::CliqueResult result =
            matching::maximal_cliques(graph_of(n, edges), matching::CliqueOptions{min_size});
        EXPECT_TRUE(result.complete) << "trial " << trial;
        EXPECT_LE(result.work, matching::CliqueOptions{}.max_work);
        EXPECT_EQ(result.cliques, boost_maximal_cliques(n, edges, min_size))
            << "n " << n << " p " << p << " min_size " << min_size;
      }
      ++trial;
    }
  }
}

TEST(CliqueBudget, MoonMoserGraphHasThreeToTheKCliques) {
  for (const int k : {1, 4, 7}) {
    const matching::CliqueResult result =
        matching::maximal_cliques(graph_of(3 * k, moon_moser_edges(k)), matching::CliqueOptions{});
    std::size_t expected = 1;
    for (int i = 0; i < k; ++i) expected *= 3;
    EXPECT_TRUE(result.complete);
    EXPECT_EQ(result.cliques.size(), k == 1 ? 0u : expected);  // k = 1: three isolated nodes
    for (const auto& clique : result.cliques) EXPECT_EQ(clique.size(), static_cast<std::size_t>(k));
  }
}

TEST(CliqueBudget, ExhaustedWorkGivesADeterministicSubsetThatGrowsWithTheBudget) {
  std::mt19937 rng(99u);
  const int n = 60;
  const auto edges = random_edges(n, 0.5, rng);
  const auto g = graph_of(n, edges);
  const matching::CliqueResult full = matching::maximal_cliques(g, matching::CliqueOptions{});
  ASSERT_TRUE(full.complete);
  ASSERT_GT(full.cliques.size(), 100u);
  const std::set<std::vector<int>> truth(full.cliques.begin(), full.cliques.end());

  // The boundary: a budget equal to the work needed completes, one unit less does not.
  matching::CliqueOptions exact;
  exact.max_work = full.work;
  EXPECT_TRUE(matching::maximal_cliques(g, exact).complete);
  exact.max_work = full.work - 1;
  EXPECT_FALSE(matching::maximal_cliques(g, exact).complete);

  std::set<std::vector<int>> previous;
  for (const std::int64_t budget :
       {full.work / 100, full.work / 10, full.work / 3, full.work / 2}) {
    matching::CliqueOptions options;
    options.max_work = budget;
    const matching::CliqueResult cut = matching::maximal_cliques(g, options);
    EXPECT_FALSE(cut.complete) << budget;
    EXPECT_GT(cut.work, budget);  // it stops at the first check past the budget
    EXPECT_LT(cut.cliques.size(), full.cliques.size());
    EXPECT_TRUE(std::is_sorted(cut.cliques.begin(), cut.cliques.end()));
    const std::set<std::vector<int>> found(cut.cliques.begin(), cut.cliques.end());
    EXPECT_TRUE(std::includes(truth.begin(), truth.end(), found.begin(), found.end())) << budget;
    // The search visits the graph in one fixed order, so a larger budget finds a superset.
    EXPECT_TRUE(std::includes(found.begin(), found.end(), previous.begin(), previous.end()));
    previous = found;
    const matching::CliqueResult again = matching::maximal_cliques(g, options);
    EXPECT_EQ(again.cliques, cut.cliques);
    EXPECT_EQ(again.work, cut.work);
  }
  // The work of a complete search is the same on every run.
  EXPECT_EQ(matching::maximal_cliques(g, matching::CliqueOptions{}).work, full.work);
}

TEST(CliqueBudget, CliqueCapStopsAtExactlyThatManyMaximalCliques) {
  const int k = 6;  // 729 maximal cliques of 6 nodes
  const auto edges = moon_moser_edges(k);
  const auto g = graph_of(3 * k, edges);
  matching::CliqueOptions options;
  options.max_cliques = 729;
  EXPECT_TRUE(matching::maximal_cliques(g, options).complete);
  options.max_cliques = 100;
  const matching::CliqueResult cut = matching::maximal_cliques(g, options);
  EXPECT_FALSE(cut.complete);
  ASSERT_EQ(cut.cliques.size(), 100u);
  for (const auto& clique : cut.cliques) EXPECT_TRUE(is_maximal_clique(clique, 3 * k, edges));
  // Isolated nodes count against the cap too.
  options.min_size = 1;
  options.max_cliques = 2;
  const matching::CliqueResult isolated = matching::maximal_cliques(graph_of(5, {{0, 1}}), options);
  EXPECT_FALSE(isolated.complete);
  EXPECT_EQ(isolated.cliques.size(), 2u);
}

TEST(CliqueBudget, AGraphWithTooManyCliquesStopsQuicklyAndSaysSo) {
  // 3^12 = 531441 maximal cliques: beyond the default cap, reached after a small part of it.
  const auto g = graph_of(36, moon_moser_edges(12));
  const matching::CliqueResult cut = matching::maximal_cliques(g, matching::CliqueOptions{});
  EXPECT_FALSE(cut.complete);
  EXPECT_EQ(cut.cliques.size(), matching::CliqueOptions{}.max_cliques);
  matching::CliqueOptions small;
  small.max_work = 1000;
  const matching::CliqueResult tiny = matching::maximal_cliques(g, small);
  EXPECT_FALSE(tiny.complete);
  EXPECT_LT(tiny.work, 2000);  // one check past the budget costs at most a set operation
  // The list form refuses to return an incomplete list.
  EXPECT_THROW(matching::maximal_cliques(g, 2), InputError);
}

TEST(CliqueBudget, OptionsOutsideTheirDomainsAreRefused) {
  const auto g = graph_of(3, {{0, 1}, {1, 2}});
  matching::CliqueOptions bad;
  bad.max_work = 0;
  EXPECT_THROW(matching::maximal_cliques(g, bad), OptionError);
  bad = {};
  bad.max_cliques = 0;
  EXPECT_THROW(matching::maximal_cliques(g, bad), OptionError);
  bad = {};
  bad.min_size = 0;
  EXPECT_THROW(matching::maximal_cliques(g, bad), OptionError);
}

}  // namespace
}  // namespace surfcomp
