// A critical point's patch as files that mesh-processing tools open (surfcomp patch-map): the
// patch as Wavefront OBJ with its harmonic map as texture coordinates, the patch's vertex
// properties as PLY, and its harmonic shape image as PNG, both as a polar plot with a colour bar
// and as the bare rings x sectors grid. PNG files are drawn with cairo by surfcomp's PNG module,
// libsurfcomp_png.so, loaded when the first one is written (surfcomp/core/loadable_module.hpp
// says where it is looked for).
#pragma once

#include "surfcomp/harmonic/disk_map.hpp"
#include "surfcomp/harmonic/shape_image.hpp"
#include "surfcomp/mesh/patch.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

namespace surfcomp::report {

/// The patch as OBJ, atomically: `v x y z` per patch vertex (A), `vt s t` per vertex with
/// (s, t) = ((u + 1) / 2, (v + 1) / 2), the map's unit disk in the unit square (a texture
/// maps onto it), and `f a/a b/b c/c` per triangle (1-based). Every number is written with 17
/// significant digits, so u = 2 s - 1 reads back exactly. Throws InputError when the map does
/// not have one point per patch vertex, FileError when the file cannot be written.
void write_patch_obj(const mesh::Patch& patch, const harmonic::DiskMap& map,
                     const std::filesystem::path& path);

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

}  // namespace surfcomp::report
