// surfcomp surf-build: a molecule (SES built here) or a mesh in; a surface with per-vertex
// normals, ESP, LP and curvature out; one summary line on stdout.
#include "command.hpp"
#include "options.hpp"

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/mesh/molecular_surface.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp surf-build INPUT -o OUT.ply [options]\n\n"
    "Builds the solvent-excluded surface (SES) of a molecule, or reads a surface mesh, and\n"
    "writes it with per-vertex normals, ESP (kcal/(mol*e)), LP, principal curvatures cc1, cc2\n"
    "(1/A, convex negative), shape index and curvedness.\n\n"
    "INPUT  a molecule (.sdf .mol .mol2 .pdb .ent .pqr) or a mesh (.ply .vert/.face .off .obj)\n"
    "Prints: input, atoms, vertices, faces, area (A^2), volume (A^3), Euler characteristic, time.";

io::ChargeModel parse_charge_model(const std::string& name) {
  require_one_of("charges", name, {"file", "gasteiger", "mmff"});
  if (name == "gasteiger") return io::ChargeModel::gasteiger;
  if (name == "mmff") return io::ChargeModel::mmff;
  return io::ChargeModel::file;
}

mesh::LipophilicKernel parse_lp_kernel(const std::string& name) {
  require_one_of("lp-kernel", name, {"fauchere", "dubost"});
  return name == "dubost" ? mesh::LipophilicKernel::dubost : mesh::LipophilicKernel::fauchere;
}

}  // namespace

int surf_build(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  const mesh::MolecularSurfaceOptions defaults;
  std::string output, charges, lp_kernel, ligand, molecule_file;
  mesh::MolecularSurfaceOptions options;
  po::options_description described("options");
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(),
       "output surface: .ply (binary, all properties), .off or .obj (geometry only)")
      ("probe", po::value(&options.ses.probe_radius)->default_value(defaults.ses.probe_radius),
       "probe radius, A (0 gives the van der Waals surface)")
      ("density", po::value(&options.ses.vertex_density)->default_value(defaults.ses.vertex_density),
       "target vertex density, vertices per A^2")
      ("voxel", po::value(&options.ses.voxel_size)->default_value(defaults.ses.voxel_size),
       "level-set voxel size, A (0 = chosen from the density)")
      ("charges", po::value(&charges)->default_value("file"),
       "partial charges: file (the file's own, else Gasteiger) | gasteiger | mmff")
      ("eps", po::value(&options.esp.dielectric)->default_value(defaults.esp.dielectric),
       "dielectric constant for the ESP")
      ("eps-distance-dependent", po::bool_switch(&options.esp.distance_dependent),
       "use eps * d (d in A) as the dielectric, e.g. --eps 4 for 4d")
      ("lp-kernel", po::value(&lp_kernel)->default_value("fauchere"),
       "lipophilic potential kernel: fauchere exp(-d) | dubost 1/(1+d)")
      ("ligand", po::value(&ligand),
       "PDB/PQR input: build the surface of this residue name only (default: the whole "
       "structure without water)")
      ("molecule", po::value(&molecule_file),
       "mesh INPUT only: molecule whose ESP and LP are mapped onto the mesh")
      ("ascii", po::bool_switch(), "write ASCII PLY instead of binary little-endian");
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, kUsage, vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing INPUT (see --help)");
  const std::filesystem::path input = vm["input"].as<std::vector<std::string>>().front();

  require_in_range("probe", options.ses.probe_radius, 0.0, 10.0);
  require_in_range("density", options.ses.vertex_density, 0.05, 100.0);
  require_in_range("voxel", options.ses.voxel_size, 0.0, 2.0);
  require_in_range("eps", options.esp.dielectric, 1e-3, 1e3);
  options.lp.kernel = parse_lp_kernel(lp_kernel);
  io::MoleculeReadOptions read_options;
  read_options.charges = parse_charge_model(charges);
  read_options.ligand = ligand;
  if (!mesh::io::is_mesh_file(output)) {
    throw OptionError("--output " + output + ": unknown surface format (use .ply, .off or .obj)");
  }
  const bool ascii = vm["ascii"].as<bool>();

  Stopwatch clock;
  mesh::Surface surface;
  std::optional<Molecule> molecule;
  if (mesh::io::is_mesh_file(input)) {
    if (vm.count("ligand")) throw OptionError("--ligand applies to a molecule INPUT, not a mesh");
    surface = mesh::io::read_mesh(input);
    if (!molecule_file.empty()) molecule = io::read_molecule(molecule_file, read_options);
    mesh::assign_surface_properties(surface, molecule ? &*molecule : nullptr, options);
  } else if (io::is_molecule_file(input)) {
    if (!molecule_file.empty()) throw OptionError("--molecule applies to a mesh INPUT");
    molecule = io::read_molecule(input, read_options);
    surface = mesh::build_molecular_surface(*molecule, options);
  } else {
    throw InputError(input.string() + ": unknown input format (molecule: .sdf .mol .mol2 .pdb "
                     ".ent .pqr; mesh: .ply .vert .face .off .obj)");
  }
  const double elapsed = clock.elapsed_ms();

  if (std::filesystem::path(output).extension() == ".ply") {
    mesh::io::write_ply(surface, output,
                        ascii ? mesh::io::PlyFormat::ascii
                              : mesh::io::PlyFormat::binary_little_endian);
  } else {
    mesh::io::write_mesh(surface, output);
  }

  const mesh::SurfaceMeasures m = mesh::measure_surface(surface);
  std::printf("%s: %zu atoms, %zu vertices, %zu faces, area %.1f A^2, ", input.string().c_str(),
              molecule ? molecule->atoms.size() : std::size_t{0}, surface.n_vertices(),
              surface.n_faces(), m.area);
  if (m.boundary_edges == 0) {
    std::printf("volume %.1f A^3, ", m.volume);
  } else {
    std::printf("volume n/a (open, %zu boundary edges), ", m.boundary_edges);
  }
  std::printf("Euler %d, %.0f ms -> %s\n", m.euler_characteristic, elapsed, output.c_str());
  return 0;
}

}  // namespace surfcomp::tools
