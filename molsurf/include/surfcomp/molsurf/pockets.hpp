// Pockets of a protein found from its atoms alone, as fpocket finds them (V. Le Guilloux,
// P. Schmidtke, P. Tuffery, BMC Bioinformatics 10, 168 (2009)): the alpha spheres of the heavy
// atoms (the empty circumspheres of CGAL's 3D Delaunay triangulation) whose radius lies between
// two bounds, kept when buried, clustered by single linkage of their centres and ranked. A
// pocket's alpha spheres are a binding site (molsurf::binding_site) wherever a site can be
// used: `match --site-pocket N`, `library build --pockets`, a screen's query.
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/molsurf/load_surface.hpp"
#include "surfcomp/molsurf/site.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace surfcomp::molsurf {

struct PocketOptions {
  /// Default 3.2 A. Smallest alpha sphere kept: its radius is the distance from its centre to
  /// the centres of its four atoms (fpocket's -m). Finite, > 0.
  double min_sphere_radius = 3.2;
  /// Default 6.4 A. Largest alpha sphere kept (fpocket's -M); larger ones lie over open
  /// surface. Finite, > min_sphere_radius.
  double max_sphere_radius = 6.4;
  /// Default 0.6. Fewest of 30 directions from an alpha sphere's centre that meet a protein atom
  /// within buried_distance (the sphere's buriedness) for the sphere to be kept. In [0, 1].
  double min_buriedness = 0.6;
  /// Default 10 A. How far a direction looks for an atom. Finite, > 0.
  double buried_distance = 10.0;
  /// Default 2.4 A. Alpha spheres whose centres are closer are in one pocket (single linkage).
  /// Finite, > 0.
  double cluster_distance = 2.4;
  /// Default 12. Fewest alpha spheres a pocket holds; smaller clusters are dropped. >= 1.
  int min_spheres = 12;
  /// Default 0: no split. A cavity (a single-linkage cluster) whose volume is above this, A^3, is
  /// split into sub-pockets: its alpha sphere centres in two by two-means, again and again, until
  /// each part holds at most this volume or would leave a side with fewer than min_spheres
  /// spheres. Each part is a pocket; Pocket::cavity keeps the hierarchy. The pockets are then
  /// ranked cavity by cavity: the best part of each cavity (cavities by summed score), then
  /// each one's second part, and so on. Finite, >= 0.
  double max_volume = 0.0;
};

/// The user's options of PocketOptions: --pocket-min-radius, --pocket-max-radius,
/// --pocket-buriedness, --pocket-min-spheres, --pocket-max-volume.
const options::Table<PocketOptions>& pocket_option_table();

/// What the user sees of --site-pocket, wherever a site is asked for: the binding site is the
/// structure's pocket N (1-based, as `surfcomp pockets` ranks them).
options::Spec site_pocket_spec();

/// A pocket, ranked by score.
struct Pocket {
  int rank = 0;        ///< 1-based, by decreasing score
  double score = 0.0;  ///< the sum of its alpha spheres' buriedness
  /// A^3: the volume of the union of its alpha spheres, each shrunk by 1.6 A (its atoms' van der
  /// Waals reach), on a 0.5 A grid.
  double volume = 0.0;
  double buriedness = 0.0;  ///< its alpha spheres' mean buriedness, in [0, 1]
  /// 1-based: the cavity it is part of, cavities numbered by decreasing summed score. A cavity
  /// not split (PocketOptions::max_volume) is one pocket; the parts of a split one share it.
  int cavity = 0;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< mean of its alpha sphere centres, A
  /// Its alpha spheres (centre, radius to their atoms' centres), A: the pocket's site spheres.
  std::vector<SiteSphere> spheres;
  /// The atoms its alpha spheres touch: indices into the structure detect_pockets was given,
  /// ascending.
  std::vector<std::size_t> lining_atoms;
  /// Their residues, "HIS142:A" (name, number, insertion code, ':' and chain when there is one),
  /// in the order of lining_atoms, each once.
  std::vector<std::string> lining_residues;
};

/// The atoms pockets are detected on and surfaced with: the structure's ATOM records (no HETATM
/// record, so no ligand, ion, cofactor or water), in order, with their properties. Throws
/// InputError naming structure.source when it holds no such atom.
Molecule pocket_structure(const Molecule& structure);

/// The pockets of pocket_structure(structure), by decreasing score (ties by centre, x then y then
/// z), ranks from 1; none when no cluster of alpha spheres passes the filters. Deterministic.
/// Throws InputError as pocket_structure, OptionError for options outside their domain.
std::vector<Pocket> detect_pockets(const Molecule& structure, const PocketOptions& options = {});

/// The binding site of pocket `rank` (1-based) of detect_pockets(structure, pocket_options): its
/// alpha spheres on pocket_structure(structure). Throws InputError naming structure.source when
/// it has fewer pockets ("has K pockets; pocket N was asked for"), and as detect_pockets and
/// binding_site.
BindingSite pocket_site(const Molecule& structure, int rank,
                        const PocketOptions& pocket_options = {},
                        const BindingSiteOptions& options = {});

/// How `surfcomp pockets` (and Python's pockets()) reads a structure and finds its pockets.
struct PocketSearchOptions {
  /// The structure's reading: --min-plddt (input.read.min_plddt) and --max-atoms
  /// (input.surface.ses.max_atoms) apply.
  molsurf::SurfaceInputOptions input;
  PocketOptions pockets;
};

/// The user's options of PocketSearchOptions: --min-plddt, --max-atoms and pocket_option_table.
const options::Table<PocketSearchOptions>& pocket_search_option_table();

/// The pockets of one structure file and what they were found on.
struct StructurePockets {
  std::size_t models = 1;         ///< models in the file; the first is read
  std::size_t protein_atoms = 0;  ///< its ATOM records (pocket_structure)
  std::vector<Pocket> pockets;    ///< detect_pockets'
};

/// The pockets of the PDB or mmCIF file `structure` (io::read_molecule with options.input.read,
/// then detect_pockets). Throws InputError for a file that is not a PDB or mmCIF structure, for
/// more atoms than options.input.surface.ses.max_atoms, and as the reader and detect_pockets.
StructurePockets find_pockets(const std::filesystem::path& structure,
                              const PocketSearchOptions& options = {});

}  // namespace surfcomp::molsurf
