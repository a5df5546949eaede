#include "surfcomp/matching/cliques.hpp"

#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"

#include <boost/graph/adjacency_matrix.hpp>
#include <boost/graph/bron_kerbosch_all_cliques.hpp>

#include <algorithm>
#include <string>

namespace surfcomp::matching {
namespace {

/// Collects each clique Boost reports, sorted.
struct CliqueCollector {
  std::vector<std::vector<int>>* cliques;
  template <typename Clique, typename Graph>
  void clique(const Clique& members, const Graph&) const {
    std::vector<int> sorted(members.begin(), members.end());
    std::sort(sorted.begin(), sorted.end());
    cliques->push_back(std::move(sorted));
  }
};

}  // namespace

std::vector<std::vector<int>> maximal_cliques(const AssociationGraph& g, int min_size) {
  detail::check_min_clique_size(min_size, "min_size", {"maximal_cliques", ""});
  const std::size_t n = g.nodes.size();
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    const auto [i, j] = g.edges[e];
    if (i < 0 || j < 0 || static_cast<std::size_t>(i) >= n || static_cast<std::size_t>(j) >= n ||
        i == j) {
      throw InputError("maximal_cliques: edge " + std::to_string(e) + " joins nodes " +
                       std::to_string(i) + " and " + std::to_string(j) +
                       ", expected two distinct indices in [0, " + std::to_string(n) + ")");
    }
  }
  // Only nodes with an edge enter Boost's graph (an isolated node is its own maximal clique),
  // numbered in increasing node order.
  std::vector<int> compact(n, -1);
  for (const auto& [i, j] : g.edges) {
    compact[static_cast<std::size_t>(i)] = 0;
    compact[static_cast<std::size_t>(j)] = 0;
  }
  std::vector<int> original;
  std::vector<std::vector<int>> cliques;
  for (std::size_t v = 0; v < n; ++v) {
    if (compact[v] == 0) {
      compact[v] = static_cast<int>(original.size());
      original.push_back(static_cast<int>(v));
    } else if (min_size <= 1) {
      cliques.push_back({static_cast<int>(v)});
    }
  }
  // An adjacency matrix makes Boost's edge(u, v) lookups, the inner loop of its Bron-Kerbosch,
  // constant time; it holds m (m + 1) / 2 small cells for the m nodes with edges.
  boost::adjacency_matrix<boost::undirectedS> graph(original.size());
  for (const auto& [i, j] : g.edges) {
    boost::add_edge(static_cast<std::size_t>(compact[static_cast<std::size_t>(i)]),
                    static_cast<std::size_t>(compact[static_cast<std::size_t>(j)]), graph);
  }
  std::vector<std::vector<int>> found;
  boost::bron_kerbosch_all_cliques(graph, CliqueCollector{&found},
                                   static_cast<std::size_t>(std::max(min_size, 2)));
  for (std::vector<int>& clique : found) {
    for (int& v : clique) v = original[static_cast<std::size_t>(v)];
    cliques.push_back(std::move(clique));  // increasing order is kept by the renumbering
  }
  std::sort(cliques.begin(), cliques.end());
  return cliques;
}

}  // namespace surfcomp::matching
