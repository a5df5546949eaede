// Single-linkage merging of clique alignments (method §6) on synthetic correspondences: each CP
// pair (a, b) gets 30 points p around a place that depends on a and their images q under the
// inverse of a chosen motion (plus noise), so that fitting B onto A recovers that motion.
#include "surfcomp/matching/clustering.hpp"
#include "surfcomp/core/error.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>

namespace surfcomp::matching {
namespace {

struct PairSpec {
  RigidTransform motion;  ///< maps the pair's B points onto its A points
  double noise = 0.0;     ///< A, Gaussian per coordinate on the B points
};

RigidTransform motion(double degrees, const Eigen::Vector3d& axis, const Eigen::Vector3d& shift) {
  RigidTransform t;
  t.rotation = Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  t.translation = shift;
  return t;
}

const RigidTransform kMotion = motion(40.0, {1, 1, 0}, {3, -2, 5});
const RigidTransform kOther = motion(120.0, {0, 0, 1}, {20, 0, 0});

class Synthetic {
 public:
  void add(int a, int b, const RigidTransform& m, double noise = 0.05) {
    specs_[{a, b}] = {m, noise};
  }

  Correspondences operator()(const MatchedPair& pair) const {
    const PairSpec& spec = specs_.at({pair.a, pair.b});
    std::mt19937 rng(static_cast<unsigned>(1000 * pair.a + pair.b + 17));
    std::uniform_real_distribution<double> box(-2.0, 2.0);
    std::normal_distribution<double> gauss;
    const Eigen::Vector3d centre(4.0 * pair.a, 6.0 * std::sin(pair.a),
                                 5.0 * std::cos(1.3 * pair.a));
    Correspondences c;
    const int n = 30;
    c.a_points.resize(3, n);
    c.b_points.resize(3, n);
    c.a_property.resize(n);
    c.b_property.resize(n);
    for (int i = 0; i < n; ++i) {
      c.a_points.col(i) = centre + Eigen::Vector3d(box(rng), box(rng), box(rng));
      c.b_points.col(i) =
          spec.motion.rotation.transpose() * (c.a_points.col(i) - spec.motion.translation) +
          spec.noise * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
      c.a_property(i) = gauss(rng);
      c.b_property(i) = c.a_property(i) + 0.3 * gauss(rng);
    }
    return c;
  }

  Correspondences of(const std::vector<MatchedPair>& pairs) const {
    std::vector<Correspondences> parts;
    for (const auto& p : pairs) parts.push_back((*this)(p));
    std::vector<const Correspondences*> pointers;
    for (const auto& p : parts) pointers.push_back(&p);
    return concatenate(pointers);
  }

 private:
  std::map<std::pair<int, int>, PairSpec> specs_;
};

std::vector<MatchedPair> pairs(std::initializer_list<std::pair<int, int>> list) {
  std::vector<MatchedPair> out;
  for (const auto& [a, b] : list) out.push_back({a, b, 0});
  return out;
}

std::vector<Cluster> run(const Synthetic& synthetic,
                         const std::vector<std::vector<MatchedPair>>& cliques,
                         const ClusteringOptions& options = {}) {
  return cluster_alignments(
      cliques, [&](const MatchedPair& p) { return synthetic(p); }, options);
}

double rotation_error(const RigidTransform& fitted, const RigidTransform& truth) {
  return rotation_angle_degrees(fitted.rotation.transpose() * truth.rotation);
}

TEST(Clustering, TwoCliquesOfOneMotionMergeAndRecoverIt) {
  Synthetic s;
  for (int k = 0; k < 4; ++k) s.add(k, k, kMotion);
  const auto clusters = run(s, {pairs({{0, 0}, {1, 1}}), pairs({{2, 2}, {3, 3}})});
  ASSERT_EQ(clusters.size(), 3u);
  const Cluster& root = clusters[2];
  EXPECT_EQ(root.pairs.size(), 4u);
  EXPECT_EQ(root.children, (std::vector<int>{0, 1}));
  EXPECT_EQ(root.parent, -1);
  EXPECT_EQ(root.clique, -1);
  EXPECT_EQ(clusters[0].parent, 2);
  EXPECT_EQ(clusters[1].parent, 2);
  EXPECT_EQ(clusters[0].clique, 0);
  EXPECT_EQ(clusters[1].clique, 1);
  EXPECT_EQ(root.fit.n_points, 120u);
  // 0.05 A noise per coordinate: RMSD ~ 0.05 sqrt(3 - 6/120) = 0.086 A.
  EXPECT_NEAR(root.fit.rmsd, 0.086, 0.015);
  EXPECT_LT(rotation_error(root.fit.transform, kMotion), 0.2);
  EXPECT_LT((root.fit.transform.translation - kMotion.translation).norm(), 0.1);
  // R_chem of properties y = x + 0.3 noise: 1 / sqrt(1 + 0.09) = 0.958.
  EXPECT_NEAR(root.r_chem, 0.958, 0.03);
  const RigidFit direct = fit_rigid(s.of(root.pairs).b_points, s.of(root.pairs).a_points);
  EXPECT_NEAR(direct.rmsd, root.fit.rmsd, 1e-12);
  std::printf("[ merge    ] root: %zu points, RMSD %.4f A, rotation error %.4f deg, R_chem %.4f\n",
              root.fit.n_points, root.fit.rmsd, rotation_error(root.fit.transform, kMotion),
              root.r_chem);
}

// CP 3 of A is paired with 3 of B in one clique and with 5 of B in the other: same motion,
// perfect fits, but the seed forbids the merge. Likewise CP 7 of B with 1 and 2 of A.
TEST(Clustering, CliquesPairingOneCriticalPointWithDifferentPartnersNeverMerge) {
  Synthetic s;
  for (auto [a, b] : {std::pair{3, 3}, {4, 4}, {3, 5}, {6, 6}, {1, 7}, {8, 8}, {2, 7}, {9, 9}}) {
    s.add(a, b, kMotion);
  }
  const auto on_a = run(s, {pairs({{3, 3}, {4, 4}}), pairs({{3, 5}, {6, 6}})});
  ASSERT_EQ(on_a.size(), 2u);
  EXPECT_EQ(on_a[0].parent, -1);
  EXPECT_EQ(on_a[1].parent, -1);
  const auto on_b = run(s, {pairs({{1, 7}, {8, 8}}), pairs({{2, 7}, {9, 9}})});
  ASSERT_EQ(on_b.size(), 2u);
  EXPECT_FALSE(compatible_pairs(on_b[0].pairs, on_b[1].pairs));
  // The same cliques without the conflicting pair do merge (the motion is shared).
  EXPECT_EQ(run(s, {pairs({{3, 3}, {4, 4}}), pairs({{6, 6}})}).size(), 3u);
  // A shared identical pair is no conflict.
  EXPECT_TRUE(compatible_pairs(pairs({{3, 3}, {4, 4}}), pairs({{3, 3}, {6, 6}})));
}

TEST(Clustering, AFarOffAlignmentStaysSeparateUnlessTheMergeCutIsLifted) {
  Synthetic s;
  for (int k = 0; k < 4; ++k) s.add(k, k, kMotion);
  s.add(10, 10, kOther);
  s.add(11, 11, kOther);
  const std::vector<std::vector<MatchedPair>> cliques = {
      pairs({{0, 0}, {1, 1}}), pairs({{10, 10}, {11, 11}}), pairs({{2, 2}, {3, 3}})};
  const auto clusters = run(s, cliques);
  ASSERT_EQ(clusters.size(), 4u);
  EXPECT_EQ(clusters[3].children, (std::vector<int>{0, 2}));
  EXPECT_EQ(clusters[1].parent, -1);
  EXPECT_LT(rotation_error(clusters[1].fit.transform, kOther), 0.5);
  const double distance =
      std::min(rmsd_under(clusters[1].fit.transform, s.of(clusters[3].pairs).b_points,
                          s.of(clusters[3].pairs).a_points),
               rmsd_under(clusters[3].fit.transform, s.of(clusters[1].pairs).b_points,
                          s.of(clusters[1].pairs).a_points));
  std::printf("[ far off  ] linkage distance to the merged cluster %.2f A\n", distance);
  EXPECT_GT(distance, 4.0);

  ClusteringOptions seed_rule;  // the seed merges whatever does not conflict
  seed_rule.merge_cut = std::numeric_limits<double>::infinity();
  const auto all = run(s, cliques, seed_rule);
  ASSERT_EQ(all.size(), 5u);
  EXPECT_EQ(all[4].pairs.size(), 6u);
  EXPECT_GT(all[4].fit.rmsd, 4.0);
  std::printf("[ far off  ] merged anyway (merge_cut inf): RMSD %.2f A\n", all[4].fit.rmsd);
}

TEST(Clustering, TheClosestPairMergesFirst) {
  Synthetic s;
  for (int k = 0; k < 6; ++k) s.add(k, k, kMotion, k == 2 || k == 3 ? 1.0 : 0.02);
  const auto clusters =
      run(s, {pairs({{0, 0}, {1, 1}}), pairs({{2, 2}, {3, 3}}), pairs({{4, 4}, {5, 5}})});
  ASSERT_EQ(clusters.size(), 5u);
  EXPECT_EQ(clusters[3].children, (std::vector<int>{0, 2}));
  EXPECT_EQ(clusters[4].children, (std::vector<int>{1, 3}));
  EXPECT_LT(clusters[3].fit.rmsd, 0.05);
  EXPECT_GT(clusters[1].fit.rmsd, 1.0);
}

TEST(Clustering, TheRmsdCutDropsABadClique) {
  Synthetic s;
  s.add(0, 0, kMotion);
  s.add(1, 1, kMotion);
  s.add(2, 2, kMotion);
  s.add(12, 12, kOther);
  const std::vector<std::vector<MatchedPair>> cliques = {pairs({{0, 0}, {12, 12}}),
                                                         pairs({{0, 0}, {1, 1}}), pairs({{2, 2}})};
  const double bad = fit_rigid(s.of(cliques[0]).b_points, s.of(cliques[0]).a_points).rmsd;
  std::printf("[ cut      ] the mixed clique fits with RMSD %.2f A\n", bad);
  EXPECT_GT(bad, 4.0);
  const auto clusters = run(s, cliques);
  ASSERT_EQ(clusters.size(), 3u);
  EXPECT_EQ(clusters[0].clique, 1);
  EXPECT_EQ(clusters[1].clique, 2);
  EXPECT_EQ(clusters[2].pairs.size(), 3u);
  ClusteringOptions keep_all;
  keep_all.rmsd_cut = std::numeric_limits<double>::infinity();
  const auto kept = run(s, cliques, keep_all);
  EXPECT_EQ(kept[0].clique, 0);
  EXPECT_NEAR(kept[0].fit.rmsd, bad, 1e-12);
}

// 40 random cliques over three motions and 30 x 30 CP indices: the tree's links agree, every
// merged cluster is its children's union and a one-to-one map, every fit is within the cut, the
// moment-based fits equal direct fits, and no two roots could still merge.
TEST(Clustering, TheTreeIsConsistentOnARandomCase) {
  const RigidTransform motions[3] = {kMotion, kOther, motion(70.0, {0, 1, 1}, {-8, 4, 0})};
  Synthetic s;
  std::mt19937 rng(99u);
  std::vector<std::vector<MatchedPair>> cliques;
  for (int c = 0; c < 40; ++c) {
    std::vector<MatchedPair> clique;
    const int m = static_cast<int>(rng() % 3);
    for (int k = 0; k < 2 + static_cast<int>(rng() % 3); ++k) {
      // a and b from disjoint blocks per motion, so a pair always belongs to one motion.
      const int a = 10 * m + static_cast<int>(rng() % 10);
      const int b = 10 * m + static_cast<int>(rng() % 10);
      if (std::any_of(clique.begin(), clique.end(),
                      [&](const MatchedPair& p) { return p.a == a || p.b == b; }))
        continue;
      clique.push_back({a, b, 0});
      s.add(a, b, motions[m], 0.2);
    }
    cliques.push_back(clique);
  }
  const auto clusters = run(s, cliques);
  int roots = 0, leaves = 0;
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    const Cluster& c = clusters[i];
    if (c.parent < 0)
      ++roots;
    else {
      EXPECT_GT(c.parent, static_cast<int>(i));
      const auto& siblings = clusters[static_cast<std::size_t>(c.parent)].children;
      EXPECT_NE(std::find(siblings.begin(), siblings.end(), static_cast<int>(i)), siblings.end());
    }
    EXPECT_LE(c.fit.rmsd, 4.0);
    EXPECT_TRUE(compatible_pairs(c.pairs, c.pairs));
    const RigidFit direct = fit_rigid(s.of(c.pairs).b_points, s.of(c.pairs).a_points);
    EXPECT_NEAR(direct.rmsd, c.fit.rmsd, 1e-9);
    if (c.children.empty()) {
      ++leaves;
      EXPECT_GE(c.clique, 0);
      continue;
    }
    ASSERT_EQ(c.children.size(), 2u);
    std::vector<MatchedPair> joined = clusters[static_cast<std::size_t>(c.children[0])].pairs;
    for (const auto& p : clusters[static_cast<std::size_t>(c.children[1])].pairs)
      joined.push_back(p);
    std::sort(joined.begin(), joined.end());
    joined.erase(std::unique(joined.begin(), joined.end()), joined.end());
    EXPECT_TRUE(joined == c.pairs);
  }
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    for (std::size_t j = i + 1; j < clusters.size(); ++j) {
      const Cluster& x = clusters[i];
      const Cluster& y = clusters[j];
      if (x.parent >= 0 || y.parent >= 0 || !compatible_pairs(x.pairs, y.pairs)) continue;
      const Correspondences cx = s.of(x.pairs), cy = s.of(y.pairs);
      EXPECT_GT(std::min(rmsd_under(y.fit.transform, cx.b_points, cx.a_points),
                         rmsd_under(x.fit.transform, cy.b_points, cy.a_points)),
                4.0);
    }
  }
  std::printf("[ random   ] seed 99: 40 cliques -> %d leaves, %zu clusters, %d roots\n", leaves,
              clusters.size(), roots);
  EXPECT_EQ(leaves, 40);
  EXPECT_EQ(static_cast<int>(clusters.size()), 2 * leaves - roots);
}

TEST(Clustering, BadInputsAreRejected) {
  Synthetic s;
  s.add(0, 0, kMotion);
  s.add(0, 1, kMotion);
  s.add(1, 1, kMotion);
  EXPECT_THROW(run(s, {{}}), InputError);
  EXPECT_THROW(run(s, {pairs({{0, 0}, {0, 1}})}), InputError);
  EXPECT_THROW(run(s, {{MatchedPair{0, 0, 3}}, {MatchedPair{0, 0, 4}}}), InputError);
  ClusteringOptions bad;
  bad.merge_cut = 0.0;
  EXPECT_THROW(run(s, {pairs({{0, 0}})}, bad), OptionError);
  bad.merge_cut = 4.0;
  bad.rmsd_cut = std::nan("");
  EXPECT_THROW(run(s, {pairs({{0, 0}})}, bad), OptionError);
}

}  // namespace
}  // namespace surfcomp::matching
