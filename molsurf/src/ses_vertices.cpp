#include "ses_vertices.hpp"

#include "surface_mesh.hpp"

#include <tbb/parallel_for.h>

namespace surfcomp::molsurf::detail {

void place_ses_vertices(mesh::Surface& surface, const SasGeometry& sas, double reach,
                        bool compensate, const BallUnion* region) {
  mesh::TriMesh& mesh = mesh::tri_mesh(surface);
  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  Eigen::MatrixX3d positions = surface.positions();
  Eigen::MatrixX3d normals(n, 3);
  Eigen::VectorXd curvature(n);
  tbb::parallel_for(Eigen::Index{0}, n, [&](Eigen::Index v) {
    const Vec3 start = positions.row(v).transpose();
    Vec3 x = start;
    Vec3 normal = Vec3::Zero();
    double h = 0.0;
    sas.project_to_ses(x, reach, normal, h);
    if (region != nullptr) place_in_region(start, sas, reach, *region, x, normal, h);
    positions.row(v) = x.transpose();
    normals.row(v) = normal.transpose();
    curvature(v) = h;
  });
  for (auto vh : mesh.vertices()) {
    const Eigen::Index v = vh.idx();
    mesh.set_point(vh, mesh::TriMesh::Point(positions(v, 0), positions(v, 1), positions(v, 2)));
  }
  // A vertex with no surface point within reach keeps its place and takes the mesh normal.
  finish_placement(surface, normals, curvature, compensate);
}

void place_in_region(const Vec3& start, const SasGeometry& sas, double reach,
                     const BallUnion& region, Vec3& x, Vec3& normal, double& mean_curvature) {
  // The surface is the boundary of (SES region) cut to the union: its nearest point to `start`
  // is the SES point if that lies in the union, or the union's sphere point if that lies in
  // the SES region, whichever is nearer; a vertex where neither holds (on the seam) stays.
  const bool on_ses = normal.squaredNorm() > 0.0 && region.value(x) <= 0.0;
  if (region.value(start) <= -reach) return;  // no sphere of the region within reach
  Vec3 y, sphere_normal;
  double sphere_curvature = 0.0;
  bool on_sphere = region.boundary_point(start, y, sphere_normal, sphere_curvature);
  if (on_sphere) {
    SasGeometry::Candidates candidates;
    sas.gather(y, 0.0, sas.probe() + reach, candidates);
    on_sphere = sas.ses_value(y, reach, candidates) <= 0.0;
  }
  if (on_sphere && (!on_ses || (y - start).norm() < (x - start).norm())) {
    x = y;
    normal = sphere_normal;
    mean_curvature = sphere_curvature;
  } else if (!on_ses) {
    x = start;
    normal = Vec3::Zero();
    mean_curvature = 0.0;
  }
}

void finish_placement(mesh::Surface& surface, Eigen::MatrixX3d& normals,
                      const Eigen::VectorXd& curvature, bool compensate) {
  if ((normals.rowwise().squaredNorm().array() == 0.0).any()) {
    surface.compute_normals();
    const Eigen::MatrixX3d mesh_normals = surface.normals();
    for (Eigen::Index v = 0; v < normals.rows(); ++v) {
      if (normals.row(v).squaredNorm() == 0.0) normals.row(v) = mesh_normals.row(v);
    }
  }
  surface.set_normals(normals);
  if (compensate) compensate_chord_gaps(surface, normals, curvature);
}

void compensate_chord_gaps(mesh::Surface& surface, const Eigen::MatrixX3d& normals,
                           const Eigen::VectorXd& curvature) {
  mesh::TriMesh& mesh = mesh::tri_mesh(surface);
  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  Eigen::MatrixX3d positions = surface.positions();
  Eigen::VectorXd squared_edges = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd face_count = Eigen::VectorXd::Zero(n);
  for (auto f : mesh.faces()) {
    double sum = 0.0;
    for (auto h : mesh.fh_range(f)) sum += mesh.calc_edge_sqr_length(h);
    for (auto v : mesh.fv_range(f)) {
      squared_edges(v.idx()) += sum;
      face_count(v.idx()) += 1.0;
    }
  }
  for (auto vh : mesh.vertices()) {
    const Eigen::Index v = vh.idx();
    if (face_count(v) == 0.0 || normals.row(v).squaredNorm() == 0.0) continue;
    const double gap = curvature(v) * squared_edges(v) / face_count(v) / 24.0;
    positions.row(v) += gap * normals.row(v);
    mesh.set_point(vh, mesh::TriMesh::Point(positions(v, 0), positions(v, 1), positions(v, 2)));
  }
}

}  // namespace surfcomp::molsurf::detail
