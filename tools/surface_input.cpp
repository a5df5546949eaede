#include "surface_input.hpp"

#include "console.hpp"
#include "options.hpp"

#include <cstdint>
#include <memory>

namespace surfcomp::tools {
namespace {

/// A progress line for an ESP or LP sum (console::ProgressLine), or none.
mesh::PotentialProgress potential_progress(const char* what) {
  if (!console::progress_shown()) return {};
  auto line = std::make_shared<console::ProgressLine>(what, "points");
  return [line](std::int64_t done, std::int64_t total) { (*line)(done, total); };
}

}  // namespace

void add_surface_options(boost::program_options::options_description& options,
                         SurfaceInput& input) {
  namespace po = boost::program_options;
  const mesh::MolecularSurfaceOptions defaults;
  // clang-format off
  options.add_options()
      ("probe-radius",
       defaulted(&input.surface.ses.probe_radius, defaults.ses.probe_radius),
       "probe radius, A (0 gives the van der Waals surface)")
      ("density",
       defaulted(&input.surface.ses.vertex_density, defaults.ses.vertex_density),
       "target vertex density, vertices per A^2")
      ("voxel", defaulted(&input.surface.ses.voxel_size, defaults.ses.voxel_size),
       "level-set voxel size, A (0 = chosen from the density)")
      ("charges", po::value(&input.charges)->default_value("file"),
       "partial charges: file (the file's own; else residue charges for a protein PDB, "
       "Gasteiger otherwise) | gasteiger | mmff")
      ("eps", defaulted(&input.surface.esp.dielectric, defaults.esp.dielectric),
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
       "mesh INPUT only: molecule whose ESP and LP are mapped onto the mesh")
      ("max-atoms", defaulted(&input.surface.ses.max_atoms, defaults.ses.max_atoms),
       "limit: atoms of a molecule INPUT")
      ("max-grid-cells",
       defaulted(&input.surface.ses.max_grid_cells, defaults.ses.max_grid_cells),
       "limit: cells of the surface grid (the atoms' extent in voxels, cubed)")
      ("max-vertices",
       defaulted(&input.surface.ses.max_vertices, defaults.ses.max_vertices),
       "limit: vertices of the surface built");
  // clang-format on
}

void finish_surface_options(SurfaceInput& input) {
  require_in_range("probe-radius", input.surface.ses.probe_radius, 0.0, 10.0);
  require_in_range("density", input.surface.ses.vertex_density, mesh::min_vertex_density,
                   mesh::max_vertex_density);
  require_in_range("voxel", input.surface.ses.voxel_size, 0.0, 2.0);
  require_in_range("eps", input.surface.esp.dielectric, 1e-3, 1e3);
  require_one_of("charges", input.charges, {"file", "gasteiger", "mmff"});
  input.read.charges = input.charges == "gasteiger" ? io::ChargeModel::gasteiger
                       : input.charges == "mmff"    ? io::ChargeModel::mmff
                                                    : io::ChargeModel::file;
  require_one_of("lp-kernel", input.lp_kernel, {"fauchere", "dubost"});
  input.surface.lp.kernel = input.lp_kernel == "dubost" ? mesh::LipophilicKernel::dubost
                                                        : mesh::LipophilicKernel::fauchere;
  input.surface.esp.progress = potential_progress("ESP");
  input.surface.lp.progress = potential_progress("LP");
}

}  // namespace surfcomp::tools
