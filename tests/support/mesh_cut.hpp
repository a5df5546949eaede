// A half of a mesh cut by a plane, as a partial scan of it: the tests of general-mesh matching
// and of the shape screen match such a half onto its whole.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace surfcomp::test {

/// The faces of `full` whose centroids lie below the plane through its centroid with normal
/// `normal` (about half the surface), as a mesh in the same frame.
inline mesh::Surface cut(const mesh::Surface& full, const Eigen::Vector3d& normal) {
  const Eigen::MatrixX3d v = full.positions();
  const Eigen::MatrixX3i f = full.faces();
  const Eigen::RowVector3d centre = v.colwise().mean();
  std::vector<int> kept;
  std::vector<int> index(static_cast<std::size_t>(v.rows()), -1);
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    const Eigen::RowVector3d centroid = (v.row(f(i, 0)) + v.row(f(i, 1)) + v.row(f(i, 2))) / 3;
    if ((centroid - centre).dot(normal.transpose()) < 0.0) kept.push_back(static_cast<int>(i));
  }
  std::vector<Eigen::RowVector3d> points;
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      int& at = index[static_cast<std::size_t>(f(kept[k], c))];
      if (at < 0) {
        at = static_cast<int>(points.size());
        points.push_back(v.row(f(kept[k], c)));
      }
      faces(static_cast<Eigen::Index>(k), c) = at;
    }
  }
  Eigen::MatrixX3d positions(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t k = 0; k < points.size(); ++k)
    positions.row(static_cast<Eigen::Index>(k)) = points[k];
  return mesh::Surface::from_arrays(positions, faces, "cut copy");
}

}  // namespace surfcomp::test
