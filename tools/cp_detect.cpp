// surfcomp cp-detect: the shape critical points (peaks and valleys) of a surface, as JSON and,
// for viewing, as PDB or PLY points.
#include "command.hpp"
#include "console.hpp"
#include "options.hpp"
#include "surface_input.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/report/critical_point_files.hpp"

#include <cstdio>
#include <iostream>

namespace surfcomp::tools {
namespace {

std::string format_length(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

constexpr const char* kUsage =
    "usage: surfcomp cp-detect INPUT -o CPS.json [--points-out CPS.pdb|CPS.ply] [options]\n\n"
    "Finds the shape critical points of a surface (method §2): peaks, convex vertices whose |cc1|\n"
    "is the largest within the on-surface radius; valleys, concave vertices whose cc1 is the\n"
    "largest within it. Each comes with its position, normal, curvature and the shape index,\n"
    "ESP and LP averaged over a small geodesic disc. A general mesh is searched in its length\n"
    "unit (--scale, --unit: the radii count in it) and its points given in its coordinates.\n\n"
    "INPUT  a molecule or mesh (as surf-build) or a .hsi file (its stored critical points)";

}  // namespace

int cp_detect(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, points_out;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "critical points as JSON")
      ("points-out", po::value(&points_out), "also write the points for viewing: .pdb or .ply");
  // clang-format on
  add_table_options(described, mesh::critical_point_option_table());
  add_surface_options(described);
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, kUsage, vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing INPUT (see --help)");
  const std::filesystem::path path = vm["input"].as<std::vector<std::string>>().front();
  const molsurf::SurfaceInputOptions input = surface_options_from(vm);
  mesh::CriticalPointOptions cp_options;
  apply_table_options(mesh::critical_point_option_table(), vm, cp_options);
  const bool from_hsi = harmonic::io::is_hsi_file(path);
  if (!from_hsi) molsurf::check_surface_input(path, input);
  io::check_command_files(
      {{{"INPUT", path}, {"--molecule", input.molecule_file}},
       {{"--output", output, {}, ""}, {"--points-out", points_out, {".pdb", ".ply"}, ""}}});

  Stopwatch clock;
  std::vector<mesh::CriticalPoint> points;
  std::size_t n_vertices = 0;
  mesh::LengthUnit unit;
  if (from_hsi) {
    const harmonic::SurfaceDescriptors stored = harmonic::io::read_hsi(path);
    if (stored.length_unit != 1.0) unit = {stored.length_unit, "stored"};
    for (const auto& cp : stored.critical_points) points.push_back(cp.point);
    cp_options = stored.options.critical_points;
    n_vertices = stored.surface.n_vertices();
  } else {
    const molsurf::LoadedSurface loaded = load_noted(path, input);
    points = mesh::detect_critical_points_in_unit(loaded.surface, loaded.unit.value, cp_options);
    n_vertices = loaded.surface.n_vertices();
    unit = loaded.unit;
  }
  const double elapsed = clock.elapsed_ms();
  std::size_t peaks = 0;
  for (const auto& p : points) peaks += p.type == mesh::CriticalPointType::peak ? 1 : 0;

  const report::CriticalPointSet set{path.string(), cp_options, n_vertices, points, unit.value};
  // The JSON goes last; if it cannot be written, the points file written before it is removed,
  // so a failure leaves no output at all.
  if (!points_out.empty()) report::write_critical_points(points_out, set);
  try {
    surfcomp::io::write_file_atomically(
        output, [&](std::ostream& out) { out << report::critical_points_json(set); });
  } catch (...) {
    if (!points_out.empty()) std::filesystem::remove(points_out);
    throw;
  }
  const std::string radius_unit =
      unit.value == 1.0 ? "A" : "units of " + format_length(unit.value) + " (" + unit.from + ")";
  console::summary("%s: %zu vertices, %zu peaks, %zu valleys (r_cp %.2f %s), %.0f ms -> %s\n",
                   path.string().c_str(), n_vertices, peaks, points.size() - peaks,
                   cp_options.radius, radius_unit.c_str(), elapsed, output.c_str());
  return 0;
}

}  // namespace surfcomp::tools
