// Binding sites (METHOD section 7): a site is a set of spheres on a structure, built around a
// ligand copy or given; its surface is the structure's without water and without that copy,
// described only at the critical points inside the spheres. match_surfaces compares two sites
// with MatchMode::binding_sites and the sites' critical-point masks.
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/mesh/molecular_surface.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace surfcomp::matching {

/// A sphere of a binding site, A.
struct SiteSphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// The sphere written "x,y,z,r" (A; what `--site-sphere` and a site list take), or none when
/// `text` is not four comma-separated numbers with a finite centre and a finite radius > 0.
std::optional<SiteSphere> parse_site_sphere(const std::string& text);

/// Site spheres as an option's value, and back.
std::vector<options::Sphere> sphere_values(const std::vector<SiteSphere>& spheres);
std::vector<SiteSphere> site_spheres(const std::vector<options::Sphere>& values);

/// What the user sees of --site-ligand and --site-sphere, wherever a site is asked for.
options::Spec site_ligand_spec();
options::Spec site_sphere_spec();

/// The repeatable option of a list of site spheres at `access(settings)` (a generic lambda as
/// for options::field).
template <class Settings, class Access>
options::Option<Settings> sphere_option(options::Spec spec, Access access) {
  spec.kind = options::Kind::spheres;
  spec.optional = true;
  return {std::move(spec),
          [access](const Settings& s) { return options::Value(sphere_values(access(s))); },
          [access](Settings& s, const options::Value& v) {
            access(s) = site_spheres(std::get<std::vector<options::Sphere>>(v));
          }};
}

/// A site's surface (build_site_surface) is the whole structure's wherever the site's patches
/// reach, up to the remeshing's small non-locality, when its margin is at least the patch
/// radius plus this, A: the SES of a point depends on atoms up to a probe diameter and an atom
/// radius away, its curvature on 2 A around it (docs/decisions.md#site-surfaces).
inline constexpr double surface_margin_beyond_patch = 8.0;

/// The surface margin a site described with patches of `patch_radius` (A) is built with:
/// `margin` raised to at least patch_radius + surface_margin_beyond_patch, or 0 (every atom)
/// when `margin` is 0.
double site_surface_margin(double margin, double patch_radius);

struct BindingSiteOptions {
  /// Default 4 A. Radius of the sphere around each atom of the ligand copy. Finite, > 0.
  double sphere_radius = 4.0;
  /// Default 0 A: the site's structure keeps every chain. When > 0, it keeps only the chains
  /// with an atom within this distance of a sphere's centre (for a ligand, the ligand's own
  /// chain among them), so that the surface, whose ESP and LP cost #vertices x #atoms, leaves
  /// out chains far from the site. Finite, >= 0.
  double chain_contact_radius = 0.0;
  /// Default 16 A (patches of up to 8 A; see surface_margin_beyond_patch). build_site_surface
  /// builds the SES of the structure's atoms within a sphere's radius plus this margin of its
  /// centre, not of the whole structure. 0: every atom. Finite, >= 0. Where a site is
  /// described (match_inputs, prepare_input, a pocket screen), it is raised to
  /// site_surface_margin of the patch radius.
  double surface_margin = 16.0;
};

/// The user's options of BindingSiteOptions: --site-radius and --site-margin.
const options::Table<BindingSiteOptions>& binding_site_option_table();

/// A binding site and the structure whose surface it lies on.
struct BindingSite {
  std::vector<SiteSphere> spheres;  ///< the site, A
  /// The atoms of the ligand copy the site was built around, in the structure's order (source
  /// and title the structure's); no atoms when the site was built from spheres.
  Molecule ligand;
  /// The structure without water, without the ligand copy (only that copy: other copies of the
  /// ligand, ions and cofactors stay) and, with chain_contact_radius > 0, without the chains
  /// out of contact; the atoms keep their order and properties.
  Molecule structure;
  double surface_margin = 0.0;  ///< BindingSiteOptions::surface_margin, A
};

/// The site of the ligand copy select_ligand(structure, ligand) takes: a sphere of
/// options.sphere_radius around each of its atoms. Throws InputError when that copy is absent
/// (select_ligand's message: the file and the residues present) or when no atom is left in the
/// site's structure; OptionError for options outside their domain.
BindingSite binding_site(const Molecule& structure, const LigandSelector& ligand,
                         const BindingSiteOptions& options = {});

/// The site made of `spheres` on `structure` (options.sphere_radius is not used). Throws
/// InputError when there is no sphere, a sphere has a non-finite centre or a radius that is not
/// a finite number > 0, or no atom is left in the site's structure; OptionError for options
/// outside their domain.
BindingSite binding_site(const Molecule& structure, std::vector<SiteSphere> spheres,
                         const BindingSiteOptions& options = {});

/// The site's surface: the SES (options.ses) of the structure's atoms within a sphere's radius
/// plus site.surface_margin of its centre (every atom when the margin is 0), sampled on the grid
/// of the whole structure (mesh::ses_voxel_size), with ESP and LP from every atom of the
/// structure and curvature (options.esp, lp, curvature); its source is the structure's. Throws
/// InputError when no atom lies within the margin, and as build_molecular_surface.
mesh::Surface build_site_surface(const BindingSite& site,
                                 const mesh::MolecularSurfaceOptions& options = {});

/// Default 4 A beyond the surface margin: the reach of the atoms a site keeps
/// (site_neighbourhood). LP sums the atoms within mesh::default_fauchere_cutoff (12 A) of a
/// vertex, so it is the whole structure's at every vertex within the margin - 8 A of a sphere:
/// at least the patch radius (site_surface_margin).
inline constexpr double neighbourhood_beyond_margin = 4.0;

/// What a site's surface and scores need of `structure`, in its order: every atom within a
/// sphere's radius + `reach` (A) of its centre, every charged atom (the ESP sums them all), each
/// chain's first standard residue (whose N terminus a reader charges) and the smallest atom
/// (which sets the SES grid); ionisable_atoms follow their atoms. A pocket library stores this
/// rather than the structure. Throws InputError when `reach` is not finite and >= 0.
Molecule site_neighbourhood(const Molecule& structure, const std::vector<SiteSphere>& spheres,
                            double reach);

/// One flag per critical point of `descriptors`, in order: its position lies in at least one
/// of `spheres` (distance to the centre <= radius).
std::vector<bool> critical_points_in_site(const harmonic::SurfaceDescriptors& descriptors,
                                          const std::vector<SiteSphere>& spheres);

/// A site's pocket lining: one flag per vertex of descriptors.surface, set when the vertex lies
/// within `radius` (A) of a critical point that takes part: allowed by `allowed` (one flag per
/// critical point; all when null) and described (not PatchStatus::skipped). The binding-site
/// overlay (MatchMode::binding_sites) compares these vertices.
std::vector<bool> pocket_lining(const harmonic::SurfaceDescriptors& descriptors,
                                const std::vector<bool>* allowed, double radius);

/// harmonic::describe_surface with patches, maps and images only at the critical points inside
/// `spheres` (as critical_points_in_site flags them); the others keep PatchStatus::skipped, so
/// that their indices stay those of detect_critical_points. Errors as describe_surface's.
harmonic::SurfaceDescriptors describe_site(mesh::Surface surface,
                                           const std::vector<SiteSphere>& spheres,
                                           const harmonic::DescriptorOptions& options = {});

/// describe_site of a surface built from `molecule`, keeping its heavy atoms
/// (SurfaceDescriptors::atoms).
harmonic::SurfaceDescriptors describe_site(mesh::Surface surface, const Molecule& molecule,
                                           const std::vector<SiteSphere>& spheres,
                                           const harmonic::DescriptorOptions& options = {});

/// The residue classes of a pocket lining's composition: aliphatic (ALA VAL LEU ILE MET),
/// aromatic (PHE TRP TYR), HIS, basic (LYS ARG), acidic (ASP GLU), polar (SER THR ASN GLN), GLY,
/// PRO and CYS.
inline constexpr std::size_t lining_classes = 9;
using LiningComposition = std::array<double, lining_classes>;

/// Default 1 A: a residue lines a site when one of its heavy atoms lies within a sphere's radius
/// plus this of its centre (within 5 A of a ligand atom for spheres of 4 A around it).
inline constexpr double lining_reach = 1.0;

/// The fraction of the site's lining residues (the 20 standard amino acids of `structure`, by
/// chain, number and name, with a heavy atom within a sphere's radius + `reach` of its centre)
/// in each class; none when no residue lines the site (a nucleic-acid site, or spheres away
/// from the protein), which then has no composition to compare.
std::optional<LiningComposition> lining_composition(const Molecule& structure,
                                                    const std::vector<SiteSphere>& spheres,
                                                    double reach = lining_reach);

/// How alike two linings' compositions are: the histogram intersection, the sum over the
/// classes of the smaller fraction, in [0, 1] (1 for equal compositions); 0 when either lining
/// is empty. Independent of the sites' sizes.
double lining_similarity(const LiningComposition& a, const LiningComposition& b);

/// The interaction classes of a site's surface points, in the spirit of IsoMIF's probes: a
/// ligand atom touching the point would meet a hydrogen-bond donor, an acceptor, an aromatic
/// ring, a positive or a negative charge, or a hydrophobic group.
inline constexpr std::size_t interaction_classes = 6;
enum class Interaction : std::size_t { donor, acceptor, aromatic, positive, negative, hydrophobic };
using InteractionComposition = std::array<double, interaction_classes>;

/// The interaction a contact with `atom` offers, as weights over the classes (summing to 1, or
/// all 0 for hydrogens): protein atoms by residue and atom name (backbone N a donor, O an
/// acceptor; Lys NZ, Arg NE/NH1/NH2 and metal ions positive; Asp OD1/OD2, Glu OE1/OE2 and OXT
/// negative; hydroxyl O, His ring N and water half donor, half acceptor; Phe/Tyr/Trp/His ring
/// carbons aromatic; other carbons and S hydrophobic); any other atom by its element (N half
/// donor, half acceptor; O an acceptor; C, S and halogens hydrophobic; P negative).
InteractionComposition interaction_of(const Atom& atom);

/// A site's surface point and the interaction a ligand atom touching it would meet.
struct InteractionPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< A
  InteractionComposition weights{};                    ///< interaction_of its nearest heavy atom
};

/// The site's surface points: each vertex of `surface` inside `spheres`, with the interaction_of
/// its nearest heavy atom of `structure`, in vertex order.
std::vector<InteractionPoint> interaction_points(const mesh::Surface& surface,
                                                 const Molecule& structure,
                                                 const std::vector<SiteSphere>& spheres);

/// The fraction of a site's interaction points in each class: independent of the site's size.
/// None when there is no point.
std::optional<InteractionComposition> interaction_composition(
    const std::vector<InteractionPoint>& points);

/// Default 1 A: two interaction points are in contact when this close.
inline constexpr double interaction_contact = 1.0;

/// How two sites' interaction points agree under an alignment.
struct AlignedInteractions {
  /// (agreement of a's points + agreement of b's points) / (|a| + |b|), in [0, 1]: a point's
  /// agreement is sum_k min(w_k, w'_k) with its nearest point of the other site within the
  /// contact distance (0 without one). 1 for a site against itself.
  double similarity = 0.0;
  /// The smaller site's agreement over its points, in [0, 1]: 1 when a site lies, class for
  /// class, inside a larger one (a ligand's site inside a detected pocket).
  double coverage = 0.0;
};

/// How the interaction points of `a` and of `b` agree when `b_to_a` (4 x 4, rigid) moves b's
/// points into a's frame, with contacts within `contact` A. All 0 when a side has no point.
AlignedInteractions aligned_interactions(const std::vector<InteractionPoint>& a,
                                         const std::vector<InteractionPoint>& b,
                                         const Eigen::Matrix4d& b_to_a,
                                         double contact = interaction_contact);

/// How alike two sites' interaction compositions are: the histogram intersection, in [0, 1].
double interaction_similarity(const InteractionComposition& a, const InteractionComposition& b);

/// The similarity of two sites: (overlay_score + weight lining) / (1 + weight), the top
/// alignment's overlay score of the pocket linings with their lining_similarity.
double site_score(double overlay_score, double lining, double weight);

/// The site score of unrelated sites (ligands of different types): its mean and spread, each
/// linear in log10 n, n the smaller site's surface points (interaction_points), over the range
/// of n it was fitted on.
struct SiteScoreNull {
  double mean_intercept = 0.0;
  double mean_slope = 0.0;
  double spread_intercept = 1.0;
  double spread_slope = 0.0;
  double min_points = 1.0;  ///< n below this is taken as this
  double max_points = 1.0;  ///< and above this as this
};

/// The default null: fitted by bench/site_null.py on the 4,904 unrelated pairs of both labelled
/// site sets (kahraman-dev and homogeneous, site_bench's default run). Fitted on one set alone,
/// it is off on the other by up to one spread (docs/benchmarks.md, "Site z-score").
inline constexpr SiteScoreNull site_score_null{0.1725, 0.0382, 0.0799, -0.0140, 556.0, 1795.0};

/// How far a site score lies above those of unrelated sites of the same size, in their spreads:
/// (score - mean(n)) / spread(n), n = min(points_a, points_b) clamped to the null's range. About
/// 0 for an unrelated pair, whatever the sizes; 3 or more is rare without a relation (see
/// docs/benchmarks.md for the measured tail). Throws InputError when a site has no point, or
/// for a null whose range is empty or whose spread is not positive over it.
double site_z_score(double score, std::size_t points_a, std::size_t points_b,
                    const SiteScoreNull& null = site_score_null);

}  // namespace surfcomp::matching
