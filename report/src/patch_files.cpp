#include "surfcomp/report/patch_files.hpp"

#include "png_module.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/loadable_module.hpp"
#include "surfcomp/mesh/io/ply.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

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

/// The PNG module, loaded on the first call; throws FileError when it cannot be loaded.
const detail::PngModule& png_module() {
  static const detail::PngModule& module = *static_cast<const detail::PngModule*>(
      module_symbol(detail::kPngModuleFile, detail::kPngModuleSymbol));
  return module;
}

bool write_to_stream(void* closure, const unsigned char* data, unsigned int length) {
  auto& out = *static_cast<std::ostream*>(closure);
  try {
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
  } catch (...) {  // the module calls this from inside cairo, which no exception may cross
    return false;
  }
  return static_cast<bool>(out);
}

/// The module's PNG, drawn by `draw(sink, closure)`, as a file at `path`, atomically.
template <class Draw>
void write_png(const std::filesystem::path& path, int width, int height, const Draw& draw) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    const detail::PngStatus status = draw(&write_to_stream, static_cast<void*>(&out));
    if (status == detail::PngStatus::no_image) {
      throw NumericError("cairo cannot make a " + std::to_string(width) + " x " +
                         std::to_string(height) + " image");
    }
    if (status != detail::PngStatus::ok)
      throw FileError(path.string(), "cannot write the PNG image");
  });
}

/// Every grid point's colour, ring after ring, as RGB triples: diverging_colour of its value,
/// light grey without one.
std::vector<std::uint8_t> grid_colours(const harmonic::ShapeImage& image, double lo, double hi) {
  std::vector<std::uint8_t> rgb;
  rgb.reserve(image.valid.size() * 3);
  for (std::size_t g = 0; g < image.valid.size(); ++g) {
    const std::array<std::uint8_t, 3> c =
        image.valid[g] != 0 ? diverging_colour(image.values(static_cast<Eigen::Index>(g)), lo, hi)
                            : std::array<std::uint8_t, 3>{kNoValue, kNoValue, kNoValue};
    rgb.insert(rgb.end(), c.begin(), c.end());
  }
  return rgb;
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
  const int d = options.diameter;
  const std::vector<std::uint8_t> wedges = grid_colours(image, options.lo, options.hi);
  std::vector<std::uint8_t> bar;  // lo at the bottom, hi at the top
  bar.reserve(static_cast<std::size_t>(d) * 3);
  for (int y = 0; y < d; ++y) {
    const double value = options.hi - (options.hi - options.lo) * (y + 0.5) / d;
    const std::array<std::uint8_t, 3> c = diverging_colour(value, options.lo, options.hi);
    bar.insert(bar.end(), c.begin(), c.end());
  }
  const std::string hi = number(options.hi), mid = number((options.lo + options.hi) / 2),
                    lo = number(options.lo);
  detail::PolarPlot plot;
  plot.rings = image.rings;
  plot.sectors = image.sectors;
  plot.wedge_colours = wedges.data();
  plot.diameter = d;
  plot.bar_colours = bar.data();
  plot.hi_text = hi.c_str();
  plot.mid_text = mid.c_str();
  plot.lo_text = lo.c_str();
  plot.caption = options.label.c_str();
  const detail::PngModule& module = png_module();
  write_png(path, d + 140, d + 60, [&](detail::PngSink sink, void* closure) {
    return module.polar_plot(&plot, sink, closure);
  });
}

void write_image_grid_png(const harmonic::ShapeImage& image, const std::filesystem::path& path,
                          double lo, double hi) {
  check_image(image);
  check_range(lo, hi);
  const std::vector<std::uint8_t> pixels = grid_colours(image, lo, hi);
  const detail::PngModule& module = png_module();
  write_png(path, image.sectors, image.rings, [&](detail::PngSink sink, void* closure) {
    return module.pixels(image.sectors, image.rings, pixels.data(), sink, closure);
  });
}

}  // namespace surfcomp::report
