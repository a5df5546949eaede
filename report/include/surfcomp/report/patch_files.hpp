// A critical point's patch as files that mesh-processing tools open (surfcomp patch-map): the
// patch as Wavefront OBJ with its harmonic map (or another parameterization) as texture
// coordinates, the patch's vertex properties as PLY, its harmonic shape image as PNG, both as a
// polar plot with a colour bar and as the bare rings x sectors grid, and several maps of the
// patch side by side as PNG, each with its distortion. PNG files are drawn with cairo by surfcomp's
// PNG module, libsurfcomp_png.so, loaded when the first one is written
// (surfcomp/core/loadable_module.hpp says where it is looked for).
#pragma once

#include "surfcomp/harmonic/disk_map.hpp"
#include "surfcomp/harmonic/shape_image.hpp"
#include "surfcomp/mesh/patch.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace surfcomp::report {

/// The patch as OBJ, atomically: `v x y z` per patch vertex (A), `vt s t` per vertex with
/// (s, t) = ((u + 1) / 2, (v + 1) / 2), the map's unit disk in the unit square (a texture
/// maps onto it), and `f a/a b/b c/c` per triangle (1-based). Every number is written with 17
/// significant digits, so u = 2 s - 1 reads back exactly. `map_name` names the map in the
/// file's comment. Throws InputError when the map does not have one point per patch vertex,
/// FileError when the file cannot be written.
void write_patch_obj(const mesh::Patch& patch, const harmonic::DiskMap& map,
                     const std::filesystem::path& path,
                     const std::string& map_name = "harmonic map onto the unit disk");

/// `uv` (#V by 2) moved and scaled, by one factor on both axes, so that its bounding box is
/// centred at the origin and its longer side spans [-1, 1]: a free-border map (LSCM, ARAP),
/// whose position and scale are arbitrary, in the square of the unit disk, with its angles and
/// aspect ratio kept. Throws InputError for a map without points, with a point that is not
/// finite, or with all its points in one place.
Eigen::MatrixX2d fit_to_disk_square(const Eigen::Ref<const Eigen::MatrixX2d>& uv);

/// The patch as binary little-endian PLY: its vertices with every property `surface` has at
/// them, plus `u`, `v` (the map) and `distance` (on-surface distance from the centre, A), and
/// its triangles. Throws as write_patch_obj.
void write_patch_ply(const mesh::Surface& surface, const mesh::Patch& patch,
                     const harmonic::DiskMap& map, const std::filesystem::path& path);

struct ImagePngOptions {
  /// Default -1 and +1 (the shape index: cup to cap). The colour bar's range; values beyond it
  /// take its end colours. lo < hi, finite.
  double lo = -1.0;
  double hi = 1.0;
  /// Default "shape index". The colour bar's caption.
  std::string label = "shape index";
  /// Default 400. Diameter of the polar plot, pixels; 64 to 4096.
  int diameter = 400;
};

/// The colour of `value` on the diverging scale from blue (lo) through white to red (hi), as
/// 8-bit RGB; values beyond the range are clamped.
std::array<std::uint8_t, 3> diverging_colour(double value, double lo, double hi);

/// The image as a polar plot, atomically: ring k an annulus at radius (k + 0.5) / rings of the
/// disk, sector j a wedge centred at j * 360 / sectors degrees counter-clockwise from +u (to
/// the right), coloured by diverging_colour; grid points without a value light grey; a colour
/// bar with its range and caption beside it. Size: diameter + 140 by diameter + 60 pixels.
/// Throws OptionError for options outside their domains, InputError for an image whose values
/// do not fill its grid, FileError when the PNG module cannot be loaded or the file cannot be
/// written.
void write_image_png(const harmonic::ShapeImage& image, const std::filesystem::path& path,
                     const ImagePngOptions& options = {});

/// The image's grid as a PNG of `sectors` by `rings` pixels, atomically: pixel (j, k) is ring
/// k (top row: ring 0, the centre), sector j, coloured by diverging_colour(value, lo, hi);
/// grid points without a value light grey (211, 211, 211). Throws as write_image_png.
void write_image_grid_png(const harmonic::ShapeImage& image, const std::filesystem::path& path,
                          double lo = -1.0, double hi = 1.0);

/// One parameterization of a patch, a column of write_methods_png.
struct MethodMap {
  std::string name;  ///< the method, written over its column
  /// The map, #V by 2, within [-1, 1]^2 (a free-border map through fit_to_disk_square); no
  /// rows when the method failed on the patch.
  Eigen::MatrixX2d uv;
};

struct MethodsPngOptions {
  /// Default 240. Width and height of one panel, pixels; 64 to 2048.
  int panel = 240;
  /// Default 8. Checker squares across the patch's diameter, 2 sqrt(patch area / pi); 1 to 64.
  int checker_squares = 8;
  /// Default 30. The angle distortion at the top of the colour scale, degrees; larger values
  /// take its top colour, so that the figures of different patches read alike. Finite, > 0.
  double angle_top_degrees = 30.0;
};

/// The maps of one patch side by side as a PNG, atomically: a column per map, its name above
/// it, each panel the square [-1, 1]^2 of the map plane (u to the right, v up).
/// - Top row: a checkerboard laid on the patch, seen through the map. The squares, of side the
///   patch's diameter / checker_squares, are the cross-sections of cubes aligned with the
///   patch's best-fit plane (the principal axes of its vertices, the plane mid-way through a
///   layer of cubes): a flat patch carries plain squares. Each pixel of a map triangle takes the
///   colour of the patch point it comes from (barycentric coordinates), so a map that keeps
///   angles shows the squares as squares, however their size changes, and shear and stretch
///   show as such.
/// - Bottom row: each map triangle coloured by its angle distortion, the mean over its corners
///   of |angle in the map - angle on the patch| (harmonic::corner_angle_distortion), on one
///   scale for every column, from 0 to angle_top_degrees (viridis: dark purple to yellow).
/// A failed map's column is empty and labelled "failed". Below the panels, the colour bar.
/// Size: maps.size() * panel by 2 * panel + 84 pixels. Throws OptionError for options outside
/// their domains, InputError for no maps or a map without one finite point per patch vertex,
/// FileError as write_image_png.
void write_methods_png(const mesh::Patch& patch, const std::vector<MethodMap>& maps,
                       const std::filesystem::path& path, const MethodsPngOptions& options = {});

}  // namespace surfcomp::report
