// surfcomp patch-map: each critical point's geodesic patch, harmonic map and shape image as files
// for mesh-processing tools (OBJ with texture coordinates, PLY, PNG), optionally compared with
// CGAL's parameterization of the same patch.
#include "command.hpp"
#include "console.hpp"
#include "describe_settings.hpp"
#include "json_text.hpp"
#include "options.hpp"
#include "surface_input.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/harmonic/cgal_reference.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/report/patch_files.hpp"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace surfcomp::tools {
namespace {

/// The usage text; %d and %g are report::MethodsPngOptions' checker_squares and
/// angle_top_degrees (usage()).
constexpr const char* kUsage =
    "usage: surfcomp patch-map INPUT -o DIR [--cp I ... | --all] [--compare-cgal]\n"
    "                          [--methods M,M,...|all] [options]\n\n"
    "Writes, for each chosen critical point I (0-based, as cp-detect numbers them; --all: every\n"
    "one), its geodesic patch and harmonic map onto the unit disk (method §3-4) into DIR\n"
    "(made if missing; a general mesh described in its length unit, --scale and --unit, with\n"
    "the files in its own coordinates):\n"
    "  cpI.obj        the patch with the map as texture coordinates: vt = ((u+1)/2, (v+1)/2)\n"
    "  cpI.ply        the patch's vertices with the surface's properties, u, v and distance\n"
    "  cpI_image.png  the harmonic shape image as a polar plot with a colour bar\n"
    "  cpI_grid.png   the image's grid, one pixel per grid point (sectors x rings)\n"
    "  patch_maps.json  every critical point written, with its files and, with --compare-cgal,\n"
    "                 the comparison; with --methods, each method's figures and file\n"
    "--compare-cgal also maps each patch with CGAL's Surface_mesh_parameterization (the same\n"
    "border and spring weights) and prints, per point, the largest and mean distance between\n"
    "the two maps, the angle and area distortion and flipped triangles of both, and both times.\n"
    "--methods maps each patch with each named method and prints, per point and method, the\n"
    "angle distortion (mean and largest |angle difference|, degrees), the area distortion\n"
    "(mean and largest |ln area ratio|), flipped triangles and the time, then each method's\n"
    "medians over the points: harmonic (ours, --weights), and CGAL's tutte, mean-value,\n"
    "discrete-conformal, discrete-authalic (unit circle border by arc length), lscm and arap\n"
    "(free border); all: every one. A method that fails on a patch says so in its row and is\n"
    "left out of its medians (failed: the count). It also writes, per point:\n"
    "  cpI_M.obj      the patch with method M's map as texture coordinates, as cpI.obj; a\n"
    "                 free-border map (lscm, arap) moved and scaled by one factor so that its\n"
    "                 longer side spans the unit square, centred, its aspect ratio kept.\n"
    "                 cpI_harmonic.obj holds cpI.obj's map. None for a method that failed.\n"
    "  cpI_methods.png  the maps side by side, a column per method (empty and labelled\n"
    "                 \"failed\" for one that failed). Top row: a checkerboard laid on the\n"
    "                 patch (squares of 1/%d of its diameter, in its best-fit plane) seen\n"
    "                 through the map: a map that keeps angles shows squares, of whatever\n"
    "                 size; shear and stretch show as such. Bottom row: each triangle's angle\n"
    "                 distortion (mean |angle in the map - angle on the patch| at its corners)\n"
    "                 on one colour scale for every method, 0 to %g degrees or more.\n\n"
    "INPUT  a molecule or mesh (as hsi-build), or a .hsi file (its stored patches and maps; the\n"
    "       description options then do not apply)";

/// kUsage with the figure's defaults, from the one place that sets them.
std::string usage() {
  const report::MethodsPngOptions figure;
  const int length =
      std::snprintf(nullptr, 0, kUsage, figure.checker_squares, figure.angle_top_degrees);
  std::string text(static_cast<std::size_t>(length) + 1, '\0');
  std::snprintf(text.data(), text.size(), kUsage, figure.checker_squares, figure.angle_top_degrees);
  text.pop_back();
  return text;
}

struct Chosen {
  std::size_t index = 0;
  harmonic::CriticalPointDescriptor descriptor;
};

nlohmann::json distortion_json(const harmonic::MapDistortion& d) {
  return {{"angle_mean_degrees", d.angle_mean_degrees},
          {"angle_max_degrees", d.angle_max_degrees},
          {"area_mean_log", d.area_mean_log},
          {"area_max_log", d.area_max_log},
          {"flipped", d.flipped}};
}

/// The options of `described` the user gave (not left at their defaults), but --threads, which
/// applies to any INPUT.
std::vector<std::string> given_options(const boost::program_options::options_description& described,
                                       const boost::program_options::variables_map& vm) {
  std::vector<std::string> given;
  for (const auto& option : described.options()) {
    const std::string& name = option->long_name();
    if (name != "threads" && vm.count(name) != 0 && !vm[name].defaulted())
      given.push_back("--" + name);
  }
  return given;
}

/// The methods named in --methods: names from harmonic::parameterization_names, comma-separated,
/// or "all".
std::vector<harmonic::Parameterization> parameterizations(const std::string& text) {
  const auto& names = harmonic::parameterization_names;
  std::vector<harmonic::Parameterization> out;
  std::string known;
  for (const char* name : names) known += std::string(known.empty() ? "" : ", ") + name;
  std::stringstream list(text);
  std::string name;
  while (std::getline(list, name, ',')) {
    if (name == "all") {
      for (std::size_t i = 0; i < names.size(); ++i)
        out.push_back(static_cast<harmonic::Parameterization>(i));
      continue;
    }
    const std::optional<harmonic::Parameterization> method =
        harmonic::parameterization_from_name(name);
    if (!method)
      throw OptionError("--methods " + text + ": unknown method '" + name + "' (" + known +
                        ", all)");
    out.push_back(*method);
  }
  // A method named twice ("all,lscm") is compared once, where it is first named: each has one
  // column and one file.
  std::vector<harmonic::Parameterization> once;
  for (const harmonic::Parameterization method : out)
    if (std::find(once.begin(), once.end(), method) == once.end()) once.push_back(method);
  out = once;
  if (out.empty()) throw OptionError("--methods: expected one or more of " + known + ", or all");
  return out;
}

const char* method_name(harmonic::Parameterization method) {
  return harmonic::parameterization_names[static_cast<std::size_t>(method)];
}

double median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2),
                   values.end());
  return values[values.size() / 2];
}

/// The critical points of a patch map's INPUT: the surface, the chosen points described, how
/// many there are, and the unit the radii count in.
struct ChosenPoints {
  std::vector<Chosen> chosen;
  mesh::Surface surface;
  std::size_t total = 0;
  double length_unit = 1.0;  ///< in the input's coordinates
};

/// The points `all` or `indices` choose, read from a .hsi (whose stored description options
/// replace settings.descriptors) or described now.
ChosenPoints choose_points(const std::filesystem::path& path, bool from_hsi, bool all,
                           const std::vector<int>& chosen_indices,
                           matching::MatchInputOptions& settings) {
  ChosenPoints out;
  std::vector<Chosen>& chosen = out.chosen;
  mesh::Surface& surface = out.surface;
  std::size_t& total = out.total;
  double& length_unit = out.length_unit;
  if (from_hsi) {
    harmonic::SurfaceDescriptors stored = harmonic::io::read_hsi(path);
    surface = std::move(stored.surface);
    length_unit = stored.length_unit;
    total = stored.critical_points.size();
    settings.descriptors = stored.options;
    for (std::size_t i = 0; i < total; ++i) {
      if (all || std::count(chosen_indices.begin(), chosen_indices.end(), static_cast<int>(i)))
        chosen.push_back({i, std::move(stored.critical_points[i])});
    }
  } else {
    // Described in the input's length unit, as hsi-build and match describe it; the files are
    // written in its own coordinates.
    molsurf::LoadedSurface loaded = load_noted(path, settings.input);
    length_unit = loaded.unit.value;
    surface = std::move(loaded.surface);
    const std::vector<mesh::CriticalPoint> points = mesh::detect_critical_points_in_unit(
        surface, length_unit, settings.descriptors.critical_points);
    total = points.size();
    std::vector<std::size_t> indices;
    std::vector<mesh::CriticalPoint> picked;
    for (std::size_t i = 0; i < total; ++i) {
      if (all || std::count(chosen_indices.begin(), chosen_indices.end(), static_cast<int>(i))) {
        indices.push_back(i);
        picked.push_back(points[i]);
      }
    }
    std::vector<harmonic::CriticalPointDescriptor> descriptions =
        harmonic::describe_points_in_unit(surface, picked, length_unit, settings.descriptors);
    for (std::size_t k = 0; k < indices.size(); ++k)
      chosen.push_back({indices[k], std::move(descriptions[k])});
  }
  return out;
}

/// The patch of `c` mapped by each of `methods`: each map's file (the harmonic one is the
/// description's map) and the side-by-side figure written into `staging` (their names added to
/// `staged` and to entry["files"]), entry["methods"] set, a table row printed per method.
std::vector<harmonic::ParameterizationResult> compare_methods(
    const Chosen& c, const std::vector<harmonic::Parameterization>& methods,
    const matching::MatchInputOptions& settings, const std::filesystem::path& staging,
    nlohmann::json& entry, std::vector<std::string>& staged) {
  const std::string stem = "cp" + std::to_string(c.index);
  const mesh::Patch& patch = c.descriptor.patch;
  auto results = harmonic::compare_parameterizations(
      patch.positions, patch.faces, patch.outer_boundary, methods, settings.descriptors.disk_map);
  nlohmann::json compared = nlohmann::json::array();
  std::vector<report::MethodMap> figure;
  for (const harmonic::ParameterizationResult& r : results) {
    const char* name = method_name(r.method);
    if (!r.failure.empty()) {
      compared.push_back({{"method", name}, {"failure", r.failure}});
      figure.push_back({name, {}});
      console::summary("%4zu %-19s failed: %s\n", c.index, name, r.failure.c_str());
      continue;
    }
    // The harmonic column is the description's map, the one cpI.obj holds (the
    // comparison recomputes it from the same patch and options).
    harmonic::DiskMap map;
    map.uv = r.method == harmonic::Parameterization::harmonic ? c.descriptor.map.uv
             : harmonic::has_free_border(r.method)            ? report::fit_to_disk_square(r.uv)
                                                              : r.uv;
    const std::string file = stem + "_" + name + ".obj";
    report::write_patch_obj(patch, map, staging / file,
                            std::string(name) + (harmonic::has_free_border(r.method)
                                                     ? " map, fitted into the unit disk's square,"
                                                     : " map onto the unit disk"));
    staged.push_back(file);
    entry["files"].push_back(file);
    figure.push_back({name, map.uv});
    nlohmann::json one = distortion_json(r.distortion);
    one["method"] = name;
    one["ms"] = r.ms;
    one["file"] = file;
    compared.push_back(one);
    console::summary("%4zu %-19s %10.3f %10.3f %10.4f %10.4f %7d %9.3f\n", c.index, name,
                     r.distortion.angle_mean_degrees, r.distortion.angle_max_degrees,
                     r.distortion.area_mean_log, r.distortion.area_max_log, r.distortion.flipped,
                     r.ms);
  }
  const std::string side_by_side = stem + "_methods.png";
  report::write_methods_png(patch, figure, staging / side_by_side);
  staged.push_back(side_by_side);
  entry["files"].push_back(side_by_side);
  entry["methods"] = compared;
  return results;
}

/// Each method's median distortions and time over the patches it mapped (and how many it
/// failed), printed as a table and returned as JSON rows.
nlohmann::json method_medians(
    const std::vector<std::vector<harmonic::ParameterizationResult>>& by_point,
    const std::vector<harmonic::Parameterization>& methods) {
  nlohmann::json summary = nlohmann::json::array();
  if (!methods.empty() && !by_point.empty()) {
    console::summary("\nmedians over %zu patches:\n%-19s %10s %10s %10s %10s %7s %9s\n",
                     by_point.size(), "method", "angle deg", "angle max", "area", "area max",
                     "flipped", "ms");
    for (std::size_t m = 0; m < methods.size(); ++m) {
      std::vector<double> angle, angle_max, area, area_max, flipped, ms;
      std::size_t failed = 0;
      for (const auto& results : by_point) {
        const harmonic::ParameterizationResult& r = results[m];
        if (!r.failure.empty()) {
          ++failed;
          continue;
        }
        angle.push_back(r.distortion.angle_mean_degrees);
        angle_max.push_back(r.distortion.angle_max_degrees);
        area.push_back(r.distortion.area_mean_log);
        area_max.push_back(r.distortion.area_max_log);
        flipped.push_back(r.distortion.flipped);
        ms.push_back(r.ms);
      }
      const char* name = method_name(methods[m]);
      const std::vector<double> medians = {median(angle),    median(angle_max), median(area),
                                           median(area_max), median(flipped),   median(ms)};
      summary.push_back({{"method", name},
                         {"angle_mean_degrees", medians[0]},
                         {"angle_max_degrees", medians[1]},
                         {"area_mean_log", medians[2]},
                         {"area_max_log", medians[3]},
                         {"flipped", medians[4]},
                         {"ms", medians[5]},
                         {"failed", failed}});
      console::summary("%-19s %10.3f %10.3f %10.4f %10.4f %7.0f %9.3f%s\n", name, medians[0],
                       medians[1], medians[2], medians[3], medians[4], medians[5],
                       failed > 0 ? (" (failed on " + std::to_string(failed) + ")").c_str() : "");
    }
  }
  return summary;
}

/// Throws before any file is written when a file the patch map writes into `folder` would
/// replace a folder or special file, or one of `inputs`.
void check_targets(const std::filesystem::path& folder, const std::vector<Chosen>& chosen,
                   const std::vector<harmonic::Parameterization>& methods,
                   const std::vector<std::filesystem::path>& inputs) {
  std::error_code error;
  std::vector<std::string> names;
  for (const Chosen& c : chosen) {
    if (c.descriptor.status != harmonic::PatchStatus::ok) continue;
    const std::string stem = "cp" + std::to_string(c.index);
    for (const char* suffix : {".obj", ".ply", "_image.png", "_grid.png"})
      names.push_back(stem + suffix);
    for (const harmonic::Parameterization method : methods)
      names.push_back(stem + "_" + method_name(method) + ".obj");
    if (!methods.empty()) names.push_back(stem + "_methods.png");
  }
  names.emplace_back("patch_maps.json");
  for (const std::string& name : names) {
    const std::filesystem::path target = folder / name;
    if (std::filesystem::exists(target, error) &&
        !std::filesystem::is_regular_file(target, error)) {
      throw FileError(target.string(), "exists and is not a regular file");
    }
    for (const std::filesystem::path& input : inputs) {
      if (!input.empty() && io::same_file(target, input)) {
        throw OptionError(target.string() + " would overwrite the input " + input.string() +
                          ": refusing to overwrite an input");
      }
    }
  }
}

/// The patch of `c` mapped by CGAL's harmonic parameterization beside ours: the distance
/// between the maps and both distortions, printed as a table row and returned as JSON.
nlohmann::json compare_with_cgal(const Chosen& c, const matching::MatchInputOptions& settings) {
  const mesh::Patch& patch = c.descriptor.patch;
  const harmonic::DiskMapComparison m = harmonic::compare_with_cgal(
      patch.positions, patch.faces, patch.outer_boundary, settings.descriptors.disk_map);
  nlohmann::json row = {{"max_distance", m.max_distance},
                        {"mean_distance", m.mean_distance},
                        {"ours", distortion_json(m.ours_distortion)},
                        {"cgal", distortion_json(m.cgal_distortion)},
                        {"ours_ms", m.ours_ms},
                        {"cgal_ms", m.cgal_ms}};
  console::summary("%4zu %8ld %12.3g %12.3g %10.3f %10.3f %10.4f %10.4f %7d %7d %9.3f %9.3f\n",
                   c.index, static_cast<long>(patch.positions.rows()), m.max_distance,
                   m.mean_distance, m.ours_distortion.angle_mean_degrees,
                   m.cgal_distortion.angle_mean_degrees, m.ours_distortion.area_mean_log,
                   m.cgal_distortion.area_mean_log, m.ours_distortion.flipped,
                   m.cgal_distortion.flipped, m.ours_ms, m.cgal_ms);
  return row;
}

/// Prints the headers of the tables the run prints: CGAL's comparison (`compare`) and the
/// parameterizations' (`methods`).
void print_table_headers(bool compare, bool methods) {
  if (compare) {
    console::summary("%4s %8s %12s %12s %10s %10s %10s %10s %7s %7s %9s %9s\n", "cp", "vertices",
                     "max |d uv|", "mean |d uv|", "angle", "angle", "area", "area", "flipped",
                     "flipped", "ours ms", "CGAL ms");
    console::summary("%4s %8s %12s %12s %10s %10s %10s %10s %7s %7s\n", "", "", "", "", "ours deg",
                     "CGAL deg", "ours", "CGAL", "ours", "CGAL");
  }
  if (methods) {
    console::summary("%4s %-19s %10s %10s %10s %10s %7s %9s\n", "cp", "method", "angle deg",
                     "angle max", "area", "area max", "flipped", "ms");
  }
}

/// Writes critical point c's patch (OBJ, PLY) and image (two PNGs) into `staging`, adding their
/// names to `staged` and to `entry`'s files, and the patch's size to `entry`.
void write_point_files(const Chosen& c, const mesh::Surface& surface,
                       const matching::MatchInputOptions& settings,
                       const std::filesystem::path& staging, nlohmann::json& entry,
                       std::vector<std::string>& staged) {
  const std::string stem = "cp" + std::to_string(c.index);
  const mesh::Patch& patch = c.descriptor.patch;
  const std::vector<std::filesystem::path> files = {
      staging / (stem + ".obj"), staging / (stem + ".ply"), staging / (stem + "_image.png"),
      staging / (stem + "_grid.png")};
  report::write_patch_obj(patch, c.descriptor.map, files[0]);
  report::write_patch_ply(surface, patch, c.descriptor.map, files[1]);
  report::ImagePngOptions png;
  png.label = settings.descriptors.image_property == mesh::property::shape_index
                  ? "shape index"
                  : settings.descriptors.image_property;
  report::write_image_png(c.descriptor.image, files[2], png);
  report::write_image_grid_png(c.descriptor.image, files[3]);
  entry["patch_vertices"] = patch.positions.rows();
  entry["patch_faces"] = patch.faces.rows();
  for (const std::filesystem::path& file : files) {
    staged.push_back(file.filename().string());
    entry["files"].push_back(staged.back());
  }
}

}  // namespace

int patch_map(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output;
  std::vector<int> chosen_indices;
  po::options_description description_options("description options");
  add_describe_options(description_options);
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "the folder to write into")
      ("cp", po::value(&chosen_indices)->composing(),
       "a critical point to write (0-based; repeatable)")
      ("all", po::bool_switch(), "write every critical point that has a patch")
      ("compare-cgal", po::bool_switch(), "compare each map with CGAL's")
      ("methods", po::value<std::string>(),
       "parameterizations to compare on each patch, comma-separated, or all");
  // clang-format on
  described.add(description_options);
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, usage().c_str(), vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing INPUT (see --help)");
  const std::filesystem::path path = vm["input"].as<std::vector<std::string>>().front();
  const bool all = vm["all"].as<bool>(), compare = vm["compare-cgal"].as<bool>();
  const std::vector<harmonic::Parameterization> methods =
      vm.count("methods") ? parameterizations(vm["methods"].as<std::string>())
                          : std::vector<harmonic::Parameterization>{};
  if (all == !chosen_indices.empty())
    throw OptionError("give --cp I (one or more) or --all, not both and not neither");
  for (const int i : chosen_indices)
    if (i < 0) throw OptionError("--cp " + std::to_string(i) + ": expected an index >= 0");
  matching::MatchInputOptions settings = describe_options_from(vm);
  const bool from_hsi = harmonic::io::is_hsi_file(path);
  if (from_hsi) {
    const std::vector<std::string> given = given_options(description_options, vm);
    if (!given.empty()) {
      throw OptionError(given.front() +
                        " does not apply to a .hsi INPUT: its patches and maps "
                        "are stored");
    }
  } else {
    molsurf::check_surface_input(path, settings.input);
  }
  // "maps/" names the folder "maps", as a shell's completion writes it.
  const std::filesystem::path folder = std::filesystem::path(output).has_filename()
                                           ? std::filesystem::path(output)
                                           : std::filesystem::path(output).parent_path();
  if (folder.empty()) throw OptionError("--output: expected a folder, got '" + output + "'");
  std::error_code error;
  if (std::filesystem::exists(folder, error) && !std::filesystem::is_directory(folder, error))
    throw FileError(folder.string(), "exists and is not a folder");
  io::check_command_files(
      {{{"INPUT", path}, {"--molecule", settings.input.molecule_file}},
       {{"--output",
         std::filesystem::exists(folder, error) ? folder / "patch_maps.json" : folder,
         {},
         ""}}});
  const ThreadLimit limit(settings.threads);

  // The critical points, and the chosen ones described.
  const Stopwatch clock;
  ChosenPoints picked = choose_points(path, from_hsi, all, chosen_indices, settings);
  std::vector<Chosen>& chosen = picked.chosen;
  const mesh::Surface& surface = picked.surface;
  const std::size_t total = picked.total;
  const double length_unit = picked.length_unit;
  for (const int i : chosen_indices) {
    if (static_cast<std::size_t>(i) >= total) {
      throw InputError(path.string() + ": --cp " + std::to_string(i) + ", but it has " +
                       std::to_string(total) + " critical points (0 to " +
                       std::to_string(static_cast<long>(total) - 1) + ")");
    }
  }

  // Every file's name is checked against the inputs, and against a folder or special file in
  // its place, before any is written. The files go into a staging folder inside DIR and move
  // into DIR once all are written, patch_maps.json last: a failure leaves DIR as it was.
  check_targets(folder, chosen, methods, {path, settings.input.molecule_file});
  const bool made_folder = !std::filesystem::exists(folder, error);
  std::filesystem::create_directories(folder, error);
  if (error) throw FileError(folder.string(), "cannot make the folder (" + error.message() + ")");
  const std::filesystem::path staging = folder / (".patch-map-" + std::to_string(::getpid()));
  std::filesystem::remove_all(staging, error);
  std::filesystem::create_directory(staging, error);
  if (error) throw FileError(staging.string(), "cannot make the folder (" + error.message() + ")");
  std::size_t written = 0;
  std::vector<std::string> staged;  // the files written into the staging folder, in order
  try {
    nlohmann::json points = nlohmann::json::array();
    print_table_headers(compare, !methods.empty());
    std::vector<std::vector<harmonic::ParameterizationResult>> by_point;
    for (const Chosen& c : chosen) {
      nlohmann::json entry = {{"index", c.index},
                              {"type", mesh::type_name(c.descriptor.point.type)},
                              {"vertex", c.descriptor.point.vertex},
                              {"status", harmonic::to_string(c.descriptor.status)},
                              {"files", nlohmann::json::array()}};
      if (c.descriptor.status == harmonic::PatchStatus::ok) {
        write_point_files(c, surface, settings, staging, entry, staged);
        if (compare) entry["cgal"] = compare_with_cgal(c, settings);
        if (!methods.empty())
          by_point.push_back(compare_methods(c, methods, settings, staging, entry, staged));
        ++written;
      }
      points.push_back(entry);
    }
    const nlohmann::json summary = method_medians(by_point, methods);
    nlohmann::json document = {
        {"input", path.string()},
        {"critical_points", total},
        {"weights", harmonic::to_string(settings.descriptors.disk_map.weights)},
        {"patch_radius", settings.descriptors.patch.radius},
        {"image_rings", settings.descriptors.image.rings},
        {"image_sectors", settings.descriptors.image.sectors},
        {"points", points}};
    if (length_unit != 1.0) document["length_unit"] = length_unit;
    if (!methods.empty()) document["method_medians"] = summary;
    io::write_file_atomically(staging / "patch_maps.json",
                              [&](std::ostream& out) { out << json_text(document); });
    staged.emplace_back("patch_maps.json");
    for (const std::string& name : staged) std::filesystem::rename(staging / name, folder / name);
    std::filesystem::remove(staging);
  } catch (...) {
    std::filesystem::remove_all(staging, error);
    if (made_folder) std::filesystem::remove(folder, error);
    throw;
  }
  console::summary("%s: %zu of %zu critical points written (%zu without a patch), %.0f ms -> %s\n",
                   path.string().c_str(), written, total, chosen.size() - written,
                   clock.elapsed_ms(), folder.string().c_str());
  return 0;
}

}  // namespace surfcomp::tools
