#include "surfcomp/matching/association_graph.hpp"

#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/matching/fuzzy.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <tuple>

namespace surfcomp::matching {
namespace {

using harmonic::PatchStatus;
using harmonic::SurfaceDescriptors;

constexpr double kPi = 3.14159265358979323846;

void check_nodes(const std::vector<PointPair>& nodes, const SurfaceDescriptors& a,
                 const SurfaceDescriptors& b, const char* where) {
  const int na = static_cast<int>(a.critical_points.size());
  const int nb = static_cast<int>(b.critical_points.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const PointPair& node = nodes[i];
    if (node.a < 0 || node.a >= na || node.b < 0 || node.b >= nb) {
      throw InputError(std::string(where) + ": node " + std::to_string(i) + " pairs (" +
                       std::to_string(node.a) + ", " + std::to_string(node.b) +
                       "), expected indices in [0, " + std::to_string(na) + ") x [0, " +
                       std::to_string(nb) + ")");
    }
  }
}

void check_edges(const std::vector<std::pair<int, int>>& edges, std::size_t n_nodes,
                 const char* where) {
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [i, j] = edges[e];
    if (i < 0 || j < 0 || static_cast<std::size_t>(i) >= n_nodes ||
        static_cast<std::size_t>(j) >= n_nodes || i == j) {
      throw InputError(std::string(where) + ": edge " + std::to_string(e) + " joins nodes " +
                       std::to_string(i) + " and " + std::to_string(j) +
                       ", expected two distinct indices in [0, " + std::to_string(n_nodes) + ")");
    }
  }
}

bool has_image(const SurfaceDescriptors& d, int point) {
  return d.critical_points[static_cast<std::size_t>(point)].status == PatchStatus::ok;
}

std::size_t pairs_of(std::size_t n) { return n < 2 ? 0 : n * (n - 1) / 2; }

/// Bearings between critical points of one surface, computed on first use.
class BearingCache {
 public:
  explicit BearingCache(const SurfaceDescriptors& d)
      : descriptors_(d),
        n_(d.critical_points.size()),
        values_(n_ * n_, std::numeric_limits<double>::quiet_NaN()) {}

  double operator()(int from, int to) {
    double& value = values_[static_cast<std::size_t>(from) * n_ + static_cast<std::size_t>(to)];
    if (std::isnan(value)) {
      value =
          patch_bearing_degrees(descriptors_.critical_points[static_cast<std::size_t>(from)],
                                descriptors_.critical_points[static_cast<std::size_t>(to)].point);
    }
    return value;
  }

 private:
  const SurfaceDescriptors& descriptors_;
  std::size_t n_;
  std::vector<double> values_;
};

}  // namespace

std::vector<PointPair> initial_pairs(const SurfaceDescriptors& a, const SurfaceDescriptors& b,
                                     const std::vector<bool>* a_allowed,
                                     const std::vector<bool>* b_allowed) {
  for (const auto& [d, allowed, name] :
       {std::tuple{&a, a_allowed, "A"}, std::tuple{&b, b_allowed, "B"}}) {
    if (allowed && allowed->size() != d->critical_points.size()) {
      throw InputError(std::string("association graph: the site restriction of surface ") + name +
                       " has " + std::to_string(allowed->size()) +
                       " entries, expected one per critical point (" +
                       std::to_string(d->critical_points.size()) + ")");
    }
  }
  std::vector<PointPair> nodes;
  for (std::size_t i = 0; i < a.critical_points.size(); ++i) {
    if (a_allowed && !(*a_allowed)[i]) continue;
    for (std::size_t j = 0; j < b.critical_points.size(); ++j) {
      if (b_allowed && !(*b_allowed)[j]) continue;
      if (a.critical_points[i].point.type != b.critical_points[j].point.type) continue;
      PointPair node;
      node.a = static_cast<int>(i);
      node.b = static_cast<int>(j);
      nodes.push_back(node);
    }
  }
  return nodes;
}

std::size_t count_complete_edges(const std::vector<PointPair>& nodes) {
  int max_a = -1, max_b = -1;
  for (const PointPair& node : nodes) {
    if (node.a < 0 || node.b < 0) {
      throw InputError("association graph: a node pairs (" + std::to_string(node.a) + ", " +
                       std::to_string(node.b) + "), expected non-negative indices");
    }
    max_a = std::max(max_a, node.a);
    max_b = std::max(max_b, node.b);
  }
  std::vector<std::size_t> uses_a(static_cast<std::size_t>(max_a + 1), 0);
  std::vector<std::size_t> uses_b(static_cast<std::size_t>(max_b + 1), 0);
  for (const PointPair& node : nodes) {
    ++uses_a[static_cast<std::size_t>(node.a)];
    ++uses_b[static_cast<std::size_t>(node.b)];
  }
  std::size_t sharing = 0;
  for (const std::size_t n : uses_a) sharing += pairs_of(n);
  for (const std::size_t n : uses_b) sharing += pairs_of(n);
  return pairs_of(nodes.size()) - sharing;
}

std::vector<PointPair> fuzzy_filter(std::vector<PointPair> nodes, const SurfaceDescriptors& a,
                                    const SurfaceDescriptors& b, double threshold) {
  check_nodes(nodes, a, b, "fuzzy_filter");
  const std::vector<double> esp_a = autoscaled_point_values(a, mesh::property::esp);
  const std::vector<double> esp_b = autoscaled_point_values(b, mesh::property::esp);
  const std::vector<double> lp_a = autoscaled_point_values(a, mesh::property::lp);
  const std::vector<double> lp_b = autoscaled_point_values(b, mesh::property::lp);
  std::vector<PointPair> kept;
  kept.reserve(nodes.size());
  for (PointPair& node : nodes) {
    const auto i = static_cast<std::size_t>(node.a);
    const auto j = static_cast<std::size_t>(node.b);
    node.fuzzy_esp = fuzzy_similarity(esp_a[i], esp_b[j]);
    node.fuzzy_lp = fuzzy_similarity(lp_a[i], lp_b[j]);
    // A NaN similarity (property missing) compares false with "<" and passes.
    if (node.fuzzy_esp < threshold || node.fuzzy_lp < threshold) continue;
    kept.push_back(node);
  }
  return kept;
}

std::vector<PointPair> with_image_matches(std::vector<PointPair> nodes, const SurfaceDescriptors& a,
                                          const SurfaceDescriptors& b) {
  check_nodes(nodes, a, b, "with_image_matches");
  // Prepare each image that some node needs, once.
  auto prepare = [&nodes](const SurfaceDescriptors& d, bool side_a) {
    std::vector<char> needed(d.critical_points.size(), 0);
    for (const PointPair& node : nodes) {
      const int point = side_a ? node.a : node.b;
      if (has_image(d, point)) needed[static_cast<std::size_t>(point)] = 1;
    }
    std::vector<std::unique_ptr<harmonic::PreparedImage>> prepared(d.critical_points.size());
    tbb::parallel_for(std::size_t{0}, prepared.size(), [&](std::size_t i) {
      if (needed[i]) {
        prepared[i] = std::make_unique<harmonic::PreparedImage>(d.critical_points[i].image);
      }
    });
    return prepared;
  };
  const auto prepared_a = prepare(a, true);
  const auto prepared_b = prepare(b, false);
  tbb::parallel_for(std::size_t{0}, nodes.size(), [&](std::size_t k) {
    PointPair& node = nodes[k];
    const auto& image_a = prepared_a[static_cast<std::size_t>(node.a)];
    const auto& image_b = prepared_b[static_cast<std::size_t>(node.b)];
    if (!image_a || !image_b) {
      node.image_correlation = -1.0;
      node.image_angle_degrees = 0.0;
      node.image_shift = 0;
      return;
    }
    const harmonic::ImageMatch match = harmonic::compare_images(*image_a, *image_b);
    node.image_correlation = match.correlation;
    node.image_angle_degrees = match.angle_degrees;
    node.image_shift = match.shift;
  });
  return nodes;
}

std::vector<PointPair> image_filter(std::vector<PointPair> nodes, const SurfaceDescriptors& a,
                                    const SurfaceDescriptors& b, double threshold) {
  nodes = with_image_matches(std::move(nodes), a, b);
  std::vector<PointPair> kept;
  kept.reserve(nodes.size());
  for (const PointPair& node : nodes) {
    if (has_image(a, node.a) && has_image(b, node.b) && node.image_correlation >= threshold) {
      kept.push_back(node);
    }
  }
  return kept;
}

std::vector<std::pair<int, int>> distance_filter(const std::vector<PointPair>& nodes,
                                                 const SurfaceDescriptors& a,
                                                 const SurfaceDescriptors& b, double tolerance,
                                                 double min_distance) {
  detail::check_distance_filter(tolerance, min_distance, {"distance_filter", ""});
  check_nodes(nodes, a, b, "distance_filter");
  auto position = [](const SurfaceDescriptors& d, int point) -> const Eigen::Vector3d& {
    return d.critical_points[static_cast<std::size_t>(point)].point.position;
  };
  std::vector<std::pair<int, int>> edges;
  const int n = static_cast<int>(nodes.size());
  for (int i = 0; i < n; ++i) {
    const PointPair& p = nodes[static_cast<std::size_t>(i)];
    for (int j = i + 1; j < n; ++j) {
      const PointPair& q = nodes[static_cast<std::size_t>(j)];
      if (p.a == q.a || p.b == q.b) continue;
      const double d_a = (position(a, p.a) - position(a, q.a)).norm();
      const double d_b = (position(b, p.b) - position(b, q.b)).norm();
      if (d_a < min_distance || d_b < min_distance) continue;
      if (std::abs(d_a - d_b) > tolerance) continue;
      edges.emplace_back(i, j);
    }
  }
  return edges;
}

double patch_bearing_degrees(const harmonic::CriticalPointDescriptor& from,
                             const mesh::CriticalPoint& to) {
  if (from.status != PatchStatus::ok) {
    throw InputError("overlap filter: the critical point at vertex " +
                     std::to_string(from.point.vertex) + " has no harmonic map (status " +
                     std::to_string(static_cast<int>(from.status)) + "), expected status ok");
  }
  const mesh::Patch& patch = from.patch;
  const Eigen::MatrixX2d& uv = from.map.uv;
  const auto found =
      std::lower_bound(patch.surface_vertex.begin(), patch.surface_vertex.end(), to.vertex);
  int target = -1;
  if (found != patch.surface_vertex.end() && *found == to.vertex) {
    target = static_cast<int>(found - patch.surface_vertex.begin());
  } else {
    double best = std::numeric_limits<double>::infinity();
    for (const int v : patch.outer_boundary) {
      const double d = (patch.positions.row(v).transpose() - to.position).squaredNorm();
      if (d < best) {
        best = d;
        target = v;
      }
    }
  }
  if (target < 0 || target == patch.center) {
    throw InputError("overlap filter: the target vertex " + std::to_string(to.vertex) +
                     " is the centre of the patch (or the patch has no border), expected "
                     "another point");
  }
  const Eigen::Vector2d direction = uv.row(target) - uv.row(patch.center);
  double degrees = std::atan2(direction.y(), direction.x()) * 180.0 / kPi;
  if (degrees < 0.0) degrees += 360.0;
  return degrees >= 360.0 ? 0.0 : degrees;
}

double angular_difference_degrees(double x, double y) {
  double d = std::fmod(std::abs(x - y), 360.0);
  return d > 180.0 ? 360.0 - d : d;
}

std::vector<std::pair<int, int>> overlap_filter(const std::vector<PointPair>& nodes,
                                                const std::vector<std::pair<int, int>>& edges,
                                                const SurfaceDescriptors& a,
                                                const SurfaceDescriptors& b,
                                                double tolerance_degrees) {
  detail::check_overlap_tolerance(tolerance_degrees, {"overlap_filter", ""});
  check_nodes(nodes, a, b, "overlap_filter");
  check_edges(edges, nodes.size(), "overlap_filter");
  BearingCache bearing_a(a), bearing_b(b);
  std::vector<std::pair<int, int>> kept;
  kept.reserve(edges.size());
  for (const auto& edge : edges) {
    const PointPair& p1 = nodes[static_cast<std::size_t>(edge.first)];
    const PointPair& p2 = nodes[static_cast<std::size_t>(edge.second)];
    if (!has_image(a, p1.a) || !has_image(b, p1.b) || !has_image(a, p2.a) || !has_image(b, p2.b)) {
      kept.push_back(edge);
      continue;
    }
    const double a1 = bearing_a(p1.a, p2.a);
    const double b1 = bearing_b(p1.b, p2.b) - p1.image_angle_degrees;
    const double a2 = bearing_a(p2.a, p1.a);
    const double b2 = bearing_b(p2.b, p1.b) - p2.image_angle_degrees;
    if (angular_difference_degrees(b1, a1) <= tolerance_degrees ||
        angular_difference_degrees(b2, a2) <= tolerance_degrees) {
      kept.push_back(edge);
    }
  }
  return kept;
}

AssociationGraph build_association_graph(const SurfaceDescriptors& a, const SurfaceDescriptors& b,
                                         const GraphOptions& options,
                                         const std::vector<bool>* a_allowed,
                                         const std::vector<bool>* b_allowed) {
  const GraphOptions& p = options;
  detail::check_graph_options(p, {"association graph", ""});

  AssociationGraph graph;
  auto start = std::chrono::steady_clock::now();
  auto record = [&](const char* stage, bool complete) {
    const auto now = std::chrono::steady_clock::now();
    TraceStage entry;
    entry.stage = stage;
    entry.nodes = graph.nodes.size();
    entry.edges = complete ? count_complete_edges(graph.nodes) : graph.edges.size();
    entry.milliseconds = std::chrono::duration<double, std::milli>(now - start).count();
    graph.trace.push_back(entry);
    start = std::chrono::steady_clock::now();
  };

  graph.nodes = initial_pairs(a, b, a_allowed, b_allowed);
  record("critical points", true);
  if (p.fuzzy_filter) graph.nodes = fuzzy_filter(std::move(graph.nodes), a, b, p.fuzzy_threshold);
  record("fuzzy", true);
  graph.nodes = p.image_filter ? image_filter(std::move(graph.nodes), a, b, p.image_threshold)
                               : with_image_matches(std::move(graph.nodes), a, b);
  record("image", true);
  if (graph.nodes.size() > p.max_nodes) {
    throw InputError(a.surface.source() + " and " + b.surface.source() + ": " +
                     std::to_string(graph.nodes.size()) +
                     " critical-point pairs pass the fuzzy and image filters, more than "
                     "the limit of " +
                     std::to_string(p.max_nodes) +
                     " (the distance filter and the clique search grow with the square of "
                     "that count); match binding sites, raise " +
                     options::named("image_threshold") + " or raise " +
                     options::named("max_graph_nodes"));
  }
  graph.edges = distance_filter(graph.nodes, a, b, p.distance_tolerance, p.min_distance);
  record("distance", false);
  if (p.overlap_filter) {
    graph.edges = overlap_filter(graph.nodes, graph.edges, a, b, p.overlap_tolerance_degrees);
  }
  record("overlap", false);
  return graph;
}

}  // namespace surfcomp::matching
