// The length unit a surface is described in. Every length option (curvature, critical point and
// patch radii, the match's distances) counts in this unit: 1 A for a molecule, and for a general
// mesh, whose coordinates may be in metres or millimetres, a length taken from its own size, so
// that the same shape gives the same critical points, patches and images at any scale
// (docs/decisions.md#mesh-scale).
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <array>
#include <string>
#include <vector>

namespace surfcomp::mesh {

/// How the length unit of a general mesh is chosen when none is given.
enum class LengthScale {
  /// "auto": 1 A for molecules and molecular meshes (with ESP and LP, an MSMS .vert/.face or a
  /// --molecule); for a general mesh, R / 12 with R its size (rms_radius; the larger of two
  /// meshes compared), so that a typical closed mesh measures about 1500 unit^2 and a 5-unit
  /// patch covers a few per cent of it.
  automatic,
  none,  ///< "none": the coordinates are in A, whatever the input
};

/// The names of LengthScale's values, as --scale takes them.
inline constexpr std::array<const char*, 2> length_scale_names = {"auto", "none"};

/// LengthScale::automatic's unit is the size over this.
inline constexpr double auto_unit_divisor = 12.0;

/// The radius, in units, over which a general mesh's curvature is fitted: wider than a
/// molecular surface's 2 A, as noisy scans need (docs/decisions.md#mesh-scale).
inline constexpr double general_mesh_curvature_radius = 3.0;

/// The area-weighted RMS distance of a surface's triangle centroids from their centroid, in its
/// coordinates: its size, which noise and a partial view change less than its area. 0 for a
/// surface of no area.
double rms_radius(const Surface& surface);

/// A length unit and how it was chosen.
struct LengthUnit {
  double value = 1.0;  ///< the coordinates' length that counts as 1 A (> 0)
  /// "none" (1), "auto" (from the size), "given" (the unit option) or "stored" (a .hsi file's).
  std::string from = "none";
};

/// The unit of general meshes compared together (one for a single mesh): `unit` when > 0, else
/// 1 for LengthScale::none, else the largest rms_radius over auto_unit_divisor. Throws
/// InputError naming `names` when `scale` is automatic and the surfaces have no extent.
LengthUnit general_mesh_unit(const std::vector<const Surface*>& surfaces, LengthScale scale,
                             double unit, const std::string& names);

/// True when a mesh file's coordinates are taken to be in A whatever the scale options: an MSMS
/// .vert/.face file, or a surface carrying ESP and LP.
bool is_molecular_mesh(const Surface& surface, const std::string& file_extension);

}  // namespace surfcomp::mesh
