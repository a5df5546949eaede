// harmonic_disk_map against CGAL's Surface_mesh_parameterization (cgal_disk_map) on the same
// patches, per weight kind: a 170-vertex sphere cap and a 173-vertex ellipsoid patch (the
// size of a 5 A patch on a ligand SES). Target: ours / CGAL <= 1. Prints Google Benchmark's
// table, then the ratios of the mean wall times measured in this run.
#include "surfcomp/harmonic/cgal_reference.hpp"
#include "surfcomp/harmonic/disk_map.hpp"

#include "disk_map_patches.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace surfcomp;
using harmonic::SpringWeights;

const std::vector<std::pair<std::string, SpringWeights>> kWeights = {
    {"inverse_length", SpringWeights::inverse_length},
    {"uniform", SpringWeights::uniform},
    {"cotangent", SpringWeights::cotangent},
    {"mean_value", SpringWeights::mean_value}};

std::map<std::string, test::TestPatch>& patches() {
  static std::map<std::string, test::TestPatch> table = {{"sphere_cap", test::sphere_cap_patch()},
                                                         {"ellipsoid", test::ellipsoid_patch()}};
  return table;
}

template <bool cgal>
void BM_DiskMap(benchmark::State& state, const std::string& patch_name, SpringWeights weights) {
  const test::TestPatch& patch = patches().at(patch_name);
  for (auto _ : state) {
    harmonic::DiskMap map = cgal ? harmonic::cgal_disk_map(patch.positions, patch.faces,
                                                           patch.outer_boundary, {weights})
                                 : harmonic::harmonic_disk_map(patch.positions, patch.faces,
                                                               patch.outer_boundary, {weights});
    benchmark::DoNotOptimize(map.uv.data());
  }
  state.counters["vertices"] = static_cast<double>(patch.positions.rows());
}

/// Keeps each benchmark's mean real time (us) by name for the ratio table.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred || run.iterations == 0) continue;
      // With --benchmark_repetitions, the mean over the repetitions stands for the run.
      if (run.run_type == Run::RT_Aggregate && run.aggregate_name != "mean") continue;
      times_us[run.run_name.str()] = run.GetAdjustedRealTime();
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> times_us;
};

}  // namespace

int main(int argc, char** argv) {
  for (const auto& [patch_name, patch] : patches()) {
    for (const auto& [weights_name, weights] : kWeights) {
      const std::string suffix = "/" + patch_name + "/" + weights_name;
      benchmark::RegisterBenchmark(("ours" + suffix).c_str(), BM_DiskMap<false>, patch_name,
                                   weights)
          ->Unit(benchmark::kMicrosecond);
      benchmark::RegisterBenchmark(("cgal" + suffix).c_str(), BM_DiskMap<true>, patch_name, weights)
          ->Unit(benchmark::kMicrosecond);
    }
  }
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);

  std::printf("\nours / CGAL (same run, mean wall time; target <= 1):\n");
  for (const auto& [patch_name, patch] : patches()) {
    for (const auto& [weights_name, weights] : kWeights) {
      const std::string suffix = "/" + patch_name + "/" + weights_name;
      const auto ours = reporter.times_us.find("ours" + suffix);
      const auto cgal = reporter.times_us.find("cgal" + suffix);
      if (ours == reporter.times_us.end() || cgal == reporter.times_us.end()) continue;
      std::printf("  %-10s (%3ld vertices) %-14s ours %8.1f us, CGAL %8.1f us: ratio %.2f\n",
                  patch_name.c_str(), static_cast<long>(patch.positions.rows()),
                  weights_name.c_str(), ours->second, cgal->second, ours->second / cgal->second);
    }
  }
  benchmark::Shutdown();
  return 0;
}
