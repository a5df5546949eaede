// ESP and LP (seed 3.2) on a protein-sized case, 30,252 surface points (an icosphere of radius
// 30 A) and 2,000 atoms on a grid inside it, beside a serial double loop computing the same
// Coulomb sum, measured in the same run. Prints Google Benchmark's table, then the ratio.
#include "analytic_meshes.hpp"

#include "surfcomp/mesh/potentials.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace {

using namespace surfcomp;

const Eigen::MatrixX3d& points() {
  static const Eigen::MatrixX3d p = test::icosphere(30.0, 55).positions();
  return p;
}

const Molecule& grid_molecule() {
  static const Molecule m = [] {
    Molecule out;
    out.source = "grid";
    for (int i = 0; i < 2000; ++i) {
      Atom a;
      a.element = "C";
      a.radius = 1.7;
      a.position = Eigen::Vector3d(i % 20 - 9.5, (i / 20) % 10 - 4.5, i / 200 - 4.5);
      a.charge = i % 2 ? 0.1 : -0.1;
      a.lipophilicity = 0.01 * (i % 7);
      out.atoms.push_back(a);
    }
    return out;
  }();
  return m;
}

void BM_Esp(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(mesh::electrostatic_potential(points(), grid_molecule()));
  state.counters["points"] = static_cast<double>(points().rows());
  state.counters["atoms"] = static_cast<double>(grid_molecule().atoms.size());
}

void BM_Lp(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(mesh::lipophilic_potential(points(), grid_molecule()));
}

/// The reference: the Coulomb sum of EspOptions' defaults (dielectric 1, no distance dependence) as
/// a plain serial loop.
void BM_EspSerialLoop(benchmark::State& state) {
  const Eigen::MatrixX3d& p = points();
  const Molecule& m = grid_molecule();
  Eigen::VectorXd esp(p.rows());
  for (auto _ : state) {
    for (Eigen::Index i = 0; i < p.rows(); ++i) {
      double sum = 0.0;
      for (const Atom& a : m.atoms)
        sum += mesh::coulomb_constant * a.charge / (p.row(i) - a.position.transpose()).norm();
      esp(i) = sum;
    }
    benchmark::DoNotOptimize(esp.data());
  }
}

/// Keeps each run's mean real time (ms) by name for the ratio line.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs)
      if (!run.error_occurred && run.iterations > 0)
        times_ms[run.run_name.function_name] = run.GetAdjustedRealTime();
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> times_ms;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::RegisterBenchmark("esp", BM_Esp)->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("lp", BM_Lp)->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("esp_serial_loop", BM_EspSerialLoop)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto& t = reporter.times_ms;
  if (t.count("esp") && t.count("esp_serial_loop"))
    std::printf("\nesp / serial loop (same run, wall time) = %.2f\n",
                t.at("esp") / t.at("esp_serial_loop"));
  benchmark::Shutdown();
  return 0;
}
