// Consensus ranking (method §6.5) on synthetic scores whose consensus values are
// computed by hand in the comments.
#include "surfcomp/matching/ranking.hpp"
#include "surfcomp/core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace surfcomp::matching {
namespace {

Cluster scored(double rmsd, std::size_t n_points, double r_chem) {
  Cluster c;
  c.fit.rmsd = rmsd;
  c.fit.n_points = n_points;
  c.r_chem = r_chem;
  return c;
}

// RMSD ascending: c2 1, c0 2, c1 = c3 share 3.5. Points descending: c1 1, c3 2, c0 = c2 3.5.
// R_chem descending: c1 = c3 share 1.5, c0 3, c2 4.
const std::vector<Cluster> kClusters = {scored(1.0, 100, 0.5), scored(2.0, 300, 0.9),
                                        scored(0.5, 100, 0.1), scored(2.0, 200, 0.9)};

std::vector<int> order(const std::vector<RankedAlignment>& ranking) {
  std::vector<int> out;
  for (const auto& r : ranking) out.push_back(r.cluster);
  return out;
}

TEST(Ranking, RankByRankAveragesFractionalRanks) {
  const auto ranking = rank_alignments(kClusters);
  // c0 (2 + 3.5 + 3) / 3, c1 (3.5 + 1 + 1.5) / 3, c2 (1 + 3.5 + 4) / 3, c3 (3.5 + 2 + 1.5) / 3;
  // c0 and c2 tie at 8.5 / 3 and keep index order.
  ASSERT_EQ(ranking.size(), 4u);
  EXPECT_EQ(order(ranking), (std::vector<int>{1, 3, 0, 2}));
  EXPECT_DOUBLE_EQ(ranking[0].consensus, 2.0);
  EXPECT_DOUBLE_EQ(ranking[1].consensus, 7.0 / 3.0);
  EXPECT_DOUBLE_EQ(ranking[2].consensus, 8.5 / 3.0);
  EXPECT_DOUBLE_EQ(ranking[3].consensus, 8.5 / 3.0);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(ranking[static_cast<std::size_t>(k)].rank, k + 1);
}

TEST(Ranking, RankByRankHonoursWeights) {
  RankingOptions options;
  options.weight_rmsd = 2.0;
  // Sum of weights 4: c0 (4 + 3.5 + 3) / 4 = 2.625, c1 (7 + 1 + 1.5) / 4 = 2.375,
  // c2 (2 + 3.5 + 4) / 4 = 2.375, c3 (7 + 2 + 1.5) / 4 = 2.625.
  const auto ranking = rank_alignments(kClusters, options);
  EXPECT_EQ(order(ranking), (std::vector<int>{1, 2, 0, 3}));
  EXPECT_DOUBLE_EQ(ranking[0].consensus, 2.375);
  EXPECT_DOUBLE_EQ(ranking[2].consensus, 2.625);
  // Only the RMSD counts: c2, c0, then c1 and c3 tied.
  options.weight_points = options.weight_chem = 0.0;
  EXPECT_EQ(order(rank_alignments(kClusters, options)), (std::vector<int>{2, 0, 1, 3}));
}

TEST(Ranking, RankByNumberAveragesNormalisedScores) {
  RankingOptions options;
  options.scheme = ConsensusScheme::rank_by_number;
  // RMSD (2 - x) / 1.5: 2/3, 0, 1, 0. Points (x - 100) / 200: 0, 1, 0, 0.5.
  // R_chem (x - 0.1) / 0.8: 0.5, 1, 0, 1. Means: 7/18, 2/3, 1/3, 1/2.
  const auto ranking = rank_alignments(kClusters, options);
  EXPECT_EQ(order(ranking), (std::vector<int>{1, 3, 0, 2}));
  EXPECT_NEAR(ranking[0].consensus, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(ranking[1].consensus, 0.5, 1e-12);
  EXPECT_NEAR(ranking[2].consensus, 7.0 / 18.0, 1e-12);
  EXPECT_NEAR(ranking[3].consensus, 1.0 / 3.0, 1e-12);
  // Equal scores everywhere normalise to 1: all tie at 1, index order.
  const auto flat = rank_alignments({scored(1, 5, 0.2), scored(1, 5, 0.2)}, options);
  EXPECT_EQ(order(flat), (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(flat[1].consensus, 1.0);
}

TEST(Ranking, RankByVoteCountsTopFractions) {
  RankingOptions options;
  options.scheme = ConsensusScheme::rank_by_vote;
  options.vote_top_fraction =
      0.25;  // k = 1: best RMSD c2, most points c1, best R_chem c1 and c3 (tie)
  auto ranking = rank_alignments(kClusters, options);
  EXPECT_EQ(order(ranking), (std::vector<int>{1, 2, 3, 0}));
  EXPECT_EQ(ranking[0].consensus, 2.0);
  EXPECT_EQ(ranking[1].consensus, 1.0);
  EXPECT_EQ(ranking[2].consensus, 1.0);
  EXPECT_EQ(ranking[3].consensus, 0.0);
  options.vote_top_fraction = 0.5;  // k = 2: RMSD c2, c0; points c1, c3; R_chem c1, c3
  ranking = rank_alignments(kClusters, options);
  EXPECT_EQ(order(ranking), (std::vector<int>{1, 3, 0, 2}));
  EXPECT_EQ(ranking[1].consensus, 2.0);
  EXPECT_EQ(ranking[2].consensus, 1.0);
  options.vote_top_fraction = 0.25;
  options.weight_chem = 3.0;  // c1 1 + 3, c3 3, c2 1, c0 0
  ranking = rank_alignments(kClusters, options);
  EXPECT_EQ(order(ranking), (std::vector<int>{1, 3, 2, 0}));
  EXPECT_EQ(ranking[0].consensus, 4.0);
  EXPECT_EQ(ranking[1].consensus, 3.0);
  options.vote_top_fraction = 0.01;  // ceil(0.04) = 1, same as 0.25
  EXPECT_EQ(order(rank_alignments(kClusters, options)), (std::vector<int>{1, 3, 2, 0}));
}

TEST(Ranking, EmptyInputAndBadOptions) {
  EXPECT_TRUE(rank_alignments({}).empty());
  RankingOptions options;
  options.weight_points = -1.0;
  EXPECT_THROW(rank_alignments(kClusters, options), OptionError);
  options = {};
  options.weight_rmsd = options.weight_points = options.weight_chem = 0.0;
  EXPECT_THROW(rank_alignments(kClusters, options), OptionError);
  options = {};
  options.vote_top_fraction = 0.0;
  EXPECT_THROW(rank_alignments(kClusters, options), OptionError);
  options.vote_top_fraction = 1.5;
  EXPECT_THROW(rank_alignments(kClusters, options), OptionError);
  EXPECT_THROW(rank_alignments({scored(std::nan(""), 3, 0.0)}), InputError);
}

}  // namespace
}  // namespace surfcomp::matching
