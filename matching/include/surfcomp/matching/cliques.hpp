// Maximal cliques of the association graph (method §6): the groups of
// critical point pairs that can all overlap at once.
#pragma once

#include "surfcomp/matching/association_graph.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace surfcomp::matching {

/// The settings of maximal_cliques.
struct CliqueOptions {
  /// Default 2. Maximal cliques with fewer nodes are not reported. >= 1.
  int min_size = 2;
  /// Default 10^8 (docs/decisions.md#clique-budget). The search stops once it has spent more
  /// work than this. One unit of work is one 64-node word of a set operation (an intersection,
  /// a difference, a count or a scan); the count depends only on the graph and the options, so
  /// a search stops at the same place on every machine. A unit takes a few nanoseconds on a
  /// graph whose bitsets fit the cache and up to about 30 on larger ones. > 0.
  std::int64_t max_work = 100'000'000;
  /// Default 10^5. The search stops rather than report more cliques than this, which bounds
  /// the memory of the list. > 0.
  std::size_t max_cliques = 100'000;
};

/// What maximal_cliques found.
struct CliqueResult {
  /// Maximal cliques of at least min_size nodes, each a sorted list of node indices; the list
  /// is sorted lexicographically.
  std::vector<std::vector<int>> cliques;
  /// True when the search finished and `cliques` holds every maximal clique of at least
  /// min_size nodes. False when it stopped at max_work or max_cliques: `cliques` then holds
  /// those found before it stopped, a subset that depends only on the graph and the options.
  bool complete = true;
  /// The work spent (units of CliqueOptions::max_work).
  std::int64_t work = 0;
};

/// The maximal cliques of g (nodes g.nodes, edges g.edges) with at least options.min_size
/// nodes, by Bron-Kerbosch with Tomita's pivot (the node of P u X with the most neighbours in
/// P, ties to the lowest index) over bitsets, children in increasing node order; a branch that
/// cannot reach min_size nodes is cut. Tomita, Tanaka and Takahashi, "The worst-case time
/// complexity for generating all maximal cliques", Theor. Comput. Sci. 363 (2006) 28-42. An
/// isolated node is a maximal clique of size 1 (reported when min_size <= 1). The adjacency
/// bitsets take m^2 / 8 bytes for the m nodes with an edge (GraphOptions::max_nodes bounds m
/// in build_association_graph). Throws InputError for an edge index outside the nodes or a
/// self-loop, OptionError for an option outside its domain.
CliqueResult maximal_cliques(const AssociationGraph& g, const CliqueOptions& options);

/// Every maximal clique of g with at least min_size nodes: maximal_cliques(g, {min_size}) with
/// the default budgets, whose cliques it returns. Throws InputError when the search stops at a
/// budget (the list would be incomplete), and what maximal_cliques throws.
std::vector<std::vector<int>> maximal_cliques(const AssociationGraph& g, int min_size = 2);

}  // namespace surfcomp::matching
