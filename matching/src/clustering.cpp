#include "surfcomp/matching/clustering.hpp"

#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <queue>
#include <string>
#include <tuple>
#include <utility>

namespace surfcomp::matching {

namespace {

/// The second moments of a cluster's correspondences (p on A, q on B) about their centroids:
/// enough to evaluate the squared residual sum under any rigid transform in O(1).
struct Moments {
  double n = 0.0;
  Eigen::Vector3d mean_p = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_q = Eigen::Vector3d::Zero();
  Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();  ///< sum (q - mean_q)(p - mean_p)^T
  double spread = 0.0;                              ///< sum |p - mean_p|^2 + |q - mean_q|^2
};

Moments moments_of(const Correspondences& c) {
  Moments m;
  m.n = static_cast<double>(c.size());
  m.mean_p = c.a_points.rowwise().mean();
  m.mean_q = c.b_points.rowwise().mean();
  const Eigen::Matrix3Xd p = c.a_points.colwise() - m.mean_p;
  const Eigen::Matrix3Xd q = c.b_points.colwise() - m.mean_q;
  m.cross = q * p.transpose();
  m.spread = p.squaredNorm() + q.squaredNorm();
  return m;
}

/// RMSD of the points of `m` under x -> R x + t (moving q onto p):
/// sum |R q + t - p|^2 = spread + n |R mean_q + t - mean_p|^2 - 2 trace(R cross).
double rmsd_from_moments(const Moments& m, const RigidTransform& t) {
  const Eigen::Vector3d offset = t.rotation * m.mean_q + t.translation - m.mean_p;
  const double sum = m.spread + m.n * offset.squaredNorm() - 2.0 * (t.rotation * m.cross).trace();
  return std::sqrt(std::max(0.0, sum) / m.n);
}

using PairKey = std::pair<int, int>;

struct Node {
  Cluster cluster;
  Moments moments;
};

class Builder {
 public:
  explicit Builder(std::map<PairKey, Correspondences> correspondences)
      : correspondences_(std::move(correspondences)) {}

  /// The cluster of `pairs` (sorted, one-to-one) with its fit, R_chem and moments.
  Node make(std::vector<MatchedPair> pairs) const {
    std::vector<const Correspondences*> parts;
    parts.reserve(pairs.size());
    for (const MatchedPair& pair : pairs) parts.push_back(&correspondences_.at({pair.a, pair.b}));
    const Correspondences all = concatenate(parts);
    Node node;
    node.cluster.pairs = std::move(pairs);
    node.cluster.fit = fit_rigid(all.b_points, all.a_points);
    node.cluster.r_chem = property_correlation(all);
    node.moments = moments_of(all);
    return node;
  }

  std::size_t count(const std::vector<MatchedPair>& pairs) const {
    std::size_t n = 0;
    for (const MatchedPair& pair : pairs) n += correspondences_.at({pair.a, pair.b}).size();
    return n;
  }

 private:
  std::map<PairKey, Correspondences> correspondences_;
};

std::string pair_text(const MatchedPair& p) {
  return "(" + std::to_string(p.a) + ", " + std::to_string(p.b) + ")";
}

double linkage(const Node& x, const Node& y) {
  return std::min(rmsd_from_moments(x.moments, y.cluster.fit.transform),
                  rmsd_from_moments(y.moments, x.cluster.fit.transform));
}

std::vector<MatchedPair> merged_pairs(const std::vector<MatchedPair>& x,
                                      const std::vector<MatchedPair>& y) {
  std::vector<MatchedPair> out;
  std::set_union(x.begin(), x.end(), y.begin(), y.end(), std::back_inserter(out));
  return out;
}

}  // namespace

bool compatible_pairs(const std::vector<MatchedPair>& x, const std::vector<MatchedPair>& y) {
  for (const MatchedPair& p : x) {
    for (const MatchedPair& q : y) {
      if ((p.a == q.a) != (p.b == q.b)) return false;
    }
  }
  return true;
}

std::vector<Cluster> cluster_alignments(const std::vector<std::vector<MatchedPair>>& cliques,
                                        const CorrespondenceProvider& correspondences,
                                        const ClusteringOptions& options) {
  detail::check_clustering_options(options, {"cluster_alignments", ""});

  // Normalise the cliques and collect the distinct pairs with their shifts.
  std::vector<std::vector<MatchedPair>> sorted(cliques.size());
  std::map<PairKey, int> shifts;
  for (std::size_t c = 0; c < cliques.size(); ++c) {
    const std::string where = "cluster_alignments: clique " + std::to_string(c);
    if (cliques[c].empty()) throw InputError(where + " is empty; expected at least one CP pair");
    std::vector<MatchedPair> pairs = cliques[c];
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      for (std::size_t j = i + 1; j < pairs.size(); ++j) {
        if (pairs[i].a == pairs[j].a || pairs[i].b == pairs[j].b) {
          throw InputError(where + " pairs " + pair_text(pairs[i]) + " and " + pair_text(pairs[j]) +
                           " share a critical point; expected a one-to-one map");
        }
      }
    }
    for (const MatchedPair& pair : cliques[c]) {
      const auto [it, inserted] = shifts.emplace(PairKey{pair.a, pair.b}, pair.image_shift);
      if (!inserted && it->second != pair.image_shift) {
        throw InputError(where + ": CP pair " + pair_text(pair) + " has image shift " +
                         std::to_string(pair.image_shift) + " here and " +
                         std::to_string(it->second) + " elsewhere; expected one shift per pair");
      }
    }
    sorted[c] = std::move(pairs);
  }
  std::map<PairKey, Correspondences> table;
  for (const auto& [key, shift] : shifts) {
    Correspondences c = correspondences(MatchedPair{key.first, key.second, shift});
    if (c.b_points.cols() != c.a_points.cols() || c.a_property.size() != c.a_points.cols() ||
        c.b_property.size() != c.a_points.cols()) {
      throw InputError("clustering: the correspondences of CP pair " +
                       pair_text(MatchedPair{key.first, key.second, shift}) +
                       " have arrays of different lengths");
    }
    table.emplace(key, std::move(c));
  }
  const Builder builder(std::move(table));

  // Leaves.
  std::vector<Node> nodes;
  for (std::size_t c = 0; c < sorted.size(); ++c) {
    const std::size_t n = builder.count(sorted[c]);
    if (n < 3) {
      throw InputError("clustering: clique " + std::to_string(c) + " has " + std::to_string(n) +
                       " correspondences; a rigid fit needs at least 3");
    }
    Node node = builder.make(sorted[c]);
    if (node.cluster.fit.rmsd > options.rmsd_cut) continue;
    node.cluster.clique = static_cast<int>(c);
    nodes.push_back(std::move(node));
  }

  // Single linkage with a heap of candidate merges; entries of merged clusters go stale.
  using Candidate = std::tuple<double, int, int>;
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> heap;
  std::vector<bool> active(nodes.size(), true);
  const auto consider = [&](int i, int j) {
    if (!compatible_pairs(nodes[static_cast<std::size_t>(i)].cluster.pairs,
                          nodes[static_cast<std::size_t>(j)].cluster.pairs)) {
      return;
    }
    const double d =
        linkage(nodes[static_cast<std::size_t>(i)], nodes[static_cast<std::size_t>(j)]);
    if (d <= options.merge_cut) heap.emplace(d, i, j);
  };
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(nodes.size()); ++j) consider(i, j);
  }
  while (!heap.empty()) {
    const auto [d, i, j] = heap.top();
    heap.pop();
    if (!active[static_cast<std::size_t>(i)] || !active[static_cast<std::size_t>(j)]) continue;
    const int k = static_cast<int>(nodes.size());
    Node merged = builder.make(merged_pairs(nodes[static_cast<std::size_t>(i)].cluster.pairs,
                                            nodes[static_cast<std::size_t>(j)].cluster.pairs));
    merged.cluster.children = {i, j};
    nodes[static_cast<std::size_t>(i)].cluster.parent = k;
    nodes[static_cast<std::size_t>(j)].cluster.parent = k;
    active[static_cast<std::size_t>(i)] = false;
    active[static_cast<std::size_t>(j)] = false;
    nodes.push_back(std::move(merged));
    active.push_back(true);
    for (int other = 0; other < k; ++other) {
      if (active[static_cast<std::size_t>(other)]) consider(other, k);
    }
  }

  std::vector<Cluster> out;
  out.reserve(nodes.size());
  for (Node& node : nodes) out.push_back(std::move(node.cluster));
  return out;
}

std::vector<Cluster> cluster_alignments(const std::vector<std::vector<MatchedPair>>& cliques,
                                        const harmonic::SurfaceDescriptors& reference,
                                        const harmonic::SurfaceDescriptors& probe,
                                        const ClusteringOptions& options,
                                        const CorrespondenceOptions& correspondence_options) {
  return cluster_alignments(
      cliques,
      [&](const MatchedPair& pair) {
        return pair_correspondences(reference, probe, pair, correspondence_options);
      },
      options);
}

}  // namespace surfcomp::matching
