#include "ses_grid.hpp"

#include "dual_marching_cubes.hpp"
#include "sparse_grid.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

namespace surfcomp::molsurf::detail {
namespace {

/// Root boxes of the adaptive sampling, voxels per side (a power of two).
constexpr int root_box = 32;
/// Boxes up to this size are sampled voxel by voxel.
constexpr int leaf_box = 2;

/// The SES as a sampled field: value() is exact within `clamp` of the surface; upper_bound()
/// is the cheap CSG bound probe + min_i (|x - c_i| - R_i) >= value, exact outside U.
struct SesField {
  const SasGeometry& sas;
  void gather(const Vec3& centre, double radius, double clamp,
              SasGeometry::Candidates& candidates) const {
    sas.gather(centre, radius, sas.probe() + clamp, candidates);
  }
  double value(const Vec3& x, double clamp, const SasGeometry::Candidates& candidates) const {
    return sas.ses_value(x, clamp, candidates);
  }
  double upper_bound(const Vec3& x, double clamp, bool& exact) const {
    const double u = sas.union_value(x, clamp + sas.probe());
    exact = u >= 0.0;
    return sas.probe() + u;
  }
};

/// The SAS as a sampled field: the CSG union min_i (|x - c_i| - R_i), 1-Lipschitz.
struct SasField {
  const SasGeometry& sas;
  void gather(const Vec3& centre, double radius, double clamp,
              SasGeometry::Candidates& candidates) const {
    sas.gather(centre, radius, clamp, candidates);
  }
  double value(const Vec3& x, double clamp, const SasGeometry::Candidates& candidates) const {
    return sas.sas_value(x, clamp, candidates);
  }
  double upper_bound(const Vec3& x, double clamp, bool& exact) const {
    exact = true;
    return sas.union_value(x, clamp);
  }
};

/// A field cut to a union of balls: max(field, region), the CSG intersection, still 1-Lipschitz.
/// Where the region's value reaches `clamp`, value() and upper_bound() return it, exact in the
/// sense the sampler needs (a value at least clamp, which only says "outside"): boxes outside
/// the region are decided by the region's value alone.
template <class Field>
struct ClippedField {
  Field field;
  const BallUnion& region;
  void gather(const Vec3& centre, double radius, double clamp,
              SasGeometry::Candidates& candidates) const {
    field.gather(centre, radius, clamp, candidates);
  }
  double value(const Vec3& x, double clamp, const SasGeometry::Candidates& candidates) const {
    const double outside = region.value(x);
    if (outside >= clamp) return outside;
    return std::max(field.value(x, clamp, candidates), outside);
  }
  double upper_bound(const Vec3& x, double clamp, bool& exact) const {
    const double outside = region.value(x);
    if (outside >= clamp) {
      exact = true;
      return outside;
    }
    const double bound = field.upper_bound(x, clamp, exact);
    if (outside >= bound) exact = true;
    return std::max(bound, outside);
  }
};

/// Samples field.value(x, clamp) on the grid nodes ijk * voxel near its zero level set,
/// refining boxes of nodes adaptively: a box whose centre value exceeds its half-diagonal plus
/// the band in magnitude lies wholly outside (background) or inside (an inactive negative
/// fill), since the field is 1-Lipschitz; the cheap upper bound decides large boxes. Only root
/// boxes within `reach` of an atom are visited. They are processed in parallel into separate
/// slots and written in a fixed order, so the grid does not depend on the thread count. Nodes
/// not sampled hold +band (outside) or, in the inside boxes, -band.
template <class Field>
SparseGrid sample_band(const Field& field, const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                       double reach, double voxel) {
  const auto band = static_cast<float>(band_voxels * voxel);
  SparseGrid grid(band);

  // Root boxes touching the ball of radius `reach` around some atom, in a sorted order.
  const double root_size = root_box * voxel;
  std::vector<std::array<int, 3>> roots;
  for (Eigen::Index a = 0; a < centers.rows(); ++a) {
    const Eigen::Vector3i lo =
        ((centers.row(a).array() - reach) / root_size).floor().cast<int>().transpose();
    const Eigen::Vector3i hi =
        ((centers.row(a).array() + reach) / root_size).floor().cast<int>().transpose();
    for (int i = lo.x(); i <= hi.x(); ++i) {
      for (int j = lo.y(); j <= hi.y(); ++j) {
        for (int k = lo.z(); k <= hi.z(); ++k) roots.push_back({i, j, k});
      }
    }
  }
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  struct Samples {
    std::vector<std::pair<GridCoord, float>> values;
    std::vector<std::pair<GridCoord, int>> inside_boxes;  ///< origin, size
  };
  std::vector<Samples> slots(roots.size());
  tbb::parallel_for(std::size_t{0}, roots.size(), [&](std::size_t r) {
    Samples& out = slots[r];
    SasGeometry::Candidates candidates;
    const Eigen::Vector3i root(roots[r][0], roots[r][1], roots[r][2]);
    std::vector<std::pair<Eigen::Vector3i, int>> stack{{root_box * root, root_box}};
    while (!stack.empty()) {
      const auto [origin, size] = stack.back();
      stack.pop_back();
      const double half_diagonal = std::sqrt(3.0) * 0.5 * (size - 1) * voxel;
      const Vec3 centre = (origin.cast<double>() + Vec3::Constant(0.5 * (size - 1))) * voxel;
      const double threshold = half_diagonal + band;
      const GridCoord corner = {origin.x(), origin.y(), origin.z()};
      bool exact = false;
      const double bound = field.upper_bound(centre, threshold + voxel, exact);
      if (bound < -threshold) {
        out.inside_boxes.emplace_back(corner, size);
        continue;
      }
      if (exact && bound > threshold) continue;
      if (size <= leaf_box) {
        field.gather(centre, half_diagonal, threshold + voxel, candidates);
        const double value = field.value(centre, threshold + voxel, candidates);
        if (value > threshold) continue;
        if (value < -threshold) {
          out.inside_boxes.emplace_back(corner, size);
          continue;
        }
        for (int i = 0; i < size; ++i) {
          for (int j = 0; j < size; ++j) {
            for (int k = 0; k < size; ++k) {
              const Eigen::Vector3i c = origin + Eigen::Vector3i(i, j, k);
              const double v =
                  field.value(c.cast<double>() * voxel, static_cast<double>(band), candidates);
              out.values.emplace_back(GridCoord{c.x(), c.y(), c.z()}, static_cast<float>(v));
            }
          }
        }
        continue;
      }
      const int child_size = size / 2;
      for (int child = 7; child >= 0; --child) {
        stack.emplace_back(
            origin + child_size * Eigen::Vector3i(child & 1, (child >> 1) & 1, child >> 2),
            child_size);
      }
    }
  });
  for (const Samples& s : slots) {
    for (const auto& [origin, size] : s.inside_boxes) grid.fill(origin, size, -band);
  }
  for (const Samples& s : slots) {
    for (const auto& [coord, value] : s.values) grid.set(coord, value);
  }
  return grid;
}

}  // namespace

TriangleSoup grid_mesh(const SasGeometry& sas, SurfaceKind kind,
                       const Eigen::Ref<const Eigen::MatrixX3d>& centers, double reach,
                       double voxel, const BallUnion* region) {
  const auto sample = [&](const auto& field) {
    if (region == nullptr) return sample_band(field, centers, reach, voxel);
    using Field = std::decay_t<decltype(field)>;
    return sample_band(ClippedField<Field>{field, *region}, centers, reach, voxel);
  };
  const SparseGrid grid =
      kind == SurfaceKind::excluded ? sample(SesField{sas}) : sample(SasField{sas});
  return dual_marching_cubes(grid, voxel);
}

}  // namespace surfcomp::molsurf::detail
