// A uniform grid of cubic cells over a point set: the points near a place, in a fixed order.
// The SES builder looks up atoms and SAS vertices with it, the overlay its surface samples.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <vector>

namespace surfcomp::mesh {

/// Points listed in the cells of a dense grid of cubic cells (compressed rows), for the points
/// near a place. Built once; queries are const and may run from any number of threads.
///
/// Geometry: the grid covers the points' bounding box grown by `reach` on every side, with its
/// origin at the grown box's low corner. Cells have edge `cell` (A), doubled until the grid has
/// at most max_cells cells (sparse inputs, such as atoms far apart, get coarser cells instead
/// of more memory). Cell (i, j, k) spans origin + cell * ([i, i+1) x [j, j+1) x [k, k+1)).
///
/// Two layouts, by `reach` (A):
/// - reach 0: each point is listed in the one cell that holds it. for_each_near(x, radius)
///   visits the points of the cells that the cube of half-width `radius` around x touches: a
///   superset of the points within `radius` of x, each once.
/// - reach > 0: each point is listed in every cell whose centre lies within reach plus half the
///   cell diagonal of it, so a cell lists every point within `reach` of any place in the cell.
///   for_each_listed(x) reads the one list of x's cell: a superset of the points within
///   `reach` of x, each once, for the cost of one list instead of a box of cells.
///
/// Order: a query visits the cells in lexicographic order of (i, j, k) and, within a cell, the
/// points by increasing index, whatever the thread count. A query outside the grid visits
/// nothing (a cube partly outside visits the cells inside); so does one with a NaN coordinate
/// or radius.
class SpatialGrid {
 public:
  /// The most cells a grid has.
  static constexpr std::size_t max_cells = std::size_t{1} << 22;

  /// An empty grid: every query visits nothing.
  SpatialGrid() = default;
  /// The grid of `points` (3 by #P, A) with cells of edge `cell` A (or a power-of-two multiple
  /// of it, see above) and the layout of `reach` A. Throws OptionError unless cell is finite
  /// and > 0 and reach finite and >= 0, InputError for a point that is not finite.
  SpatialGrid(const Eigen::Ref<const Eigen::Matrix3Xd>& points, double cell, double reach = 0.0);

  /// Calls visit(i) for every point i listed in the cells that the cube of half-width `radius`
  /// (A) around x touches. With reach 0 these are the points of those cells, each once; with
  /// reach > 0 a point listed in several of them is visited once per cell.
  template <class Visit>
  void for_each_near(const Eigen::Vector3d& x, double radius, Visit&& visit) const {
    if (indices_.empty() || std::isnan(x.x()) || std::isnan(x.y()) || std::isnan(x.z()) ||
        std::isnan(radius))
      return;
    const Eigen::Vector3i lo = cell_of(x - Eigen::Vector3d::Constant(radius));
    const Eigen::Vector3i hi = cell_of(x + Eigen::Vector3d::Constant(radius));
    if ((hi.array() < 0).any() || (lo.array() >= dims_.array()).any()) return;
    const Eigen::Vector3i from = clamp(lo);
    const Eigen::Vector3i to = clamp(hi);
    for (int i = from.x(); i <= to.x(); ++i) {
      for (int j = from.y(); j <= to.y(); ++j) {
        // The cells (i, j, from.z() .. to.z()) are consecutive: one run of the compressed rows.
        const std::size_t row = flat(Eigen::Vector3i(i, j, 0));
        const std::size_t begin = offsets_[row + static_cast<std::size_t>(from.z())];
        const std::size_t end = offsets_[row + static_cast<std::size_t>(to.z()) + 1];
        for (std::size_t p = begin; p < end; ++p) visit(indices_[p]);
      }
    }
  }

  /// Calls visit(i) for every point i listed in the cell that holds x, by increasing index:
  /// for_each_near(x, 0, visit). With reach > 0, a superset of the points within reach of x.
  template <class Visit>
  void for_each_listed(const Eigen::Vector3d& x, Visit&& visit) const {
    const Eigen::Array3d local = (x - origin_).array() / cell_;
    // Outside the grid, or not a number (also guards the conversion to int below).
    if (!((local >= 0.0).all() && (local < dims_.cast<double>().array()).all())) return;
    const std::size_t cell = flat(local.floor().cast<int>().matrix());
    for (std::size_t p = offsets_[cell]; p < offsets_[cell + 1]; ++p) visit(indices_[p]);
  }

  /// The grid's low corner (A).
  const Eigen::Vector3d& origin() const { return origin_; }
  /// The cells' edge (A): the `cell` asked for, doubled as often as the cell cap needs.
  double cell_size() const { return cell_; }
  /// The number of cells along each axis (all 0 for an empty grid).
  const Eigen::Vector3i& dims() const { return dims_; }
  /// The layout's reach (A).
  double reach() const { return reach_; }
  /// The cell (i, j, k) that holds x, each coordinate saturated to [-1, dims] (-1 and dims:
  /// beyond the grid on that side). x must not be NaN.
  Eigen::Vector3i cell_of(const Eigen::Vector3d& x) const {
    const Eigen::Array3d c = ((x - origin_) / cell_).array().floor();
    // Far-away places saturate instead of overflowing int.
    return c.max(-1.0).min(dims_.cast<double>().array()).cast<int>().matrix();
  }

 private:
  Eigen::Vector3i clamp(const Eigen::Vector3i& c) const {
    return c.cwiseMax(0).cwiseMin(dims_ - Eigen::Vector3i::Ones());
  }
  std::size_t flat(const Eigen::Vector3i& c) const {
    return (static_cast<std::size_t>(c.x()) * static_cast<std::size_t>(dims_.y()) +
            static_cast<std::size_t>(c.y())) *
               static_cast<std::size_t>(dims_.z()) +
           static_cast<std::size_t>(c.z());
  }

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double cell_ = 1.0;
  double reach_ = 0.0;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  std::vector<std::size_t> offsets_;  ///< cell c lists indices_[offsets_[c] .. offsets_[c + 1])
  std::vector<int> indices_;
};

}  // namespace surfcomp::mesh
