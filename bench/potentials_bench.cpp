// ESP and LP (method §0.3-0.4) on a protein-sized case, 30,252 surface points (an icosphere of
// radius 30 A) and 2,000 atoms on a grid inside it, beside a serial double loop computing the same
// Coulomb sum, measured in the same run. Then the LP over 4we2's surface (1,949 atoms,
// datasets/cache from datasets/fetch.sh; skipped when absent): the exact sum against
// LpOptions::cutoff of 8, 10 and 12 A, with each cutoff's error over the vertices (RMS and max,
// relative to the exact LP's range) and its bound exp(-cutoff) * sum |f_i|; and the ESP over
// the same vertices, exact against the treecode at tolerances 1e-4, 1e-3 and 1e-2 kcal/(mol e)
// per box, with its errors. Prints Google Benchmark's table, then the ratios and errors.
#include "analytic_meshes.hpp"
#include "test_support.hpp"

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "surfcomp/molsurf/potentials.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
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

/// The exact ESP (the treecode has its rows on 4we2), for the ratio to the serial loop.
void BM_Esp(benchmark::State& state) {
  molsurf::EspOptions exact;
  exact.treecode_tolerance = 0.0;
  for (auto _ : state)
    benchmark::DoNotOptimize(molsurf::electrostatic_potential(points(), grid_molecule(), exact));
  state.counters["points"] = static_cast<double>(points().rows());
  state.counters["atoms"] = static_cast<double>(grid_molecule().atoms.size());
}

/// The exact LP (every atom; the grid's atoms lie beyond the default cutoff of every point).
void BM_Lp(benchmark::State& state) {
  molsurf::LpOptions every_atom;
  every_atom.cutoff = 0.0;
  for (auto _ : state)
    benchmark::DoNotOptimize(molsurf::lipophilic_potential(points(), grid_molecule(), every_atom));
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
        sum += molsurf::coulomb_constant * a.charge / (p.row(i) - a.position.transpose()).norm();
      esp(i) = sum;
    }
    benchmark::DoNotOptimize(esp.data());
  }
}

/// 4we2 and its surface's vertices, when datasets/cache has it.
struct Protein {
  Molecule molecule;
  Eigen::MatrixX3d vertices;
};
const Protein* protein() {
  static const std::optional<Protein> p = []() -> std::optional<Protein> {
    const auto path = test::fetched_dataset("edtsurf/4we2.pdb");
    if (!path) return std::nullopt;
    Protein out;
    out.molecule = io::read_molecule(*path);
    out.vertices = molsurf::build_molecular_surface(out.molecule).positions();
    return out;
  }();
  return p ? &*p : nullptr;
}

molsurf::LpOptions cutoff_of(double cutoff) {
  molsurf::LpOptions options;
  options.cutoff = cutoff;
  return options;
}

void BM_LpProtein(benchmark::State& state, double cutoff) {
  const Protein& p = *protein();
  for (auto _ : state)
    benchmark::DoNotOptimize(
        molsurf::lipophilic_potential(p.vertices, p.molecule, cutoff_of(cutoff)));
  state.counters["vertices"] = static_cast<double>(p.vertices.rows());
}

std::string tolerance_name(double tolerance) {
  char name[16];
  std::snprintf(name, sizeof name, "%.0e", tolerance);
  return name;
}

molsurf::EspOptions theta_of(double theta) {
  molsurf::EspOptions options;
  options.treecode_tolerance = theta;
  return options;
}

void BM_EspProtein(benchmark::State& state, double theta) {
  const Protein& p = *protein();
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        molsurf::electrostatic_potential(p.vertices, p.molecule, theta_of(theta)));
  }
  state.counters["vertices"] = static_cast<double>(p.vertices.rows());
}

/// Each opening angle's error against the exact ESP over 4we2's vertices.
void print_treecode_errors(const std::vector<double>& thetas) {
  const Protein& p = *protein();
  const Eigen::VectorXd exact =
      molsurf::electrostatic_potential(p.vertices, p.molecule, theta_of(0.0));
  const double range = exact.maxCoeff() - exact.minCoeff();
  std::printf("\n4we2 ESP: exact range %.4g (%.4g to %.4g) kcal/(mol e)\n", range, exact.minCoeff(),
              exact.maxCoeff());
  for (const double theta : thetas) {
    const Eigen::VectorXd error =
        molsurf::electrostatic_potential(p.vertices, p.molecule, theta_of(theta)) - exact;
    const double max_error = error.cwiseAbs().maxCoeff();
    const double rms = std::sqrt(error.squaredNorm() / static_cast<double>(error.size()));
    std::printf("tolerance %.0e: max |error| %.3g (%.3g of the range), RMS %.3g (%.3g)\n", theta,
                max_error, max_error / range, rms, rms / range);
  }
}

/// Each cutoff's error against the exact LP over 4we2's vertices.
void print_cutoff_errors(const std::vector<double>& cutoffs) {
  const Protein& p = *protein();
  const Eigen::VectorXd exact =
      molsurf::lipophilic_potential(p.vertices, p.molecule, cutoff_of(0.0));
  const double range = exact.maxCoeff() - exact.minCoeff();
  double sum_abs_f = 0.0;
  for (const Atom& atom : p.molecule.atoms) sum_abs_f += std::abs(atom.lipophilicity);
  std::printf("\n4we2 LP: %lld vertices, %zu atoms, exact LP range %.4f (%.4f to %.4f)\n",
              static_cast<long long>(p.vertices.rows()), p.molecule.atoms.size(), range,
              exact.minCoeff(), exact.maxCoeff());
  for (const double cutoff : cutoffs) {
    const Eigen::VectorXd cut =
        molsurf::lipophilic_potential(p.vertices, p.molecule, cutoff_of(cutoff));
    const Eigen::VectorXd error = cut - exact;
    const double rms = std::sqrt(error.squaredNorm() / static_cast<double>(error.size()));
    std::printf(
        "cutoff %4.1f A: max |error| %.3g (%.3g of the range), RMS %.3g (%.3g), bound %.3g\n",
        cutoff, error.cwiseAbs().maxCoeff(), error.cwiseAbs().maxCoeff() / range, rms, rms / range,
        std::exp(-cutoff) * sum_abs_f);
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
  const std::vector<double> cutoffs{8.0, 10.0, 12.0};
  const std::vector<double> thetas{1e-4, 1e-3, 1e-2};
  if (protein() != nullptr) {
    benchmark::RegisterBenchmark("esp_4we2/exact", BM_EspProtein, 0.0)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    for (const double theta : thetas) {
      benchmark::RegisterBenchmark(("esp_4we2/tolerance_" + tolerance_name(theta)).c_str(),
                                   BM_EspProtein, theta)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
    benchmark::RegisterBenchmark("lp_4we2/exact", BM_LpProtein, 0.0)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    for (const double cutoff : cutoffs) {
      benchmark::RegisterBenchmark(("lp_4we2/cutoff_" + std::to_string(int(cutoff))).c_str(),
                                   BM_LpProtein, cutoff)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  } else {
    std::printf("skipping 4we2: datasets/cache/edtsurf/4we2.pdb is absent (datasets/fetch.sh)\n");
  }
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto& t = reporter.times_ms;
  if (t.count("esp") && t.count("esp_serial_loop"))
    std::printf("\nesp / serial loop (same run, wall time) = %.2f\n",
                t.at("esp") / t.at("esp_serial_loop"));
  if (protein() != nullptr && t.count("lp_4we2/exact")) {
    for (const double cutoff : cutoffs) {
      const std::string name = "lp_4we2/cutoff_" + std::to_string(int(cutoff));
      if (t.count(name))
        std::printf("%s / exact (same run, wall time) = %.3f\n", name.c_str(),
                    t.at(name) / t.at("lp_4we2/exact"));
    }
    print_cutoff_errors(cutoffs);
  }
  if (protein() != nullptr && t.count("esp_4we2/exact")) {
    for (const double theta : thetas) {
      const std::string name = "esp_4we2/tolerance_" + tolerance_name(theta);
      if (t.count(name))
        std::printf("%s / exact (same run, wall time) = %.3f\n", name.c_str(),
                    t.at(name) / t.at("esp_4we2/exact"));
    }
    print_treecode_errors(thetas);
  }
  benchmark::Shutdown();
  return 0;
}
