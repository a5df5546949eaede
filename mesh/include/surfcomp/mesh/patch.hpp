// Surface patches: the piece of a surface within an on-surface radius of a centre vertex, cut
// out as a triangulated disk (with holes) whose border can be walked once, counter-clockwise
// (method §3.1). The harmonic map (method §4) embeds it.
//
// The steps are separate functions over sorted lists of surface vertex and face indices, so
// that each can be tested alone; extract_patch composes them. Every function here is const
// on the surface and uses no global state, so patches of one surface may be extracted in
// parallel.
#pragma once

#include "surfcomp/mesh/geodesic.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace surfcomp::mesh {

struct PatchOptions {
  /// Default 5.0 A. The patch radius: on-surface distance (by `distance`) from the centre.
  /// method §3 [choice]: about 5 A for ligands, larger for protein sites. Finite and
  /// > 0.
  double radius = 5.0;
  /// Default 0.05 (method §3.1: 5 %). Vertices up to radius * (1 + margin) that share an edge with
  /// a vertex within the radius are selected too (step 3). Finite and >= 0.
  double margin = 0.05;
  /// Default dijkstra (method §3.1, step 2). How the on-surface distances of steps 2-3 are
  /// computed; fast_marching gives round patches where Dijkstra's balls are polygons.
  /// describe_surface uses fast_marching by default (harmonic::DescriptorOptions::patch;
  /// docs/decisions.md#patch-distances).
  GeodesicMethod distance = GeodesicMethod::dijkstra;
};

/// A patch: a connected triangle mesh, manifold at every vertex, whose border loops are passed
/// once each. It is a topological disk with `holes.size()` holes (Euler characteristic
/// 1 - #holes, genus 0) unless the radius exceeds half the length of a loop around a handle of
/// the surface (a tunnel): then `genus` > 0 and the harmonic map, which needs a disk, does not
/// apply. Patch-local vertex i is surface vertex surface_vertex[i]; patch vertices are sorted
/// by surface index.
struct Patch {
  int center = -1;                  ///< patch-local index of the centre vertex
  std::vector<int> surface_vertex;  ///< step 7: surface vertex index of each patch vertex
  Eigen::MatrixX3d positions;       ///< #patch vertices by 3, A, copied from the surface
  Eigen::MatrixX3i faces;           ///< patch-local triangles, same orientation as on the surface
  Eigen::VectorXd distance;         ///< on-surface distance from the centre, A
  /// The outer border: patch-local vertices joined by border edges, each once, starting at the
  /// lowest index and walked counter-clockwise seen from outside (the side the faces'
  /// counter-clockwise order points to), i.e. with the patch on the left: each step a -> b is a
  /// border edge that some patch triangle traverses as a -> b. It is the border loop of the
  /// largest perimeter (ties: the loop with the lowest vertex index); see boundary_loops.
  std::vector<int> outer_boundary;
  /// The other border loops (left unfilled, method §3), each walked with the patch on its left
  /// (clockwise around the hole seen from outside), ordered by their lowest vertex index.
  std::vector<std::vector<int>> holes;
  /// Handles of the patch: (2 - V + E - F - #border loops) / 2; 0 for a disk with holes.
  int genus = 0;
};

/// Step 1: the surface vertices within Euclidean distance `radius` (A) of `center_vertex`,
/// sorted. No vertex outside it can have an on-surface distance <= radius, because a path on
/// the surface of length L never leaves the ball of radius L. Throws InputError for a vertex out of
/// range, OptionError for a radius that is not finite and >= 0.
std::vector<int> preselect_euclidean(const Surface& surface, int center_vertex, double radius);

/// Step 2: on-surface distances (A) by `method` (method §3.1: Dijkstra) from `center_vertex`
/// over paths inside the `preselected` vertices (sorted, unique, containing the centre), up to
/// `max_distance`, as (vertex, distance) pairs sorted by vertex. Throws InputError for indices out
/// of range, unsorted or without the centre, OptionError for a max_distance that is not finite and
/// >= 0.
std::vector<std::pair<int, double>> patch_distances(
    const Surface& surface, int center_vertex, const std::vector<int>& preselected,
    double max_distance, GeodesicMethod method = GeodesicMethod::dijkstra);

/// Step 3: the vertices with distance <= radius, plus those with distance <= radius * (1 +
/// margin) that share an edge with one of them (method §3.1, step 3), sorted. `distances` as
/// patch_distances returns them. Throws InputError for indices out of range or unsorted,
/// OptionError for radius or margin outside their domain.
std::vector<int> select_within_radius(const Surface& surface,
                                      const std::vector<std::pair<int, double>>& distances,
                                      double radius, double margin);

/// Step 4: the surface faces whose three vertices are all in `selected` (sorted, unique),
/// sorted by face index. Throws InputError for indices out of range or unsorted.
std::vector<int> faces_with_three_selected(const Surface& surface,
                                           const std::vector<int>& selected);

/// Step 5, one pass: `faces` (sorted, unique face indices) without the dangling triangles,
/// those with more than one border edge (an edge is a border edge when the face across it is
/// not in `faces` or does not exist). Removing them exposes new border edges, so the pass is
/// repeated (refine_patch) until none is left. Throws InputError for bad indices.
std::vector<int> remove_dangling_triangles(const Surface& surface, const std::vector<int>& faces);

/// Step 6: the `vertices` (sorted, unique) that belong to at least one of `faces`, sorted.
/// Throws InputError for bad indices.
std::vector<int> remove_isolated_vertices(const Surface& surface, const std::vector<int>& vertices,
                                          const std::vector<int>& faces);

/// Makes every vertex of `faces` manifold: a vertex where the patch's triangles form more than
/// one fan (a "bow-tie", where the border passes twice) keeps only its largest fan (most
/// triangles; ties: the fan with the lowest face index); the triangles of its other fans at
/// that vertex are removed. Vertices are resolved in increasing index order. Returns the
/// remaining faces, sorted. Throws InputError for bad indices.
std::vector<int> resolve_nonmanifold_vertices(const Surface& surface,
                                              const std::vector<int>& faces);

/// The faces of `faces` that are edge-connected (through shared edges) to the lowest-index
/// face of `faces` incident to `vertex`, sorted; empty when no face is incident to `vertex`.
/// Throws InputError for bad indices.
std::vector<int> keep_component(const Surface& surface, const std::vector<int>& faces, int vertex);

/// A patch under construction: sorted surface vertex and face indices.
struct PatchSelection {
  std::vector<int> vertices;
  std::vector<int> faces;
};

/// Steps 5 and 6 repeated until consistency, together with resolve_nonmanifold_vertices and
/// keep_component(center_vertex): afterwards every face has at most one border edge, every
/// vertex is in a face and on at most one border loop, which it passes once, and the faces
/// are edge-connected and contain the centre (unless no face is left). Throws InputError for
/// bad indices.
PatchSelection refine_patch(const Surface& surface, PatchSelection selection, int center_vertex);

/// The border loops of `faces` (surface vertex indices).
struct BoundaryLoops {
  std::vector<int> outer;               ///< empty when the faces form a closed surface
  std::vector<std::vector<int>> holes;  ///< ordered by their lowest vertex index
};

/// The border loops of `faces` (a refined selection), each walked along the border edges in
/// the direction of their faces' halfedges (the faces on the left, so counter-clockwise
/// around the patch seen from outside), starting at its lowest vertex index. The outer loop is
/// the one of the largest perimeter (sum of Euclidean edge lengths, A); ties go to the loop
/// with the lowest vertex index. On a patch all of whose border vertices lie at about the
/// patch radius, a hole encloses a region that does not contain the centre (the foot of a
/// pillar), while the outer border encircles the centre, which makes it the longest loop.
/// Throws TopologyError when a vertex has more than one outgoing border edge (a bow-tie;
/// run refine_patch first), InputError for bad indices.
BoundaryLoops boundary_loops(const Surface& surface, const std::vector<int>& faces);

/// Step 7 and the borders: the patch made of `faces` (a refined selection containing
/// center_vertex), with its vertices' back-references, positions and distances looked up in
/// `distances` (as patch_distances returns them). Throws InputError when a patch vertex has no
/// distance or center_vertex is not in a face, TopologyError as boundary_loops.
Patch assemble_patch(const Surface& surface, int center_vertex, const std::vector<int>& faces,
                     const std::vector<std::pair<int, double>>& distances);

/// The patch of on-surface radius options.radius around `center_vertex` (method §3): steps 1-4,
/// refine_patch, assemble_patch. The Euclidean preselection and the on-surface distances
/// (options.distance) run to radius * (1 + margin). Throws TopologyError for a surface without
/// vertices or faces, or when no triangle is left around the centre (radius shorter than its
/// edges), InputError when center_vertex is out of range, OptionError for options outside their
/// domain.
/// Deterministic, const on the surface, thread-safe.
Patch extract_patch(const Surface& surface, int center_vertex, const PatchOptions& options = {});

/// Scales a patch by `factor`, as a change of length unit: its positions and on-surface
/// distances times it. `factor` is not checked.
void scale_patch(Patch& patch, double factor);

/// extract_patch of `surface` described in the length unit `unit` (the length of its
/// coordinates that options.radius counts as 1 A, mesh::general_mesh_unit): cut on its copy
/// scaled by 1 / unit and given back in its coordinates (scale_patch). With
/// harmonic::DescriptorOptions::patch, the patch describe_surface cuts around that vertex of a
/// general mesh described in that unit. Throws as extract_patch; InputError for a unit that is
/// not finite and > 0.
Patch extract_patch_in_unit(const Surface& surface, int center_vertex, double unit,
                            const PatchOptions& options = {});

}  // namespace surfcomp::mesh
