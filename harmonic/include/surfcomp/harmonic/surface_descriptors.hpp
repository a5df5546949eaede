// The coarse level of a surface, computed once and stored (.hsi): its shape critical points and,
// for each, the geodesic patch around it, the patch's harmonic map onto the unit disk and its
// harmonic shape image (method §2-4).
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/harmonic/disk_map.hpp"
#include "surfcomp/harmonic/shape_image.hpp"
#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/mesh/patch.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace surfcomp::harmonic {

struct DescriptorOptions {
  mesh::CriticalPointOptions critical_points;  ///< r_cp 2.5 A, property disc 1 A, Dijkstra
  /// Radius 5 A, margin 5 %, and fast-marching distances instead of the seed's Dijkstra:
  /// Dijkstra's polygonal balls depend on the mesh, fast marching's round patches much less,
  /// so two samplings of one surface give more alike images (docs/decisions.md#patch-distances).
  mesh::PatchOptions patch = [] {
    mesh::PatchOptions options;
    options.distance = mesh::GeodesicMethod::fast_marching;
    return options;
  }();
  DiskMapOptions disk_map;  ///< spring weights 1/|p_i - p_j| (method §4.2)
  ImageOptions image;       ///< 16 rings x 180 sectors (2-degree steps)
  /// The vertex property resampled into the images; default the shape index (method §0.2).
  std::string image_property = mesh::property::shape_index;
  /// Default 1 GiB (CLI --max-image-bytes); must be >= 1. describe_surface refuses, before
  /// building any image, a description whose images would take more memory than this:
  /// image_bytes(image, n) for the n critical points to be imaged
  /// (docs/decisions.md#resource-limits).
  std::int64_t max_image_bytes = std::int64_t{1} << 30;
  /// Default none. Called as critical points are described (done, total), from the worker
  /// threads (it must be thread-safe), and once with done == total at the end. Not kept in
  /// SurfaceDescriptors::options.
  std::function<void(std::int64_t done, std::int64_t total)> progress;
};

/// The user's options of DescriptorOptions: --critical-point-radius --patch-radius
/// --image-rings --image-sectors --weights --max-image-bytes, with their ranges.
const options::Table<DescriptorOptions>& descriptor_option_table();

/// The memory of `count` shape images on the grid of `image`, bytes: per grid point a value,
/// a validity flag, a face index and three barycentric coordinates.
double image_bytes(const ImageOptions& image, std::int64_t count);

/// Why a critical point has no image. Such points stay in the list (their indices are stable)
/// but take no part in image comparisons.
enum class PatchStatus : std::uint8_t {
  ok = 0,          ///< patch, map and image built
  empty = 1,       ///< the patch lost every triangle in its refinement (method §3.1, steps 5-6)
  not_a_disk = 2,  ///< the patch has a handle (genus > 0); a harmonic map needs a disk
  map_failed = 3,  ///< the harmonic map could not be solved (degenerate patch geometry)
  skipped = 4,     ///< not asked for (outside a binding site, see describe_surface)
  /// The patch reaches a border: the surface's own (a cut or partial mesh), so that its image
  /// would be that of a truncated patch, or its refinement left the centre on the patch's
  /// border (a folded or noisy mesh), so that the centre has no direction around it.
  at_border = 5,
};

/// One critical point with its patch, map and image (the latter three empty unless status ok).
struct CriticalPointDescriptor {
  mesh::CriticalPoint point;
  PatchStatus status = PatchStatus::ok;
  mesh::Patch patch;  ///< patch-local vertices refer back to the surface (surface_vertex)
  DiskMap map;        ///< uv of each patch vertex in the unit disk
  ShapeImage image;   ///< image_property resampled on the polar grid
};

/// "ok", "empty", "not_a_disk", "map_failed", "skipped" or "at_border".
const char* to_string(PatchStatus status);

/// A heavy atom of the molecule a surface was built from, kept with the description so that a
/// comparison can judge a pose on atoms too (matching::OverlayOptions::atom_weight).
struct SurfaceAtom {
  std::string element;                                 ///< capitalised symbol, "C", "Cl"
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< A, in the surface's frame
};

/// A surface with its coarse-level description.
struct SurfaceDescriptors {
  DescriptorOptions options;
  mesh::Surface surface;
  std::vector<CriticalPointDescriptor> critical_points;  ///< detect_critical_points order
  /// The heavy atoms of the molecule the surface was built from (surface_atoms); empty when
  /// the surface came from a mesh without a molecule (describe_surface without a molecule).
  std::vector<SurfaceAtom> atoms;
  /// The length, in the surface's coordinates, that `options`' radii count as 1 A: 1 for a
  /// molecule, a general mesh's length unit (mesh::general_mesh_unit) when it was described in
  /// one and given back in its own coordinates. Finite, > 0.
  double length_unit = 1.0;
};

/// The heavy (non-hydrogen) atoms of `molecule`, in its order.
std::vector<SurfaceAtom> surface_atoms(const Molecule& molecule);

/// describe_surface of a surface built from `molecule` (or carrying its properties), keeping
/// the molecule's heavy atoms in SurfaceDescriptors::atoms.
SurfaceDescriptors describe_surface(
    mesh::Surface surface, const Molecule& molecule, const DescriptorOptions& options = {},
    const std::function<bool(const mesh::CriticalPoint&)>& describe_if = {});

/// Detects the critical points of `surface` and builds, for each, its patch (extract_patch),
/// harmonic map (harmonic_disk_map) and image (harmonic_shape_image of
/// options.image_property). Patches, maps and images are built in parallel with TBB, each into
/// its own slot: the result does not depend on the thread count.
/// Requires the properties cc1, cc2 and options.image_property (InputError naming the surface
/// otherwise); option errors as the stages' own (OptionError); InputError when the images would
/// exceed options.max_image_bytes.
/// `describe_if`, when given, selects the critical points that get a patch, map and image (a
/// binding site's, say); the others keep status skipped.
SurfaceDescriptors describe_surface(
    mesh::Surface surface, const DescriptorOptions& options = {},
    const std::function<bool(const mesh::CriticalPoint&)>& describe_if = {});

/// The patch, map and image around `point.vertex` of `surface`, as describe_surface builds them
/// for each critical point (point is copied into the result; only its vertex is used).
/// Requires the property options.image_property (InputError otherwise).
CriticalPointDescriptor describe_point(const mesh::Surface& surface,
                                       const mesh::CriticalPoint& point,
                                       const DescriptorOptions& options = {});

/// describe_point of each of `points` (critical points of `surface`, as
/// mesh::detect_critical_points gives them), in parallel (TBB), in their order: a chosen few of
/// a surface's critical points described as describe_surface would describe them. Requires the
/// property options.image_property (InputError otherwise).
std::vector<CriticalPointDescriptor> describe_points(const mesh::Surface& surface,
                                                     const std::vector<mesh::CriticalPoint>& points,
                                                     const DescriptorOptions& options = {});

/// describe_points of `points` on `surface` described in the length unit `unit` (the length of
/// its coordinates that options' radii count as 1 A, mesh::general_mesh_unit), as describe_surface
/// describes a general mesh: the points (in the surface's coordinates, as
/// mesh::detect_critical_points_in_unit gives them) are described on the surface's copy scaled by
/// 1 / unit and given back in its coordinates (scale_point_descriptor). Throws as
/// describe_points; InputError for a unit that is not finite and > 0.
std::vector<CriticalPointDescriptor> describe_points_in_unit(
    const mesh::Surface& surface, const std::vector<mesh::CriticalPoint>& points, double unit,
    const DescriptorOptions& options = {});

/// Scales a description's geometry by `factor` (> 0, finite), as a change of length unit: the
/// surface (mesh::scale_surface), the critical points' positions and curvatures (cc1, cc2,
/// curvedness divided by it), the patches' positions and on-surface distances, the atoms, and
/// the images' values when options.image_property is a curvature. The options (radii) stay as
/// they were applied, so length_unit is multiplied by `factor`. Maps are on the unit disk and
/// do not change. Throws InputError for another factor.
void scale_descriptors(SurfaceDescriptors& descriptors, double factor);

/// One critical point's description scaled as scale_descriptors scales each: its point, its
/// patch and, when `image_property` (DescriptorOptions::image_property) is a curvature, its
/// image's values. `factor` is not checked.
void scale_point_descriptor(CriticalPointDescriptor& descriptor, double factor,
                            const std::string& image_property);

/// Counts of a description, for summaries.
struct DescriptorCounts {
  std::size_t peaks = 0, valleys = 0, imaged = 0;
};
DescriptorCounts count_descriptors(const SurfaceDescriptors& descriptors);

}  // namespace surfcomp::harmonic
