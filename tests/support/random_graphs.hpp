// Random graphs for the clique search (tests/matching/cliques_test.cpp against brute force,
// bench/cliques_bench.cpp at the association graph's sizes).
#pragma once

#include "surfcomp/matching/association_graph.hpp"

#include <cstddef>
#include <random>
#include <utility>
#include <vector>

namespace surfcomp::test {

/// An association graph of `n` nodes (default pairs) and the given edges.
inline matching::AssociationGraph graph_of(int n, const std::vector<std::pair<int, int>>& edges) {
  matching::AssociationGraph g;
  g.nodes.resize(static_cast<std::size_t>(n));
  g.edges = edges;
  return g;
}

/// The edges (i < j, sorted) of an Erdos-Renyi graph G(n, p) drawn from `rng`; with `adjacent`,
/// also its n x n adjacency matrix.
inline std::vector<std::pair<int, int>> random_edges(
    int n, double p, std::mt19937& rng, std::vector<std::vector<bool>>* adjacent = nullptr) {
  std::bernoulli_distribution coin(p);
  std::vector<std::pair<int, int>> edges;
  if (adjacent)
    adjacent->assign(static_cast<std::size_t>(n),
                     std::vector<bool>(static_cast<std::size_t>(n), false));
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (!coin(rng)) continue;
      edges.emplace_back(i, j);
      if (adjacent)
        (*adjacent)[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] =
            (*adjacent)[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)] = true;
    }
  }
  return edges;
}

}  // namespace surfcomp::test
