// surfcomp hsi-build: a surface's critical points, patches, harmonic maps and harmonic shape
// images, stored in a .hsi file so that comparisons never rebuild them.
#include "command.hpp"
#include "command_files.hpp"
#include "options.hpp"
#include "surface_input.hpp"

#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"

#include <tbb/global_control.h>

#include <cstdio>
#include <iostream>
#include <memory>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp hsi-build INPUT -o OUT.hsi [options]\n\n"
    "Builds the coarse level of a surface (METHOD sections 2-4): its critical points and, for\n"
    "each, the geodesic patch around it, the patch's harmonic map onto the unit disk and its\n"
    "harmonic shape image of the shape index on a polar grid; writes them, the surface and the\n"
    "parameters to a versioned, checksummed binary file (byte-identical for any --threads).\n\n"
    "INPUT  a molecule or mesh (as surf-build)";

harmonic::SpringWeights parse_weights(const std::string& name) {
  require_one_of("weights", name, {"inverse-length", "uniform", "cotangent", "mean-value"});
  if (name == "uniform") return harmonic::SpringWeights::uniform;
  if (name == "cotangent") return harmonic::SpringWeights::cotangent;
  if (name == "mean-value") return harmonic::SpringWeights::mean_value;
  return harmonic::SpringWeights::inverse_length;
}

}  // namespace

int hsi_build(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, weights;
  int threads = 0;
  SurfaceInput input;
  harmonic::DescriptorOptions options;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "output .hsi file")
      ("critical-point-radius",
       defaulted(&options.critical_points.radius),
       "critical point radius r_cp (on-surface), A")
      ("patch-radius", defaulted(&options.patch.radius),
       "patch radius (on-surface), A; about 5 for ligands, larger for protein sites")
      ("image-rings", defaulted(&options.image.rings),
       "image grid: rings of the polar grid")
      ("image-sectors", defaulted(&options.image.sectors),
       "image grid: sectors (samples per ring; 180 = 2-degree rotation steps)")
      ("weights", po::value(&weights)->default_value("inverse-length"),
       "harmonic map spring weights: inverse-length (seed) | uniform | cotangent | mean-value")
      ("threads", po::value(&threads)->default_value(0), "worker threads (0 = all cores)")
      ("max-image-bytes",
       defaulted(&options.max_image_bytes),
       "limit: memory of the shape images, bytes");
  // clang-format on
  add_surface_options(described, input);
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, kUsage, vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing INPUT (see --help)");
  const std::filesystem::path path = vm["input"].as<std::vector<std::string>>().front();
  finish_surface_options(input);
  require_in_range("critical-point-radius", options.critical_points.radius, 1e-3, 100.0);
  require_in_range("patch-radius", options.patch.radius, 0.1, 100.0);
  require_in_range("image-rings", options.image.rings, 1, 1024);
  require_in_range("image-sectors", options.image.sectors, 1, 4096);
  require_in_range("threads", threads, 0, 1024);
  options.disk_map.weights = parse_weights(weights);
  mesh::check_surface_input(path, input);
  check_command_files({{{"INPUT", path}, {"--molecule", input.molecule_file}},
                       {{"--output", output, {".hsi"}, ""}}});
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) {
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<std::size_t>(threads));
  }

  Stopwatch clock;
  mesh::LoadedSurface loaded = mesh::load_surface(path, input);
  const double surface_ms = clock.elapsed_ms();
  const harmonic::SurfaceDescriptors descriptors =
      loaded.molecule
          ? harmonic::describe_surface(std::move(loaded.surface), *loaded.molecule, options)
          : harmonic::describe_surface(std::move(loaded.surface), options);
  const double total_ms = clock.elapsed_ms();
  harmonic::io::write_hsi(descriptors, output);

  const harmonic::DescriptorCounts counts = harmonic::count_descriptors(descriptors);
  std::printf(
      "%s: %zu vertices, %zu peaks, %zu valleys, %zu images, surface %.0f ms, "
      "images %.0f ms -> %s\n",
      path.string().c_str(), descriptors.surface.n_vertices(), counts.peaks, counts.valleys,
      counts.imaged, surface_ms, total_ms - surface_ms, output.c_str());
  return 0;
}

}  // namespace surfcomp::tools
