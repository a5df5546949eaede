// Binding sites (method §7): a site is a set of spheres on a structure, built around a
// ligand copy or given; its surface is the structure's without water and without that copy,
// described only at the critical points inside the spheres. match_surfaces compares two sites
// with MatchMode::binding_sites and the sites' critical-point masks.
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/site.hpp"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace surfcomp::matching {

/// One flag per critical point of `descriptors`, in order: its position lies in at least one
/// of `spheres` (distance to the centre <= radius).
std::vector<bool> critical_points_in_site(const harmonic::SurfaceDescriptors& descriptors,
                                          const std::vector<molsurf::SiteSphere>& spheres);

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
                                           const std::vector<molsurf::SiteSphere>& spheres,
                                           const harmonic::DescriptorOptions& options = {});

/// describe_site of a surface built from `molecule`, keeping its heavy atoms
/// (SurfaceDescriptors::atoms).
harmonic::SurfaceDescriptors describe_site(mesh::Surface surface, const Molecule& molecule,
                                           const std::vector<molsurf::SiteSphere>& spheres,
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
                                                    const std::vector<molsurf::SiteSphere>& spheres,
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
                                                 const std::vector<molsurf::SiteSphere>& spheres);

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
