// The fine level and the answer (METHOD sections 5-7): two described surfaces in, their ranked
// rigid alignments out. Composes the association graph, maximal cliques, rigid fits with
// single-linkage merging, and the consensus ranking.
#pragma once

#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/association_graph.hpp"
#include "surfcomp/matching/clustering.hpp"
#include "surfcomp/matching/correspondences.hpp"
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/ranking.hpp"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace surfcomp::matching {

struct MatchOptions {
  GraphParameters graph;                  ///< filter thresholds F, R, t, d_min, j_tol
  int min_clique_size = 2;                ///< smaller cliques are not fitted
  CorrespondenceOptions correspondences;  ///< image grid subsampling, R_chem property (esp)
  ClusteringOptions clustering;           ///< RMSD cut 4 A, merge cut 4 A
  RankingOptions ranking;                 ///< rank-by-rank, weights 1
  /// Default 10. The alignments first in the consensus ranking that are refined on the whole
  /// surfaces (SurfaceOverlay::refine) and then ranked by their overlay score, ahead of the
  /// others; an alignment whose refined pose repeats a better one's (every sampled probe
  /// point within 0.5 A) goes after the distinct ones; the first of them may then be polished
  /// (polish_top). 0 ranks by the consensus alone (the seed). Must be >= 0.
  int refine_top = 10;
  /// Default 24. With refine_top > 0, this many principal-axes superpositions of the two
  /// samples (principal_axes_starts: 4 in the axes' variance order, or 24 in any order) are
  /// refined too and listed among the refined alignments, source principal_axes, unless they
  /// land on a pose already found: a route to the right pose independent of the cliques.
  /// Measured on ligands (bench/overlay_bench, seed 20261122), 0 / 4 / 24 starts: with the
  /// heteroatom term (refined candidates re-ranked offline) five ligands top-1 90 / 90 / 99 %,
  /// therm 61 / 66 / 76 % (in the match itself, 0 and 24 starts, with the polish: 90 / 100 % and
  /// 64 / 76 %); without it,
  /// five ligands 90 % each, therm 53 / 49 / 51 %. Must be 0, 4 or 24.
  int principal_axes_starts = 24;
  /// Default 5. Where the overlay uses atoms (OverlayOptions::atom_weight), the first
  /// polish_top alignments of the refined order are refined again on the whole score, each
  /// heteroatom pulled toward the reference's of its element too, and ordered again. Measured
  /// (bench/overlay_bench), 0 / 5: seed 20261122 five ligands top-1 99 / 100 %, top-5 99 / 100 %,
  /// median RMSD 0.80 / 0.53 A, therm top-1 74 / 76 %, top-5 85 / 88 %; seed 7 five ligands
  /// 100 / 100 %, therm top-1 76 / 72 %, top-5 86 / 88 % (median 0.78 / 0.65 A). Pulling the
  /// heteroatoms in every refinement instead (seed 20261122, pulls of 7, 2.1 and 0.7 times this
  /// one's strength) gave five ligands 94 / 92 / 90 % and therm 67 / 65 / 68 %. 0 leaves them as
  /// the surfaces' refinement left them. On by default for what it does to the crystal overlays
  /// (the five ligands: every top-5 within 2 A, median 0.80 -> 0.53 A) and to the pose
  /// precision on therm; its effect on the therm top-1 is mixed (+2 and -4 points on the two
  /// seeds). Must be >= 0.
  int polish_top = 5;
  OverlayOptions overlay;  ///< sigma 1 A, spacing 1.5 A, chemistry weight 6, atom weight 14
  /// What changes when the match is restricted to binding sites (allowed masks, or descriptions
  /// built only at a site's critical points, the others skipped).
  struct Site {
    /// Default 2 A. The overlay samples only the vertices within this distance of a critical
    /// point taking part: the pocket lining. Must be > 0.
    double overlay_radius = 2.0;
    /// Default 0: site poses are refined and ranked on the shape Tanimoto alone.
    double chem_weight = 0.0;
    /// Default 24 (principal_axes_starts for sites). Must be 0, 4 or 24.
    int principal_axes_starts = 24;
  };
  /// Measured on the Kahraman dev set (bench/site_bench, 36 sites, 630 pairs), ROC AUC of the
  /// top-1 shape Tanimoto for same against different ligand types, these defaults 0.802; without
  /// axes starts 0.502 (7 pairs get a clique); 4 starts 0.780; linings within 4 / 8 A 0.742 /
  /// 0.662; ranked on (shape + 6 chem) / 7 0.727. Chosen on that same set (no held-out check).
  Site site;
};

/// Where an alignment came from.
enum class AlignmentSource {
  cliques,         ///< a cluster of the merge tree (CP correspondences)
  principal_axes,  ///< a principal-axes superposition of the whole samples, refined
};

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
  bool refined = false;       ///< transform refined on the whole surfaces (refine_top)
  OverlayScore overlay;       ///< Tanimoto scores of the transform (whole surfaces, or
                              ///< the pocket linings of a site match), for the first
                              ///< refine_top of the consensus ranking and the axes
                              ///< starts; 0 for the others
};

struct MatchResult {
  std::vector<Alignment> alignments;  ///< every cluster of the tree and each distinct
                                      ///< principal-axes pose, best first
  std::vector<TraceStage> trace;      ///< nodes and edges after each graph stage
  std::size_t cliques = 0;            ///< maximal cliques of at least min_clique_size
  std::vector<std::pair<std::string, double>> timing_ms;  ///< per stage, in order
};

/// Aligns `probe` onto `reference`. `reference_allowed` / `probe_allowed` (one flag per
/// critical point, or null for all) restrict the graph to a binding site (METHOD section 7).
/// Throws InputError when the two descriptions were built with different image grids (their
/// images cannot be compared), a mask has the wrong size, or a site's overlay region holds no
/// vertex while cliques need scoring; OptionError for options outside their domain (start
/// counts other than 0, 4, 24; site.overlay_radius <= 0; site.chem_weight < 0).
MatchResult match_surfaces(const harmonic::SurfaceDescriptors& reference,
                           const harmonic::SurfaceDescriptors& probe,
                           const MatchOptions& options = {},
                           const std::vector<bool>* reference_allowed = nullptr,
                           const std::vector<bool>* probe_allowed = nullptr);

/// A sphere of a binding site, A.
struct SiteSphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// One flag per critical point of `descriptors`: inside at least one of `spheres`.
std::vector<bool> critical_points_in_site(const harmonic::SurfaceDescriptors& descriptors,
                                          const std::vector<SiteSphere>& spheres);

}  // namespace surfcomp::matching
