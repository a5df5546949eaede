// SpatialGrid against brute force: a query visits exactly the points its documentation names,
// in the documented order, and never misses a point within its radius (or the grid's reach).
#include "surfcomp/mesh/spatial_grid.hpp"
#include "surfcomp/core/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

namespace surfcomp::mesh {
namespace {

/// Points clustered in three balls of a box about 20 A wide, plus uniform ones (cells with
/// many points, cells with none).
Eigen::Matrix3Xd random_points(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> box(-10.0, 10.0);
  std::normal_distribution<double> blob(0.0, 1.5);
  const Eigen::Vector3d centres[3] = {{-5.0, 2.0, 1.0}, {4.0, -3.0, 6.0}, {0.5, 0.5, -7.0}};
  Eigen::Matrix3Xd points(3, n);
  for (int i = 0; i < n; ++i) {
    if (i % 4 == 0) {
      points.col(i) << box(rng), box(rng), box(rng);
    } else {
      points.col(i) = centres[i % 3] + Eigen::Vector3d(blob(rng), blob(rng), blob(rng));
    }
  }
  return points;
}

std::vector<int> near(const SpatialGrid& grid, const Eigen::Vector3d& x, double radius) {
  std::vector<int> visited;
  grid.for_each_near(x, radius, [&](int i) { visited.push_back(i); });
  return visited;
}

std::vector<int> listed(const SpatialGrid& grid, const Eigen::Vector3d& x) {
  std::vector<int> visited;
  grid.for_each_listed(x, [&](int i) { visited.push_back(i); });
  return visited;
}

/// The cell of x as the class documents it: floor((x - origin) / cell), clamped to the grid.
Eigen::Vector3i cell_of(const SpatialGrid& grid, const Eigen::Vector3d& x) {
  Eigen::Vector3i c;
  for (int d = 0; d < 3; ++d) {
    const double k = std::floor((x(d) - grid.origin()(d)) / grid.cell_size());
    c(d) = static_cast<int>(std::clamp(k, 0.0, static_cast<double>(grid.dims()(d) - 1)));
  }
  return c;
}

std::tuple<int, int, int, int> cell_then_index(const SpatialGrid& grid, const Eigen::Vector3d& p,
                                               int i) {
  const Eigen::Vector3i c = cell_of(grid, p);
  return {c.x(), c.y(), c.z(), i};
}

/// A binned grid (reach 0): a box query visits exactly the points of the cells the cube of
/// half-width `radius` touches, by cell then index, each once; so every point within the
/// radius.
void expect_box_queries_exact(const Eigen::Matrix3Xd& points, const SpatialGrid& grid,
                              std::mt19937& rng, double query_half_width) {
  std::uniform_real_distribution<double> where(-query_half_width, query_half_width);
  std::uniform_real_distribution<double> how_far(0.0, 4.0);
  for (int q = 0; q < 300; ++q) {
    const Eigen::Vector3d x(where(rng), where(rng), where(rng));
    const double radius = q % 10 == 0 ? 0.0 : how_far(rng);
    const std::vector<int> visited = near(grid, x, radius);
    // Brute force: the cells [lo, hi] of the cube's corners; a cube beyond the grid on some
    // side touches no cell.
    const Eigen::Array3d lo = ((x.array() - radius) - grid.origin().array()) / grid.cell_size();
    const Eigen::Array3d hi = ((x.array() + radius) - grid.origin().array()) / grid.cell_size();
    const bool touches =
        (hi.floor() >= 0.0).all() && (lo.floor() < grid.dims().cast<double>().array()).all();
    std::vector<std::tuple<int, int, int, int>> expected;
    if (touches) {
      const Eigen::Vector3i from = cell_of(grid, x - Eigen::Vector3d::Constant(radius));
      const Eigen::Vector3i to = cell_of(grid, x + Eigen::Vector3d::Constant(radius));
      for (int i = 0; i < points.cols(); ++i) {
        const Eigen::Vector3i c = cell_of(grid, points.col(i));
        if ((c.array() >= from.array()).all() && (c.array() <= to.array()).all()) {
          expected.push_back(cell_then_index(grid, points.col(i), i));
        }
      }
    }
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(visited.size(), expected.size()) << "query " << q;
    for (std::size_t k = 0; k < visited.size(); ++k) {
      ASSERT_EQ(std::get<3>(expected[k]), visited[k]) << "query " << q << ", visit " << k;
    }
    for (int i = 0; i < points.cols(); ++i) {
      if ((points.col(i) - x).norm() <= radius) {
        EXPECT_NE(std::find(visited.begin(), visited.end(), i), visited.end())
            << "point " << i << " within " << radius << " A of query " << q << " not visited";
      }
    }
  }
}

TEST(SpatialGrid, BoxQueriesVisitTheTouchedCellsByCellThenIndex) {
  std::mt19937 rng(11);
  const Eigen::Matrix3Xd points = random_points(600, rng);
  const SpatialGrid grid(points, 1.5);
  EXPECT_EQ(grid.cell_size(), 1.5);
  EXPECT_EQ(grid.origin(), Eigen::Vector3d(points.rowwise().minCoeff()));
  // Queries inside, across and beyond the points' box.
  expect_box_queries_exact(points, grid, rng, 16.0);
}

TEST(SpatialGrid, ListsHoldEveryPointWithinReachByIndex) {
  std::mt19937 rng(12);
  const Eigen::Matrix3Xd points = random_points(400, rng);
  for (const double reach : {0.5, 3.0}) {
    const SpatialGrid grid(points, 1.0, reach);
    EXPECT_EQ(grid.origin(), Eigen::Vector3d(points.rowwise().minCoeff().array() - reach));
    const double diagonal = std::sqrt(3.0) * grid.cell_size();
    std::uniform_real_distribution<double> where(-10.0 - 2.0 * reach, 10.0 + 2.0 * reach);
    for (int q = 0; q < 500; ++q) {
      const Eigen::Vector3d x(where(rng), where(rng), where(rng));
      const std::vector<int> visited = listed(grid, x);
      EXPECT_TRUE(std::is_sorted(visited.begin(), visited.end()));
      EXPECT_EQ(std::adjacent_find(visited.begin(), visited.end()), visited.end());
      EXPECT_EQ(visited, near(grid, x, 0.0));
      for (int i = 0; i < points.cols(); ++i) {
        const double d = (points.col(i) - x).norm();
        const bool is_visited = std::binary_search(visited.begin(), visited.end(), i);
        // Every point within reach; none beyond reach plus a cell diagonal (x and the point
        // are each within half a diagonal of the cell's centre, give or take the reach).
        if (d <= reach) {
          EXPECT_TRUE(is_visited) << "reach " << reach << ", point " << i;
        } else if (d > reach + diagonal) {
          EXPECT_FALSE(is_visited) << "reach " << reach << ", point " << i;
        }
      }
    }
  }
}

TEST(SpatialGrid, QueriesOutsideTheGridOrNotANumberVisitNothing) {
  std::mt19937 rng(13);
  const Eigen::Matrix3Xd points = random_points(200, rng);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double reach : {0.0, 2.0}) {
    const SpatialGrid grid(points, 1.5, reach);
    const Eigen::Vector3d far(0.0, 1e6, 0.0);
    EXPECT_TRUE(near(grid, far, 3.0).empty());
    EXPECT_TRUE(listed(grid, far).empty());
    EXPECT_TRUE(listed(grid, Eigen::Vector3d(-1e300, 0.0, 0.0)).empty());
    EXPECT_TRUE(listed(grid, Eigen::Vector3d(0.0, 0.0, inf)).empty());
    EXPECT_TRUE(near(grid, Eigen::Vector3d(nan, 0.0, 0.0), 3.0).empty());
    EXPECT_TRUE(near(grid, Eigen::Vector3d::Zero(), nan).empty());
    EXPECT_TRUE(listed(grid, Eigen::Vector3d(0.0, nan, 0.0)).empty());
    // A cube reaching into the grid from far away visits the cells inside: here all of them.
    if (reach == 0.0) {
      EXPECT_EQ(near(grid, far, 1e6 + 20.0).size(), static_cast<std::size_t>(points.cols()));
    }
  }
  const SpatialGrid empty(Eigen::Matrix3Xd(3, 0), 1.0);
  EXPECT_TRUE(near(empty, Eigen::Vector3d::Zero(), 10.0).empty());
  EXPECT_TRUE(listed(empty, Eigen::Vector3d::Zero()).empty());
  EXPECT_TRUE(listed(SpatialGrid(), Eigen::Vector3d::Zero()).empty());
}

TEST(SpatialGrid, SparseInputsGetCoarserCellsUnderTheCap) {
  std::mt19937 rng(14);
  // Two clusters 3000 A apart: 1 A cells would need about 10^10 of them.
  Eigen::Matrix3Xd points = random_points(300, rng);
  points.rightCols(150).array() += 3000.0;
  const SpatialGrid grid(points, 1.0);
  const Eigen::Vector3d dims = grid.dims().cast<double>();
  EXPECT_LE(dims.prod(), static_cast<double>(SpatialGrid::max_cells));
  const double doublings = std::log2(grid.cell_size());
  EXPECT_EQ(doublings, std::round(doublings));
  EXPECT_GT(doublings, 0.0);
  // One doubling fewer would have broken the cap.
  const Eigen::Array3d extent = points.rowwise().maxCoeff() - points.rowwise().minCoeff();
  EXPECT_GT(((extent / (0.5 * grid.cell_size())).floor() + 1.0).prod(),
            static_cast<double>(SpatialGrid::max_cells));
  expect_box_queries_exact(points, grid, rng, 3020.0);

  // Points on a line 10^7 A long: no axis overflows.
  Eigen::Matrix3Xd line = Eigen::Matrix3Xd::Zero(3, 3);
  line(0, 1) = 5e6;
  line(0, 2) = 1e7;
  const SpatialGrid long_grid(line, 1.0, 2.0);
  EXPECT_LE(long_grid.dims().cast<double>().prod(), static_cast<double>(SpatialGrid::max_cells));
  EXPECT_EQ(listed(long_grid, Eigen::Vector3d(5e6 + 1.0, 0.0, 0.0)), std::vector<int>{1});
}

TEST(SpatialGrid, RejectsBadCellsReachesAndPoints) {
  const Eigen::Matrix3Xd points = Eigen::Matrix3Xd::Zero(3, 2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double cell : {0.0, -1.0, nan, std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(SpatialGrid(points, cell), OptionError) << cell;
  }
  for (const double reach : {-0.5, nan}) {
    EXPECT_THROW(SpatialGrid(points, 1.0, reach), OptionError) << reach;
  }
  Eigen::Matrix3Xd bad = points;
  bad(1, 1) = nan;
  EXPECT_THROW(SpatialGrid(bad, 1.0), InputError);
}

}  // namespace
}  // namespace surfcomp::mesh
