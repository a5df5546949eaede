#include "surfcomp/report/patch_files.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/mesh/io/ply.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>

namespace surfcomp::report {
namespace {

constexpr std::uint8_t kNoValue = 211;  // light grey

void check_map(const mesh::Patch& patch, const harmonic::DiskMap& map) {
  if (map.uv.rows() != patch.positions.rows()) {
    throw InputError("patch map: " + std::to_string(map.uv.rows()) + " map points for " +
                     std::to_string(patch.positions.rows()) + " patch vertices");
  }
}

void check_image(const harmonic::ShapeImage& image) {
  const auto points = static_cast<Eigen::Index>(image.rings) * image.sectors;
  if (image.rings < 1 || image.sectors < 1 || image.values.size() != points ||
      image.valid.size() != static_cast<std::size_t>(points)) {
    throw InputError("shape image: its values do not fill its " + std::to_string(image.rings) +
                     " x " + std::to_string(image.sectors) + " grid");
  }
}

void check_range(double lo, double hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
    throw OptionError("image colour range [" + std::to_string(lo) + ", " + std::to_string(hi) +
                      "]: expected finite lo < hi");
  }
}

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

cairo_status_t write_to_stream(void* closure, const unsigned char* data, unsigned int length) {
  auto& out = *static_cast<std::ostream*>(closure);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
  return out ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

/// `surface` as a PNG file at `path`, atomically.
void write_png(cairo_surface_t* surface, const std::filesystem::path& path) {
  cairo_surface_flush(surface);
  io::write_file_atomically(path, [&](std::ostream& out) {
    if (cairo_surface_write_to_png_stream(surface, &write_to_stream, &out) !=
        CAIRO_STATUS_SUCCESS) {
      throw FileError(path.string(), "cannot write the PNG image");
    }
  });
}

SurfacePtr image_surface(cairo_format_t format, int width, int height) {
  SurfacePtr surface(cairo_image_surface_create(format, width, height), &cairo_surface_destroy);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw NumericError("cairo cannot make a " + std::to_string(width) + " x " +
                       std::to_string(height) + " image");
  return surface;
}

void set_colour(cairo_t* cr, const std::array<std::uint8_t, 3>& rgb) {
  cairo_set_source_rgb(cr, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

void write_patch_obj(const mesh::Patch& patch, const harmonic::DiskMap& map,
                     const std::filesystem::path& path) {
  check_map(patch, map);
  io::write_file_atomically(path, [&](std::ostream& out) {
    char line[160];
    out << "# surfcomp patch-map: a geodesic patch with its harmonic map onto the unit disk as\n"
           "# texture coordinates, (s, t) = ((u + 1) / 2, (v + 1) / 2)\n";
    for (Eigen::Index v = 0; v < patch.positions.rows(); ++v) {
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", patch.positions(v, 0),
                    patch.positions(v, 1), patch.positions(v, 2));
      out << line;
    }
    for (Eigen::Index v = 0; v < map.uv.rows(); ++v) {
      std::snprintf(line, sizeof line, "vt %.17g %.17g\n", (map.uv(v, 0) + 1.0) / 2.0,
                    (map.uv(v, 1) + 1.0) / 2.0);
      out << line;
    }
    for (Eigen::Index f = 0; f < patch.faces.rows(); ++f) {
      const int a = patch.faces(f, 0) + 1, b = patch.faces(f, 1) + 1, c = patch.faces(f, 2) + 1;
      std::snprintf(line, sizeof line, "f %d/%d %d/%d %d/%d\n", a, a, b, b, c, c);
      out << line;
    }
  });
}

void write_patch_ply(const mesh::Surface& surface, const mesh::Patch& patch,
                     const harmonic::DiskMap& map, const std::filesystem::path& path) {
  check_map(patch, map);
  mesh::Surface out = mesh::Surface::from_arrays(patch.positions, patch.faces, surface.source());
  const auto n = static_cast<Eigen::Index>(patch.surface_vertex.size());
  for (const std::string& name : surface.property_names()) {
    const Eigen::VectorXd all = surface.property(name);
    Eigen::VectorXd values(n);
    for (Eigen::Index v = 0; v < n; ++v)
      values(v) = all(patch.surface_vertex[static_cast<std::size_t>(v)]);
    out.set_property(name, values, surface.property_type(name));
  }
  out.set_property("u", map.uv.col(0));
  out.set_property("v", map.uv.col(1));
  if (patch.distance.size() == n) out.set_property("distance", patch.distance);
  mesh::io::write_ply(out, path);
}

std::array<std::uint8_t, 3> diverging_colour(double value, double lo, double hi) {
  // Blue (33, 102, 172) -> white -> red (178, 24, 43), the ends of ColorBrewer's RdBu.
  const double t = std::clamp((value - (lo + hi) / 2.0) / ((hi - lo) / 2.0), -1.0, 1.0);
  const std::array<double, 3> end =
      t < 0 ? std::array<double, 3>{33, 102, 172} : std::array<double, 3>{178, 24, 43};
  const double w = std::abs(t);
  std::array<std::uint8_t, 3> rgb{};
  for (std::size_t k = 0; k < 3; ++k)
    rgb[k] = static_cast<std::uint8_t>(std::lround(255.0 + (end[k] - 255.0) * w));
  return rgb;
}

void write_image_png(const harmonic::ShapeImage& image, const std::filesystem::path& path,
                     const ImagePngOptions& options) {
  check_image(image);
  check_range(options.lo, options.hi);
  if (options.diameter < 64 || options.diameter > 4096)
    throw OptionError("image diameter " + std::to_string(options.diameter) +
                      " pixels: expected 64 to 4096");
  const int d = options.diameter, width = d + 140, height = d + 60;
  const SurfacePtr surface = image_surface(CAIRO_FORMAT_ARGB32, width, height);
  const ContextPtr context(cairo_create(surface.get()), &cairo_destroy);
  cairo_t* cr = context.get();
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);

  // The disk, u to the right and v up; wedges without antialiasing keep exact colours.
  cairo_save(cr);
  cairo_translate(cr, 20 + d / 2.0, 20 + d / 2.0);
  cairo_scale(cr, 1, -1);
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  const double radius = d / 2.0, step = 2.0 * M_PI / image.sectors;
  for (int k = 0; k < image.rings; ++k) {
    const double r0 = radius * k / image.rings, r1 = radius * (k + 1) / image.rings;
    for (int j = 0; j < image.sectors; ++j) {
      const std::size_t g = static_cast<std::size_t>(k) * static_cast<std::size_t>(image.sectors) +
                            static_cast<std::size_t>(j);
      const double a0 = (j - 0.5) * step, a1 = (j + 0.5) * step;
      set_colour(cr, image.valid[g] != 0
                         ? diverging_colour(image.values(static_cast<Eigen::Index>(g)), options.lo,
                                            options.hi)
                         : std::array<std::uint8_t, 3>{kNoValue, kNoValue, kNoValue});
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

  // The colour bar: lo at the bottom, hi at the top.
  const double bar_x = d + 50, bar_top = 20, bar_height = d, bar_width = 20;
  for (int y = 0; y < static_cast<int>(bar_height); ++y) {
    const double value = options.hi - (options.hi - options.lo) * (y + 0.5) / bar_height;
    set_colour(cr, diverging_colour(value, options.lo, options.hi));
    cairo_rectangle(cr, bar_x, bar_top + y, bar_width, 1);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, bar_x, bar_top, bar_width, bar_height);
  cairo_stroke(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 13);
  const auto label = [&](double y, const std::string& text) {
    cairo_move_to(cr, bar_x + bar_width + 6, y + 4);
    cairo_show_text(cr, text.c_str());
  };
  label(bar_top, number(options.hi));
  label(bar_top + bar_height / 2, number((options.lo + options.hi) / 2));
  label(bar_top + bar_height, number(options.lo));
  cairo_move_to(cr, bar_x - 10, bar_top + bar_height + 34);
  cairo_show_text(cr, options.label.c_str());
  write_png(surface.get(), path);
}

void write_image_grid_png(const harmonic::ShapeImage& image, const std::filesystem::path& path,
                          double lo, double hi) {
  check_image(image);
  check_range(lo, hi);
  const SurfacePtr surface = image_surface(CAIRO_FORMAT_RGB24, image.sectors, image.rings);
  cairo_surface_flush(surface.get());
  unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (int k = 0; k < image.rings; ++k) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(k) * stride);
    for (int j = 0; j < image.sectors; ++j) {
      const std::size_t g = static_cast<std::size_t>(k) * static_cast<std::size_t>(image.sectors) +
                            static_cast<std::size_t>(j);
      const std::array<std::uint8_t, 3> rgb =
          image.valid[g] != 0 ? diverging_colour(image.values(static_cast<Eigen::Index>(g)), lo, hi)
                              : std::array<std::uint8_t, 3>{kNoValue, kNoValue, kNoValue};
      row[j] = 0xFF000000u | (std::uint32_t{rgb[0]} << 16) | (std::uint32_t{rgb[1]} << 8) |
               std::uint32_t{rgb[2]};
    }
  }
  cairo_surface_mark_dirty(surface.get());
  write_png(surface.get(), path);
}

}  // namespace surfcomp::report
