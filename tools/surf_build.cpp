// surfcomp surf-build: a molecule (SES built here) or a mesh in; a surface with per-vertex
// normals, ESP, LP and curvature out; one summary line on stdout.
#include "command.hpp"
#include "console.hpp"
#include "options.hpp"
#include "surface_input.hpp"

#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"

#include <cstdio>
#include <iostream>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp surf-build INPUT -o OUT.ply [options]\n\n"
    "Builds the solvent-excluded surface (SES) of a molecule, or reads a surface mesh, and\n"
    "writes it with per-vertex normals, ESP (kcal/(mol*e)), LP, principal curvatures cc1, cc2\n"
    "(1/A, convex negative), shape index and curvedness. A general mesh (no ESP and LP) keeps its\n"
    "coordinates; its curvature is fitted over 3 of its length units (--scale, --unit) and given\n"
    "per length of its coordinates.\n\n"
    "INPUT  a molecule or a mesh (%s)\n"
    "Prints: input, atoms, vertices, faces, area (A^2; a general mesh's in its coordinates'\n"
    "units), volume, a general mesh's length unit, Euler characteristic, time.";

}  // namespace

int surf_build(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(),
       "output surface: .ply (binary, all properties), .off or .obj (geometry only)")
      ("ascii", po::bool_switch(), "write ASCII PLY instead of binary little-endian");
  // clang-format on
  add_surface_options(described);
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, with_formats(kUsage).c_str(), vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing INPUT (see --help)");
  const std::filesystem::path path = vm["input"].as<std::vector<std::string>>().front();
  const molsurf::SurfaceInputOptions input = surface_options_from(vm);
  molsurf::check_surface_input(path, input);
  io::check_command_files({{{"INPUT", path}, {"--molecule", input.molecule_file}},
                           {{"--output", output, {".ply", ".off", ".obj"}, ""}}});

  Stopwatch clock;
  const molsurf::LoadedSurface loaded = load_noted(path, input);
  const double elapsed = clock.elapsed_ms();
  if (io::lowercase_extension(output) == ".ply") {
    mesh::io::write_ply(loaded.surface, output,
                        vm["ascii"].as<bool>() ? mesh::io::PlyFormat::ascii
                                               : mesh::io::PlyFormat::binary_little_endian);
  } else {
    mesh::io::write_mesh(loaded.surface, output);
  }

  const mesh::SurfaceMeasures m = mesh::measure_surface(loaded.surface);
  console::summary("%s: %zu atoms, %zu vertices, %zu faces, ", path.string().c_str(),
                   loaded.molecule ? loaded.molecule->atoms.size() : std::size_t{0},
                   loaded.surface.n_vertices(), loaded.surface.n_faces());
  // A general mesh's lengths are in its own coordinates' units, whatever they are.
  if (loaded.general_mesh) {
    console::summary("area %.6g, ", m.area);
  } else {
    console::summary("area %.1f A^2, ", m.area);
  }
  if (m.boundary_edges != 0) {
    console::summary("volume n/a (open, %zu boundary edges), ", m.boundary_edges);
  } else if (loaded.general_mesh) {
    console::summary("volume %.6g, ", m.volume);
  } else {
    console::summary("volume %.1f A^3, ", m.volume);
  }
  if (loaded.general_mesh) {
    console::summary("length unit %.6g (%s), ", loaded.unit.value, loaded.unit.from.c_str());
  }
  console::summary("Euler %d, %.0f ms -> %s\n", m.euler_characteristic, elapsed, output.c_str());
  return 0;
}

}  // namespace surfcomp::tools
