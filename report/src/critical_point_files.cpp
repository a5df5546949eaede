#include "surfcomp/report/critical_point_files.hpp"

#include "match_document.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/mesh/io/ply.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace surfcomp::report {

std::string critical_points_json(const CriticalPointSet& set) {
  nlohmann::json list = nlohmann::json::array();
  std::size_t peaks = 0;
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    const mesh::CriticalPoint& p = set.points[i];
    peaks += p.type == mesh::CriticalPointType::peak ? 1 : 0;
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
  nlohmann::json document = {
      {"input", set.input},
      {"parameters",
       {{"radius", set.options.radius}, {"disc_radius", set.options.property_disc_radius}}},
      {"surface_vertices", set.surface_vertices},
      {"peaks", peaks},
      {"valleys", set.points.size() - peaks},
      {"critical_points", list}};
  if (set.length_unit != 1.0) document["parameters"]["length_unit"] = set.length_unit;
  return detail::json_text(document, 2) + "\n";
}

void write_critical_points_pdb(const std::vector<mesh::CriticalPoint>& points, std::ostream& out) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const mesh::CriticalPoint& p = points[i];
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

mesh::Surface critical_points_cloud(const std::vector<mesh::CriticalPoint>& points) {
  Eigen::MatrixX3d positions(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::MatrixX3d normals(positions.rows(), 3);
  Eigen::VectorXd type(positions.rows()), cc1(positions.rows());
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    const mesh::CriticalPoint& p = points[static_cast<std::size_t>(i)];
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

void write_critical_points(const std::filesystem::path& path, const CriticalPointSet& set) {
  const std::string extension = io::lowercase_extension(path);
  if (extension == ".json") {
    io::write_file_atomically(path, [&](std::ostream& out) { out << critical_points_json(set); });
  } else if (extension == ".pdb") {
    io::write_file_atomically(
        path, [&](std::ostream& out) { write_critical_points_pdb(set.points, out); });
  } else if (extension == ".ply") {
    mesh::io::write_ply(critical_points_cloud(set.points), path, mesh::io::PlyFormat::ascii);
  } else {
    throw InputError(path.string() + ": critical points are written as .json, .pdb or .ply");
  }
}

}  // namespace surfcomp::report
