// CGAL adapter: mesh::Surface <-> CGAL::Surface_mesh, isotropic remeshing. CGAL stays in this
// translation unit.
#include "surfcomp/mesh/remesh.hpp"

#include "surface_mesh.hpp"
#include "surfcomp/core/error.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <string>
#include <vector>

namespace surfcomp::mesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;

CgalMesh to_cgal(const Surface& surface) {
  const TriMesh& in = tri_mesh(surface);
  CgalMesh out;
  out.reserve(static_cast<CgalMesh::size_type>(in.n_vertices()),
              static_cast<CgalMesh::size_type>(in.n_edges()),
              static_cast<CgalMesh::size_type>(in.n_faces()));
  std::vector<CgalMesh::Vertex_index> handles;
  handles.reserve(in.n_vertices());
  for (auto v : in.vertices()) {
    const auto& p = in.point(v);
    handles.push_back(out.add_vertex(Kernel::Point_3(p[0], p[1], p[2])));
  }
  std::vector<CgalMesh::Vertex_index> tri;
  tri.reserve(3);
  for (auto f : in.faces()) {
    tri.clear();
    for (auto v : in.fv_range(f)) tri.push_back(handles[static_cast<std::size_t>(v.idx())]);
    if (out.add_face(tri) == CgalMesh::null_face()) {
      throw TopologyError(surface.source() + ": triangle " + std::to_string(f.idx()) +
                          " cannot be added to a 2-manifold mesh for remeshing");
    }
  }
  return out;
}

Surface from_cgal(CgalMesh& in, const std::string& source) {
  in.collect_garbage();
  Eigen::MatrixX3d positions(static_cast<Eigen::Index>(in.number_of_vertices()), 3);
  for (auto v : in.vertices()) {
    const auto& p = in.point(v);
    positions.row(static_cast<Eigen::Index>(v.idx())) << p.x(), p.y(), p.z();
  }
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(in.number_of_faces()), 3);
  for (auto f : in.faces()) {
    int k = 0;
    for (auto v : CGAL::vertices_around_face(in.halfedge(f), in)) {
      faces(static_cast<Eigen::Index>(f.idx()), k++) = static_cast<int>(v.idx());
    }
  }
  return Surface::from_arrays(positions, faces, source);
}

}  // namespace

double edge_length_for_density(double vertex_density) {
  if (!std::isfinite(vertex_density) || vertex_density <= 0.0) {
    throw OptionError("vertex density " + std::to_string(vertex_density) +
                      " per A^2: expected a finite value > 0");
  }
  return std::sqrt(2.0 / (std::sqrt(3.0) * vertex_density));
}

Surface isotropic_remesh(const Surface& input, double target_edge_length, int iterations,
                         bool project_to_input) {
  if (!std::isfinite(target_edge_length) || target_edge_length <= 0.0) {
    throw OptionError(input.source() + ": target edge length " +
                      std::to_string(target_edge_length) + " A: expected a finite value > 0");
  }
  if (iterations < 1) {
    throw OptionError(input.source() + ": " + std::to_string(iterations) +
                      " remeshing iterations: expected at least 1");
  }
  if (input.n_faces() == 0)
    throw TopologyError(input.source() + ": nothing to remesh (no triangles)");
  CgalMesh mesh = to_cgal(input);
  const auto rounds = static_cast<unsigned int>(iterations);
  if (project_to_input) {
    CGAL::Polygon_mesh_processing::isotropic_remeshing(
        faces(mesh), target_edge_length, mesh, CGAL::parameters::number_of_iterations(rounds));
  } else {
    // CGAL builds an AABB tree of the input for its default projection even when projection is
    // off; a projection of our own (never called) spares the tree. The result is the same.
    const auto unused_projection = [&mesh](CgalMesh::Vertex_index v) { return mesh.point(v); };
    CGAL::Polygon_mesh_processing::isotropic_remeshing(
        faces(mesh), target_edge_length, mesh,
        CGAL::parameters::number_of_iterations(rounds).do_project(false).projection_functor(
            unused_projection));
  }
  return from_cgal(mesh, input.source());
}

}  // namespace surfcomp::mesh
