#include "surfcomp/mesh/spatial_grid.hpp"

#include "surfcomp/core/error.hpp"

#include <numeric>
#include <string>

namespace surfcomp::mesh {

SpatialGrid::SpatialGrid(const Eigen::Ref<const Eigen::Matrix3Xd>& points, double cell,
                         double reach)
    : cell_(cell), reach_(reach) {
  if (!(std::isfinite(cell) && cell > 0.0)) {
    throw OptionError("spatial grid: cell " + std::to_string(cell) +
                      " A; expected a finite value > 0");
  }
  if (!(std::isfinite(reach) && reach >= 0.0)) {
    throw OptionError("spatial grid: reach " + std::to_string(reach) +
                      " A; expected a finite value >= 0");
  }
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    if (!points.col(i).allFinite()) {
      throw InputError("spatial grid: point " + std::to_string(i) +
                       " is not finite; expected finite coordinates");
    }
  }
  if (points.cols() == 0) return;
  const Eigen::Vector3d lo = points.rowwise().minCoeff();
  const Eigen::Vector3d hi = points.rowwise().maxCoeff();
  origin_ = lo - Eigen::Vector3d::Constant(reach);
  const Eigen::Vector3d extent = (hi + Eigen::Vector3d::Constant(reach)) - origin_;
  const auto cells_along = [&] { return (extent / cell_).array().floor() + 1.0; };
  while (cells_along().prod() > static_cast<double>(max_cells)) cell_ *= 2.0;
  dims_ = cells_along().cast<int>().matrix();

  // The cells that list point i, in increasing flat index.
  const double listing_reach = reach + 0.5 * std::sqrt(3.0) * cell_;
  const auto for_each_cell_of = [&](Eigen::Index i, const auto& visit) {
    const Eigen::Vector3d p = points.col(i);
    if (reach == 0.0) {
      visit(flat(clamp(cell_of(p))));
      return;
    }
    const Eigen::Vector3i from = clamp(cell_of(p - Eigen::Vector3d::Constant(listing_reach)));
    const Eigen::Vector3i to = clamp(cell_of(p + Eigen::Vector3d::Constant(listing_reach)));
    for (int x = from.x(); x <= to.x(); ++x) {
      for (int y = from.y(); y <= to.y(); ++y) {
        for (int z = from.z(); z <= to.z(); ++z) {
          const Eigen::Vector3d centre =
              origin_ + cell_ * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
          if ((centre - p).squaredNorm() <= listing_reach * listing_reach) {
            visit(flat(Eigen::Vector3i(x, y, z)));
          }
        }
      }
    }
  };
  // Two passes, count then fill, both in point order: each cell lists its points by index.
  const std::size_t n_cells = static_cast<std::size_t>(dims_.x()) *
                              static_cast<std::size_t>(dims_.y()) *
                              static_cast<std::size_t>(dims_.z());
  offsets_.assign(n_cells + 1, 0);
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    for_each_cell_of(i, [&](std::size_t c) { ++offsets_[c + 1]; });
  }
  std::partial_sum(offsets_.begin(), offsets_.end(), offsets_.begin());
  indices_.resize(offsets_.back());
  std::vector<std::size_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    for_each_cell_of(i, [&](std::size_t c) { indices_[fill[c]++] = static_cast<int>(i); });
  }
}

}  // namespace surfcomp::mesh
