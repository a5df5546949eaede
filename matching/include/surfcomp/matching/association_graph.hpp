// The association graph of two surfaces' critical points and the four filters that thin it
// (method §5.1-5.5). Nodes are pairs of same-type critical points
// (peak-peak, valley-valley); the fuzzy and image filters remove nodes, the distance filter
// creates the edges, the overlap filter removes edges. Each filter is its own function, so that
// it can be tested and traced alone; build_association_graph runs them in the seed's order.
#pragma once

#include "surfcomp/harmonic/surface_descriptors.hpp"

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::matching {

/// A node of the association graph: critical point `a` of surface A paired with critical
/// point `b` of surface B (indices into SurfaceDescriptors::critical_points), and what the node
/// filters learnt about the pair.
struct PointPair {
  int a = -1, b = -1;
  /// Fuzzy similarity (fuzzy.hpp, in [0, 1]) of the autoscaled ESP and LP of the two points;
  /// NaN when either surface lacks the property; 0 until fuzzy_filter ran.
  double fuzzy_esp = 0, fuzzy_lp = 0;
  /// Best image correlation (harmonic::compare_images of a's image with b's), in [-1, 1]; -1
  /// when either point has no image (status != ok) or no rotation overlaps enough.
  double image_correlation = 0;
  /// The rotation carrying a's image onto b's (ImageMatch::angle_degrees, [0, 360)): a
  /// direction at polar angle phi in a's harmonic map corresponds to phi + angle in b's.
  double image_angle_degrees = 0;
  int image_shift = 0;  ///< the same rotation in angular grid steps (ImageMatch::shift)
};

/// The filter options (method §8 starting values [choice], except F).
struct GraphOptions {
  /// Default 0.3 (method §8: 0.5). F: a pair is dropped when the fuzzy similarity of its
  /// autoscaled ESP or of its LP is below F (a property missing on either surface is not
  /// filtered). In [0, 1]. With the fuzzy Jaccard similarity (fuzzy.hpp) F is roughly
  /// (1 - dz) / (1 + dz) for z-scores dz apart, so 0.5 allows dz <= 1/3 and 0.3 about
  /// dz <= 0.54; 0.5 drops most true pairs (docs/decisions.md#fuzzy-threshold).
  double fuzzy_threshold = 0.3;
  /// Default 0.5 (method §8). R: a pair is dropped when its best image correlation is below R.
  /// In [-1, 1] (--image-threshold). See docs/decisions.md#image-threshold.
  double image_threshold = 0.5;
  /// Default 1.5 A. t: two pairs are joined when |d_A - d_B| <= t (method §5.4). Finite, >= 0.
  double distance_tolerance = 1.5;
  /// Default 2.0 A. d_min: ... and d_A >= d_min and d_B >= d_min. Finite, >= 0.
  double min_distance = 2.0;
  /// Default 30 degrees. j_tol: an edge is dropped when neither heading difference (method §5.5)
  /// is within it. In [0, 180].
  double overlap_tolerance_degrees = 30.0;
  /// Default 20000 (docs/decisions.md#clique-budget). The most nodes the graph may keep after
  /// the image filter: the distance filter compares every pair of nodes, and the clique search
  /// holds n^2 / 8 bytes of adjacency bitsets, so build_association_graph refuses a larger
  /// graph (InputError) rather than run for minutes through gigabytes. > 0.
  std::size_t max_nodes = 20000;
  /// Default true each: run the filter. A filter turned off keeps everything (its trace stage
  /// is still recorded, with unchanged counts); the image comparisons are made in any case,
  /// since the overlap filter and the alignments need the angles.
  bool fuzzy_filter = true;
  bool image_filter = true;
  bool overlap_filter = true;
};

/// The graph size after one stage (method §5.6-5.7).
struct TraceStage {
  /// "critical points", "fuzzy", "image", "distance" or "overlap".
  std::string stage;
  /// Nodes and edges after the stage. Before the distance filter creates edges, `edges` is the
  /// edge count of the complete association graph on the nodes (count_complete_edges), as the
  /// reference trace reports it (method §5.7); the graph itself is never materialised.
  std::size_t nodes = 0, edges = 0;
  double milliseconds = 0;  ///< wall-clock time of the stage
};

/// The association graph after all filters.
struct AssociationGraph {
  std::vector<PointPair> nodes;            ///< sorted by (a, b)
  std::vector<std::pair<int, int>> edges;  ///< node indices (i < j), sorted
  std::vector<TraceStage> trace;           ///< one entry per stage, in order
};

/// The initial nodes (method §5.1): every pair of a peak of A with a peak of B and of a valley of
/// A with a valley of B, sorted by (a, b). With a site restriction (method §7), only critical
/// points i with (*a_allowed)[i] (resp. b) enter; nullptr allows all. Throws InputError when a
/// restriction's size differs from the number of critical points.
std::vector<PointPair> initial_pairs(const harmonic::SurfaceDescriptors& a,
                                     const harmonic::SurfaceDescriptors& b,
                                     const std::vector<bool>* a_allowed = nullptr,
                                     const std::vector<bool>* b_allowed = nullptr);

/// The number of edges of the complete association graph on `nodes`: unordered pairs of
/// distinct nodes that share no critical point on either surface, counted as
/// C(n, 2) - sum_i C(#nodes using A's point i, 2) - sum_j C(#nodes using B's point j, 2).
std::size_t count_complete_edges(const std::vector<PointPair>& nodes);

/// The fuzzy filter (method §5.2): fills fuzzy_esp and fuzzy_lp of every node from the autoscaled
/// point values (fuzzy.hpp, autoscaled_point_values) and keeps the nodes whose similarity is
/// >= threshold for ESP and for LP; a NaN similarity (property missing) passes. Order kept.
/// Throws InputError when a node's indices are outside the critical point lists.
std::vector<PointPair> fuzzy_filter(std::vector<PointPair> nodes,
                                    const harmonic::SurfaceDescriptors& a,
                                    const harmonic::SurfaceDescriptors& b, double threshold);

/// Compares the images of every node's two points (each image prepared once, comparisons in
/// parallel with TBB into per-node slots, so the result does not depend on the thread count)
/// and records the correlation, angle and shift; a node whose point has no image (status !=
/// ok) gets correlation -1, angle 0 and shift 0. Throws InputError for bad node indices or
/// images of different grid sizes.
std::vector<PointPair> with_image_matches(std::vector<PointPair> nodes,
                                          const harmonic::SurfaceDescriptors& a,
                                          const harmonic::SurfaceDescriptors& b);

/// The harmonic shape image filter (method §5.3): with_image_matches, then keeps the nodes whose
/// two points both have images and whose best correlation is >= threshold. Order kept.
std::vector<PointPair> image_filter(std::vector<PointPair> nodes,
                                    const harmonic::SurfaceDescriptors& a,
                                    const harmonic::SurfaceDescriptors& b, double threshold);

/// The distance filter (method §5.4), which creates the edges: nodes i < j are joined
/// when they share no critical point (a_i != a_j and b_i != b_j), d_A = |p(a_i) - p(a_j)| and
/// d_B = |p(b_i) - p(b_j)| (critical point positions, A) satisfy |d_A - d_B| <= tolerance and
/// d_A, d_B >= min_distance. Returns (i, j) with i < j, sorted. Throws InputError for bad node
/// indices, OptionError for a tolerance or min_distance not finite and >= 0.
std::vector<std::pair<int, int>> distance_filter(const std::vector<PointPair>& nodes,
                                                 const harmonic::SurfaceDescriptors& a,
                                                 const harmonic::SurfaceDescriptors& b,
                                                 double tolerance, double min_distance);

/// The bearing (degrees in [0, 360), counter-clockwise from the +u axis of the harmonic map)
/// from critical point `from` towards the point `to` of the same surface, read in from's
/// harmonic map [choice; the seed's "closest point on the border" of the projected CP axis]:
/// the polar angle of the uv of `to`'s own vertex when that vertex lies in from's patch, else
/// the polar angle of the outer-border vertex of from's patch nearest in 3D to to.position
/// (ties: the earlier vertex of the border walk). Throws InputError when from has no image
/// (status != ok) or to's vertex is from's centre.
double patch_bearing_degrees(const harmonic::CriticalPointDescriptor& from,
                             const mesh::CriticalPoint& to);

/// The smaller angle between two directions given in degrees: |x - y| reduced mod 360 into
/// [0, 180].
double angular_difference_degrees(double x, double y);

/// The overlap filter (method §5.5). For an edge between pp1 = (A1, B1) and
/// pp2 = (A2, B2): a1 = bearing of A2 in A1's map, b1 = bearing of B2 in B1's map minus pp1's
/// image angle (so that both are in A1's image frame, the alignment axis of pp1), and likewise
/// a2 (A1 in A2's map) and b2 (B1 in B2's map minus pp2's image angle). The edge is kept when
/// angular_difference_degrees(b1, a1) <= tolerance_degrees or
/// angular_difference_degrees(b2, a2) <= tolerance_degrees. An edge with a node whose points
/// lack images cannot be judged and is kept. Nodes must carry their image angles
/// (with_image_matches). Order kept. Throws InputError for bad node or edge indices,
/// OptionError for a tolerance outside [0, 180].
std::vector<std::pair<int, int>> overlap_filter(const std::vector<PointPair>& nodes,
                                                const std::vector<std::pair<int, int>>& edges,
                                                const harmonic::SurfaceDescriptors& a,
                                                const harmonic::SurfaceDescriptors& b,
                                                double tolerance_degrees);

/// The association graph of a and b after all filters, in the seed's order: initial_pairs
/// (restricted to the allowed points), fuzzy_filter, image_filter, distance_filter,
/// overlap_filter, with a trace entry per stage. Nodes removed by a filter are gone; edges
/// refer to the surviving nodes. Throws OptionError for options outside their domains,
/// InputError when more than options.max_nodes nodes pass the image filter, and what the
/// stages throw. Nearly all of its time goes to the image comparisons.
AssociationGraph build_association_graph(const harmonic::SurfaceDescriptors& a,
                                         const harmonic::SurfaceDescriptors& b,
                                         const GraphOptions& options = {},
                                         const std::vector<bool>* a_allowed = nullptr,
                                         const std::vector<bool>* b_allowed = nullptr);

}  // namespace surfcomp::matching
