// hsi-build on the 1THL crystal ligand: critical points, patches, harmonic maps and images
// (describe_surface) and the .hsi encoding, beside the surface build they start from, in one
// run. Target (issue 3): <= 50 ms for describe_surface on a ~1,200-vertex, ~28-CP surface.
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "test_support.hpp"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <filesystem>

namespace {

using namespace surfcomp;

const std::filesystem::path kLigand =
    test::shared_datasets_root() / "thermolysin/ligands-common-frame/1THL_ligand.sdf";

const mesh::Surface& ligand_surface() {
  static const mesh::Surface surface = molsurf::build_molecular_surface(io::read_molecule(kLigand));
  return surface;
}

void BM_SurfaceBuild(benchmark::State& state) {
  const Molecule molecule = io::read_molecule(kLigand);
  for (auto _ : state) benchmark::DoNotOptimize(molsurf::build_molecular_surface(molecule));
}

void BM_DescribeSurface(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(state.range(0)));
  std::size_t points = 0;
  for (auto _ : state) points = harmonic::describe_surface(ligand_surface()).critical_points.size();
  state.counters["vertices"] = static_cast<double>(ligand_surface().n_vertices());
  state.counters["critical_points"] = static_cast<double>(points);
}

void BM_EncodeHsi(benchmark::State& state) {
  const auto descriptors = harmonic::describe_surface(ligand_surface());
  std::size_t bytes = 0;
  for (auto _ : state) bytes = harmonic::io::encode_hsi(descriptors).size();
  state.counters["bytes"] = static_cast<double>(bytes);
}

}  // namespace

int main(int argc, char** argv) {
  if (!std::filesystem::exists(kLigand)) {
    std::printf("skipped: %s is absent\n", kLigand.c_str());
    return 0;
  }
  benchmark::RegisterBenchmark("surface_build/1THL", BM_SurfaceBuild)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("describe_surface/1THL/threads", BM_DescribeSurface)
      ->Arg(1)
      ->Arg(2)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("encode_hsi/1THL", BM_EncodeHsi)->Unit(benchmark::kMillisecond);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
