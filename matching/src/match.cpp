#include "surfcomp/matching/match.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/matching/cliques.hpp"

#include <chrono>
#include <map>

namespace surfcomp::matching {
namespace {

double since_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

MatchResult match_surfaces(const harmonic::SurfaceDescriptors& reference,
                           const harmonic::SurfaceDescriptors& probe, const MatchOptions& options,
                           const std::vector<bool>* reference_allowed,
                           const std::vector<bool>* probe_allowed) {
  const auto& ga = reference.options.image;
  const auto& gb = probe.options.image;
  if (ga.radial_samples != gb.radial_samples || ga.angular_samples != gb.angular_samples) {
    throw InputError(reference.surface.source() + " and " + probe.surface.source() +
                     ": the images were built on different grids (" +
                     std::to_string(ga.radial_samples) + "x" + std::to_string(ga.angular_samples) +
                     " and " + std::to_string(gb.radial_samples) + "x" +
                     std::to_string(gb.angular_samples) + "); rebuild them with the same parameters");
  }
  MatchResult result;
  auto clock = std::chrono::steady_clock::now();
  const AssociationGraph graph =
      build_association_graph(reference, probe, options.graph, reference_allowed, probe_allowed);
  result.trace = graph.trace;
  for (const TraceStage& stage : graph.trace) result.timing_ms.emplace_back("graph: " + stage.stage, stage.milliseconds);

  clock = std::chrono::steady_clock::now();
  const std::vector<std::vector<int>> cliques = maximal_cliques(graph, options.min_clique_size);
  result.cliques = cliques.size();
  std::vector<std::vector<MatchedPair>> pair_cliques;
  pair_cliques.reserve(cliques.size());
  for (const auto& clique : cliques) {
    std::vector<MatchedPair> pairs;
    for (int node : clique) {
      const PointPair& p = graph.nodes[static_cast<std::size_t>(node)];
      pairs.push_back(MatchedPair{p.a, p.b, p.image_shift});
    }
    pair_cliques.push_back(std::move(pairs));
  }
  result.timing_ms.emplace_back("cliques", since_ms(clock));

  clock = std::chrono::steady_clock::now();
  const std::vector<Cluster> clusters = cluster_alignments(pair_cliques, reference, probe,
                                                           options.clustering, options.correspondences);
  result.timing_ms.emplace_back("fits and merging", since_ms(clock));

  clock = std::chrono::steady_clock::now();
  const std::vector<RankedAlignment> ranking = rank_alignments(clusters, options.ranking);
  std::vector<int> rank_of(clusters.size(), 0);
  for (const RankedAlignment& r : ranking) rank_of[static_cast<std::size_t>(r.cluster)] = r.rank;
  for (const RankedAlignment& r : ranking) {
    const Cluster& c = clusters[static_cast<std::size_t>(r.cluster)];
    Alignment a;
    a.rank = r.rank;
    a.transform = c.fit.transform.matrix();
    a.rmsd = c.fit.rmsd;
    a.n_points = c.fit.n_points;
    a.r_chem = c.r_chem;
    a.consensus = r.consensus;
    for (const MatchedPair& p : c.pairs) a.cp_pairs.emplace_back(p.a, p.b);
    a.parent = c.parent >= 0 ? rank_of[static_cast<std::size_t>(c.parent)] : 0;
    for (int child : c.children) a.children.push_back(rank_of[static_cast<std::size_t>(child)]);
    result.alignments.push_back(std::move(a));
  }
  result.timing_ms.emplace_back("ranking", since_ms(clock));
  return result;
}

std::vector<bool> critical_points_in_site(const harmonic::SurfaceDescriptors& descriptors,
                                          const std::vector<SiteSphere>& spheres) {
  std::vector<bool> inside(descriptors.critical_points.size(), false);
  for (std::size_t i = 0; i < inside.size(); ++i) {
    const Eigen::Vector3d& p = descriptors.critical_points[i].point.position;
    for (const SiteSphere& s : spheres) {
      if ((p - s.center).norm() <= s.radius) {
        inside[i] = true;
        break;
      }
    }
  }
  return inside;
}

}  // namespace surfcomp::matching
