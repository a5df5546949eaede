#include "surfcomp/matching/match.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/matching/cliques.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <utility>

#include <tbb/parallel_for.h>

namespace surfcomp::matching {
namespace {

double since_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

/// An alignment in its final place.
struct Placed {
  int cluster = -1;  ///< index in the merge tree; -1 for a principal-axes pose
  double consensus = 0.0;
  RigidTransform transform;
  bool refined = false;
  OverlayScore overlay;
};

/// The vertices the overlay compares: all of them, unless the match is restricted to a binding
/// site, by an `allowed` mask or by descriptions built only at a site's critical points (the
/// others skipped); then those within `radius` of a critical point that takes part.
std::optional<std::vector<bool>> site_vertices(const harmonic::SurfaceDescriptors& descriptors,
                                               const std::vector<bool>* allowed, double radius) {
  const auto& cps = descriptors.critical_points;
  const auto skipped = [&](std::size_t c) {
    return cps[c].status == harmonic::PatchStatus::skipped;
  };
  bool any_skipped = false;
  for (std::size_t c = 0; c < cps.size(); ++c) any_skipped = any_skipped || skipped(c);
  if (allowed == nullptr && !any_skipped) return std::nullopt;
  const Eigen::MatrixX3d positions = descriptors.surface.positions();
  std::vector<bool> inside(static_cast<std::size_t>(positions.rows()), false);
  for (std::size_t c = 0; c < cps.size(); ++c) {
    if ((allowed != nullptr && !(*allowed)[c]) || skipped(c)) continue;
    const Eigen::Vector3d centre = cps[c].point.position;
    for (Eigen::Index v = 0; v < positions.rows(); ++v) {
      if ((Eigen::Vector3d(positions.row(v)) - centre).squaredNorm() <= radius * radius)
        inside[static_cast<std::size_t>(v)] = true;
    }
  }
  return inside;
}

/// The consensus order with its first options.refine_top alignments refined on the whole
/// surfaces (those whose start does not repeat an earlier one's) and moved ahead together with
/// the refined principal-axes starts (MatchOptions::principal_axes_starts), best overlay score
/// first, repeats of a better pose after the distinct ones (MatchOptions::refine_top), the
/// first polish_top of them polished on the whole score where atoms take part
/// (MatchOptions::polish_top). Those first refine_top alignments get their overlay score. A
/// site match overlays the pocket linings with MatchOptions::site's settings.
std::vector<Placed> refine_and_order(const std::vector<RankedAlignment>& ranking,
                                     const std::vector<Cluster>& clusters,
                                     const harmonic::SurfaceDescriptors& reference,
                                     const harmonic::SurfaceDescriptors& probe,
                                     const MatchOptions& options,
                                     const std::vector<bool>* reference_allowed,
                                     const std::vector<bool>* probe_allowed) {
  constexpr double kRepeatDistance = 0.5;  // A, largest move of a sampled probe point
  if (options.refine_top < 0)
    throw OptionError("refine_top must be >= 0, got " + std::to_string(options.refine_top));
  if (options.polish_top < 0)
    throw OptionError("polish_top must be >= 0, got " + std::to_string(options.polish_top));
  const auto check_starts = [](int n, const char* name) {
    if (!is_axes_start_count(n))
      throw OptionError(std::string(name) + " must be 0, 4 or 24, got " + std::to_string(n));
  };
  check_starts(options.principal_axes_starts, "principal_axes_starts");
  check_starts(options.site.principal_axes_starts, "site.principal_axes_starts");
  if (!(options.site.overlay_radius > 0.0) || !std::isfinite(options.site.overlay_radius)) {
    throw OptionError("site.overlay_radius must be a finite number > 0, got " +
                      std::to_string(options.site.overlay_radius));
  }
  if (!(options.site.chem_weight >= 0.0) || !std::isfinite(options.site.chem_weight)) {
    throw OptionError("site.chem_weight must be a finite number >= 0, got " +
                      std::to_string(options.site.chem_weight));
  }
  std::vector<Placed> placed;
  for (const RankedAlignment& r : ranking) {
    Placed p;
    p.cluster = r.cluster;
    p.consensus = r.consensus;
    p.transform = clusters[static_cast<std::size_t>(r.cluster)].fit.transform;
    placed.push_back(p);
  }
  if (options.refine_top == 0) return placed;
  const auto reference_mask =
      site_vertices(reference, reference_allowed, options.site.overlay_radius);
  const auto probe_mask = site_vertices(probe, probe_allowed, options.site.overlay_radius);
  const bool site = reference_mask.has_value() || probe_mask.has_value();
  OverlayOptions overlay_options = options.overlay;
  if (site) {
    overlay_options.chem_weight = options.site.chem_weight;
    overlay_options.atom_weight = 0.0;  // pockets are compared on their linings' shape
  }
  const int n_axes_starts =
      site ? options.site.principal_axes_starts : options.principal_axes_starts;
  if (placed.empty() && n_axes_starts == 0) return placed;
  SurfaceSample reference_sample = sample_surface(reference.surface, overlay_options.spacing,
                                                  reference_mask ? &*reference_mask : nullptr);
  SurfaceSample probe_sample =
      sample_surface(probe.surface, overlay_options.spacing, probe_mask ? &*probe_mask : nullptr);
  // A site region can be empty (no participating CP); then there is nothing to overlay.
  if (reference_sample.size() == 0 || probe_sample.size() == 0) {
    if (placed.empty()) return placed;
    throw InputError(reference.surface.source() + " and " + probe.surface.source() +
                     ": the overlay region of the " +
                     (reference_sample.size() == 0 ? "reference" : "probe") + " has no vertices");
  }
  std::vector<RigidTransform> axes_starts;
  if (n_axes_starts > 0)
    axes_starts = principal_axes_starts(reference_sample, probe_sample, n_axes_starts == 24);
  const SurfaceOverlay overlay(std::move(reference_sample), std::move(probe_sample),
                               overlay_options, site ? AtomSample{} : sample_atoms(reference.atoms),
                               site ? AtomSample{} : sample_atoms(probe.atoms));
  const std::size_t n_refined =
      std::min(placed.size(), static_cast<std::size_t>(options.refine_top));
  const Eigen::Matrix3Xd& points = overlay.probe_points();
  const auto largest_move = [&](const RigidTransform& x, const RigidTransform& y) {
    return (x.apply(points) - y.apply(points)).colwise().norm().maxCoeff();
  };
  // A start within kRepeatDistance of an earlier refined start (merge-tree neighbours often
  // share their transform) would refine to the same pose: it is scored where it is. The
  // refinements are independent, each into its own slot, and run in parallel (TBB): the result
  // does not depend on the thread count.
  std::vector<RigidTransform> starts;
  std::vector<std::size_t> to_refine;
  for (std::size_t k = 0; k < n_refined; ++k) {
    if (std::none_of(starts.begin(), starts.end(), [&](const RigidTransform& s) {
          return largest_move(s, placed[k].transform) <= kRepeatDistance;
        })) {
      starts.push_back(placed[k].transform);
      to_refine.push_back(k);
    } else {
      placed[k].overlay = overlay.score(placed[k].transform);
    }
  }
  tbb::parallel_for(std::size_t{0}, to_refine.size(), [&](std::size_t i) {
    Placed& p = placed[to_refine[i]];
    p.transform = overlay.refine(p.transform, &p.overlay);
    p.refined = true;
  });
  std::vector<Placed> candidates(placed.begin(),
                                 placed.begin() + static_cast<std::ptrdiff_t>(n_refined));
  // A principal-axes start whose refinement comes within kRepeatDistance of a pose refined
  // from the cliques is taken for a repeat of it and abandoned there (it could have climbed on
  // past it; the benchmark figures are with this rule). The probe points' centroid moves no
  // farther than the farthest point: a cheap first test.
  const Eigen::Vector3d centroid = points.rowwise().mean();
  const auto reached = [&](const RigidTransform& pose) {
    const Eigen::Vector3d moved = pose.rotation * centroid + pose.translation;
    return std::any_of(candidates.begin(), candidates.end(), [&](const Placed& c) {
      const Eigen::Vector3d other = c.transform.rotation * centroid + c.transform.translation;
      return c.refined && (other - moved).norm() <= kRepeatDistance &&
             largest_move(c.transform, pose) <= kRepeatDistance;
    });
  };
  std::vector<std::optional<Placed>> axes_poses(axes_starts.size());
  tbb::parallel_for(std::size_t{0}, axes_starts.size(), [&](std::size_t i) {
    Placed p;  // no cluster
    const std::optional<RigidTransform> refined =
        overlay.refine(axes_starts[i], &p.overlay, reached);
    if (!refined) return;
    p.transform = *refined;
    p.refined = true;
    axes_poses[i] = p;
  });
  for (const auto& p : axes_poses) {
    if (p) candidates.push_back(*p);
  }
  // Refined ones by score, then the repeats (a pose within kRepeatDistance of a better one); a
  // principal-axes pose that repeats a better one is dropped (it has no merge tree place to
  // keep). Ties keep the order given: first the consensus order, then the axes starts.
  struct Ordered {
    std::vector<Placed> list;  ///< the distinct ones, then the repeats
    std::size_t distinct = 0;
  };
  const auto best_first = [&](std::vector<Placed> all) {
    std::stable_sort(all.begin(), all.end(), [](const Placed& x, const Placed& y) {
      return x.overlay.score > y.overlay.score;
    });
    Ordered out;
    std::vector<Placed> repeats;
    for (const Placed& candidate : all) {
      const bool repeat = std::any_of(out.list.begin(), out.list.end(), [&](const Placed& d) {
        return largest_move(d.transform, candidate.transform) <= kRepeatDistance;
      });
      if (!repeat) {
        out.list.push_back(candidate);
      } else if (candidate.cluster >= 0) {
        repeats.push_back(candidate);
      }
    }
    out.distinct = out.list.size();
    out.list.insert(out.list.end(), repeats.begin(), repeats.end());
    return out;
  };
  Ordered ordered = best_first(std::move(candidates));
  // The first polish_top distinct refined poses are polished on the whole score, their
  // heteroatoms pulled too (SurfaceOverlay::refine with pull_atoms), and the list is ordered
  // again (a polished pose that comes to repeat a better one goes after the distinct ones).
  if (overlay.uses_atoms() && options.polish_top > 0) {
    std::vector<std::size_t> to_polish;
    for (std::size_t i = 0;
         i < ordered.distinct && to_polish.size() < static_cast<std::size_t>(options.polish_top);
         ++i) {
      if (ordered.list[i].refined) to_polish.push_back(i);
    }
    tbb::parallel_for(std::size_t{0}, to_polish.size(), [&](std::size_t k) {
      Placed& p = ordered.list[to_polish[k]];
      p.transform = *overlay.refine(p.transform, &p.overlay, {}, true);
    });
    ordered = best_first(std::move(ordered.list));
  }
  ordered.list.insert(ordered.list.end(), placed.begin() + static_cast<std::ptrdiff_t>(n_refined),
                      placed.end());
  return ordered.list;
}

}  // namespace

MatchResult match_surfaces(const harmonic::SurfaceDescriptors& reference,
                           const harmonic::SurfaceDescriptors& probe, const MatchOptions& options,
                           const std::vector<bool>* reference_allowed,
                           const std::vector<bool>* probe_allowed) {
  const auto& ga = reference.options.image;
  const auto& gb = probe.options.image;
  if (ga.radial_samples != gb.radial_samples || ga.angular_samples != gb.angular_samples) {
    throw InputError(
        reference.surface.source() + " and " + probe.surface.source() +
        ": the images were built on different grids (" + std::to_string(ga.radial_samples) + "x" +
        std::to_string(ga.angular_samples) + " and " + std::to_string(gb.radial_samples) + "x" +
        std::to_string(gb.angular_samples) + "); rebuild them with the same parameters");
  }
  MatchResult result;
  auto clock = std::chrono::steady_clock::now();
  const AssociationGraph graph =
      build_association_graph(reference, probe, options.graph, reference_allowed, probe_allowed);
  result.trace = graph.trace;
  for (const TraceStage& stage : graph.trace)
    result.timing_ms.emplace_back("graph: " + stage.stage, stage.milliseconds);

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
  const std::vector<Cluster> clusters = cluster_alignments(
      pair_cliques, reference, probe, options.clustering, options.correspondences);
  result.timing_ms.emplace_back("fits and merging", since_ms(clock));

  clock = std::chrono::steady_clock::now();
  const std::vector<RankedAlignment> ranking = rank_alignments(clusters, options.ranking);
  result.timing_ms.emplace_back("ranking", since_ms(clock));

  clock = std::chrono::steady_clock::now();
  const std::vector<Placed> placed = refine_and_order(ranking, clusters, reference, probe, options,
                                                      reference_allowed, probe_allowed);
  std::vector<int> rank_of(clusters.size(), 0);
  for (std::size_t k = 0; k < placed.size(); ++k) {
    if (placed[k].cluster >= 0)
      rank_of[static_cast<std::size_t>(placed[k].cluster)] = static_cast<int>(k) + 1;
  }
  for (std::size_t k = 0; k < placed.size(); ++k) {
    const Placed& p = placed[k];
    Alignment a;
    a.source = p.cluster >= 0 ? AlignmentSource::cliques : AlignmentSource::principal_axes;
    a.rank = static_cast<int>(k) + 1;
    a.transform = p.transform.matrix();
    a.consensus = p.consensus;
    a.refined = p.refined;
    a.overlay = p.overlay;
    if (p.cluster >= 0) {
      const Cluster& c = clusters[static_cast<std::size_t>(p.cluster)];
      a.rmsd = c.fit.rmsd;
      a.n_points = c.fit.n_points;
      a.r_chem = c.r_chem;
      for (const MatchedPair& pair : c.pairs) a.cp_pairs.emplace_back(pair.a, pair.b);
      a.parent = c.parent >= 0 ? rank_of[static_cast<std::size_t>(c.parent)] : 0;
      for (int child : c.children) a.children.push_back(rank_of[static_cast<std::size_t>(child)]);
    }
    result.alignments.push_back(std::move(a));
  }
  result.timing_ms.emplace_back("overlay refinement", since_ms(clock));
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
