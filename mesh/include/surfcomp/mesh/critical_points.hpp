// Shape critical points (method §2.1): the peaks and valleys
// that form SURFCOMP's coarse-level representation of a surface.
#pragma once

#include "surfcomp/core/option_table.hpp"
#include "surfcomp/mesh/geodesic.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <vector>

namespace surfcomp::mesh {

enum class CriticalPointType { peak, valley };

/// The type's name in every output (JSON, PDB, the report, Python): "peak" or "valley".
constexpr const char* type_name(CriticalPointType type) {
  return type == CriticalPointType::peak ? "peak" : "valley";
}

struct CriticalPointOptions {
  /// Default 2.5 A. The on-surface radius r_cp of the neighbourhood N(p, r_cp) in which a
  /// critical point must have the extreme curvature, on-surface (see `distance`). Must be
  /// finite and > 0. method §2's value; on the default molecular surfaces it gives
  /// about the reference counts of method §2.4 (docs/decisions.md#curvature-neighbourhood).
  double radius = 2.5;
  /// Default 1.0 A. Radius of the on-surface disc over which a critical point's shape index,
  /// esp and lp are averaged (weighted by vertex area, a third of the incident triangles'
  /// area); 0 takes the vertex's own values. method §2.3 [choice]. Finite and >= 0.
  double property_disc_radius = 1.0;
  /// Default dijkstra (method §2). How the on-surface distances of both radii are
  /// computed (geodesic.hpp).
  GeodesicMethod distance = GeodesicMethod::dijkstra;
};

/// The user's options of CriticalPointOptions: --critical-point-radius and --disc-radius.
const options::Table<CriticalPointOptions>& critical_point_option_table();

struct CriticalPoint {
  CriticalPointType type = CriticalPointType::peak;
  int vertex = -1;              ///< surface vertex index
  Eigen::Vector3d position;     ///< A
  Eigen::Vector3d normal;       ///< unit; surface.normals() when has_normals(), else the
                                ///< area-weighted normal of the incident triangles
  double cc1 = 0.0, cc2 = 0.0;  ///< at the vertex, 1/A, seed sign (convex < 0)
  double shape_index = 0.0;     ///< disc average, [-1, 1] (cap +1)
  double curvedness = 0.0;      ///< at the vertex, 1/A
  double esp = 0.0;             ///< disc average, kcal/(mol*e); NaN without property esp
  double lp = 0.0;              ///< disc average; NaN without property lp
};

/// The peaks and valleys of `surface` (method §2.1):
/// - peak: a convex vertex (cc1 < 0 and cc2 < 0) whose |cc1| is larger than that of every
///   other convex vertex within the on-surface distance options.radius;
/// - valley: a concave vertex (cc1 > 0 and cc2 > 0) whose cc1 is larger than that of every
///   other concave vertex within options.radius.
/// Saddles (mixed signs) and flat vertices are never critical points, and vertices of the
/// other kind do not compete. Ties: of two vertices with equal |cc1| the lower index wins, so
/// no two peaks (or two valleys) are within options.radius of each other.
/// Uses the surface's properties cc1 and cc2 (curvature.hpp); shape_index and curvedness come
/// from the properties of those names when present, else from cc1 and cc2 (Koenderink, with
/// k = -cc). Throws InputError (naming the surface) when cc1 or cc2 is missing, OptionError
/// for options outside their domain. Result sorted by type (peaks first), then by vertex.
/// Deterministic; O(#V) plus one bounded on-surface distance run (options.distance) per vertex
/// that beats its one-ring.
std::vector<CriticalPoint> detect_critical_points(const Surface& surface,
                                                  const CriticalPointOptions& options = {});

/// detect_critical_points of `surface` described in the length unit `unit` (> 0; the length of
/// its coordinates that options' radii count as 1 A, mesh::general_mesh_unit): found on its
/// copy scaled by 1 / unit and given back in its coordinates (scale_critical_point). The same
/// points as describe_surface finds on a general mesh in that unit.
std::vector<CriticalPoint> detect_critical_points_in_unit(const Surface& surface, double unit,
                                                          const CriticalPointOptions& options = {});

/// Scales a critical point by `factor`, as a change of length unit: its position times it, its
/// curvatures (cc1, cc2, curvedness) divided by it. `factor` is not checked.
void scale_critical_point(CriticalPoint& point, double factor);

}  // namespace surfcomp::mesh
