// The interface between surfcomp::report and its PNG module, libsurfcomp_png.so (png_module.cpp):
// the cairo drawing of patch_files.hpp's images, as plain functions over colours already chosen.
// The module alone links cairo, and write_image_png and write_image_grid_png load it on their
// first call, so that no other run maps and initialises cairo with its font and X11 libraries
// (docs/decisions.md#loadable-modules).
#pragma once

#include <cstdint>

namespace surfcomp::report::detail {

/// The module file and its one exported symbol, a `const PngModule`. The symbol's number
/// changes with PngModule's layout, so that a module of another layout is not found.
constexpr const char* kPngModuleFile = "libsurfcomp_png.so";
constexpr const char* kPngModuleSymbol = "surfcomp_png_module_2";

/// Takes the next `length` bytes of the PNG file; returns false when they cannot be written.
/// It must not throw: the module calls it from inside cairo.
using PngSink = bool (*)(void* closure, const unsigned char* data, unsigned int length);

/// What write_image_png draws (patch_files.hpp describes the picture).
struct PolarPlot {
  int rings = 0;
  int sectors = 0;
  /// rings x sectors RGB triples, ring after ring: the wedge of ring k, sector j at
  /// 3 * (k * sectors + j).
  const std::uint8_t* wedge_colours = nullptr;
  int diameter = 0;  ///< of the disk, pixels
  /// `diameter` RGB triples: the colour bar's rows of pixels from the top (hi) down (lo).
  const std::uint8_t* bar_colours = nullptr;
  const char* hi_text = "";   ///< beside the bar's top
  const char* mid_text = "";  ///< beside its middle
  const char* lo_text = "";   ///< beside its bottom
  const char* caption = "";   ///< below the bar
};

/// What write_methods_png draws (patch_files.hpp describes the picture): a strip of titles
/// 24 pixels high, two rows of `columns` square panels, and a strip of 60 pixels with the colour
/// bar, its labels and its caption; columns * panel by 2 * panel + 84 pixels in all.
struct PanelGrid {
  int columns = 0;
  int panel = 0;  ///< side of one panel, pixels
  /// The two rows of panels, drawn already: 2 * panel rows of columns * panel RGB triples each,
  /// from the top.
  const std::uint8_t* panel_rgb = nullptr;
  const char* const* titles = nullptr;  ///< `columns` texts, one over each column
  const char* const* notes =
      nullptr;  ///< `columns` texts ("" for none), in each panel of its column
  int bar_samples = 0;
  /// `bar_samples` RGB triples: the colour bar from its left end (lo) to its right end (hi).
  const std::uint8_t* bar_colours = nullptr;
  const char* lo_text = "";   ///< below the bar's left end
  const char* mid_text = "";  ///< below its middle
  const char* hi_text = "";   ///< below its right end
  const char* caption = "";   ///< below the labels, centred
};

/// The outcome of a drawing.
enum class PngStatus : int { ok = 0, no_image = 1, write_failed = 2 };

/// The module's entry points.
struct PngModule {
  /// The polar plot as a PNG of diameter + 140 by diameter + 60 pixels, to `sink`.
  PngStatus (*polar_plot)(const PolarPlot* plot, PngSink sink, void* closure);
  /// A PNG of `width` by `height` pixels, row after row of RGB triples from `rgb`, to `sink`.
  PngStatus (*pixels)(int width, int height, const std::uint8_t* rgb, PngSink sink, void* closure);
  /// The panels with their titles, notes and colour bar as a PNG, to `sink`.
  PngStatus (*panel_grid)(const PanelGrid* grid, PngSink sink, void* closure);
};

}  // namespace surfcomp::report::detail
