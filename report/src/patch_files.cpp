#include "surfcomp/report/patch_files.hpp"

#include "png_module.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/loadable_module.hpp"
#include "surfcomp/harmonic/map_distortion.hpp"
#include "surfcomp/mesh/io/ply.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
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

/// The colour of `value` on viridis from 0 (dark purple) to `top` (yellow), as 8-bit RGB;
/// values beyond the range are clamped.
std::array<std::uint8_t, 3> viridis_colour(double value, double top) {
  // Viridis at 0, 1/4, 1/2, 3/4 and 1, linearly between.
  static constexpr std::array<std::array<double, 3>, 5> anchors = {
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  const double t = std::clamp(value / top, 0.0, 1.0) * 4.0;
  const auto below = std::min<std::size_t>(static_cast<std::size_t>(t), 3);
  const double w = t - static_cast<double>(below);
  std::array<std::uint8_t, 3> rgb{};
  for (std::size_t k = 0; k < 3; ++k)
    rgb[k] = static_cast<std::uint8_t>(
        std::lround(anchors[below][k] + (anchors[below + 1][k] - anchors[below][k]) * w));
  return rgb;
}

/// The checkerboard laid on a patch (write_methods_png): the colour of a patch point.
class PatchCheckerboard {
 public:
  PatchCheckerboard(const mesh::Patch& patch, int squares) {
    const Eigen::MatrixX3d& p = patch.positions;
    centre_ = p.colwise().mean().transpose();
    const Eigen::MatrixX3d centred = p.rowwise() - centre_.transpose();
    // Eigenvalues ascending: the normal of the best-fit plane first, then its two axes.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> axes(centred.transpose() * centred);
    frame_ = axes.eigenvectors().rowwise().reverse().transpose();
    double area = 0.0;
    for (Eigen::Index f = 0; f < patch.faces.rows(); ++f) {
      const Eigen::Vector3d a = p.row(patch.faces(f, 0)), b = p.row(patch.faces(f, 1)),
                            c = p.row(patch.faces(f, 2));
      area += 0.5 * (b - a).cross(c - a).norm();
    }
    const double side = 2.0 * std::sqrt(area / M_PI) / squares;
    per_side_ = side > 0.0 && std::isfinite(side) ? 1.0 / side : 0.0;
  }

  std::array<std::uint8_t, 3> colour(const Eigen::Vector3d& point) const {
    const Eigen::Vector3d cell = frame_ * (point - centre_) * per_side_;
    // The best-fit plane lies mid-way through a layer of cubes.
    const long long parity = static_cast<long long>(std::floor(cell.x())) +
                             static_cast<long long>(std::floor(cell.y())) +
                             static_cast<long long>(std::floor(cell.z() + 0.5));
    return parity % 2 == 0 ? std::array<std::uint8_t, 3>{45, 85, 140}
                           : std::array<std::uint8_t, 3>{200, 215, 235};
  }

 private:
  Eigen::Vector3d centre_;
  Eigen::Matrix3d frame_;  ///< rows: the plane's first and second axis, its normal
  double per_side_ = 0.0;  ///< 1 / the squares' side, 1/A
};

/// An RGB image of whole panels, and the drawing of a map's triangles into one of them.
class PanelCanvas {
 public:
  PanelCanvas(int columns, int rows, int panel)
      : width_(columns * panel),
        panel_(panel),
        rgb_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(rows * panel) * 3, 255) {}

  /// Draws the triangles of `uv` (the square [-1, 1]^2, v up, a margin around it) into the
  /// panel at (column, row): each pixel whose centre lies in triangle f (later triangles over
  /// earlier ones) takes colour(f, barycentric coordinates).
  void draw(int column, int row, const Eigen::MatrixX3i& faces, const Eigen::MatrixX2d& uv,
            const std::function<std::array<std::uint8_t, 3>(Eigen::Index, const Eigen::Vector3d&)>&
                colour) {
    const double margin = std::max(4.0, panel_ / 24.0), scale = (panel_ - 2.0 * margin) / 2.0;
    const double x0 = column * panel_, y0 = row * panel_;
    const auto pixel = [&](Eigen::Index v) {
      return Eigen::Vector2d(x0 + panel_ / 2.0 + scale * uv(v, 0),
                             y0 + panel_ / 2.0 - scale * uv(v, 1));
    };
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      const Eigen::Vector2d a = pixel(faces(f, 0)), b = pixel(faces(f, 1)), c = pixel(faces(f, 2));
      const double twice_area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      if (twice_area == 0.0) continue;
      // The pixels whose centres lie within the triangle's bounding box and the panel.
      const auto first = [&](double lo, double start) {
        return static_cast<int>(std::clamp(std::ceil(lo - 0.5), start, start + panel_));
      };
      const auto last = [&](double hi, double start) {
        return static_cast<int>(std::clamp(std::floor(hi - 0.5), start - 1, start + panel_ - 1));
      };
      const int xa = first(std::min({a.x(), b.x(), c.x()}), x0);
      const int xb = last(std::max({a.x(), b.x(), c.x()}), x0);
      const int ya = first(std::min({a.y(), b.y(), c.y()}), y0);
      const int yb = last(std::max({a.y(), b.y(), c.y()}), y0);
      for (int y = ya; y <= yb; ++y) {
        for (int x = xa; x <= xb; ++x) {
          const Eigen::Vector2d q(x + 0.5, y + 0.5);
          const double wb = ((q - a).x() * (c - a).y() - (q - a).y() * (c - a).x()) / twice_area;
          const double wc = ((b - a).x() * (q - a).y() - (b - a).y() * (q - a).x()) / twice_area;
          const double wa = 1.0 - wb - wc;
          constexpr double kEdge = -1e-9;  // a pixel centre on a shared edge is drawn
          if (wa < kEdge || wb < kEdge || wc < kEdge) continue;
          const std::array<std::uint8_t, 3> rgb = colour(f, Eigen::Vector3d(wa, wb, wc));
          std::copy(rgb.begin(), rgb.end(),
                    rgb_.begin() + 3 * (static_cast<std::ptrdiff_t>(y) * width_ + x));
        }
      }
    }
  }

  /// Fills the panel at (column, row) with `rgb`.
  void fill(int column, int row, const std::array<std::uint8_t, 3>& rgb) {
    for (int y = row * panel_; y < (row + 1) * panel_; ++y)
      for (int x = column * panel_; x < (column + 1) * panel_; ++x)
        std::copy(rgb.begin(), rgb.end(),
                  rgb_.begin() + 3 * (static_cast<std::ptrdiff_t>(y) * width_ + x));
  }

  const std::uint8_t* data() const { return rgb_.data(); }

 private:
  int width_, panel_;
  std::vector<std::uint8_t> rgb_;
};

}  // namespace

void write_patch_obj(const mesh::Patch& patch, const harmonic::DiskMap& map,
                     const std::filesystem::path& path, const std::string& map_name) {
  check_map(patch, map);
  io::write_file_atomically(path, [&](std::ostream& out) {
    char line[160];
    out << "# surfcomp patch-map: a geodesic patch with its " << map_name
        << " as\n# texture coordinates, (s, t) = ((u + 1) / 2, (v + 1) / 2)\n";
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

Eigen::MatrixX2d fit_to_disk_square(const Eigen::Ref<const Eigen::MatrixX2d>& uv) {
  if (uv.rows() == 0 || !uv.allFinite())
    throw InputError("free-border map: expected finite points, got " +
                     std::string(uv.rows() == 0 ? "none" : "one that is not finite"));
  const Eigen::RowVector2d lo = uv.colwise().minCoeff(), hi = uv.colwise().maxCoeff();
  const double side = (hi - lo).maxCoeff();
  if (!(side > 0.0))
    throw InputError("free-border map: all its " + std::to_string(uv.rows()) +
                     " points are at one place");
  return (uv.rowwise() - (lo + hi) / 2.0) * (2.0 / side);
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

void write_methods_png(const mesh::Patch& patch, const std::vector<MethodMap>& maps,
                       const std::filesystem::path& path, const MethodsPngOptions& options) {
  if (options.panel < 64 || options.panel > 2048)
    throw OptionError("panel " + std::to_string(options.panel) + " pixels: expected 64 to 2048");
  if (options.checker_squares < 1 || options.checker_squares > 64)
    throw OptionError("checker squares " + std::to_string(options.checker_squares) +
                      ": expected 1 to 64");
  if (!std::isfinite(options.angle_top_degrees) || !(options.angle_top_degrees > 0.0))
    throw OptionError("angle scale top " + std::to_string(options.angle_top_degrees) +
                      " degrees: expected finite and > 0");
  if (maps.empty()) throw InputError("patch maps figure: no maps to draw");
  for (const MethodMap& m : maps) {
    if (m.uv.rows() == 0) continue;
    if (m.uv.rows() != patch.positions.rows() || !m.uv.allFinite()) {
      throw InputError("patch maps figure: the " + m.name + " map has " +
                       std::to_string(m.uv.rows()) + " points, not one finite point per " +
                       std::to_string(patch.positions.rows()) + " patch vertices");
    }
  }
  const int columns = static_cast<int>(maps.size()), p = options.panel;
  const PatchCheckerboard checker(patch, options.checker_squares);
  PanelCanvas canvas(columns, 2, p);
  std::vector<const char*> titles, notes;
  for (int c = 0; c < columns; ++c) {
    const MethodMap& m = maps[static_cast<std::size_t>(c)];
    titles.push_back(m.name.c_str());
    notes.push_back(m.uv.rows() == 0 ? "failed" : "");
    if (m.uv.rows() == 0) {
      canvas.fill(c, 0, {kNoValue, kNoValue, kNoValue});
      canvas.fill(c, 1, {kNoValue, kNoValue, kNoValue});
      continue;
    }
    const Eigen::MatrixX3i& faces = patch.faces;
    canvas.draw(c, 0, faces, m.uv, [&](Eigen::Index f, const Eigen::Vector3d& w) {
      const Eigen::Vector3d point = w(0) * patch.positions.row(faces(f, 0)).transpose() +
                                    w(1) * patch.positions.row(faces(f, 1)).transpose() +
                                    w(2) * patch.positions.row(faces(f, 2)).transpose();
      return checker.colour(point);
    });
    const Eigen::VectorXd angle =
        harmonic::corner_angle_distortion(patch.positions, faces, m.uv).rowwise().mean();
    canvas.draw(c, 1, faces, m.uv, [&](Eigen::Index f, const Eigen::Vector3d&) {
      return viridis_colour(angle(f), options.angle_top_degrees);
    });
  }
  constexpr int kBarSamples = 256;
  std::vector<std::uint8_t> bar;
  bar.reserve(std::size_t{3} * kBarSamples);
  for (int i = 0; i < kBarSamples; ++i) {
    const std::array<std::uint8_t, 3> c = viridis_colour(
        options.angle_top_degrees * (i + 0.5) / kBarSamples, options.angle_top_degrees);
    bar.insert(bar.end(), c.begin(), c.end());
  }
  const std::string lo = "0", mid = number(options.angle_top_degrees / 2),
                    hi = number(options.angle_top_degrees) + "+";
  detail::PanelGrid grid;
  grid.columns = columns;
  grid.panel = p;
  grid.panel_rgb = canvas.data();
  grid.titles = titles.data();
  grid.notes = notes.data();
  grid.bar_samples = kBarSamples;
  grid.bar_colours = bar.data();
  grid.lo_text = lo.c_str();
  grid.mid_text = mid.c_str();
  grid.hi_text = hi.c_str();
  grid.caption =
      "angle distortion per triangle: mean |angle in the map - angle on the patch|, "
      "degrees";
  const detail::PngModule& module = png_module();
  write_png(path, columns * p, 2 * p + 84, [&](detail::PngSink sink, void* closure) {
    return module.panel_grid(&grid, sink, closure);
  });
}

}  // namespace surfcomp::report
