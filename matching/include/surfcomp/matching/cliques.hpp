// Maximal cliques of the association graph (seed section 3.9; METHOD section 6): the groups of
// critical point pairs that can all overlap at once.
#pragma once

#include "surfcomp/matching/association_graph.hpp"

#include <vector>

namespace surfcomp::matching {

/// All maximal cliques of g (nodes g.nodes, edges g.edges) with at least min_size nodes, by
/// Bron-Kerbosch (Boost.Graph's bron_kerbosch_all_cliques). Each clique is a sorted list of node
/// indices; the list is sorted lexicographically, so the result is deterministic. An isolated
/// node is a maximal clique of size 1 (reported when min_size <= 1). Throws InputError for an
/// edge index outside the nodes or a self-loop, OptionError for min_size < 1.
std::vector<std::vector<int>> maximal_cliques(const AssociationGraph& g, int min_size = 2);

}  // namespace surfcomp::matching
