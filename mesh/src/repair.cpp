// CGAL adapter: a triangle soup repaired with Polygon Mesh Processing. CGAL stays in this
// translation unit.
#include "surfcomp/mesh/repair.hpp"

#include "io/stl_soup.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/mesh/io/formats.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <string>
#include <vector>

namespace surfcomp::mesh {
namespace {

namespace pmp = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using CgalMesh = CGAL::Surface_mesh<Point>;
using Polygons = std::vector<std::vector<std::size_t>>;

std::string count(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

/// The soup repaired into a 2-manifold mesh, counting the changes.
RepairedMesh repair_soup(std::vector<Point> points, Polygons polygons, const std::string& source) {
  RepairedMesh out;
  RepairReport& report = out.report;
  const std::size_t points_read = points.size();
  const std::size_t polygons_read = polygons.size();
  pmp::repair_polygon_soup(points, polygons);
  report.merged_vertices = points_read > points.size() ? points_read - points.size() : 0;
  report.removed_faces = polygons_read > polygons.size() ? polygons_read - polygons.size() : 0;
  if (polygons.empty()) throw InputError(source + ": no face is left after the repair");
  const std::size_t before_orienting = points.size();
  pmp::orient_polygon_soup(points, polygons);
  report.split_vertices = points.size() - before_orienting;

  CgalMesh mesh;
  pmp::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (!CGAL::is_triangle_mesh(mesh)) pmp::triangulate_faces(mesh);
  report.stitched_edges = pmp::stitch_borders(mesh);
  // A degenerate face goes by a collapse (the face count drops) or by an edge flip that makes
  // two proper triangles of it and a neighbour (the count stays): count whichever is more.
  const std::size_t faces_before = mesh.number_of_faces();
  std::size_t degenerate = 0;
  for (const auto f : mesh.faces()) degenerate += pmp::is_degenerate_triangle_face(f, mesh);
  pmp::remove_degenerate_faces(mesh);
  mesh.collect_garbage();
  const std::size_t collapsed =
      faces_before > mesh.number_of_faces() ? faces_before - mesh.number_of_faces() : 0;
  report.removed_faces += std::max(collapsed, degenerate);
  report.dropped_components = pmp::keep_largest_connected_components(mesh, 1);
  mesh.collect_garbage();
  if (mesh.number_of_faces() == 0) throw InputError(source + ": no face is left after the repair");
  if (CGAL::is_closed(mesh) && !pmp::is_outward_oriented(mesh)) {
    pmp::reverse_face_orientations(mesh);
    report.reoriented = true;
  }

  Eigen::MatrixX3d positions(static_cast<Eigen::Index>(mesh.number_of_vertices()), 3);
  for (const auto v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    positions.row(static_cast<Eigen::Index>(v.idx())) << p.x(), p.y(), p.z();
  }
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(mesh.number_of_faces()), 3);
  for (const auto f : mesh.faces()) {
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      faces(static_cast<Eigen::Index>(f.idx()), k++) = static_cast<int>(v.idx());
  }
  out.surface = Surface::from_arrays(positions, faces, source);
  return out;
}

}  // namespace

std::string repair_note(const std::string& source, const RepairReport& report) {
  return source + ": repaired: " + report.summary();
}

std::string RepairReport::summary() const {
  std::vector<std::string> parts;
  if (merged_vertices > 0) {
    parts.push_back("merged or dropped " + count(merged_vertices, "duplicate or unused vertex",
                                                 "duplicate or unused vertices"));
  }
  if (removed_faces > 0) {
    parts.push_back("removed " + count(removed_faces, "degenerate or duplicate face",
                                       "degenerate or duplicate faces"));
  }
  if (split_vertices > 0) {
    parts.push_back(
        "split " + count(split_vertices, "non-manifold vertex copy", "non-manifold vertex copies"));
  }
  if (stitched_edges > 0)
    parts.push_back("stitched " + count(stitched_edges, "border edge pair", "border edge pairs"));
  if (dropped_components > 0) {
    parts.push_back("dropped " + count(dropped_components, "small component", "small components") +
                    " (the largest kept)");
  }
  if (reoriented) parts.emplace_back("turned the faces outward");
  if (parts.empty()) return "nothing to repair";
  std::string text = parts.front();
  for (std::size_t i = 1; i < parts.size(); ++i) text += ", " + parts[i];
  return text;
}

RepairedMesh repair_triangles(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                              const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                              const std::string& source) {
  std::vector<Point> points;
  points.reserve(static_cast<std::size_t>(positions.rows()));
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    if (!positions.row(i).allFinite()) {
      throw InputError(source + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
    points.emplace_back(positions(i, 0), positions(i, 1), positions(i, 2));
  }
  Polygons polygons(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int v = faces(f, c);
      if (v < 0 || v >= positions.rows()) {
        throw InputError(source + ": face " + std::to_string(f) + " names vertex " +
                         std::to_string(v) + ", outside 0.." +
                         std::to_string(positions.rows() - 1));
      }
      polygons[static_cast<std::size_t>(f)].push_back(static_cast<std::size_t>(v));
    }
  }
  return repair_soup(std::move(points), std::move(polygons), source);
}

namespace {

/// The polygon soup of `path`: STL through surfcomp's own reader (its messages name the file
/// and what is wrong), the other formats through CGAL's.
void read_soup(const std::filesystem::path& path, const io::MeshFormat& format,
               std::vector<Point>& points, Polygons& polygons) {
  if (format.extension == ".stl") {
    const io::detail::StlSoup soup =
        io::detail::read_stl_soup(surfcomp::io::read_input_file(path), path.string());
    for (std::size_t i = 0; i < soup.positions.size(); i += 3) {
      points.emplace_back(soup.positions[i], soup.positions[i + 1], soup.positions[i + 2]);
    }
    for (std::size_t t = 0; t < soup.triangles.size(); t += 3) {
      polygons.push_back({static_cast<std::size_t>(soup.triangles[t]),
                          static_cast<std::size_t>(soup.triangles[t + 1]),
                          static_cast<std::size_t>(soup.triangles[t + 2])});
    }
    return;
  }
  bool read = false;
  try {
    read = CGAL::IO::read_polygon_soup(path.string(), points, polygons,
                                       CGAL::parameters::verbose(false));
  } catch (const std::exception&) {
    read = false;
  }
  if (!read)
    throw InputError(path.string() + ": cannot be read as a polygon mesh for " +
                     options::named("repair"));
}

}  // namespace

RepairedMesh repair_mesh_file(const std::filesystem::path& path, std::size_t max_vertices) {
  const io::MeshFormat* format = io::find_mesh_format(path);
  if (format == nullptr || !format->repairable) {
    throw InputError(path.string() + ": " + options::named("repair") + " reads " +
                     io::mesh_extensions(io::MeshUse::repair) + " meshes, found '" +
                     path.extension().string() + "'");
  }
  std::vector<Point> points;
  Polygons polygons;
  read_soup(path, *format, points, polygons);
  if (points.empty() || polygons.empty()) {
    throw InputError(path.string() + ": cannot be read as a polygon mesh for " +
                     options::named("repair"));
  }
  if (points.size() > max_vertices) {
    throw InputError(path.string() + ": " + std::to_string(points.size()) +
                     " vertices, more than " + options::named("max_vertices") + " " +
                     std::to_string(max_vertices));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    surfcomp::io::check_read_position(Eigen::Vector3d(p.x(), p.y(), p.z()), path.string(),
                                      "vertex " + std::to_string(i));
  }
  for (const auto& polygon : polygons) {
    for (const std::size_t v : polygon) {
      if (v >= points.size())
        throw InputError(path.string() + ": a face names a vertex that does not exist");
    }
  }
  return repair_soup(std::move(points), std::move(polygons), path.string());
}

}  // namespace surfcomp::mesh
