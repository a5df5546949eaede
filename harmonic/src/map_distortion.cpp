#include "surfcomp/harmonic/map_distortion.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/harmonic/disk_map.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace surfcomp::harmonic {
namespace {

/// The angle at corner `a` of triangle (a, b, c), radians; 0 for a degenerate corner.
template <class Point>
double corner_angle(const Point& a, const Point& b, const Point& c) {
  const Point u = b - a, v = c - a;
  const double norms = u.norm() * v.norm();
  if (!(norms > 0.0)) return 0.0;
  return std::acos(std::clamp(u.dot(v) / norms, -1.0, 1.0));
}

/// Throws InputError unless `uv` has a point per patch vertex and every face index is a vertex.
void check_map_input(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                     const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                     const Eigen::Ref<const Eigen::MatrixX2d>& uv) {
  if (uv.rows() != positions.rows()) {
    throw InputError("map distortion: " + std::to_string(uv.rows()) + " map points for " +
                     std::to_string(positions.rows()) + " patch vertices");
  }
  const Eigen::Index n = positions.rows();
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= n)
        throw InputError("map distortion: face " + std::to_string(f) + " has a vertex index " +
                         std::to_string(faces(f, k)) + " outside [0, " + std::to_string(n) + ")");
}

/// The corners of face `f` on the patch (`p`) and in the map (`q`).
struct Corners {
  std::array<Eigen::Vector3d, 3> p;
  std::array<Eigen::Vector2d, 3> q;
};

Corners corners_of(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                   const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                   const Eigen::Ref<const Eigen::MatrixX2d>& uv, Eigen::Index f) {
  Corners corners;
  for (int k = 0; k < 3; ++k) {
    corners.p[static_cast<std::size_t>(k)] = positions.row(faces(f, k)).transpose();
    corners.q[static_cast<std::size_t>(k)] = uv.row(faces(f, k)).transpose();
  }
  return corners;
}

}  // namespace

Eigen::MatrixX3d corner_angle_distortion(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                         const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                         const Eigen::Ref<const Eigen::MatrixX2d>& uv) {
  check_map_input(positions, faces, uv);
  Eigen::MatrixX3d out(faces.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const auto [p, q] = corners_of(positions, faces, uv, f);
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t b = (k + 1) % 3, c = (k + 2) % 3;
      out(f, static_cast<Eigen::Index>(k)) =
          std::abs(corner_angle(q[k], q[b], q[c]) - corner_angle(p[k], p[b], p[c])) * 180.0 / M_PI;
    }
  }
  return out;
}

MapDistortion map_distortion(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                             const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                             const Eigen::Ref<const Eigen::MatrixX2d>& uv) {
  const Eigen::MatrixX3d angles = corner_angle_distortion(positions, faces, uv);
  MapDistortion out;
  out.flipped = count_flipped_triangles(uv, faces);
  std::vector<double> patch_area(static_cast<std::size_t>(faces.rows()));
  std::vector<double> map_area(patch_area.size());
  double patch_total = 0.0, map_total = 0.0, angle_sum = 0.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const auto [p, q] = corners_of(positions, faces, uv, f);
    for (int k = 0; k < 3; ++k) {
      angle_sum += angles(f, k);
      out.angle_max_degrees = std::max(out.angle_max_degrees, angles(f, k));
    }
    const double a3 = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const Eigen::Vector2d e1 = q[1] - q[0], e2 = q[2] - q[0];
    const double a2 = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    patch_area[static_cast<std::size_t>(f)] = a3;
    map_area[static_cast<std::size_t>(f)] = a2;
    if (a3 > 0.0 && a2 > 0.0) {
      patch_total += a3;
      map_total += a2;
    }
  }
  out.angle_mean_degrees = angle_sum / static_cast<double>(3 * faces.rows());
  if (!(patch_total > 0.0) || !(map_total > 0.0)) {  // every triangle flipped or degenerate
    out.area_mean_log = out.area_max_log = std::nan("");
    return out;
  }
  double weighted = 0.0;
  for (std::size_t t = 0; t < patch_area.size(); ++t) {
    if (!(patch_area[t] > 0.0 && map_area[t] > 0.0)) continue;
    const double log_ratio =
        std::abs(std::log((map_area[t] / map_total) / (patch_area[t] / patch_total)));
    weighted += patch_area[t] * log_ratio;
    out.area_max_log = std::max(out.area_max_log, log_ratio);
  }
  out.area_mean_log = weighted / patch_total;
  return out;
}

}  // namespace surfcomp::harmonic
