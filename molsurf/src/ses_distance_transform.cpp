#include "ses_distance_transform.hpp"

#include "ses_grid.hpp"
#include "ses_vertices.hpp"
#include "sparse_grid.hpp"
#include "surface_mesh.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace surfcomp::molsurf::detail {
namespace {

/// The field kept for placing vertices holds values within this many voxels: its interpolation
/// at a vertex reads nodes up to two voxels from the vertex's cell.
constexpr double field_voxels = 3.5;
/// s is stamped this many voxels beyond each ball R_i: beyond the field's clamp and the outside
/// nodes the refinement looks at.
constexpr double stamp_voxels = 4.0;
/// The box reaches this many voxels beyond the balls R_i: the stamped nodes and one more.
constexpr double box_margin_voxels = stamp_voxels + 1.0;
/// Newton steps of TransformField::project.
constexpr int projection_steps = 4;
constexpr float unset = std::numeric_limits<float>::infinity();

/// The box of nodes within `margin` + R_i of some atom, cut to the region's bounding box grown by
/// the probe and the margin (a node's field reads the outside of U up to a probe radius away).
/// Empty when they do not meet.
NodeBox node_box(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                 const Eigen::Ref<const Eigen::VectorXd>& radii, double probe, double margin,
                 double voxel, const BallUnion* region) {
  const double reach = radii.maxCoeff() + probe + margin;
  Eigen::Array3d lo = centers.colwise().minCoeff().transpose().array() - reach;
  Eigen::Array3d hi = centers.colwise().maxCoeff().transpose().array() + reach;
  if (region != nullptr) {
    lo = lo.max(region->lower().array() - probe - margin);
    hi = hi.min(region->upper().array() + probe + margin);
    if ((hi < lo).any()) return {};  // before the casts: a far region's bounds may not fit an int
  }
  NodeBox box;
  box.lo = (lo / voxel).floor().cast<int>().matrix();
  const Eigen::Vector3i top = (hi / voxel).ceil().cast<int>().matrix();
  box.n = top - box.lo + Eigen::Vector3i::Ones();
  return box;
}

/// One line of the squared distance transform (Felzenszwalb & Huttenlocher): for each q,
/// d[q] = min_p ((q - p)^2 + f[p]) over the p with finite f[p], and arg[q] that p (-1 and an
/// infinite d when there is none). `v` and `z` are scratch of n and n + 1 entries.
void distance_line(const float* f, int n, float* d, int* arg, std::vector<int>& v,
                   std::vector<double>& z) {
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (!std::isfinite(f[q])) continue;
    double s = -std::numeric_limits<double>::infinity();
    while (k >= 0) {
      const int p = v[static_cast<std::size_t>(k)];
      s = ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * (q - p));
      if (k > 0 && s <= z[static_cast<std::size_t>(k)]) {
        --k;
      } else {
        break;
      }
    }
    ++k;
    v[static_cast<std::size_t>(k)] = q;
    z[static_cast<std::size_t>(k)] = k == 0 ? -std::numeric_limits<double>::infinity() : s;
  }
  if (k < 0) {
    std::fill(d, d + n, unset);
    std::fill(arg, arg + n, -1);
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (j < k && z[static_cast<std::size_t>(j) + 1] < q) ++j;
    const int p = v[static_cast<std::size_t>(j)];
    d[q] = static_cast<float>(double(q - p) * (q - p) + f[p]);
    arg[q] = p;
  }
}

/// The squared distance (in voxels^2) from every node to the nearest node outside U (s >= 0), and
/// that node's index in the box (-1 when there is none), by three passes of distance_line along
/// k, j and i.
void distance_transform(const NodeBox& box, const std::vector<float>& s,
                        std::vector<float>& squared, std::vector<std::int32_t>& nearest) {
  const std::size_t size = box.size();
  squared.assign(size, unset);
  nearest.assign(size, -1);
  for (std::size_t p = 0; p < size; ++p) {
    if (s[p] >= 0.0F) squared[p] = 0.0F;
  }
  // Pass a runs along axis a over the lines indexed by the other two axes.
  for (int axis = 2; axis >= 0; --axis) {
    const int n = box.n(axis);
    const int u_axis = axis == 0 ? 1 : 0, w_axis = axis == 2 ? 1 : 2;
    const int lines_u = box.n(u_axis), lines_w = box.n(w_axis);
    tbb::parallel_for(tbb::blocked_range<int>(0, lines_u), [&](const tbb::blocked_range<int>& r) {
      std::vector<float> f(static_cast<std::size_t>(n)), d(static_cast<std::size_t>(n));
      std::vector<int> arg(static_cast<std::size_t>(n)), v(static_cast<std::size_t>(n));
      std::vector<double> z(static_cast<std::size_t>(n) + 1);
      std::vector<std::int32_t> from(static_cast<std::size_t>(n));
      for (int u = r.begin(); u != r.end(); ++u) {
        for (int w = 0; w < lines_w; ++w) {
          Eigen::Vector3i c;
          c(u_axis) = u;
          c(w_axis) = w;
          const auto at = [&](int t) {
            c(axis) = t;
            return box.index(c);
          };
          for (int t = 0; t < n; ++t) {
            const std::size_t p = at(t);
            f[static_cast<std::size_t>(t)] = squared[p];
            from[static_cast<std::size_t>(t)] =
                axis == 2 ? static_cast<std::int32_t>(p) : nearest[p];
          }
          distance_line(f.data(), n, d.data(), arg.data(), v, z);
          for (int t = 0; t < n; ++t) {
            const std::size_t p = at(t);
            squared[p] = d[static_cast<std::size_t>(t)];
            const int a = arg[static_cast<std::size_t>(t)];
            nearest[p] = a < 0 ? -1 : from[static_cast<std::size_t>(a)];
          }
        }
      }
    });
  }
}

}  // namespace

double distance_transform_nodes(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                                const Eigen::Ref<const Eigen::VectorXd>& radii, double probe,
                                double voxel, const BallUnion* region) {
  const NodeBox box = node_box(centers, radii, probe, box_margin_voxels * voxel, voxel, region);
  return static_cast<double>(box.n.x()) * box.n.y() * box.n.z();
}

TransformMesh distance_transform_mesh(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                                      const Eigen::Ref<const Eigen::VectorXd>& radii, double probe,
                                      double voxel, const BallUnion* region) {
  const NodeBox box = node_box(centers, radii, probe, box_margin_voxels * voxel, voxel, region);
  const auto band = static_cast<float>(band_voxels * voxel);
  SparseGrid grid(band);
  if (box.size() == 0) return {dual_marching_cubes(grid, voxel), {}};
  const auto position = [&](int i, int j, int k) {
    return Eigen::Vector3d((box.lo + Eigen::Vector3i(i, j, k)).cast<double>() * voxel);
  };

  // s(x) = min_i (|x - c_i| - R_i) within stamp_voxels of each ball, by slabs of i so that
  // each slab's nodes are written by one task.
  std::vector<float> s(box.size(), unset);
  std::vector<std::vector<Eigen::Index>> slab_atoms(static_cast<std::size_t>(box.n.x()));
  const double stamp = stamp_voxels * voxel;
  for (Eigen::Index a = 0; a < centers.rows(); ++a) {
    const double reach = radii(a) + probe + stamp;
    const int first =
        std::max(0, static_cast<int>(std::ceil((centers(a, 0) - reach) / voxel)) - box.lo.x());
    const int last = std::min(
        box.n.x() - 1, static_cast<int>(std::floor((centers(a, 0) + reach) / voxel)) - box.lo.x());
    for (int i = first; i <= last; ++i) slab_atoms[static_cast<std::size_t>(i)].push_back(a);
  }
  tbb::parallel_for(0, box.n.x(), [&](int i) {
    for (const Eigen::Index a : slab_atoms[static_cast<std::size_t>(i)]) {
      const Eigen::Vector3d c = centers.row(a).transpose();
      const double big_r = radii(a) + probe, reach = big_r + stamp;
      const double dx = (box.lo.x() + i) * voxel - c.x();
      const double across = reach * reach - dx * dx;
      if (across < 0.0) continue;
      const double half = std::sqrt(across);
      const int j0 = std::max(0, static_cast<int>(std::ceil((c.y() - half) / voxel)) - box.lo.y());
      const int j1 = std::min(box.n.y() - 1,
                              static_cast<int>(std::floor((c.y() + half) / voxel)) - box.lo.y());
      for (int j = j0; j <= j1; ++j) {
        const double dy = (box.lo.y() + j) * voxel - c.y();
        const double rest = across - dy * dy;
        if (rest < 0.0) continue;
        const double h = std::sqrt(rest);
        const int k0 = std::max(0, static_cast<int>(std::ceil((c.z() - h) / voxel)) - box.lo.z());
        const int k1 =
            std::min(box.n.z() - 1, static_cast<int>(std::floor((c.z() + h) / voxel)) - box.lo.z());
        for (int k = k0; k <= k1; ++k) {
          const double dz = (box.lo.z() + k) * voxel - c.z();
          const auto value = static_cast<float>(std::sqrt(dx * dx + dy * dy + dz * dz) - big_r);
          float& slot = s[box.index(i, j, k)];
          slot = std::min(slot, value);
        }
      }
    }
  });

  // The field at every node, clamped to +-clamp.
  const auto clamp = static_cast<float>(field_voxels * voxel);
  std::vector<float> field(box.size(), clamp);
  if (probe == 0.0) {
    for (std::size_t p = 0; p < field.size(); ++p) field[p] = std::clamp(s[p], -clamp, clamp);
  } else {
    std::vector<float> squared;
    std::vector<std::int32_t> nearest;
    distance_transform(box, s, squared, nearest);
    // A node whose distance to the nearest outside node leaves it deeper than this stays
    // clamped: the refinement lowers the distance by at most |q - q0| + s(q), under about four
    // voxels for the outside nodes q it looks at (around the nearest one, q0).
    const double deep = clamp + 4.0 * voxel;
    tbb::parallel_for(0, box.n.x(), [&](int i) {
      for (int j = 0; j < box.n.y(); ++j) {
        for (int k = 0; k < box.n.z(); ++k) {
          const std::size_t p = box.index(i, j, k);
          if (s[p] >= 0.0F) {
            field[p] = std::min(clamp, static_cast<float>(probe + s[p]));
            continue;
          }
          const double d0 = std::sqrt(static_cast<double>(squared[p])) * voxel;
          if (nearest[p] < 0 || probe - d0 < -deep) {
            field[p] = -clamp;
            continue;
          }
          // The outside nodes around the nearest one: |x - q| - s(q) bounds the distance
          // from x to U's boundary from above, and is close to it for the q beyond the
          // boundary point nearest x.
          const Eigen::Vector3d x = position(i, j, k);
          const Eigen::Vector3i q0 = box.node(static_cast<std::size_t>(nearest[p]));
          double d = d0;
          for (int di = -1; di <= 1; ++di) {
            for (int dj = -1; dj <= 1; ++dj) {
              for (int dk = -1; dk <= 1; ++dk) {
                const Eigen::Vector3i q = q0 + Eigen::Vector3i(di, dj, dk);
                if (!box.contains(q)) continue;
                const float sq = s[box.index(q)];
                if (!(sq >= 0.0F) || !std::isfinite(sq)) continue;
                d = std::min(d, (position(q.x(), q.y(), q.z()) - x).norm() - sq);
              }
            }
          }
          field[p] = static_cast<float>(
              std::clamp(probe - std::max(d, 0.0), -double(clamp), double(clamp)));
        }
      }
    });
  }
  if (region != nullptr) {
    tbb::parallel_for(0, box.n.x(), [&](int i) {
      for (int j = 0; j < box.n.y(); ++j) {
        for (int k = 0; k < box.n.z(); ++k) {
          float& value = field[box.index(i, j, k)];
          if (value >= clamp) continue;
          value = std::min(clamp,
                           std::max(value, static_cast<float>(region->value(position(i, j, k)))));
        }
      }
    });
  }

  // Into the sparse grid by blocks: a block all outside stays background, one all deep inside
  // is filled whole.
  const int w = SparseGrid::block_width;
  const Eigen::Vector3i hi = box.lo + box.n - Eigen::Vector3i::Ones();
  const auto block = [&](int v) { return v >= 0 ? v / w : -((-v + w - 1) / w); };
  for (int bi = block(box.lo.x()); bi <= block(hi.x()); ++bi) {
    for (int bj = block(box.lo.y()); bj <= block(hi.y()); ++bj) {
      for (int bk = block(box.lo.z()); bk <= block(hi.z()); ++bk) {
        const Eigen::Vector3i origin(bi * w, bj * w, bk * w);
        bool all_band = true, all_inside = true;
        for (int a = 0; a < w && (all_band || all_inside); ++a) {
          for (int b = 0; b < w; ++b) {
            for (int c = 0; c < w; ++c) {
              const Eigen::Vector3i g = origin + Eigen::Vector3i(a, b, c) - box.lo;
              const float value =
                  box.contains(g) ? std::clamp(field[box.index(g)], -band, band) : band;
              all_band = all_band && value >= band;
              all_inside = all_inside && value <= -band;
            }
          }
        }
        if (all_band) continue;
        if (all_inside) {
          grid.fill({origin.x(), origin.y(), origin.z()}, w, -band);
          continue;
        }
        for (int a = 0; a < w; ++a) {
          for (int b = 0; b < w; ++b) {
            for (int c = 0; c < w; ++c) {
              const Eigen::Vector3i g = origin + Eigen::Vector3i(a, b, c) - box.lo;
              if (!box.contains(g)) continue;
              const float value = std::clamp(field[box.index(g)], -band, band);
              if (value < band)
                grid.set({g.x() + box.lo.x(), g.y() + box.lo.y(), g.z() + box.lo.z()}, value);
            }
          }
        }
      }
    }
  }
  TriangleSoup soup = dual_marching_cubes(grid, voxel);
  return {std::move(soup), TransformField(box, voxel, std::move(field))};
}

bool TransformField::sample(const Eigen::Vector3d& x, double& value,
                            Eigen::Vector3d& gradient) const {
  const Eigen::Vector3d g = x / voxel_ - box_.lo.cast<double>();
  const Eigen::Vector3d cell = g.array().floor().matrix();
  // The cell and the nodes one beyond it, which the second differences read (false for NaN).
  if (!((cell.array() >= 1.0) && (cell.array() < (box_.n.array() - 2).cast<double>())).all()) {
    return false;
  }
  const Eigen::Vector3i c = cell.cast<int>();
  const Eigen::Vector3d t = g - cell;
  const auto at = [&](int a, int b, int d) {
    return static_cast<double>(values_[box_.index(c.x() + a, c.y() + b, c.z() + d)]);
  };
  // Trilinear interpolation of the values and, for the correction, of the second differences
  // along each axis: linear interpolation along an axis errs by t (1 - t) / 2 times the second
  // difference, so subtracting that makes the interpolation exact for quadratics.
  double lin = 0.0, second[3] = {0.0, 0.0, 0.0};
  Eigen::Vector3d grad = Eigen::Vector3d::Zero();
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      for (int d = 0; d < 2; ++d) {
        const double wx = a ? t.x() : 1.0 - t.x(), wy = b ? t.y() : 1.0 - t.y(),
                     wz = d ? t.z() : 1.0 - t.z();
        const double f = at(a, b, d), w = wx * wy * wz;
        lin += w * f;
        grad += f * Eigen::Vector3d((a ? 1.0 : -1.0) * wy * wz, (b ? 1.0 : -1.0) * wx * wz,
                                    (d ? 1.0 : -1.0) * wx * wy);
        second[0] += w * (at(a + 1, b, d) - 2.0 * f + at(a - 1, b, d));
        second[1] += w * (at(a, b + 1, d) - 2.0 * f + at(a, b - 1, d));
        second[2] += w * (at(a, b, d + 1) - 2.0 * f + at(a, b, d - 1));
      }
    }
  }
  value = lin - 0.5 * (t.x() * (1.0 - t.x()) * second[0] + t.y() * (1.0 - t.y()) * second[1] +
                       t.z() * (1.0 - t.z()) * second[2]);
  gradient = grad / voxel_;
  return true;
}

Eigen::Vector3d TransformField::project(Eigen::Vector3d& x) const {
  Eigen::Vector3d y = x, gradient;
  double value = 0.0;
  for (int step = 0; step < projection_steps; ++step) {
    if (!sample(y, value, gradient) || !(gradient.squaredNorm() > 0.0))
      return Eigen::Vector3d::Zero();
    Eigen::Vector3d move = -value * gradient / gradient.squaredNorm();
    const double length = move.norm();
    if (length > 0.5 * voxel_) move *= 0.5 * voxel_ / length;
    y += move;
    if (length < 1e-6 * voxel_) break;
  }
  if (!sample(y, value, gradient) || !(gradient.squaredNorm() > 0.0))
    return Eigen::Vector3d::Zero();
  x = y;
  return gradient.normalized();
}

void place_on_field(mesh::Surface& surface, const TransformField& field) {
  mesh::TriMesh& mesh = mesh::tri_mesh(surface);
  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  Eigen::MatrixX3d positions = surface.positions();
  Eigen::MatrixX3d normals(n, 3);
  tbb::parallel_for(Eigen::Index{0}, n, [&](Eigen::Index v) {
    Eigen::Vector3d x = positions.row(v).transpose();
    normals.row(v) = field.project(x).transpose();
    positions.row(v) = x.transpose();
  });
  for (auto vh : mesh.vertices()) {
    const Eigen::Index v = vh.idx();
    mesh.set_point(vh, mesh::TriMesh::Point(positions(v, 0), positions(v, 1), positions(v, 2)));
  }
  finish_placement(surface, normals, Eigen::VectorXd::Zero(n), false);
}

}  // namespace surfcomp::molsurf::detail
