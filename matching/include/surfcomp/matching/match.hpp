// The fine level and the answer (method §5-7): two described surfaces in, their ranked
// rigid alignments out. Composes the association graph, maximal cliques, rigid fits with
// single-linkage merging, the consensus ranking and the overlay refinement of the first poses.
#pragma once

#include "surfcomp/core/option_table.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/association_graph.hpp"
#include "surfcomp/matching/atom_polish.hpp"
#include "surfcomp/matching/cliques.hpp"
#include "surfcomp/matching/clustering.hpp"
#include "surfcomp/matching/correspondences.hpp"
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/ranking.hpp"
#include "surfcomp/matching/surface_fit.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::matching {

/// What match_surfaces compares.
enum class MatchMode {
  /// Whole surfaces: the overlay scores and refines poses on every vertex of both surfaces
  /// with MatchOptions::overlay and principal_axes_starts; the critical-point masks, if any,
  /// restrict only the association graph.
  whole_surfaces,
  /// Binding sites (method §7): the overlay compares the pocket linings, the vertices
  /// within SiteMatchOptions::overlay_radius of the critical points that take part (allowed by
  /// the side's mask and not PatchStatus::skipped), with MatchOptions::site's settings.
  binding_sites,
};

/// The settings of a binding-site match (MatchMode::binding_sites).
struct SiteMatchOptions {
  /// Default 2 A. The pocket lining is the vertices within this distance of a critical point
  /// that takes part. Finite, > 0.
  double overlay_radius = 2.0;
  /// Default 0.25: poses are refined and ranked on (shape + 0.25 chem) / 1.25 of the linings,
  /// mostly shape, with the ESP/LP colour telling pockets of like size apart
  /// (docs/decisions.md#site-matches). The overlay's chem_weight for sites (the atom term takes
  /// no part). Finite, >= 0.
  double chem_weight = 0.25;
  /// Default 0.3. The site score of two sites is (overlay + w lining) / (1 + w) with the
  /// lining_similarity of their lining residues' compositions (site.hpp): a chemistry term
  /// independent of the sites' sizes (docs/decisions.md#site-score). Finite, >= 0.
  double lining_weight = 0.3;
  /// Default 24. principal_axes_starts for sites: 0, 4 or 24.
  int principal_axes_starts = 24;
};

struct MatchOptions {
  MatchMode mode = MatchMode::whole_surfaces;  ///< whole surfaces or binding sites
  /// Default false. Match by shape alone: no fuzzy ESP/LP filter, no R_chem in the ranking
  /// (CorrespondenceOptions::property empty, RankingOptions::weight_chem 0), no ESP/LP or atom
  /// term in the overlay; the surfaces need no "esp" or "lp". match_inputs sets it when a side
  /// carries no ESP and LP (a general mesh). shape_only_options gives the options it stands for.
  bool shape_only = false;
  GraphOptions graph;       ///< filter thresholds F, R, t, d_min, j_tol
  int min_clique_size = 2;  ///< smaller cliques are not fitted; >= 1
  /// Default CliqueOptions::max_work. The clique search stops after this much work
  /// (CliqueOptions, cliques.hpp), and the match goes on with the cliques found. > 0.
  std::int64_t max_clique_work = CliqueOptions{}.max_work;
  /// Default 1000 (docs/decisions.md#clique-budget). The clique search stops rather than
  /// report more cliques than this: each clique is fitted, and the merging takes time
  /// quadratic in their number. > 0.
  std::size_t max_cliques = 1000;
  CorrespondenceOptions correspondences;  ///< image grid subsampling, R_chem property (esp)
  ClusteringOptions clustering;           ///< RMSD cut 4 A, merge cut 4 A
  RankingOptions ranking;                 ///< rank-by-rank, weights 1
  /// Default 10. The first refine_top alignments of the consensus ranking are refined on the
  /// overlay (SurfaceOverlay::refine) and ranked by their overlay score (between molecules, +
  /// atom_polish.weight atom fit: atom_polish) ahead of the others,
  /// a pose that repeats a better one's (every sampled probe point within 0.5 A) after the
  /// distinct ones. 0 ranks by the consensus alone (the seed). >= 0.
  int refine_top = 10;
  /// Default 24. With refine_top > 0, this many principal-axes superpositions of the two
  /// samples (principal_axes_starts() of overlay.hpp: 4 in the axes' variance order, or 24 in
  /// any order) are refined too and listed among the refined alignments (source
  /// principal_axes) unless they reach a pose already found. 0, 4 or 24.
  int principal_axes_starts = 24;
  /// Default 2 (docs/decisions.md, "Coarse to fine in a match"). With refine_top > 0, every
  /// start (the refine_top alignments and the principal-axes superpositions) is refined first in
  /// single precision on the packed samples (PackedQuery::refine, packed_overlay.hpp), and only
  /// the fine_top best of those distinct poses again in double precision (SurfaceOverlay::refine);
  /// the others keep their single-precision pose, scored in double. 0: every start refined in
  /// double precision alone. >= 0.
  int fine_top = 2;
  /// Default 5. Where the overlay uses atoms (OverlayOptions::atom_weight), the first
  /// polish_top distinct refined alignments are refined again on the whole score, heteroatoms
  /// pulled too, and ordered again. 0 leaves them as refined. >= 0.
  int polish_top = 5;
  /// Where both sides are molecules (SurfaceDescriptors::atoms) and the mode is whole surfaces,
  /// the first polish_top distinct scored alignments are polished last on their heavy atoms
  /// (AtomOverlap::polish, atom_polish.hpp) and scored again, and the scored alignments are
  /// ordered by overlay score + weight atom fit. sigma 0 turns it off (as shape_only does).
  AtomPolishOptions atom_polish;
  OverlayOptions overlay;  ///< sigma 1 A, spacing 1.5 A, chemistry weight 6, atom weight 14
  SiteMatchOptions site;   ///< used with MatchMode::binding_sites
  /// Default 1 A (a general mesh: 1 unit). The first refine_top distinct alignments get their
  /// coverage (CoverageScore, surface_fit.hpp): the fraction of each surface within this
  /// distance of the other (of the pocket linings in a site match). 0: no coverage. Finite,
  /// >= 0.
  double coverage_distance = 1.0;
  /// Default 0: none. The first icp_top distinct scored alignments are polished last by
  /// point-to-plane ICP on the whole surfaces (SurfaceFit::icp, with `icp`), then scored again;
  /// the order stays. >= 0.
  int icp_top = 0;
  IcpOptions icp;  ///< how the ICP polish pairs points and when it stops
};

/// Throws OptionError, naming the option, its value and its domain, for the first option of
/// `options` outside its domain: a user's option as the command line spells it
/// ("--fuzzy-threshold", match_option_table), one no option sets by its field; match_surfaces calls
/// it before any work, and a caller may call it before building the surfaces.
void validate(const MatchOptions& options);

/// The user's options of MatchOptions, with their ranges: the association graph's filters and
/// size limit, the clique budget, --rmsd-cut, --ranking, the overlay refinement and the site
/// overlay. validate() checks these first, naming each option as the command line spells it.
const options::Table<MatchOptions>& match_option_table();

/// Where an alignment came from.
enum class AlignmentSource {
  cliques,         ///< a cluster of the merge tree (CP correspondences)
  principal_axes,  ///< a principal-axes superposition of the whole samples, refined
};

/// The names of the sources, indexed by AlignmentSource (as the result file and Python give
/// them).
inline constexpr std::array<const char*, 2> alignment_source_names = {"cliques", "principal_axes"};

/// One alignment of PROBE onto REF. From the cliques it is a cluster of the merge tree: rmsd,
/// n_points and r_chem describe the fit of the cluster's CP correspondences, and transform is
/// that fit, refined when `refined`. From the principal axes it has no CP correspondences:
/// rmsd, n_points, r_chem and consensus are 0, cp_pairs, parent and children empty.
struct Alignment {
  AlignmentSource source = AlignmentSource::cliques;
  int rank = 0;  ///< 1-based, best first
  Eigen::Matrix4d transform =
      Eigen::Matrix4d::Identity();  ///< moves PROBE coordinates into REF's frame
  double rmsd = 0.0;                ///< A, over the corresponding surface points
  std::size_t n_points = 0;         ///< corresponding surface points
  double r_chem = 0.0;              ///< Pearson correlation of the property at those points
  double consensus = 0.0;           ///< the ranking scheme's value
  std::vector<std::pair<int, int>> cp_pairs;  ///< (REF critical point, PROBE critical point)
  int parent = 0;             ///< rank of the cluster this one merged into; 0 for a root
  std::vector<int> children;  ///< ranks of the two clusters merged into this one
  /// Transform refined on the whole surfaces (refine_top); with fine_top, the best refined in
  /// double precision, the others in single precision only.
  bool refined = false;
  OverlayScore overlay;  ///< Tanimoto scores of the transform (whole surfaces, or
                         ///< the pocket linings of a site match), for the first
                         ///< refine_top of the consensus ranking and the axes
                         ///< starts; 0 for the others
  /// The heavy-atom fit of the transform (AtomOverlap::fit, width MatchOptions::atom_polish
  /// sigma), [0, 1], where the atom polish took part (two molecules, whole surfaces): the
  /// scored alignments are ordered by overlay.score + atom_polish.weight atom_fit. 0 otherwise.
  double atom_fit = 0.0;
  /// How much of each surface lies on the other under the transform (MatchOptions::
  /// coverage_distance), for the first refine_top distinct alignments; 0 for the others.
  CoverageScore coverage;
  /// 0 for a distinct pose; else the rank of a better alignment whose pose this one repeats
  /// (no sampled probe point moves more than 0.5 A between the two; 0.5 units for a general
  /// mesh). The merge tree keeps every cluster; a reader that wants distinct poses skips these.
  int repeat_of = 0;
  /// Whether the ICP polish moved it (MatchOptions::icp_top).
  bool icp = false;
};

struct MatchResult {
  std::vector<Alignment> alignments;  ///< every cluster of the tree and each distinct
                                      ///< principal-axes pose, best first; repeats marked
                                      ///< (Alignment::repeat_of)
  std::vector<TraceStage> trace;      ///< nodes and edges after each graph stage
  std::size_t cliques = 0;            ///< maximal cliques of at least min_clique_size
  /// False when the clique search stopped at max_clique_work or max_cliques: the alignments
  /// come from the cliques found before it stopped, and some may be missing.
  bool cliques_complete = true;
  std::int64_t clique_work = 0;  ///< work the clique search spent (CliqueResult::work)
  std::vector<std::pair<std::string, double>> timing_ms;  ///< per stage, in order
};

/// `options` as match_surfaces applies them: with shape_only, the chemistry steps aside (the
/// fuzzy filter off, R_chem's property none and its ranking weight 0, the overlay's and the
/// site overlay's chem and atom weights 0); otherwise `options` as they are.
MatchOptions shape_only_options(MatchOptions options);

/// The overlay options a match in options.mode scores and refines with: options.overlay, or for
/// binding sites the same with options.site.chem_weight and no atom term; without the chem and
/// atom terms for a shape-only match.
OverlayOptions mode_overlay_options(const MatchOptions& options);

/// Throws InputError naming the surface's source when it lacks a vertex property the match
/// needs: "esp" and "lp" (the fuzzy filter and the chemical correlation R_chem compare them).
/// A surface built from a molecule has both; a mesh gets them from its file or from the
/// molecule it is mapped from. A shape-only match (MatchOptions::shape_only) needs neither.
void require_match_properties(const mesh::Surface& surface);

/// Aligns `probe` onto `reference`. `reference_allowed` / `probe_allowed` (one flag per
/// critical point, or null for all) restrict the association graph to the flagged critical
/// points, a binding site's say (critical_points_in_site, site.hpp); options.mode says whether
/// the overlay then compares the whole surfaces or the sites' pocket linings (MatchMode).
/// Throws OptionError for options outside their domain (validate, before any work);
/// InputError when a surface lacks "esp" or "lp" (require_match_properties; not for a
/// shape-only match), the two
/// descriptions were built with different image grids (their images cannot be compared), a mask has
/// the wrong size, or a site's pocket lining holds no vertex while alignments need scoring.
MatchResult match_surfaces(const harmonic::SurfaceDescriptors& reference,
                           const harmonic::SurfaceDescriptors& probe,
                           const MatchOptions& options = {},
                           const std::vector<bool>* reference_allowed = nullptr,
                           const std::vector<bool>* probe_allowed = nullptr);

}  // namespace surfcomp::matching
