#include "surfcomp/harmonic/cgal_reference.hpp"

#include "surfcomp/core/error.hpp"

#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Barycentric_mapping_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_authalic_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/Fixed_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Two_vertices_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <Eigen/SparseLU>

#include <cmath>
#include <string>

namespace surfcomp::harmonic {
namespace {

namespace smp = CGAL::Surface_mesh_parameterization;

using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexDescriptor = boost::graph_traits<Mesh>::vertex_descriptor;
using HalfedgeDescriptor = boost::graph_traits<Mesh>::halfedge_descriptor;
using Border = smp::Circular_border_arc_length_parameterizer_3<Mesh>;
using Solver = CGAL::Eigen_solver_traits<
    Eigen::SparseLU<CGAL::Eigen_sparse_matrix<double>::EigenType, Eigen::COLAMDOrdering<int>>>;

/// Zhang & Hebert's springs k_ij = 1 / |p_i - p_j| (method §4.2), written like CGAL's
/// Barycentric_mapping_parameterizer_3, which returns 1 from the same hook.
class InverseLengthParameterizer : public smp::Fixed_border_parameterizer_3<Mesh, Border, Solver> {
  using Base = smp::Fixed_border_parameterizer_3<Mesh, Border, Solver>;

 public:
  using Base::Base;

 protected:
  double compute_w_ij(
      const Mesh& mesh, VertexDescriptor main_vertex_v_i,
      CGAL::Vertex_around_target_circulator<Mesh> neighbor_vertex_v_j) const override {
    const Kernel::Vector_3 edge = mesh.point(*neighbor_vertex_v_j) - mesh.point(main_vertex_v_i);
    return 1.0 / std::sqrt(edge.squared_length());
  }
};

template <typename Parameterizer>
smp::Error_code run(Mesh& mesh, HalfedgeDescriptor border_halfedge,
                    Mesh::Property_map<VertexDescriptor, Kernel::Point_2> uv) {
  return smp::parameterize(mesh, Parameterizer(), border_halfedge, uv);
}

/// The patch as a CGAL::Surface_mesh with its uv map and the border halfedge that leaves
/// outer_boundary[0] (CGAL walks the border opposite to the faces).
struct CgalPatch {
  Mesh mesh;
  HalfedgeDescriptor border;
  Mesh::Property_map<VertexDescriptor, Kernel::Point_2> uv;
};

CgalPatch cgal_patch(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                     const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                     const std::vector<int>& outer_boundary, const std::string& where) {
  check_disk_map_input(positions, faces, outer_boundary);
  CgalPatch out;
  Mesh& mesh = out.mesh;
  mesh.reserve(static_cast<Mesh::size_type>(positions.rows()),
               static_cast<Mesh::size_type>(3 * faces.rows()),
               static_cast<Mesh::size_type>(faces.rows()));
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    mesh.add_vertex(Kernel::Point_3(positions(v, 0), positions(v, 1), positions(v, 2)));
  }
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const auto face = mesh.add_face(Mesh::Vertex_index(static_cast<Mesh::size_type>(faces(f, 0))),
                                    Mesh::Vertex_index(static_cast<Mesh::size_type>(faces(f, 1))),
                                    Mesh::Vertex_index(static_cast<Mesh::size_type>(faces(f, 2))));
    if (face == Mesh::null_face()) {
      throw TopologyError(where + "CGAL::Surface_mesh rejected face " + std::to_string(f) +
                          ", expected a 2-manifold patch");
    }
  }
  // The border halfedge leaving outer_boundary[0] runs to the last outer boundary vertex.
  out.border =
      mesh.halfedge(Mesh::Vertex_index(static_cast<Mesh::size_type>(outer_boundary.front())),
                    Mesh::Vertex_index(static_cast<Mesh::size_type>(outer_boundary.back())));
  if (out.border == Mesh::null_halfedge() || !mesh.is_border(out.border)) {
    throw TopologyError(where + "no border halfedge runs from " +
                        std::to_string(outer_boundary.front()) + " to " +
                        std::to_string(outer_boundary.back()) +
                        ", expected the outer boundary counter-clockwise seen from outside");
  }
  out.uv = mesh.add_property_map<VertexDescriptor, Kernel::Point_2>("v:surfcomp_uv").first;
  return out;
}

/// The uv of every vertex, checked finite.
Eigen::MatrixX2d uv_of(const CgalPatch& patch, Eigen::Index n, const std::string& where) {
  Eigen::MatrixX2d uv(n, 2);
  for (Eigen::Index v = 0; v < n; ++v) {
    const Kernel::Point_2& p = patch.uv[Mesh::Vertex_index(static_cast<Mesh::size_type>(v))];
    uv.row(v) << p.x(), p.y();
  }
  if (!uv.allFinite()) {
    throw NumericError(where +
                       "CGAL's parameterization has non-finite coordinates, expected a "
                       "non-singular system");
  }
  return uv;
}

void check_status(smp::Error_code status, const std::string& where) {
  if (status != smp::OK) {
    throw NumericError(where + "CGAL's parameterizer failed: " + smp::get_error_message(status) +
                       ", expected a solvable system");
  }
}

}  // namespace

DiskMap cgal_disk_map(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                      const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                      const std::vector<int>& outer_boundary, const DiskMapOptions& options) {
  const std::string where = "CGAL disk map: ";
  CgalPatch patch = cgal_patch(positions, faces, outer_boundary, where);
  smp::Error_code status = smp::OK;
  switch (options.weights) {
    case SpringWeights::inverse_length:
      status = run<InverseLengthParameterizer>(patch.mesh, patch.border, patch.uv);
      break;
    case SpringWeights::uniform:
      status = run<smp::Barycentric_mapping_parameterizer_3<Mesh, Border, Solver>>(
          patch.mesh, patch.border, patch.uv);
      break;
    case SpringWeights::cotangent:
      status = run<smp::Discrete_conformal_map_parameterizer_3<Mesh, Border, Solver>>(
          patch.mesh, patch.border, patch.uv);
      break;
    case SpringWeights::mean_value:
      status = run<smp::Mean_value_coordinates_parameterizer_3<Mesh, Border, Solver>>(
          patch.mesh, patch.border, patch.uv);
      break;
  }
  check_status(status, where);
  DiskMap map;
  map.uv = (uv_of(patch, positions.rows(), where).array() - 0.5) * 2.0;
  return map;
}

std::optional<Parameterization> parameterization_from_name(const std::string& name) {
  for (std::size_t i = 0; i < parameterization_names.size(); ++i) {
    if (name == parameterization_names[i]) return static_cast<Parameterization>(i);
  }
  return std::nullopt;
}

Eigen::MatrixX2d parameterize_patch(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                    const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                    const std::vector<int>& outer_boundary, Parameterization method,
                                    const DiskMapOptions& options) {
  const std::string where =
      std::string(parameterization_names[static_cast<std::size_t>(method)]) + " map: ";
  if (method == Parameterization::harmonic)
    return harmonic_disk_map(positions, faces, outer_boundary, options).uv;
  // The fixed-border maps with spring weights of their own are cgal_disk_map's.
  switch (method) {
    case Parameterization::tutte:
      return cgal_disk_map(positions, faces, outer_boundary, {SpringWeights::uniform}).uv;
    case Parameterization::mean_value:
      return cgal_disk_map(positions, faces, outer_boundary, {SpringWeights::mean_value}).uv;
    case Parameterization::discrete_conformal:
      return cgal_disk_map(positions, faces, outer_boundary, {SpringWeights::cotangent}).uv;
    default:
      break;
  }
  CgalPatch patch = cgal_patch(positions, faces, outer_boundary, where);
  using FreeBorder = smp::Two_vertices_parameterizer_3<Mesh>;
  smp::Error_code status = smp::OK;
  if (method == Parameterization::discrete_authalic) {
    status = run<smp::Discrete_authalic_parameterizer_3<Mesh, Border, Solver>>(
        patch.mesh, patch.border, patch.uv);
  } else if (method == Parameterization::lscm) {
    status = run<smp::LSCM_parameterizer_3<Mesh, FreeBorder>>(patch.mesh, patch.border, patch.uv);
  } else {
    status = run<smp::ARAP_parameterizer_3<Mesh, FreeBorder, Solver>>(patch.mesh, patch.border,
                                                                      patch.uv);
  }
  check_status(status, where);
  Eigen::MatrixX2d uv = uv_of(patch, positions.rows(), where);
  if (has_free_border(method)) {
    double signed_area = 0.0;  // mirrored when the map turns the patch over
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      const Eigen::RowVector2d a = uv.row(faces(f, 0)), b = uv.row(faces(f, 1)),
                               c = uv.row(faces(f, 2));
      signed_area += (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    }
    if (signed_area < 0.0) uv.col(0) = -uv.col(0);
  } else {
    uv = (uv.array() - 0.5) * 2.0;
  }
  return uv;
}

}  // namespace surfcomp::harmonic
