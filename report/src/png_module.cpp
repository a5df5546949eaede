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

PngStatus pixels(int width, int height, const std::uint8_t* rgb, PngSink sink, void* closure) {
  const SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height),
                           &cairo_surface_destroy);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) return PngStatus::no_image;
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
  return write_png(surface.get(), sink, closure);
}

}  // namespace
}  // namespace surfcomp::report::detail

extern "C" __attribute__((visibility("default")))
const surfcomp::report::detail::PngModule surfcomp_png_module_1 = {
    &surfcomp::report::detail::polar_plot, &surfcomp::report::detail::pixels};
