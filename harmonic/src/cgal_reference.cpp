#include "surfcomp/harmonic/cgal_reference.hpp"

#include "surfcomp/core/error.hpp"

#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Barycentric_mapping_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/Fixed_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
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

/// Zhang & Hebert's springs k_ij = 1 / |p_i - p_j| (seed eq. 3-2), written like CGAL's
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

}  // namespace

DiskMap cgal_disk_map(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                      const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                      const std::vector<int>& outer_boundary, const DiskMapOptions& options) {
  const std::string where = "cgal_disk_map: ";
  check_disk_map_input(positions, faces, outer_boundary);

  Mesh mesh;
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
  const HalfedgeDescriptor border_halfedge =
      mesh.halfedge(Mesh::Vertex_index(static_cast<Mesh::size_type>(outer_boundary.front())),
                    Mesh::Vertex_index(static_cast<Mesh::size_type>(outer_boundary.back())));
  if (border_halfedge == Mesh::null_halfedge() || !mesh.is_border(border_halfedge)) {
    throw TopologyError(where + "no border halfedge runs from " +
                        std::to_string(outer_boundary.front()) + " to " +
                        std::to_string(outer_boundary.back()) +
                        ", expected the outer boundary counter-clockwise seen from outside");
  }

  auto uv = mesh.add_property_map<VertexDescriptor, Kernel::Point_2>("v:surfcomp_uv").first;
  smp::Error_code status = smp::OK;
  switch (options.weights) {
    case SpringWeights::inverse_length:
      status = run<InverseLengthParameterizer>(mesh, border_halfedge, uv);
      break;
    case SpringWeights::uniform:
      status = run<smp::Barycentric_mapping_parameterizer_3<Mesh, Border, Solver>>(
          mesh, border_halfedge, uv);
      break;
    case SpringWeights::cotangent:
      status = run<smp::Discrete_conformal_map_parameterizer_3<Mesh, Border, Solver>>(
          mesh, border_halfedge, uv);
      break;
    case SpringWeights::mean_value:
      status = run<smp::Mean_value_coordinates_parameterizer_3<Mesh, Border, Solver>>(
          mesh, border_halfedge, uv);
      break;
  }
  if (status != smp::OK) {
    throw NumericError(where + "CGAL's parameterizer failed: " + smp::get_error_message(status) +
                       ", expected a solvable system");
  }

  DiskMap map;
  map.uv.resize(positions.rows(), 2);
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const Kernel::Point_2& p = uv[Mesh::Vertex_index(static_cast<Mesh::size_type>(v))];
    map.uv.row(v) << 2.0 * (p.x() - 0.5), 2.0 * (p.y() - 0.5);
  }
  if (!map.uv.allFinite()) {
    throw NumericError(where +
                       "CGAL's parameterization has non-finite coordinates, expected a "
                       "non-singular system");
  }
  return map;
}

}  // namespace surfcomp::harmonic
