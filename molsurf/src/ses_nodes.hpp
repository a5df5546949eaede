// The node grid of the SES point sampler (ses_points.cpp, src/ only): nodes over the atoms'
// probe-grown balls, and which are inside the union of the balls, which the solvent outside reaches
// and which it does not (cavities), found on runs of rows.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace surfcomp::molsurf::detail {

/// Node states.
enum : std::uint8_t { kSolvent = 0, kInside = 1, kUnreached = 2 };

/// ceil and floor of x (|x| < 2^31), without the library calls that baseline x86-64 makes of
/// std::ceil and std::floor.
inline int ceil_int(double x) {
  const int i = static_cast<int>(x);
  return i + (x > i ? 1 : 0);
}
inline int floor_int(double x) {
  const int i = static_cast<int>(x);
  return i - (x < i ? 1 : 0);
}

/// A dense grid of nodes origin + spacing * (i, j, k), i fastest.
struct NodeGrid {
  Eigen::Vector3d origin;
  double spacing = 1.0;
  int nx = 0, ny = 0, nz = 0;

  std::size_t size() const {
    return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) *
           static_cast<std::size_t>(nz);
  }
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * static_cast<std::size_t>(ny) +
            static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(nx) +
           static_cast<std::size_t>(i);
  }
  Eigen::Vector3d position(int i, int j, int k) const {
    return origin + spacing * Eigen::Vector3d(i, j, k);
  }
  /// The number of row (j, k), j fastest.
  std::size_t row(int j, int k) const {
    return static_cast<std::size_t>(k) * static_cast<std::size_t>(ny) + static_cast<std::size_t>(j);
  }
  std::size_t rows() const { return static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz); }
  /// The index step to the next node along `axis` (0: x, 1: y, 2: z).
  std::size_t step(int axis) const {
    return axis == 0   ? 1
           : axis == 1 ? static_cast<std::size_t>(nx)
                       : static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  }
  /// Calls row(first index, first i, count, dx of the first node in spacings, squared distance
  /// of the row's line from `centre` in A^2) for each row of nodes within `radius` of `centre`
  /// (the run of a row is found from its chord).
  template <class Row>
  void for_each_row_in_ball(const Eigen::Vector3d& centre, double radius, Row&& row) const {
    const Eigen::Vector3d local = (centre - origin) / spacing;
    const double r = radius / spacing;
    const int k0 = std::max(0, ceil_int(local.z() - r));
    const int k1 = std::min(nz - 1, floor_int(local.z() + r));
    const int j0 = std::max(0, ceil_int(local.y() - r));
    const int j1 = std::min(ny - 1, floor_int(local.y() + r));
    for (int k = k0; k <= k1; ++k) {
      const double dz = k - local.z();
      for (int j = j0; j <= j1; ++j) {
        const double dy = j - local.y();
        const double rest = r * r - dy * dy - dz * dz;
        if (rest < 0.0) continue;
        const double chord = std::sqrt(rest);
        const int i0 = std::max(0, ceil_int(local.x() - chord));
        const int i1 = std::min(nx - 1, floor_int(local.x() + chord));
        if (i1 < i0) continue;
        row(index(i0, j, k), i0, i1 - i0 + 1, i0 - local.x(),
            (dy * dy + dz * dz) * spacing * spacing);
      }
    }
  }
};

/// Runs [first, last] of nodes in each row (j + ny k) of a grid, in compressed rows.
struct RowRuns {
  std::vector<std::size_t> offsets;  ///< row r's runs are runs[offsets[r] .. offsets[r + 1])
  std::vector<std::pair<int, int>> runs;

  std::pair<const std::pair<int, int>*, const std::pair<int, int>*> row(std::size_t r) const {
    return {runs.data() + offsets[r], runs.data() + offsets[r + 1]};
  }
};

/// The nodes inside the union of grown balls (each with an atom whose ball holds it), the
/// solvent (the nodes outside that the border reaches, 6-connected) and the unreached rest
/// (cavities), found on runs of rows rather than node by node.
struct NodeStates {
  std::vector<std::uint8_t> state;
  std::vector<std::int32_t> atom;  ///< for an inside node, an atom whose grown ball holds it
  RowRuns inside;                  ///< the runs of inside nodes
};

/// The state of every node of `grid` against the balls of `centers` (rows) and radii `grown`.
NodeStates node_states(const NodeGrid& grid, const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                       const Eigen::VectorXd& grown);

}  // namespace surfcomp::molsurf::detail
