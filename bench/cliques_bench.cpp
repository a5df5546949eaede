// Maximal cliques (method §6) on random graphs at and beyond the association graph's
// sizes (a ligand pair gives ~60 nodes and ~100 edges after all filters). Graphs are drawn with
// std::mt19937 seed 7, one per size, the same in every run.
#include "surfcomp/matching/cliques.hpp"

#include "random_graphs.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <random>

namespace {

using namespace surfcomp;

/// The graph of the benchmark's size (nodes, edge probability in per mille), seed 7.
matching::AssociationGraph graph_for(const benchmark::State& state) {
  std::mt19937 rng(7u);
  const int n = static_cast<int>(state.range(0));
  const double p = static_cast<double>(state.range(1)) / 1000.0;
  return test::graph_of(n, test::random_edges(n, p, rng));
}

void BM_MaximalCliques(benchmark::State& state) {
  const matching::AssociationGraph graph = graph_for(state);
  std::size_t count = 0, largest = 0;
  for (auto _ : state) {
    const auto cliques = matching::maximal_cliques(graph);
    count = cliques.size();
    largest = 0;
    for (const auto& c : cliques) largest = std::max(largest, c.size());
  }
  state.counters["edges"] = static_cast<double>(graph.edges.size());
  state.counters["cliques"] = static_cast<double>(count);
  state.counters["largest"] = static_cast<double>(largest);
}

}  // namespace

int main(int argc, char** argv) {
  std::printf("random graphs G(n, p), std::mt19937 seed 7; args: nodes, p in per mille\n");
  benchmark::RegisterBenchmark("maximal_cliques", BM_MaximalCliques)
      ->Args({100, 50})
      ->Args({400, 50})
      ->Args({1000, 20})
      ->Args({2000, 10})
      ->Unit(benchmark::kMillisecond);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
