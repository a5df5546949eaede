// surfcomp hsi-build: a surface's critical points, patches, harmonic maps and harmonic shape
// images, stored in a .hsi file so that comparisons never rebuild them.
#include "command.hpp"
#include "console.hpp"
#include "describe_settings.hpp"
#include "options.hpp"
#include "surface_input.hpp"

#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"

#include <cstdio>
#include <iostream>
#include <memory>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp hsi-build INPUT -o OUT.hsi [options]\n\n"
    "Builds the coarse level of a surface (method §2-4): its critical points and, for\n"
    "each, the geodesic patch around it, the patch's harmonic map onto the unit disk and its\n"
    "harmonic shape image of the shape index on a polar grid; writes them, the surface and the\n"
    "parameters to a versioned, checksummed binary file (byte-identical for any --threads).\n\n"
    "A general mesh (no ESP and LP) is described in its length unit (--scale, --unit; the radii\n"
    "count in it) and stored in its own coordinates with that unit (file format version 3).\n\n"
    "INPUT  a molecule or mesh (as surf-build)";

}  // namespace

int hsi_build(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "output .hsi file");
  // clang-format on
  add_describe_options(described);
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, kUsage, vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing INPUT (see --help)");
  const std::filesystem::path path = vm["input"].as<std::vector<std::string>>().front();
  const matching::MatchInputOptions settings = describe_options_from(vm);
  const molsurf::SurfaceInputOptions& input = settings.input;
  molsurf::check_surface_input(path, input);
  io::check_command_files({{{"INPUT", path}, {"--molecule", input.molecule_file}},
                           {{"--output", output, {".hsi"}, ""}}});
  const ThreadLimit limit(settings.threads);

  Stopwatch clock;
  matching::MatchInput input_file;
  input_file.path = path;
  const matching::PreparedInput prepared = matching::prepare_input(input_file, settings);
  for (const std::string& note : prepared.notes) console::note(note);
  const harmonic::SurfaceDescriptors& descriptors = prepared.descriptors;
  const double total_ms = clock.elapsed_ms();
  harmonic::io::write_hsi(descriptors, output);

  const harmonic::DescriptorCounts counts = harmonic::count_descriptors(descriptors);
  console::summary("%s: %zu vertices, %zu peaks, %zu valleys, %zu images, ", path.string().c_str(),
                   descriptors.surface.n_vertices(), counts.peaks, counts.valleys, counts.imaged);
  if (prepared.unit.value != 1.0) {
    console::summary("length unit %.6g (%s), ", prepared.unit.value, prepared.unit.from.c_str());
  }
  console::summary("%.0f ms -> %s\n", total_ms, output.c_str());
  return 0;
}

}  // namespace surfcomp::tools
