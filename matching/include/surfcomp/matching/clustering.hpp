// From cliques of critical-point pairs to a tree of rigid alignments (method §6.3-6.4): each
// clique's correspondences are fitted, poor fits dropped, and the rest merged by single linkage
// into larger clusters while no critical point gets two partners.
#pragma once

#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/correspondences.hpp"
#include "surfcomp/matching/rigid_fit.hpp"

#include <functional>
#include <limits>
#include <vector>

namespace surfcomp::matching {

/// One node of the merge tree: a set of CP pairs and the rigid alignment they define.
struct Cluster {
  /// The CP pairs, sorted by (a, b), each once; a one-to-one map (no CP of A or of B appears
  /// twice).
  std::vector<MatchedPair> pairs;
  /// Least-squares fit of the union of the pairs' correspondences moving B onto A (from =
  /// b_points, to = a_points): the transform maps PROBE (B) coordinates into REF's (A) frame;
  /// rmsd is method §6.3, n_points the number of correspondences.
  RigidFit fit;
  /// Pearson correlation of the property at the corresponding points (property_correlation).
  double r_chem = 0.0;
  /// Index into the cliques given to cluster_alignments for a leaf; -1 for a merged cluster.
  int clique = -1;
  /// Index of the cluster this one was merged into; -1 for a root.
  int parent = -1;
  /// The two clusters merged into this one (lower index first); empty for a leaf.
  std::vector<int> children;
};

struct ClusteringOptions {
  /// Default 4.0 A (method §6.3). Primary cliques whose fit has a larger RMSD are dropped. Must be
  /// > 0 (infinity keeps every clique).
  double rmsd_cut = 4.0;
  /// Default 4.0 A [choice]. Two clusters merge only when their single-linkage distance is at
  /// most this. Because the union's least-squares fit is at least as good as either cluster's
  /// own transform on the union, merging two clusters of RMSD <= c at distance <= c gives a
  /// cluster of RMSD <= c: with merge_cut <= rmsd_cut every cluster of the tree fits within
  /// the RMSD cut. Infinity reproduces the seed, which merges until only CP conflicts stop it
  /// and then finds its top-level clusters "often poor alignments" (method §6.5). Must be > 0.
  double merge_cut = 4.0;
};

/// The correspondences of one CP pair (called once per distinct pair, in ascending (a, b)
/// order); e.g. pair_correspondences of two described surfaces, or synthetic ones in tests.
using CorrespondenceProvider = std::function<Correspondences(const MatchedPair&)>;

/// The merge tree of the cliques (method §6):
/// 1. Each clique (a list of MatchedPair; order irrelevant) becomes a leaf: its pairs'
/// correspondences
///    are concatenated and fitted (fit_rigid, B onto A); cliques with RMSD > rmsd_cut are dropped.
///    Leaves keep the order of the cliques they come from.
/// 2. Single linkage: distance(X, Y) = min(RMSD of X's correspondences under Y's transform,
///    RMSD of Y's under X's). Two clusters are compatible unless one CP of A is paired with
///    different CPs of B in them, or one CP of B with different CPs of A. The closest compatible
///    pair of active clusters with distance <= merge_cut (ties: lowest first index, then lowest
///    second) is merged into a new cluster (the union of their pairs, re-fitted) that replaces
///    both; repeat until no pair merges.
/// Returns every cluster ever formed: the leaves first, then the merged ones in merge order,
/// with parent and children indices into the result. The roots (parent -1) are the final
/// alignments; rank_alignments ranks them all, whatever their level (method §6.5).
/// Distances use the second moments of each cluster's points about their centroids, so each
/// costs O(1) after one pass over the points per cluster: O(L^2) for L leaves.
/// Throws InputError when a clique is empty, pairs one CP with two partners, or gives one CP
/// pair two different image shifts, when the provider's correspondences for a pair are fewer
/// than 3 in a clique's union or their arrays differ in length; OptionError for a cut <= 0 or
/// NaN; and what the provider throws.
std::vector<Cluster> cluster_alignments(const std::vector<std::vector<MatchedPair>>& cliques,
                                        const CorrespondenceProvider& correspondences,
                                        const ClusteringOptions& options = {});

/// cluster_alignments with pair_correspondences(reference, probe, pair, correspondence_options)
/// as the provider: reference is surface A (REF), probe surface B (PROBE).
std::vector<Cluster> cluster_alignments(const std::vector<std::vector<MatchedPair>>& cliques,
                                        const harmonic::SurfaceDescriptors& reference,
                                        const harmonic::SurfaceDescriptors& probe,
                                        const ClusteringOptions& options = {},
                                        const CorrespondenceOptions& correspondence_options = {});

/// True when the two sorted pair lists pair no CP of A, and no CP of B, with different partners.
bool compatible_pairs(const std::vector<MatchedPair>& x, const std::vector<MatchedPair>& y);

}  // namespace surfcomp::matching
