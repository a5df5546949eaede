#include "surfcomp/molsurf/load_surface.hpp"

#include "surfcomp/molsurf/ses.hpp"

namespace surfcomp::molsurf {

const options::Table<SurfaceInputOptions>& surface_input_option_table() {
  using options::Kind;
  using S = SurfaceInputOptions;
  static const options::Table<S> table = {
      options::field<S>(
          {"probe-radius", Kind::real, "probe radius (0 gives the van der Waals surface)", "A", 0.0,
           10.0},
          [](auto& s) -> auto& { return s.surface.ses.probe_radius; }),
      options::field<S>(
          {"density", Kind::real, "target vertex density", "vertices per A^2", min_vertex_density,
           max_vertex_density},
          [](auto& s) -> auto& { return s.surface.ses.vertex_density; }),
      options::field<S>(
          {"voxel", Kind::real, "level-set voxel size (0: chosen from the density)", "A", 0.0, 2.0},
          [](auto& s) -> auto& { return s.surface.ses.voxel_size; }),
      options::choice<S>(
          {"ses-method", Kind::choice,
           "molecule INPUT: exact (the exact SES, exact normals) or edt (a distance transform "
           "on a dense grid, as EDTSurf: about half the time for a protein; crevices thinner "
           "than a voxel bridged, vertices about 0.14 A off on average)"},
          [](auto& s) -> auto& { return s.surface.ses.method; }, ses_method_names),
      options::choice<S>(
          {"charges", Kind::choice,
           "partial charges: file (the file's own; else residue charges for a "
           "protein PDB, Gasteiger otherwise), gasteiger or mmff"},
          [](auto& s) -> auto& { return s.read.charges; }, surfcomp::io::charge_model_names),
      options::field<S>(
          {"eps", Kind::real, "dielectric constant for the ESP", "", 1e-3, 1e3},
          [](auto& s) -> auto& { return s.surface.esp.dielectric; }),
      options::field<S>(
          {"eps-distance-dependent", Kind::flag,
           "use eps * d (d in A) as the dielectric, e.g. {eps} 4 for 4d"},
          [](auto& s) -> auto& { return s.surface.esp.distance_dependent; }),
      options::choice<S>(
          {"lp-kernel", Kind::choice,
           "lipophilic potential kernel: fauchere exp(-d) or dubost 1/(1+d)"},
          [](auto& s) -> auto& { return s.surface.lp.kernel; }, lipophilic_kernel_names),
      options::field<S>(
          {"ligand",
           Kind::text,
           "PDB/PQR input: use one copy of this residue only, RES[:CHAIN[:NUMBER]] (default: "
           "the whole structure without water)",
           "",
           0,
           0,
           false,
           {},
           true},
          [](auto& s) -> auto& { return s.read.ligand; }),
      options::field<S>(
          {"record",
           Kind::integer,
           "SDF/MOL2 input holding several molecules: read molecule N (1-based)",
           "",
           1,
           1e9,
           false,
           {},
           true},
          [](auto& s) -> auto& { return s.read.record; }),
      options::field<S>(
          surfcomp::io::min_plddt_spec(), [](auto& s) -> auto& { return s.read.min_plddt; }),
      options::field<S>(
          {"molecule",
           Kind::text,
           "mesh INPUT only: molecule whose ESP and LP are mapped onto the mesh",
           "",
           0,
           0,
           false,
           {},
           true},
          [](auto& s) -> auto& { return s.molecule_file; }),
      options::field<S>(
          {"repair", Kind::flag,
           "mesh INPUT only: repair it first (CGAL: duplicate vertices merged, degenerate and "
           "duplicate faces removed, non-manifold vertices split, borders stitched, the largest "
           "component kept, faces turned outward) and say what changed; vertex properties "
           "are not kept"},
          [](auto& s) -> auto& { return s.repair; }),
      options::choice<S>(
          {"scale", Kind::choice,
           "length unit of a general mesh (no ESP and LP), in which every length option counts: "
           "auto (1/12 of its RMS radius; of the larger mesh in a match) or none (its own "
           "coordinates, taken as A); molecules are always in A"},
          [](auto& s) -> auto& { return s.scale; }, mesh::length_scale_names),
      options::field<S>(
          {"unit",
           Kind::real,
           "a general mesh's length, in its coordinates, that every length option counts as 1 A "
           "(default: from {scale})",
           "",
           0.0,
           1e12,
           true,
           {},
           true},
          [](auto& s) -> auto& { return s.unit; }),
      options::field<S>(
          {"max-atoms", Kind::integer, "limit: atoms of a molecule INPUT", "", 1, 1e12},
          [](auto& s) -> auto& { return s.surface.ses.max_atoms; }),
      options::field<S>(
          {"max-grid-cells", Kind::real,
           "limit: cells of the surface grid (the atoms' extent in voxels, cubed)", "", 1, 1e15},
          [](auto& s) -> auto& { return s.surface.ses.max_grid_cells; }),
      options::field<S>(
          {"max-vertices", Kind::integer, "limit: vertices of the surface built", "", 1, 1e12},
          [](auto& s) -> auto& { return s.surface.ses.max_vertices; }),
  };
  return table;
}

}  // namespace surfcomp::molsurf
