// surfcomp surf-build: a molecule (SES built here) or a mesh in; a surface with per-vertex
// normals, ESP, LP and curvature out; one summary line on stdout.
#include "command.hpp"
#include "command_files.hpp"
#include "console.hpp"
#include "options.hpp"
#include "surface_input.hpp"

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
    "(1/A, convex negative), shape index and curvedness.\n\n"
    "INPUT  a molecule (.sdf .mol .mol2 .pdb .ent .cif .cif.gz .pqr) or a mesh (.ply .vert/.face "
    ".off .obj)\n"
    "Prints: input, atoms, vertices, faces, area (A^2), volume (A^3), Euler characteristic, time.";

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
  if (!parse_command_line(args, described, 1, kUsage, vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing INPUT (see --help)");
  const std::filesystem::path path = vm["input"].as<std::vector<std::string>>().front();
  const mesh::SurfaceInputOptions input = surface_options_from(vm);
  mesh::check_surface_input(path, input);
  check_command_files({{{"INPUT", path}, {"--molecule", input.molecule_file}},
                       {{"--output", output, {".ply", ".off", ".obj"}, ""}}});

  Stopwatch clock;
  const mesh::LoadedSurface loaded = load_noted(path, input);
  const double elapsed = clock.elapsed_ms();
  if (io::lowercase_extension(output) == ".ply") {
    mesh::io::write_ply(loaded.surface, output,
                        vm["ascii"].as<bool>() ? mesh::io::PlyFormat::ascii
                                               : mesh::io::PlyFormat::binary_little_endian);
  } else {
    mesh::io::write_mesh(loaded.surface, output);
  }

  const mesh::SurfaceMeasures m = mesh::measure_surface(loaded.surface);
  console::summary("%s: %zu atoms, %zu vertices, %zu faces, area %.1f A^2, ", path.string().c_str(),
                   loaded.molecule ? loaded.molecule->atoms.size() : std::size_t{0},
                   loaded.surface.n_vertices(), loaded.surface.n_faces(), m.area);
  if (m.boundary_edges == 0) {
    console::summary("volume %.1f A^3, ", m.volume);
  } else {
    console::summary("volume n/a (open, %zu boundary edges), ", m.boundary_edges);
  }
  console::summary("Euler %d, %.0f ms -> %s\n", m.euler_characteristic, elapsed, output.c_str());
  return 0;
}

}  // namespace surfcomp::tools
