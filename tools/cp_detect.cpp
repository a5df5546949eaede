// surfcomp cp-detect: the shape critical points (peaks and valleys) of a surface, as JSON and,
// for viewing, as PDB or PLY points.
#include "command.hpp"
#include "command_files.hpp"
#include "console.hpp"
#include "json_text.hpp"
#include "options.hpp"
#include "surface_input.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/mesh/io/ply.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp cp-detect INPUT -o CPS.json [--points-out CPS.pdb|CPS.ply] [options]\n\n"
    "Finds the shape critical points of a surface (seed 3.2): peaks, convex vertices whose |cc1|\n"
    "is the largest within the on-surface radius; valleys, concave vertices whose cc1 is the\n"
    "largest within it. Each comes with its position, normal, curvature and the shape index,\n"
    "ESP and LP averaged over a small geodesic disc.\n\n"
    "INPUT  a molecule or mesh (as surf-build) or a .hsi file (its stored critical points)";

nlohmann::json to_json(const std::vector<mesh::CriticalPoint>& points) {
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    list.push_back({{"index", i},
                    {"type", mesh::type_name(p.type)},
                    {"vertex", p.vertex},
                    {"position", {p.position.x(), p.position.y(), p.position.z()}},
                    {"normal", {p.normal.x(), p.normal.y(), p.normal.z()}},
                    {"cc1", p.cc1},
                    {"cc2", p.cc2},
                    {"shape_index", p.shape_index},
                    {"curvedness", p.curvedness},
                    {"esp", p.esp},
                    {"lp", p.lp}});
  }
  return list;
}

/// HETATM records, one per point: name PK/VL, residue CPK/CVL, B-factor = cc1.
void write_points_pdb(const std::vector<mesh::CriticalPoint>& points, std::ostream& out) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    const bool peak = p.type == mesh::CriticalPointType::peak;
    char line[96];
    std::snprintf(line, sizeof line,
                  "HETATM%5zu  %-3s %3s X%4zu    %8.3f%8.3f%8.3f  1.00%6.2f           %s\n",
                  (i + 1) % 100000, peak ? "PK" : "VL", peak ? "CPK" : "CVL", (i + 1) % 10000,
                  p.position.x(), p.position.y(), p.position.z(), p.cc1, peak ? "C" : "O");
    out << line;
  }
  out << "END\n";
}

/// A point cloud PLY (no faces) with normals and per-point type (0 peak, 1 valley) and cc1.
mesh::Surface points_as_surface(const std::vector<mesh::CriticalPoint>& points) {
  Eigen::MatrixX3d positions(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::MatrixX3d normals(positions.rows(), 3);
  Eigen::VectorXd type(positions.rows()), cc1(positions.rows());
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    const auto& p = points[static_cast<std::size_t>(i)];
    positions.row(i) = p.position.transpose();
    normals.row(i) = p.normal.transpose();
    type(i) = p.type == mesh::CriticalPointType::peak ? 0 : 1;
    cc1(i) = p.cc1;
  }
  mesh::Surface cloud = mesh::Surface::from_arrays(positions, Eigen::MatrixX3i(0, 3), "<points>");
  cloud.set_normals(normals);
  cloud.set_property("type", type, mesh::ValueType::uint8);
  cloud.set_property(mesh::property::cc1, cc1);
  return cloud;
}

}  // namespace

int cp_detect(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, points_out;
  SurfaceInput input;
  mesh::CriticalPointOptions cp_options;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "critical points as JSON")
      ("points-out", po::value(&points_out), "also write the points for viewing: .pdb or .ply")
      ("critical-point-radius", defaulted(&cp_options.radius),
       "critical point radius r_cp (on-surface), A")
      ("disc-radius",
       defaulted(&cp_options.property_disc_radius),
       "geodesic disc over which shape index, ESP and LP are averaged, A");
  // clang-format on
  add_surface_options(described, input);
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, kUsage, vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing INPUT (see --help)");
  const std::filesystem::path path = vm["input"].as<std::vector<std::string>>().front();
  finish_surface_options(input);
  require_in_range("critical-point-radius", cp_options.radius, 1e-3, 100.0);
  require_in_range("disc-radius", cp_options.property_disc_radius, 0.0, 100.0);
  const bool from_hsi = harmonic::io::is_hsi_file(path);
  if (!from_hsi) mesh::check_surface_input(path, input);
  check_command_files(
      {{{"INPUT", path}, {"--molecule", input.molecule_file}},
       {{"--output", output, {}, ""}, {"--points-out", points_out, {".pdb", ".ply"}, ""}}});

  Stopwatch clock;
  std::vector<mesh::CriticalPoint> points;
  std::size_t n_vertices = 0;
  if (from_hsi) {
    const harmonic::SurfaceDescriptors stored = harmonic::io::read_hsi(path);
    for (const auto& cp : stored.critical_points) points.push_back(cp.point);
    cp_options = stored.options.critical_points;
    n_vertices = stored.surface.n_vertices();
  } else {
    const mesh::LoadedSurface loaded = mesh::load_surface(path, input);
    points = mesh::detect_critical_points(loaded.surface, cp_options);
    n_vertices = loaded.surface.n_vertices();
  }
  const double elapsed = clock.elapsed_ms();
  std::size_t peaks = 0;
  for (const auto& p : points) peaks += p.type == mesh::CriticalPointType::peak ? 1 : 0;

  const nlohmann::json document = {
      {"input", path.string()},
      {"parameters",
       {{"radius", cp_options.radius}, {"disc_radius", cp_options.property_disc_radius}}},
      {"surface_vertices", n_vertices},
      {"peaks", peaks},
      {"valleys", points.size() - peaks},
      {"critical_points", to_json(points)}};
  // The JSON goes last; if it cannot be written, the points file written before it is removed,
  // so a failure leaves no output at all.
  if (!points_out.empty()) {
    if (io::lowercase_extension(points_out) == ".pdb") {
      surfcomp::io::write_file_atomically(
          points_out, [&](std::ostream& out) { write_points_pdb(points, out); });
    } else {
      mesh::io::write_ply(points_as_surface(points), points_out, mesh::io::PlyFormat::ascii);
    }
  }
  try {
    surfcomp::io::write_file_atomically(output,
                                        [&](std::ostream& out) { out << json_text(document); });
  } catch (...) {
    if (!points_out.empty()) std::filesystem::remove(points_out);
    throw;
  }
  console::summary("%s: %zu vertices, %zu peaks, %zu valleys (r_cp %.2f A), %.0f ms -> %s\n",
                   path.string().c_str(), n_vertices, peaks, points.size() - peaks,
                   cp_options.radius, elapsed, output.c_str());
  return 0;
}

}  // namespace surfcomp::tools
