// libsurfcomp_png.so: patch_files.hpp's images drawn with cairo (png_module.hpp).
#include "png_module.hpp"

#include <cairo.h>

#include <cmath>
#include <memory>

namespace surfcomp::report::detail {
namespace {

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

struct Destination {
  PngSink sink;
  void* closure;
};

cairo_status_t write_to_sink(void* closure, const unsigned char* data, unsigned int length) {
  const auto* to = static_cast<const Destination*>(closure);
  return to->sink(to->closure, data, length) ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

PngStatus write_png(cairo_surface_t* surface, PngSink sink, void* closure) {
  cairo_surface_flush(surface);
  Destination to{sink, closure};
  return cairo_surface_write_to_png_stream(surface, &write_to_sink, &to) == CAIRO_STATUS_SUCCESS
             ? PngStatus::ok
             : PngStatus::write_failed;
}

void set_colour(cairo_t* cr, const std::uint8_t* rgb) {
  cairo_set_source_rgb(cr, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
}

PngStatus polar_plot(const PolarPlot* plot, PngSink sink, void* closure) {
  const int d = plot->diameter, width = d + 140, height = d + 60;
  const SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height),
                           &cairo_surface_destroy);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) return PngStatus::no_image;
  const ContextPtr context(cairo_create(surface.get()), &cairo_destroy);
  cairo_t* cr = context.get();
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);

  // The disk, u to the right and v up; wedges without antialiasing keep exact colours.
  cairo_save(cr);
  cairo_translate(cr, 20 + d / 2.0, 20 + d / 2.0);
  cairo_scale(cr, 1, -1);
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  const double radius = d / 2.0, step = 2.0 * M_PI / plot->sectors;
  for (int k = 0; k < plot->rings; ++k) {
    const double r0 = radius * k / plot->rings, r1 = radius * (k + 1) / plot->rings;
    for (int j = 0; j < plot->sectors; ++j) {
      const double a0 = (j - 0.5) * step, a1 = (j + 0.5) * step;
      set_colour(cr,
                 plot->wedge_colours + 3 * (static_cast<std::ptrdiff_t>(k) * plot->sectors + j));
      cairo_new_path(cr);
      cairo_arc(cr, 0, 0, r1, a0, a1);
      if (r0 > 0) {
        cairo_arc_negative(cr, 0, 0, r0, a1, a0);
      } else {
        cairo_line_to(cr, 0, 0);
      }
      cairo_close_path(cr);
      cairo_fill(cr);
    }
  }
  cairo_restore(cr);
  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  cairo_set_line_width(cr, 1);
  cairo_arc(cr, 20 + d / 2.0, 20 + d / 2.0, d / 2.0, 0, 2 * M_PI);
  cairo_stroke(cr);

  // The colour bar: hi at the top, lo at the bottom.
  const double bar_x = d + 50, bar_top = 20, bar_height = d, bar_width = 20;
  for (int y = 0; y < d; ++y) {
    set_colour(cr, plot->bar_colours + 3 * static_cast<std::ptrdiff_t>(y));
    cairo_rectangle(cr, bar_x, bar_top + y, bar_width, 1);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, bar_x, bar_top, bar_width, bar_height);
  cairo_stroke(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 13);
  const auto label = [&](double y, const char* text) {
    cairo_move_to(cr, bar_x + bar_width + 6, y + 4);
    cairo_show_text(cr, text);
  };
  label(bar_top, plot->hi_text);
  label(bar_top + bar_height / 2, plot->mid_text);
  label(bar_top + bar_height, plot->lo_text);
  cairo_move_to(cr, bar_x - 10, bar_top + bar_height + 34);
  cairo_show_text(cr, plot->caption);
  return write_png(surface.get(), sink, closure);
}

/// A cairo image of `width` by `height` pixels holding `rgb` (row after row of RGB triples);
/// its status is not success when cairo cannot make it.
SurfacePtr image_of(int width, int height, const std::uint8_t* rgb) {
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height),
                     &cairo_surface_destroy);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) return surface;
  cairo_surface_flush(surface.get());
  unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (int y = 0; y < height; ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* p = rgb + 3 * (static_cast<std::ptrdiff_t>(y) * width + x);
      row[x] = 0xFF000000u | (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) |
               std::uint32_t{p[2]};
    }
  }
  cairo_surface_mark_dirty(surface.get());
  return surface;
}

PngStatus pixels(int width, int height, const std::uint8_t* rgb, PngSink sink, void* closure) {
  const SurfacePtr surface = image_of(width, height, rgb);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) return PngStatus::no_image;
  return write_png(surface.get(), sink, closure);
}

/// Shows `text` with its horizontal centre at x, its baseline at y, in the font size `size`,
/// or smaller so that it is at most `width` pixels wide.
void show_centred(cairo_t* cr, double x, double y, const char* text, double size, double width) {
  cairo_set_font_size(cr, size);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text, &extents);
  if (extents.x_advance > width && extents.x_advance > 0) {
    cairo_set_font_size(cr, size * width / extents.x_advance);
    cairo_text_extents(cr, text, &extents);
  }
  cairo_move_to(cr, x - extents.width / 2 - extents.x_bearing, y);
  cairo_show_text(cr, text);
}

PngStatus panel_grid(const PanelGrid* grid, PngSink sink, void* closure) {
  constexpr double kTitles = 24;  // the strip of titles over the panels
  const int p = grid->panel, width = grid->columns * p, height = 2 * p + 84;
  const SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height),
                           &cairo_surface_destroy);
  const SurfacePtr panels = image_of(width, 2 * p, grid->panel_rgb);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS ||
      cairo_surface_status(panels.get()) != CAIRO_STATUS_SUCCESS)
    return PngStatus::no_image;
  const ContextPtr context(cairo_create(surface.get()), &cairo_destroy);
  cairo_t* cr = context.get();
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_source_surface(cr, panels.get(), 0, kTitles);
  cairo_paint(cr);

  // Thin grey lines between the columns and between the rows.
  cairo_set_source_rgb(cr, 0.75, 0.75, 0.75);
  cairo_set_line_width(cr, 1);
  for (int c = 1; c < grid->columns; ++c) {
    cairo_move_to(cr, c * p + 0.5, 0);
    cairo_line_to(cr, c * p + 0.5, kTitles + 2 * p);
  }
  cairo_move_to(cr, 0, kTitles + p + 0.5);
  cairo_line_to(cr, width, kTitles + p + 0.5);
  cairo_stroke(cr);

  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  for (int c = 0; c < grid->columns; ++c)
    show_centred(cr, c * p + p / 2.0, 17, grid->titles[c], 13, p - 6);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  for (int c = 0; c < grid->columns; ++c) {
    if (grid->notes[c][0] == '\0') continue;
    for (int row = 0; row < 2; ++row) {
      show_centred(cr, c * p + p / 2.0, kTitles + row * p + p / 2.0 + 4, grid->notes[c], 13, p - 6);
    }
  }

  // The colour bar, lo at the left; its samples without antialiasing keep exact colours.
  const double bar_x = 20, bar_y = kTitles + 2 * p + 8, bar_length = width - 40, bar_height = 12;
  cairo_save(cr);
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  for (int i = 0; i < grid->bar_samples; ++i) {
    const double x0 = bar_x + bar_length * i / grid->bar_samples;
    const double x1 = bar_x + bar_length * (i + 1) / grid->bar_samples;
    set_colour(cr, grid->bar_colours + 3 * static_cast<std::ptrdiff_t>(i));
    cairo_rectangle(cr, x0, bar_y, x1 - x0, bar_height);
    cairo_fill(cr);
  }
  cairo_restore(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, bar_x, bar_y, bar_length, bar_height);
  cairo_stroke(cr);
  const double labels_y = bar_y + bar_height + 14;
  cairo_set_font_size(cr, 12);
  cairo_text_extents_t extents;
  cairo_move_to(cr, bar_x, labels_y);
  cairo_show_text(cr, grid->lo_text);
  cairo_text_extents(cr, grid->hi_text, &extents);
  cairo_move_to(cr, bar_x + bar_length - extents.width - extents.x_bearing, labels_y);
  cairo_show_text(cr, grid->hi_text);
  show_centred(cr, bar_x + bar_length / 2, labels_y, grid->mid_text, 12, bar_length / 4);
  show_centred(cr, width / 2.0, labels_y + 18, grid->caption, 12, width - 8);
  return write_png(surface.get(), sink, closure);
}

}  // namespace
}  // namespace surfcomp::report::detail

extern "C" __attribute__((visibility("default")))
const surfcomp::report::detail::PngModule surfcomp_png_module_2 = {
    &surfcomp::report::detail::polar_plot, &surfcomp::report::detail::pixels,
    &surfcomp::report::detail::panel_grid};
