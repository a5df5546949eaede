// Internal to the molsurf module (not installed): the first stage of build_ses with
// SesMethod::distance_transform, the SES's field from a Euclidean distance transform on a dense
// grid (EDTSurf's approach) instead of grid_mesh's exact band.
#pragma once

#include "dual_marching_cubes.hpp"
#include "ses_region.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <utility>
#include <vector>

namespace surfcomp::molsurf::detail {

/// The nodes of the dense box distance_transform_mesh spans for these arguments (16 bytes each):
/// the bounding box of the balls of radius r + probe + 5 voxels, cut to the region's bounding
/// box grown by the probe and 5 voxels when there is one.
double distance_transform_nodes(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                                const Eigen::Ref<const Eigen::VectorXd>& radii, double probe,
                                double voxel, const BallUnion* region);

/// A dense box of grid nodes: node (i, j, k) of the box is grid node lo + (i, j, k), stored at
/// (i * n.y + j) * n.z + k.
struct NodeBox {
  Eigen::Vector3i lo = Eigen::Vector3i::Zero();
  Eigen::Vector3i n = Eigen::Vector3i::Zero();
  std::size_t size() const {
    return static_cast<std::size_t>(n.x()) * static_cast<std::size_t>(n.y()) *
           static_cast<std::size_t>(n.z());
  }
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(i) * static_cast<std::size_t>(n.y()) +
            static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(n.z()) +
           static_cast<std::size_t>(k);
  }
  std::size_t index(const Eigen::Vector3i& c) const { return index(c.x(), c.y(), c.z()); }
  /// The box coordinates of the node stored at `index`.
  Eigen::Vector3i node(std::size_t index) const {
    const auto nz = static_cast<std::size_t>(n.z()), ny = static_cast<std::size_t>(n.y());
    return {static_cast<int>(index / (ny * nz)), static_cast<int>((index / nz) % ny),
            static_cast<int>(index % nz)};
  }
  /// Whether box coordinates `c` name a node of the box.
  bool contains(const Eigen::Vector3i& c) const {
    return (c.array() >= 0).all() && (c.array() < n.array()).all();
  }
};

/// The field distance_transform_mesh meshed, on its dense box of nodes, clamped to 3.5 voxels
/// from its zero level, and interpolated trilinearly between the nodes with a correction by the
/// second differences along each axis (exact for quadratics).
class TransformField {
 public:
  TransformField() = default;
  TransformField(NodeBox box, double voxel, std::vector<float> values)
      : box_(std::move(box)), voxel_(voxel), values_(std::move(values)) {}

  /// Moves `x` onto the interpolated zero level by Newton steps along the gradient (each at
  /// most half a voxel), and returns the gradient's direction there, the outward normal; x
  /// unchanged and a zero vector where the field is flat or x leaves the box.
  Eigen::Vector3d project(Eigen::Vector3d& x) const;

 private:
  /// The interpolated value at x and its gradient; false outside the box.
  bool sample(const Eigen::Vector3d& x, double& value, Eigen::Vector3d& gradient) const;

  NodeBox box_;
  double voxel_ = 1.0;
  std::vector<float> values_;  ///< at box_.index(i, j, k)
};

/// The grid mesh and the field it was meshed from.
struct TransformMesh {
  TriangleSoup soup;
  TransformField field;
};

/// The grid mesh of the SES of the atoms (`centers` #A by 3, `radii` #A, A) for a probe of
/// radius `probe`, on the nodes ijk * voxel. The SAS region U (balls of radius r + probe) is
/// stamped on a dense box of nodes around the atoms with s = min_i (|x - c_i| - R_i), and the
/// distance from each node inside U to the nearest node outside it found by a separable exact
/// distance transform (Felzenszwalb & Huttenlocher 2012) that also keeps that node. The SES
/// field is probe - d(x, outside U); near the surface d is refined to the smallest
/// |x - q| - s(q) over the outside nodes q around the nearest one, an upper bound on the
/// distance to U's boundary within a small fraction of a voxel of it where U's boundary is
/// smooth. Outside U the field is probe + s. With a `region`, max(field, region value) as
/// grid_mesh does. Meshed by dual marching cubes (the values clamped to the same band as
/// grid_mesh's): a closed, 2-manifold mesh, with the field for placing the remeshed vertices
/// (TransformField::project). The grid misses the crevices of U's outside thinner than a voxel
/// and bridges them (docs/decisions.md#distance-transform-ses).
/// Parallel, deterministic.
TransformMesh distance_transform_mesh(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                                      const Eigen::Ref<const Eigen::VectorXd>& radii, double probe,
                                      double voxel, const BallUnion* region = nullptr);

/// Projects every vertex of `surface` onto `field`'s zero level (TransformField::project) and sets
/// the field's gradient directions as the normals (the mesh normal where the field gives none).
/// Parallel, deterministic.
void place_on_field(mesh::Surface& surface, const TransformField& field);

}  // namespace surfcomp::molsurf::detail
