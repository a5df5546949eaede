// surf-build against EDTSurf, measured in one run: the 1THL crystal ligand and 4we2 (1,949 atoms),
// file to file (read the molecule, build the surface with its properties, write the PLY).
// EDTSurf runs as a process on the same files, at scale factors giving a similar vertex count.
// Both SES methods (exact, --ses-method edt). Prints Google Benchmark's table, then the ratios and
// the SES areas side by side.
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "test_support.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using namespace surfcomp;

const fs::path kWork = fs::temp_directory_path() / "surfcomp_bench";

struct Input {
  std::string name;
  fs::path molecule;     // what surf-build reads
  fs::path edtsurf_pdb;  // the same atoms as ATOM records, what EDTSurf reads
  int edtsurf_scale;     // EDTSurf -f, chosen for a vertex count similar to ours
};

std::map<std::string, Input>& inputs() {
  static std::map<std::string, Input> table;
  return table;
}

/// EDTSurf reads ATOM records only: copy a file's ATOM/HETATM records (no water) as ATOM.
fs::path atom_records_copy(const fs::path& pdb, const std::string& name) {
  const fs::path out = kWork / (name + "_atoms.pdb");
  std::ifstream in(pdb);
  std::ofstream o(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("HETATM", 0) == 0) {
      if (line.substr(17, 3) == "HOH") continue;
      line.replace(0, 6, "ATOM  ");
    }
    if (line.rfind("ATOM  ", 0) == 0) o << line << "\n";
  }
  o << "END\n";
  return out;
}

struct EdtsurfRun {
  std::size_t vertices = 0;
  double area = 0.0;
};

EdtsurfRun run_edtsurf(const Input& input, int scale) {
  const fs::path out = kWork / ("edt_" + input.name + "_" + std::to_string(scale));
  const fs::path log = out.string() + ".log";
  const std::string command = "EDTSurf -i " + input.edtsurf_pdb.string() + " -o " + out.string() +
                              " -s 3 -f " + std::to_string(scale) + " > " + log.string() + " 2>&1";
  if (std::system(command.c_str()) != 0) return {};
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  EdtsurfRun run;
  std::smatch m;
  if (std::regex_search(s, m, std::regex(R"(No\. vertices (\d+))")))
    run.vertices = std::stoul(m[1]);
  if (std::regex_search(s, m, std::regex(R"(Total area ([0-9.]+))"))) run.area = std::stod(m[1]);
  return run;
}

void BM_SurfBuild(benchmark::State& state, const std::string& name, molsurf::SesMethod method) {
  const Input& input = inputs().at(name);
  std::size_t vertices = 0;
  double area = 0.0;
  molsurf::MolecularSurfaceOptions options;
  options.ses.method = method;
  for (auto _ : state) {
    const Molecule molecule = io::read_molecule(input.molecule);
    const mesh::Surface surface = molsurf::build_molecular_surface(molecule, options);
    mesh::io::write_ply(surface, kWork / (name + ".ply"));
    vertices = surface.n_vertices();
    area = mesh::measure_surface(surface).area;
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["area_A2"] = area;
}

void BM_SesOnly(benchmark::State& state, const std::string& name, molsurf::SesMethod method) {
  const Input& input = inputs().at(name);
  const Molecule molecule = io::read_molecule(input.molecule);
  Eigen::MatrixX3d centers(static_cast<Eigen::Index>(molecule.atoms.size()), 3);
  Eigen::VectorXd radii(centers.rows());
  for (Eigen::Index i = 0; i < centers.rows(); ++i) {
    centers.row(i) = molecule.atoms[static_cast<std::size_t>(i)].position.transpose();
    radii(i) = molecule.atoms[static_cast<std::size_t>(i)].radius;
  }
  std::size_t vertices = 0;
  molsurf::SesOptions options;
  options.method = method;
  for (auto _ : state) vertices = molsurf::build_ses(centers, radii, options).n_vertices();
  state.counters["vertices"] = static_cast<double>(vertices);
}

void BM_Edtsurf(benchmark::State& state, const std::string& name) {
  const Input& input = inputs().at(name);
  EdtsurfRun run;
  for (auto _ : state) run = run_edtsurf(input, input.edtsurf_scale);
  if (run.vertices == 0) state.SkipWithError("EDTSurf failed (is the edtsurf package installed?)");
  state.counters["vertices"] = static_cast<double>(run.vertices);
  state.counters["area_A2"] = run.area;
}

/// Keeps each run's mean real time (ms) by name for the ratio table.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred || run.iterations == 0) continue;
      times_ms[run.run_name.function_name] = run.GetAdjustedRealTime();
      vertices[run.run_name.function_name] =
          run.counters.count("vertices") ? run.counters.at("vertices").value : 0;
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> times_ms, vertices;
};

}  // namespace

int main(int argc, char** argv) {
  fs::create_directories(kWork);
  const fs::path ligand =
      test::shared_datasets_root() / "thermolysin" / "ligands-common-frame" / "1THL_ligand.pdb";
  const fs::path protein = test::source_dir() / "datasets" / "cache" / "edtsurf" / "4we2.pdb";
  if (fs::exists(ligand)) {
    inputs()["1THL_ligand"] = {"1THL_ligand", ligand.string(), atom_records_copy(ligand, "1THL"),
                               2};
  } else {
    std::printf("skipping the 1THL ligand: %s is absent\n", ligand.c_str());
  }
  if (fs::exists(protein)) {
    inputs()["4we2"] = {"4we2", protein.string(), atom_records_copy(protein, "4we2"), 2};
  } else {
    std::printf("skipping 4we2: %s is absent (run datasets/fetch.sh)\n", protein.c_str());
  }
  for (const auto& [name, input] : inputs()) {
    for (const auto method : {molsurf::SesMethod::exact, molsurf::SesMethod::distance_transform}) {
      const std::string suffix = method == molsurf::SesMethod::exact ? "" : "_edt";
      benchmark::RegisterBenchmark(("surf_build" + suffix + "/" + name).c_str(), BM_SurfBuild, name,
                                   method)
          ->Unit(benchmark::kMillisecond)
          ->MinTime(1.0);
      benchmark::RegisterBenchmark(("ses_only" + suffix + "/" + name).c_str(), BM_SesOnly, name,
                                   method)
          ->Unit(benchmark::kMillisecond)
          ->MinTime(1.0);
    }
    benchmark::RegisterBenchmark(("edtsurf/" + name).c_str(), BM_Edtsurf, name)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(1.0);
  }
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);

  std::printf("\nratios (same run, mean wall time):\n");
  for (const auto& [name, input] : inputs()) {
    for (const std::string suffix : {"", "_edt"}) {
      const auto ours = reporter.times_ms.find("surf_build" + suffix + "/" + name);
      const auto ses = reporter.times_ms.find("ses_only" + suffix + "/" + name);
      const auto edt = reporter.times_ms.find("edtsurf/" + name);
      if (ours == reporter.times_ms.end() || ses == reporter.times_ms.end() ||
          edt == reporter.times_ms.end()) {
        continue;
      }
      std::printf(
          "  %-12s %-14s surf-build %.1f ms (%.0f vertices), SES geometry only %.1f ms, EDTSurf "
          "-f %d %.1f ms (%.0f vertices): surf-build / EDTSurf = %.2f, SES only / EDTSurf = "
          "%.2f\n",
          name.c_str(), suffix.empty() ? "exact SES" : "--ses-method edt", ours->second,
          reporter.vertices["surf_build" + suffix + "/" + name], ses->second, input.edtsurf_scale,
          edt->second, reporter.vertices["edtsurf/" + name], ours->second / edt->second,
          ses->second / edt->second);
    }
  }
  std::printf(
      "\nSES area beside EDTSurf's (no exact reference: EDTSurf's area grows with its scale):\n");
  for (const auto& [name, input] : inputs()) {
    const mesh::Surface ours = molsurf::build_molecular_surface(io::read_molecule(input.molecule));
    std::printf("  %-12s surfcomp %.1f A^2 (%zu vertices)", name.c_str(),
                mesh::measure_surface(ours).area, ours.n_vertices());
    for (int scale : {2, 4, 8}) {
      const EdtsurfRun run = run_edtsurf(input, scale);
      std::printf(", EDTSurf -f %d %.1f A^2 (%zu vertices)", scale, run.area, run.vertices);
    }
    std::printf("\n");
  }
  benchmark::Shutdown();
  return 0;
}
