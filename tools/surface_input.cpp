#include "surface_input.hpp"

#include "options.hpp"

#include "surfcomp/mesh/io/read_mesh.hpp"

namespace surfcomp::tools {

void add_surface_options(boost::program_options::options_description& options,
                         SurfaceInput& input) {
  namespace po = boost::program_options;
  const mesh::MolecularSurfaceOptions defaults;
  // clang-format off
  options.add_options()
      ("probe-radius",
       po::value(&input.surface.ses.probe_radius)->default_value(defaults.ses.probe_radius),
       "probe radius, A (0 gives the van der Waals surface)")
      ("density",
       po::value(&input.surface.ses.vertex_density)->default_value(defaults.ses.vertex_density),
       "target vertex density, vertices per A^2")
      ("voxel", po::value(&input.surface.ses.voxel_size)->default_value(defaults.ses.voxel_size),
       "level-set voxel size, A (0 = chosen from the density)")
      ("charges", po::value(&input.charges)->default_value("file"),
       "partial charges: file (the file's own; else residue charges for a protein PDB, "
       "Gasteiger otherwise) | gasteiger | mmff")
      ("eps", po::value(&input.surface.esp.dielectric)->default_value(defaults.esp.dielectric),
       "dielectric constant for the ESP")
      ("eps-distance-dependent", po::bool_switch(&input.surface.esp.distance_dependent),
       "use eps * d (d in A) as the dielectric, e.g. --eps 4 for 4d")
      ("lp-kernel", po::value(&input.lp_kernel)->default_value("fauchere"),
       "lipophilic potential kernel: fauchere exp(-d) | dubost 1/(1+d)")
      ("ligand", po::value(&input.read.ligand),
       "PDB/PQR input: use this residue name only (default: the whole structure without water)")
      ("record", po::value(&input.read.record),
       "SDF/MOL2 input holding several molecules: read molecule N (1-based)")
      ("molecule", po::value(&input.molecule_file),
       "mesh INPUT only: molecule whose ESP and LP are mapped onto the mesh");
  // clang-format on
}

void finish_surface_options(SurfaceInput& input) {
  require_in_range("probe-radius", input.surface.ses.probe_radius, 0.0, 10.0);
  require_in_range("density", input.surface.ses.vertex_density, 0.05, 100.0);
  require_in_range("voxel", input.surface.ses.voxel_size, 0.0, 2.0);
  require_in_range("eps", input.surface.esp.dielectric, 1e-3, 1e3);
  require_one_of("charges", input.charges, {"file", "gasteiger", "mmff"});
  input.read.charges = input.charges == "gasteiger" ? io::ChargeModel::gasteiger
                       : input.charges == "mmff"    ? io::ChargeModel::mmff
                                                    : io::ChargeModel::file;
  require_one_of("lp-kernel", input.lp_kernel, {"fauchere", "dubost"});
  input.surface.lp.kernel = input.lp_kernel == "dubost" ? mesh::LipophilicKernel::dubost
                                                        : mesh::LipophilicKernel::fauchere;
}

void check_surface_input(const std::filesystem::path& path, const SurfaceInput& input) {
  if (mesh::io::is_mesh_file(path)) {
    if (!input.read.ligand.empty())
      throw OptionError("--ligand applies to a molecule INPUT, not a mesh");
  } else if (io::is_molecule_file(path)) {
    if (!input.molecule_file.empty()) throw OptionError("--molecule applies to a mesh INPUT");
  } else {
    throw InputError(path.string() + ": unknown input format (" + kInputFormats + ")");
  }
}

LoadedSurface load_surface(const std::filesystem::path& path, const SurfaceInput& input) {
  check_surface_input(path, input);
  LoadedSurface loaded;
  if (mesh::io::is_mesh_file(path)) {
    loaded.surface = mesh::io::read_mesh(path);
    if (!input.molecule_file.empty())
      loaded.molecule = io::read_molecule(input.molecule_file, input.read);
    mesh::assign_surface_properties(loaded.surface, loaded.molecule ? &*loaded.molecule : nullptr,
                                    input.surface);
  } else {
    loaded.molecule = io::read_molecule(path, input.read);
    loaded.surface = mesh::build_molecular_surface(*loaded.molecule, input.surface);
  }
  return loaded;
}

}  // namespace surfcomp::tools
