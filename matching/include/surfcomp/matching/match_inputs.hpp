// The whole comparison `surfcomp match` makes, for every caller that starts from files or from
// what a program holds (the CLI, the Python module, the report, a screen's query): each side
// read or built (a molecule's SES, a mesh with its properties, a .hsi file's stored
// description, a molecule, surface or description in memory), its binding site set up,
// described with common parameters, and the two matched (match_surfaces).
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/match.hpp"
#include "surfcomp/matching/site.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/load_surface.hpp"
#include "surfcomp/molsurf/pockets.hpp"

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace surfcomp::matching {

/// One side of a comparison: a file, or what a program holds. Exactly one of `path`,
/// `descriptors`, `surface`, `molecule` is the input; `molecule` may also come with `surface`
/// as the molecule the surface was built from (its heavy atoms are kept with the description).
struct MatchInput {
  /// A molecule (.sdf .mol .mol2 .pdb .ent .cif .cif.gz .pqr), a mesh (.ply .vert .off .obj) or a
  /// .hsi file.
  std::filesystem::path path;
  std::optional<harmonic::SurfaceDescriptors> descriptors;  ///< a description in memory
  std::optional<mesh::Surface> surface;  ///< a surface in memory, with its esp and lp
  /// Default 0: none. A general mesh `surface` whose curvature properties were fitted at this
  /// length unit (molsurf::assign_general_mesh_curvature; a mesh library's entries): a comparison
  /// in that unit keeps them instead of fitting them again, which costs most of a large mesh's
  /// description. Any other unit fits them again.
  double curvature_unit = 0.0;
  std::optional<Molecule> molecule;  ///< a molecule in memory (its SES is built)
  /// A binding site around one copy of this ligand residue (MatchInputOptions::site): the
  /// structure's surface is built without water and without that copy. A molecule input only.
  std::string site_ligand;
  /// Spheres of a binding site (with site_ligand: more spheres), any input.
  std::vector<molsurf::SiteSphere> site_spheres;
  /// Default 0: none. The binding site is pocket N (1-based) of detect_pockets
  /// (MatchInputOptions::pockets): its alpha spheres on the structure's ATOM records
  /// (pocket_site). A molecule input only; not with site_ligand or site_spheres.
  int site_pocket = 0;

  /// The side's name in messages: the path, the molecule's or surface's source, or the
  /// description's surface source.
  std::string name() const;
};

/// How match_inputs and prepare_input read, build, describe and match their inputs.
struct MatchInputOptions {
  /// How files and molecules become surfaces. Its scale and unit set the length unit of general
  /// meshes: of one side alone in prepare_input, of both together in match_inputs (the larger
  /// side's size under --scale auto), which describes them in it and gives every result back in
  /// the inputs' coordinates (a result file's parameters stay in units).
  molsurf::SurfaceInputOptions input;
  /// How a side that is not a description already is described. When the other side is a
  /// stored description (a .hsi file or descriptors in memory), its parameters are used instead
  /// (all but max_image_bytes), so that the two sides' images compare.
  harmonic::DescriptorOptions descriptors;
  molsurf::BindingSiteOptions site;  ///< spheres of 4 A around a site ligand, surface margin 16 A
  molsurf::PocketOptions pockets;    ///< how a site_pocket's pockets are detected
  /// The match; its mode is set to MatchMode::binding_sites when either side has a site.
  MatchOptions match;
  /// Default 0: all cores. The worker threads the caller lets TBB use while this runs (the CLI
  /// and the Python module limit TBB's pool to it).
  int threads = 0;
  /// Default none. Told, one line each, what each step did as it ends (a side read and
  /// surfaced, a side described, the match), for a verbose front end.
  std::function<void(const std::string&)> log;
};

/// The user's options of describing one input: the surface options
/// (molsurf::surface_input_option_table), the descriptor options
/// (harmonic::descriptor_option_table) and --threads.
const options::Table<MatchInputOptions>& describe_option_table();

/// The binding sites a pair match asks for, as a user gives them: a ligand residue and spheres
/// on both sides, or on one side only (default: none, whole surfaces).
struct PairSites {
  std::string ligand;                                  ///< both sides' site ligand
  std::string reference_ligand;                        ///< REF's, instead of `ligand`
  std::string probe_ligand;                            ///< PROBE's, instead of `ligand`
  std::vector<molsurf::SiteSphere> spheres;            ///< on both sides
  std::vector<molsurf::SiteSphere> reference_spheres;  ///< on REF only, after `spheres`
  std::vector<molsurf::SiteSphere> probe_spheres;      ///< on PROBE only, after `spheres`
  int pocket = 0;                                      ///< both sides' site pocket (0: none)
  int reference_pocket = 0;                            ///< REF's, instead of `pocket`
  int probe_pocket = 0;                                ///< PROBE's, instead of `pocket`
};

/// A pair match as a user asks for it: how the sides are read, described and matched, and
/// their sites.
struct PairMatchOptions {
  MatchInputOptions inputs;  ///< how both sides are read, described and matched
  PairSites sites;           ///< the sites asked for; none: whole surfaces
};

/// The user's options of a pair match, each defined once: the surface options, --patch-radius,
/// --max-image-bytes, --site-radius, --site-margin, the match's (match_option_table), the site
/// ligands and spheres, and --threads.
const options::Table<PairMatchOptions>& pair_match_option_table();

/// `input` with REF's (`reference`) or PROBE's site from `sites`: its ligand and its spheres.
MatchInput with_site(MatchInput input, const PairSites& sites, bool reference);

/// The option that names REF's (`reference`) or PROBE's site ligand as `sites` holds it:
/// ref_site_ligand or probe_site_ligand when that was given, else site_ligand (options::named).
std::string site_ligand_option(const PairSites& sites, bool reference);

/// A side ready to be matched.
struct PreparedInput {
  std::string name;                          ///< MatchInput::name, for messages
  harmonic::SurfaceDescriptors descriptors;  ///< its surface and description
  /// The molecule the surface was built from, or the mesh's --molecule; for a site with a
  /// ligand, the structure without water and without the ligand copy.
  std::optional<Molecule> molecule;
  std::vector<molsurf::SiteSphere> site;  ///< the site's spheres; empty for a whole surface
  std::vector<bool> site_points;          ///< critical_points_in_site; empty without a site
  /// The length unit it was described in; its descriptions are given back in its own
  /// coordinates, their parameters (DescriptorOptions) stay in units.
  mesh::LengthUnit unit;
  /// What a reader may want to know of reading it, one line each (molsurf::LoadedSurface::notes).
  std::vector<std::string> notes;
};

/// Checks from names and options alone, before any work, that `input` can be read as asked:
/// exactly one input; a site ligand only on a molecule (a file or in memory), never a water
/// (readers drop waters) and not with options.input.read.ligand; a file's extension and the
/// surface options that apply to it (molsurf::check_surface_input). `role` ("REF", "PROBE",
/// "QUERY") names the side and `site_option` the site ligand's option in messages (empty: the
/// site_ligand option, as options::named spells it). Throws OptionError or InputError.
void check_match_input(const MatchInput& input, const MatchInputOptions& options, const char* role,
                       const std::string& site_option = "");

/// One side read or built and described as match_inputs does it (a site side: its surface
/// built with site_surface_margin of options.descriptors' patch radius, described at its site's
/// critical points only, matching::describe_site); a general mesh is described in its own length
/// unit (mesh::general_mesh_unit of options.input's scale and unit; its curvature fitted as
/// molsurf::assign_general_mesh_curvature does) and given back in its coordinates, so that it gets
/// the critical points, patches and images that molsurf::load_surface's curvature and
/// describe_surface give in that unit. Throws as check_match_input,
/// the readers, the surface construction and the description; InputError when a site holds no
/// critical point.
PreparedInput prepare_input(const MatchInput& input, const MatchInputOptions& options);

/// The comparison of two inputs and what it took.
struct InputMatch {
  PreparedInput reference, probe;
  MatchResult result;
  /// What the match cut, one line each (the clique search ran out of --max-clique-work:
  /// alignments may be missing); empty when nothing was.
  std::vector<std::string> warnings;
  /// What a reader may want to know, one line each (a side carries no atoms, so poses are
  /// judged on the surfaces alone; the clique budget was reached).
  std::vector<std::string> notes;
  /// The length unit the match ran at (SurfaceInputOptions::unit): 1 for molecules. The
  /// alignments, descriptions and sites above are in the inputs' coordinates whatever it is.
  double unit = 1.0;
  /// How `unit` was chosen: "none" (1), "auto", "given" (the unit option) or "stored".
  std::string unit_from = "none";
  /// True when the match set ESP, LP and atoms aside (MatchOptions::shape_only), asked or
  /// because a side carries no ESP and LP.
  bool shape_only = false;
  /// Two sites on structures, matched with chemistry: the lining_similarity of their lining
  /// residues (site.hpp); none otherwise.
  std::optional<double> lining;
  /// With `lining` and an alignment: the sites' similarity, site_score of the top alignment's
  /// overlay score and `lining` (MatchOptions::site.lining_weight).
  std::optional<double> site_score;
  /// With `site_score`: its site_z_score over the sites' surface points (site.hpp), the number of
  /// spreads it lies above unrelated sites' of the same size; none when a site has no point or
  /// a site setting (MatchOptions::site) is not the default (the null was fitted for the default
  /// score).
  std::optional<double> site_z;
  /// With `lining`: the interaction_similarity of the sites' surface points' interaction
  /// compositions (site.hpp); none when a site has no surface point.
  std::optional<double> interactions;
  /// With `interactions` and an alignment: the sites' interaction points compared under the top
  /// alignment (aligned_interactions): `coverage` is the smaller site's agreement, 1 when it
  /// lies, class for class, inside the other (a ligand's site in a detected pocket).
  std::optional<AlignedInteractions> fields;
  double prepare_ms = 0.0;  ///< reading, surfaces and descriptions
  double match_ms = 0.0;    ///< match_surfaces
};

/// Aligns `probe` onto `reference` as `surfcomp match` does: both sides checked
/// (check_match_input), both read or built before either is described (a probe that cannot be
/// matched is refused before the reference's descriptors are computed; a stored description is
/// read first, as its parameters are the other side's), described with common parameters, a
/// site's surface built with site_surface_margin of their patch radius, their sites' critical
/// points flagged, then match_surfaces. A side without ESP and LP makes the match shape-only
/// (MatchOptions::shape_only), with a note; options.input.scale and options.input.unit set the
/// length unit (InputMatch::unit). Throws OptionError for options outside their domain (before any
/// work), InputError when two stored descriptions were built with different parameters, and what
/// prepare_input and match_surfaces throw.
InputMatch match_inputs(const MatchInput& reference, const MatchInput& probe,
                        const MatchInputOptions& options = {});

}  // namespace surfcomp::matching
