// Principal curvatures (method §0.2) on icospheres at the surface builder's density (2.5 vertices
// per A^2), 1,212 and 30,252 vertices: the quadric fit (the default) beside CGAL's jet fit,
// measured in the same run. Prints Google Benchmark's table, then the ratios.
#include "analytic_meshes.hpp"

#include "surfcomp/mesh/curvature.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace {

using namespace surfcomp;

/// An icosphere of the given frequency whose radius gives 2.5 vertices per A^2.
mesh::Surface sphere_of(int frequency) {
  const double r = std::sqrt(10.0 * frequency * frequency / (4 * M_PI * 2.5));
  return test::icosphere(r, frequency);
}

void BM_Curvatures(benchmark::State& state, mesh::CurvatureMethod method) {
  const mesh::Surface sphere = sphere_of(static_cast<int>(state.range(0)));
  mesh::CurvatureOptions options;
  options.method = method;
  for (auto _ : state) benchmark::DoNotOptimize(mesh::principal_curvatures(sphere, options));
  state.counters["vertices"] = static_cast<double>(sphere.n_vertices());
}

/// Keeps each run's mean real time (ms) by full name for the ratio lines.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs)
      if (!run.error_occurred && run.iterations > 0)
        times_ms[run.benchmark_name()] = run.GetAdjustedRealTime();
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> times_ms;
};

}  // namespace

int main(int argc, char** argv) {
  for (const auto& [name, method] : {std::pair{"quadric", mesh::CurvatureMethod::quadric},
                                     std::pair{"jet", mesh::CurvatureMethod::jet}}) {
    benchmark::RegisterBenchmark((std::string("curvatures/") + name).c_str(), BM_Curvatures, method)
        ->Arg(11)
        ->Arg(55)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf("\nquadric / jet (same run, wall time):\n");
  for (const char* frequency : {"11", "55"}) {
    const auto quadric =
        reporter.times_ms.find(std::string("curvatures/quadric/") + frequency + "/real_time");
    const auto jet =
        reporter.times_ms.find(std::string("curvatures/jet/") + frequency + "/real_time");
    if (quadric == reporter.times_ms.end() || jet == reporter.times_ms.end()) continue;
    std::printf("  frequency %s: %.2f\n", frequency, quadric->second / jet->second);
  }
  benchmark::Shutdown();
  return 0;
}
