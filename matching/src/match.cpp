#include "surfcomp/matching/match.hpp"

#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/matching/cliques.hpp"
#include "surfcomp/matching/packed_overlay.hpp"
#include "surfcomp/matching/site.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

#include <tbb/parallel_for.h>

namespace surfcomp::matching {
namespace {

/// Largest move of a sampled probe point (A) below which two poses are the same pose.
constexpr double kRepeatDistance = 0.5;

/// An alignment in its final place.
struct Placed {
  int cluster = -1;  ///< index in the merge tree; -1 for a principal-axes pose
  double consensus = 0.0;
  RigidTransform transform;
  bool refined = false;
  OverlayScore overlay;
  double atom_fit = 0.0;  ///< AtomOverlap::fit, where the atom polish is on
  CoverageScore coverage;
  bool icp = false;  ///< polished by ICP
};

/// The clusters in the consensus order, with the clusters' fits as their transforms.
std::vector<Placed> consensus_order(const std::vector<RankedAlignment>& ranking,
                                    const std::vector<Cluster>& clusters) {
  std::vector<Placed> placed;
  for (const RankedAlignment& r : ranking) {
    Placed p;
    p.cluster = r.cluster;
    p.consensus = r.consensus;
    p.transform = clusters[static_cast<std::size_t>(r.cluster)].fit.transform;
    placed.push_back(p);
  }
  return placed;
}

/// The overlay the poses are refined and scored on, and the principal-axes starts refined
/// with them.
struct Refinement {
  SurfaceOverlay overlay;
  std::vector<RigidTransform> axes_starts;
  /// The surfaces (or linings) indexed for the coverage and the ICP polish; none when neither
  /// is asked for, or when a site's lining keeps no whole triangle.
  std::optional<SurfaceFit> fit;
  /// The two samples packed for the single-precision refinement (MatchOptions::fine_top > 0).
  std::optional<PackedQuery> packed_reference;
  PackedSample packed_probe;
};

/// The Refinement of a match in options.mode: the whole surfaces with options.overlay, the
/// atoms and principal_axes_starts, or the pocket linings with options.site's settings and no
/// atoms. None when there is nothing to refine (no alignment, and no axes start or an empty
/// lining). Throws InputError when a lining is empty while there are alignments.
std::optional<Refinement> prepare_refinement(const harmonic::SurfaceDescriptors& reference,
                                             const harmonic::SurfaceDescriptors& probe,
                                             const MatchOptions& options,
                                             const std::vector<bool>* reference_allowed,
                                             const std::vector<bool>* probe_allowed,
                                             bool have_alignments) {
  const bool site = options.mode == MatchMode::binding_sites;
  const OverlayOptions overlay_options = mode_overlay_options(options);
  const int n_axes_starts =
      site ? options.site.principal_axes_starts : options.principal_axes_starts;
  if (!have_alignments && n_axes_starts == 0) return std::nullopt;
  std::vector<bool> reference_lining, probe_lining;
  if (site) {
    reference_lining = pocket_lining(reference, reference_allowed, options.site.overlay_radius);
    probe_lining = pocket_lining(probe, probe_allowed, options.site.overlay_radius);
  }
  SurfaceSample reference_sample = sample_surface(reference.surface, overlay_options.spacing,
                                                  site ? &reference_lining : nullptr);
  SurfaceSample probe_sample =
      sample_surface(probe.surface, overlay_options.spacing, site ? &probe_lining : nullptr);
  // A lining can be empty (no critical point takes part); then there is nothing to overlay.
  if (reference_sample.size() == 0 || probe_sample.size() == 0) {
    if (!have_alignments) return std::nullopt;
    throw InputError(reference.surface.source() + " and " + probe.surface.source() +
                     ": the overlay region of the " +
                     (reference_sample.size() == 0 ? "reference" : "probe") + " has no vertices");
  }
  std::vector<RigidTransform> axes_starts;
  if (n_axes_starts > 0)
    axes_starts = principal_axes_starts(reference_sample, probe_sample, n_axes_starts == 24);
  AtomSample reference_atoms = site ? AtomSample{} : sample_atoms(reference.atoms);
  AtomSample probe_atoms = site ? AtomSample{} : sample_atoms(probe.atoms);
  std::optional<PackedQuery> packed_reference;
  PackedSample packed_probe;
  if (options.fine_top > 0) {
    try {
      packed_reference.emplace(PackedSample(reference_sample, reference_atoms,
                                            overlay_options.sigma, SampleKind::surface));
      packed_probe =
          PackedSample(probe_sample, probe_atoms, overlay_options.sigma, SampleKind::surface);
    } catch (const InputError&) {
      // A sample too large for the packed index (2^26 cells): every start in double precision.
      packed_reference.reset();
    }
  }
  std::optional<SurfaceFit> fit;
  if (options.coverage_distance > 0.0 || options.icp_top > 0) {
    try {
      fit.emplace(reference.surface, probe.surface, site ? &reference_lining : nullptr,
                  site ? &probe_lining : nullptr);
    } catch (const InputError&) {
      if (!site) throw;  // a lining of scattered vertices holds no whole triangle: no coverage
    }
  }
  return Refinement{
      SurfaceOverlay(std::move(reference_sample), std::move(probe_sample), overlay_options,
                     std::move(reference_atoms), std::move(probe_atoms)),
      std::move(axes_starts), std::move(fit), std::move(packed_reference), std::move(packed_probe)};
}

/// The largest distance between a sampled probe point moved by `x` and moved by `y`, A.
double largest_move(const SurfaceOverlay& overlay, const RigidTransform& x,
                    const RigidTransform& y) {
  const Eigen::Matrix3Xd& points = overlay.probe_points();
  return (x.apply(points) - y.apply(points)).colwise().norm().maxCoeff();
}

/// Of the first `n` alignments of `placed`, those to refine: each whose transform is not within
/// kRepeatDistance of an earlier one's (merge-tree neighbours often share their transform, and
/// would refine to the same pose); the others are scored where they are.
std::vector<std::size_t> distinct_head(std::vector<Placed>& placed, std::size_t n,
                                       const SurfaceOverlay& overlay) {
  std::vector<std::size_t> distinct;
  for (std::size_t k = 0; k < n; ++k) {
    if (std::none_of(distinct.begin(), distinct.end(), [&](std::size_t d) {
          return largest_move(overlay, placed[d].transform, placed[k].transform) <= kRepeatDistance;
        })) {
      distinct.push_back(k);
    } else {
      placed[k].overlay = overlay.score(placed[k].transform);
    }
  }
  return distinct;
}

/// Refines the first `n` alignments of `placed` on the overlay and gives them their overlay
/// score. A start within kRepeatDistance of an earlier refined start (merge-tree neighbours
/// often share their transform) would refine to the same pose: it is scored where it is. The
/// refinements are independent, each into its own slot, and run in parallel (TBB): the result
/// does not depend on the thread count.
void refine_consensus_head(std::vector<Placed>& placed, std::size_t n,
                           const SurfaceOverlay& overlay) {
  const std::vector<std::size_t> to_refine = distinct_head(placed, n, overlay);
  tbb::parallel_for(std::size_t{0}, to_refine.size(), [&](std::size_t i) {
    Placed& p = placed[to_refine[i]];
    const RefineResult refined = overlay.refine(p.transform);
    p.transform = refined.transform;
    p.overlay = refined.score;
    p.refined = true;
  });
}

/// The refined principal-axes poses, in the order of `starts`, in parallel (TBB, one slot
/// each). A start whose refinement comes within kRepeatDistance of a refined pose of `found`
/// is taken for a repeat of it and abandoned there (it could have climbed on past it). The
/// probe points' centroid moves no farther than the farthest point: a cheap first test.
std::vector<Placed> refine_axes_starts(const std::vector<RigidTransform>& starts,
                                       const std::vector<Placed>& found,
                                       const SurfaceOverlay& overlay) {
  const Eigen::Vector3d centroid = overlay.probe_points().rowwise().mean();
  const auto reached = [&](const RigidTransform& pose) {
    const Eigen::Vector3d moved = pose.rotation * centroid + pose.translation;
    return std::any_of(found.begin(), found.end(), [&](const Placed& c) {
      const Eigen::Vector3d other = c.transform.rotation * centroid + c.transform.translation;
      return c.refined && (other - moved).norm() <= kRepeatDistance &&
             largest_move(overlay, c.transform, pose) <= kRepeatDistance;
    });
  };
  RefineOptions refine_options;
  refine_options.abandon = reached;
  std::vector<std::optional<Placed>> poses(starts.size());
  tbb::parallel_for(std::size_t{0}, starts.size(), [&](std::size_t i) {
    const RefineResult refined = overlay.refine(starts[i], refine_options);
    if (refined.abandoned) return;
    Placed p;  // no cluster
    p.transform = refined.transform;
    p.overlay = refined.score;
    p.refined = true;
    poses[i] = p;
  });
  std::vector<Placed> out;
  for (const auto& p : poses) {
    if (p) out.push_back(*p);
  }
  return out;
}

/// Coarse to fine (MatchOptions::fine_top): the first `n` alignments of `placed` (one that
/// repeats an earlier start is scored where it is, as refine_consensus_head does) and the
/// principal-axes starts refined in single precision on the packed samples and scored in double
/// precision there, then the `fine_top` best of them, distinct poses only, refined again in
/// double precision from there, until the fine_top best are all so refined; the others keep
/// their single-precision pose. The head's poses are set in `placed`; the principal-axes poses
/// are returned, in the order of the starts. In parallel (TBB, one slot each): the result does
/// not depend on the thread count.
std::vector<Placed> refine_coarse_to_fine(std::vector<Placed>& placed, std::size_t n,
                                          const Refinement& refinement, int fine_top) {
  const SurfaceOverlay& overlay = refinement.overlay;
  // The alignments of `placed` refined, then the axes starts.
  const std::vector<std::size_t> head = distinct_head(placed, n, overlay);
  std::vector<RigidTransform> starts;
  starts.reserve(head.size() + refinement.axes_starts.size());
  for (const std::size_t k : head) starts.push_back(placed[k].transform);
  starts.insert(starts.end(), refinement.axes_starts.begin(), refinement.axes_starts.end());
  const PackedSampleView probe = refinement.packed_probe.view();
  std::vector<RefineResult> coarse(starts.size());
  tbb::parallel_for(std::size_t{0}, starts.size(), [&](std::size_t i) {
    coarse[i] = refinement.packed_reference->refine(probe, starts[i], overlay.options());
  });
  // Each pose scored in double precision where it stopped; then, until the fine_top best
  // distinct poses by that score are all refined in double precision, those that are not yet
  // are (a refinement can move a pose past another), so that the poses given are converged in
  // double precision, not where single precision stopped.
  std::vector<Placed> poses(starts.size());
  tbb::parallel_for(std::size_t{0}, starts.size(), [&](std::size_t i) {
    poses[i].transform = coarse[i].transform;
    poses[i].overlay = overlay.score(coarse[i].transform);
    poses[i].refined = true;
  });
  std::vector<bool> fine(starts.size(), false);
  for (;;) {
    std::vector<std::size_t> order(starts.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
      return poses[x].overlay.score > poses[y].overlay.score;
    });
    std::vector<std::size_t> best, unrefined;
    for (const std::size_t i : order) {
      if (best.size() == static_cast<std::size_t>(fine_top)) break;
      if (std::any_of(best.begin(), best.end(), [&](std::size_t b) {
            return largest_move(overlay, poses[b].transform, poses[i].transform) <= kRepeatDistance;
          })) {
        continue;
      }
      best.push_back(i);
      if (!fine[i]) unrefined.push_back(i);
    }
    if (unrefined.empty()) break;
    tbb::parallel_for(std::size_t{0}, unrefined.size(), [&](std::size_t k) {
      Placed& p = poses[unrefined[k]];
      const RefineResult refined = overlay.refine(p.transform);
      p.transform = refined.transform;
      p.overlay = refined.score;
    });
    for (const std::size_t i : unrefined) fine[i] = true;
  }
  for (std::size_t k = 0; k < head.size(); ++k) {
    Placed& p = placed[head[k]];
    p.transform = poses[k].transform;
    p.overlay = poses[k].overlay;
    p.refined = true;
  }
  return {poses.begin() + static_cast<std::ptrdiff_t>(head.size()), poses.end()};
}

/// Poses ordered best overlay score first, the distinct ones ahead of the repeats.
struct Ordered {
  std::vector<Placed> list;  ///< the distinct ones, then the repeats
  std::size_t distinct = 0;
};

/// `all` by overlay score + fit_weight atom fit, then the repeats (a pose within
/// kRepeatDistance of a better one); a principal-axes pose that repeats a better one is dropped
/// (it has no merge-tree place to keep). Ties keep the order given: first the consensus order,
/// then the axes starts.
Ordered order_distinct_then_repeats(std::vector<Placed> all, const SurfaceOverlay& overlay,
                                    double fit_weight = 0.0) {
  std::stable_sort(all.begin(), all.end(), [&](const Placed& x, const Placed& y) {
    return x.overlay.score + fit_weight * x.atom_fit > y.overlay.score + fit_weight * y.atom_fit;
  });
  Ordered out;
  std::vector<Placed> repeats;
  for (const Placed& candidate : all) {
    const bool repeat = std::any_of(out.list.begin(), out.list.end(), [&](const Placed& d) {
      return largest_move(overlay, d.transform, candidate.transform) <= kRepeatDistance;
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
}

/// The first `polish_top` distinct refined poses of `ordered` polished on the whole score,
/// their heteroatoms pulled too (RefineOptions::pull_atoms), in parallel (TBB),
/// and the list ordered again (a polished pose that comes to repeat a better one goes after
/// the distinct ones).
Ordered polish(Ordered ordered, int polish_top, const SurfaceOverlay& overlay) {
  std::vector<std::size_t> to_polish;
  for (std::size_t i = 0;
       i < ordered.distinct && to_polish.size() < static_cast<std::size_t>(polish_top); ++i) {
    if (ordered.list[i].refined) to_polish.push_back(i);
  }
  RefineOptions refine_options;
  refine_options.pull_atoms = true;
  tbb::parallel_for(std::size_t{0}, to_polish.size(), [&](std::size_t k) {
    Placed& p = ordered.list[to_polish[k]];
    const RefineResult polished = overlay.refine(p.transform, refine_options);
    p.transform = polished.transform;
    p.overlay = polished.score;
  });
  return order_distinct_then_repeats(std::move(ordered.list), overlay);
}

/// The first `polish_top` distinct poses of `ordered` polished on the two molecules' heavy atoms
/// (AtomOverlap::polish; a pose scored where it started counts as refined once moved), in
/// parallel (TBB), and scored again; every pose of the list, repeats too, given its atom fit, and
/// the list ordered again by overlay score + weight atom fit.
Ordered polish_on_atoms(Ordered ordered, const MatchOptions& options, const AtomOverlap& atoms,
                        const SurfaceOverlay& overlay) {
  const std::size_t n =
      std::min(ordered.distinct, static_cast<std::size_t>(std::max(options.polish_top, 0)));
  tbb::parallel_for(std::size_t{0}, ordered.list.size(), [&](std::size_t k) {
    Placed& p = ordered.list[k];
    if (k < n) {
      p.transform = atoms.polish(overlay, p.transform, options.atom_polish);
      p.overlay = overlay.score(p.transform);
      p.refined = true;
    }
    p.atom_fit = atoms.fit(p.transform);
  });
  return order_distinct_then_repeats(std::move(ordered.list), overlay, options.atom_polish.weight);
}

/// The first options.icp_top distinct poses of `ordered` polished by ICP (SurfaceFit::icp) and
/// scored again, in place (the order stays), and the first options.refine_top distinct poses
/// given their coverage, in parallel (TBB, one slot each).
void polish_and_cover(Ordered& ordered, const MatchOptions& options, const SurfaceFit& fit,
                      const SurfaceOverlay& overlay) {
  const std::size_t n_icp =
      std::min(ordered.distinct, static_cast<std::size_t>(std::max(options.icp_top, 0)));
  const std::size_t n_covered =
      std::min(ordered.distinct, static_cast<std::size_t>(options.refine_top));
  tbb::parallel_for(std::size_t{0}, std::max(n_icp, n_covered), [&](std::size_t k) {
    Placed& p = ordered.list[k];
    if (k < n_icp) {
      p.transform = fit.icp(p.transform, options.icp);
      p.overlay = overlay.score(p.transform);
      p.icp = true;
    }
    if (options.coverage_distance > 0.0 && k < n_covered)
      p.coverage = fit.coverage(p.transform, options.coverage_distance);
  });
}

/// The consensus order with its first options.refine_top alignments refined on the overlay and
/// moved ahead together with the refined principal-axes starts, coarse to fine with
/// options.fine_top (refine_coarse_to_fine), else each in double precision
/// (refine_consensus_head, refine_axes_starts), best overlay score first, repeats after the
/// distinct ones (order_distinct_then_repeats), the first polish_top of them polished where the
/// overlay uses atoms (polish), polished by ICP and given their coverage (polish_and_cover); the
/// rest follow in the consensus order, unscored. `probe_points` is set to the probe points the
/// poses are compared on (the overlay's sample).
std::vector<Placed> refine_and_order(
    const std::vector<RankedAlignment>& ranking, const std::vector<Cluster>& clusters,
    const harmonic::SurfaceDescriptors& reference, const harmonic::SurfaceDescriptors& probe,
    const MatchOptions& options, const std::vector<bool>* reference_allowed,
    const std::vector<bool>* probe_allowed, Eigen::Matrix3Xd& probe_points) {
  std::vector<Placed> placed = consensus_order(ranking, clusters);
  const std::optional<Refinement> refinement =
      options.refine_top == 0 ? std::nullopt
                              : prepare_refinement(reference, probe, options, reference_allowed,
                                                   probe_allowed, !placed.empty());
  if (!refinement) {  // the poses are told apart on the whole probe surface
    probe_points = sample_surface(probe.surface, mode_overlay_options(options).spacing).points;
    return placed;
  }
  const SurfaceOverlay& overlay = refinement->overlay;
  probe_points = overlay.probe_points();
  const std::size_t n_refined =
      std::min(placed.size(), static_cast<std::size_t>(options.refine_top));
  std::vector<Placed> axes_poses;
  if (refinement->packed_reference) {
    axes_poses = refine_coarse_to_fine(placed, n_refined, *refinement, options.fine_top);
  } else {
    refine_consensus_head(placed, n_refined, overlay);
    axes_poses = refine_axes_starts(
        refinement->axes_starts,
        std::vector<Placed>(placed.begin(),
                            placed.begin() + static_cast<std::ptrdiff_t>(n_refined)),
        overlay);
  }
  std::vector<Placed> candidates(placed.begin(),
                                 placed.begin() + static_cast<std::ptrdiff_t>(n_refined));
  candidates.insert(candidates.end(), axes_poses.begin(), axes_poses.end());
  Ordered ordered = order_distinct_then_repeats(std::move(candidates), overlay);
  if (overlay.uses_atoms() && options.polish_top > 0)
    ordered = polish(std::move(ordered), options.polish_top, overlay);
  if (options.mode == MatchMode::whole_surfaces && options.atom_polish.sigma > 0.0 &&
      !reference.atoms.empty() && !probe.atoms.empty()) {
    const AtomOverlap atoms(reference.atoms, probe.atoms, options.atom_polish.sigma);
    ordered = polish_on_atoms(std::move(ordered), options, atoms, overlay);
  }
  if (refinement->fit) polish_and_cover(ordered, options, *refinement->fit, overlay);
  ordered.list.insert(ordered.list.end(), placed.begin() + static_cast<std::ptrdiff_t>(n_refined),
                      placed.end());
  return ordered.list;
}

/// For each of `placed`, the index + 1 of the first earlier pose that it repeats (no point of
/// `points` moves more than kRepeatDistance between the two), 0 for a distinct one. Four points
/// (the centroid and three of the sample) are compared first: a cheap test that rules most
/// pairs out, since no point moves farther than the farthest.
std::vector<int> repeats(const std::vector<Placed>& placed, const Eigen::Matrix3Xd& points) {
  std::vector<int> repeat_of(placed.size(), 0);
  if (points.cols() == 0) return repeat_of;
  Eigen::Matrix3Xd keys(3, 4);
  keys << points.rowwise().mean(), points.col(0), points.col(points.cols() / 3),
      points.col(2 * points.cols() / 3);
  std::vector<Eigen::Matrix3Xd> moved_keys;
  moved_keys.reserve(placed.size());
  for (const Placed& p : placed) moved_keys.push_back(p.transform.apply(keys));
  std::vector<std::size_t> distinct;
  for (std::size_t k = 0; k < placed.size(); ++k) {
    for (std::size_t j : distinct) {
      if ((moved_keys[j] - moved_keys[k]).colwise().norm().maxCoeff() > kRepeatDistance) continue;
      const Eigen::Matrix3Xd a = placed[j].transform.apply(points);
      const Eigen::Matrix3Xd b = placed[k].transform.apply(points);
      if ((a - b).colwise().norm().maxCoeff() <= kRepeatDistance) {
        repeat_of[k] = static_cast<int>(j) + 1;
        break;
      }
    }
    if (repeat_of[k] == 0) distinct.push_back(k);
  }
  return repeat_of;
}

}  // namespace

OverlayOptions mode_overlay_options(const MatchOptions& asked_options) {
  const MatchOptions options = shape_only_options(asked_options);
  OverlayOptions overlay = options.overlay;
  if (options.mode == MatchMode::binding_sites) {
    overlay.chem_weight = options.site.chem_weight;
    overlay.atom_weight = 0.0;  // pockets are compared on their linings' shape
  }
  return overlay;
}

void validate(const MatchOptions& options) {
  surfcomp::options::check_all(match_option_table(), options);
  const std::string caller = "match options";
  const detail::OptionCheck check{caller, ""};
  check.require(
      options.mode == MatchMode::whole_surfaces || options.mode == MatchMode::binding_sites, "mode",
      static_cast<int>(options.mode), "whole_surfaces or binding_sites");
  detail::check_graph_options(options.graph, {caller, "graph."});
  detail::check_min_clique_size(options.min_clique_size, "min_clique_size", check);
  detail::check_clique_work(options.max_clique_work, "max_clique_work", check);
  detail::check_clique_count(options.max_cliques, "max_cliques", check);
  detail::check_correspondence_options(options.correspondences, {caller, "correspondences."});
  detail::check_clustering_options(options.clustering, {caller, "clustering."});
  detail::check_ranking_options(options.ranking, {caller, "ranking."});
  check.require(options.refine_top >= 0, "refine_top", options.refine_top, ">= 0");
  check.require(options.fine_top >= 0, "fine_top", options.fine_top, ">= 0");
  detail::check_axes_start_count(options.principal_axes_starts, "principal_axes_starts", check);
  check.require(options.polish_top >= 0, "polish_top", options.polish_top, ">= 0");
  check.require(std::isfinite(options.coverage_distance) && options.coverage_distance >= 0.0,
                "coverage_distance", options.coverage_distance, "a finite value >= 0");
  check.require(options.icp_top >= 0, "icp_top", options.icp_top, ">= 0");
  check.require(std::isfinite(options.icp.max_distance) && options.icp.max_distance > 0.0,
                "icp.max_distance", options.icp.max_distance, "a finite value > 0");
  check.require(options.icp.iterations >= 1, "icp.iterations", options.icp.iterations, ">= 1");
  check.require(std::isfinite(options.icp.tolerance) && options.icp.tolerance >= 0.0,
                "icp.tolerance", options.icp.tolerance, "a finite value >= 0");
  detail::check_atom_polish_options(options.atom_polish, {caller, "atom_polish."});
  detail::check_overlay_options(options.overlay, {caller, "overlay."});
  const SiteMatchOptions& site = options.site;
  check.require(std::isfinite(site.overlay_radius) && site.overlay_radius > 0.0,
                "site.overlay_radius", site.overlay_radius, "a finite value > 0 A");
  check.require(std::isfinite(site.chem_weight) && site.chem_weight >= 0.0, "site.chem_weight",
                site.chem_weight, "a finite value >= 0");
  check.require(std::isfinite(site.lining_weight) && site.lining_weight >= 0.0,
                "site.lining_weight", site.lining_weight, "a finite value >= 0");
  detail::check_axes_start_count(site.principal_axes_starts, "site.principal_axes_starts", check);
}

MatchOptions shape_only_options(MatchOptions options) {
  if (!options.shape_only) return options;
  options.graph.fuzzy_filter = false;
  options.correspondences.property.clear();
  options.ranking.weight_chem = 0.0;
  options.overlay.chem_weight = 0.0;
  options.overlay.atom_weight = 0.0;
  options.site.chem_weight = 0.0;
  options.site.lining_weight = 0.0;
  options.atom_polish.sigma = 0.0;
  return options;
}

void require_match_properties(const mesh::Surface& surface) {
  for (const char* name : {mesh::property::esp, mesh::property::lp}) {
    if (surface.has_property(name)) continue;
    throw InputError(surface.source() + ": the surface has no vertex property '" + name +
                     "', which the match compares (give the mesh's molecule with " +
                     options::named("molecule") +
                     ", "
                     "or a mesh file with 'esp' and 'lp' vertex properties)");
  }
}

MatchResult match_surfaces(const harmonic::SurfaceDescriptors& reference,
                           const harmonic::SurfaceDescriptors& probe,
                           const MatchOptions& asked_options,
                           const std::vector<bool>* reference_allowed,
                           const std::vector<bool>* probe_allowed) {
  validate(asked_options);
  const MatchOptions options = shape_only_options(asked_options);
  const auto& ga = reference.options.image;
  const auto& gb = probe.options.image;
  if (ga.rings != gb.rings || ga.sectors != gb.sectors) {
    throw InputError(reference.surface.source() + " and " + probe.surface.source() +
                     ": the images were built on different grids (" + std::to_string(ga.rings) +
                     " rings x " + std::to_string(ga.sectors) + " sectors and " +
                     std::to_string(gb.rings) + " rings x " + std::to_string(gb.sectors) +
                     " sectors); rebuild them with the same image grid");
  }
  if (!options.shape_only) {
    require_match_properties(reference.surface);
    require_match_properties(probe.surface);
  }
  MatchResult result;
  Stopwatch clock;
  const AssociationGraph graph =
      build_association_graph(reference, probe, options.graph, reference_allowed, probe_allowed);
  result.trace = graph.trace;
  for (const TraceStage& stage : graph.trace)
    result.timing_ms.emplace_back("graph: " + stage.stage, stage.milliseconds);

  clock.restart();
  CliqueOptions clique_options;
  clique_options.min_size = options.min_clique_size;
  clique_options.max_work = options.max_clique_work;
  clique_options.max_cliques = options.max_cliques;
  const CliqueResult found = maximal_cliques(graph, clique_options);
  const std::vector<std::vector<int>>& cliques = found.cliques;
  result.cliques = cliques.size();
  result.cliques_complete = found.complete;
  result.clique_work = found.work;
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
  result.timing_ms.emplace_back("cliques", clock.elapsed_ms());

  clock.restart();
  const std::vector<Cluster> clusters = cluster_alignments(
      pair_cliques, reference, probe, options.clustering, options.correspondences);
  result.timing_ms.emplace_back("fits and merging", clock.elapsed_ms());

  clock.restart();
  const std::vector<RankedAlignment> ranking = rank_alignments(clusters, options.ranking);
  result.timing_ms.emplace_back("ranking", clock.elapsed_ms());

  clock.restart();
  Eigen::Matrix3Xd probe_points;
  const std::vector<Placed> placed = refine_and_order(
      ranking, clusters, reference, probe, options, reference_allowed, probe_allowed, probe_points);
  const std::vector<int> repeat_of = repeats(placed, probe_points);
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
    a.atom_fit = p.atom_fit;
    a.coverage = p.coverage;
    a.icp = p.icp;
    a.repeat_of = repeat_of[k];
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
  result.timing_ms.emplace_back("overlay refinement", clock.elapsed_ms());
  return result;
}

}  // namespace surfcomp::matching
