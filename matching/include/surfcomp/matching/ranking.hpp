// Consensus ranking of alignments (method §6.5; Wang &
// Wang's consensus schemes): three scores per cluster, RMSD (lower is better), number of
// corresponding points (higher is better) and R_chem (higher is better), combined into one.
#pragma once

#include "surfcomp/matching/clustering.hpp"

#include <array>
#include <vector>

namespace surfcomp::matching {

enum class ConsensusScheme {
  /// method §6.5, rank by rank: the weighted mean of the three ranks; rank 1 is the best score,
  /// clusters
  /// with equal scores share the mean of the ranks they span (fractional ranking). Lower
  /// consensus is better.
  rank_by_rank,
  /// method §6.5, rank by number: the weighted mean of the three scores normalised to [0, 1] over
  /// the clusters,
  /// 1 for the best and 0 for the worst value ((max - x) / (max - min) for RMSD, (x - min) /
  /// (max - min) for the others; 1 for all when max == min). Higher consensus is better.
  rank_by_number,
  /// method §6.5, rank by vote: the weighted count of scores in whose top fraction the cluster is:
  /// a cluster
  /// gets the vote of a score when its value is at least as good as the k-th best value, k =
  /// max(1, ceil(vote_top_fraction * #clusters)) (ties at the border all vote). Higher
  /// consensus is better.
  rank_by_vote,
};

/// The names of the schemes, indexed by ConsensusScheme (as --ranking spells them).
inline constexpr std::array<const char*, 3> consensus_scheme_names = {"rank", "number", "vote"};

struct RankingOptions {
  /// Default rank_by_rank (the seed's choice).
  ConsensusScheme scheme = ConsensusScheme::rank_by_rank;
  /// Default 1 each (method §6.5). Weights of RMSD, point count and R_chem; finite, >= 0, and
  /// not all 0.
  double weight_rmsd = 1.0;
  double weight_points = 1.0;
  double weight_chem = 1.0;
  /// Default 0.1 (the top 10 %). The fraction for rank_by_vote; in (0, 1].
  double vote_top_fraction = 0.1;
};

/// One entry of the ranking.
struct RankedAlignment {
  int cluster = -1;        ///< index into the clusters ranked
  double consensus = 0.0;  ///< the scheme's consensus value (see ConsensusScheme)
  int rank = 0;            ///< 1-based position in the ranking
};

/// Every cluster ranked best first by the consensus of options.scheme over fit.rmsd,
/// fit.n_points and r_chem; clusters with equal consensus keep index order (deterministic).
/// All clusters are ranked, whatever their level in the merge tree (method §6.5).
/// Throws InputError when a score is not finite; OptionError for weights or a fraction
/// outside their domain.
std::vector<RankedAlignment> rank_alignments(const std::vector<Cluster>& clusters,
                                             const RankingOptions& options = {});

}  // namespace surfcomp::matching
