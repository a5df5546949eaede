// SES and SAS: an exact distance field sampled near the surface into a sparse OpenVDB grid,
// meshed by OpenVDB, remeshed by CGAL (remesh.cpp), vertices projected back onto the exact
// surface. OpenVDB stays in this translation unit.
#include "surfcomp/mesh/ses.hpp"

#include "surface_mesh.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/remesh.hpp"

#include <Eigen/Geometry>
#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

namespace surfcomp::mesh {
namespace {

using Vec3 = Eigen::Vector3d;

/// Automatic voxel size as a fraction of the target edge length: the grid mesh then has a
/// little more than the target density, so remeshing mostly flips, collapses and relaxes. The
/// grid decides only the topology; vertices are projected onto the exact surface.
constexpr double auto_voxel_per_edge = 1.0;
/// The smallest atom must span this many voxels (radius / voxel).
constexpr double min_atom_voxels = 2.0;
/// Grid values are exact within this many voxels of the surface and clamped beyond.
constexpr double band_voxels = 1.5;
/// Vertices are searched for their surface point this many voxels away.
constexpr double reach_voxels = 3.0;
/// Rounds of isotropic remeshing: the grid mesh is already close to the target.
constexpr int remesh_iterations = 2;
/// Projections of a vertex onto the exact surface (the nearest feature can change once).
constexpr int projection_rounds = 3;
/// A projection has converged when it moves a vertex less than this, A.
constexpr double convergence = 1e-12;
/// Marks "not a candidate" in the per-thread gap table.
constexpr double limit_none = std::numeric_limits<double>::infinity();
/// Tolerance for "a point on sphere i lies inside sphere j", A.
constexpr double burial_tolerance = 1e-9;
/// Cell size of the atom index, A.
constexpr double sphere_cell = 1.5;
/// Root boxes of the adaptive sampling, voxels per side (a power of two).
constexpr int root_box = 32;
/// Boxes up to this size are sampled voxel by voxel.
constexpr int leaf_box = 2;
/// Passes that split (or snap onto the crease) the SAS edges whose ends lie on no common sphere.
constexpr int crease_rounds = 3;
/// A crease point this close to an edge's end (in edge lengths L) moves that end instead.
constexpr double snap_fraction = 0.2;
/// SAS edges shorter than this (in L) after the crease splits are collapsed.
constexpr double collapse_fraction = 0.5;
/// Passes over the edges collapsing the short ones (stops early when one changes nothing).
constexpr int collapse_passes = 3;
/// Triangles of the crease splits and collapses keep at least this area (in L^2).
constexpr double crease_min_area = 1e-4;

/// Points binned into a dense grid of cubic cells (compressed rows) for radius queries.
/// Visits points in a fixed order: by cell, then by index.
class CellIndex {
 public:
  CellIndex() = default;
  CellIndex(const std::vector<Vec3>& points, double cell) : cell_(cell) {
    if (points.empty()) return;
    Vec3 hi = points.front();
    lo_ = points.front();
    for (const Vec3& p : points) {
      lo_ = lo_.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    // Cap the cell count for sparse inputs (atoms far apart) by coarsening the cells.
    const Vec3 extent = hi - lo_;
    while ((extent / cell_).array().floor().prod() > static_cast<double>(max_cells)) cell_ *= 2.0;
    dims_ = (extent / cell_).array().floor().cast<int>() + 1;
    std::vector<int> cell_of_point(points.size());
    offsets_.assign(static_cast<std::size_t>(dims_.prod()) + 1, 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3i c = clamp(cell_of(points[i]));
      cell_of_point[i] = flat(c);
      ++offsets_[static_cast<std::size_t>(cell_of_point[i]) + 1];
    }
    std::partial_sum(offsets_.begin(), offsets_.end(), offsets_.begin());
    indices_.resize(points.size());
    std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i) {
      indices_[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_of_point[i])]++)] =
          static_cast<int>(i);
    }
  }

  /// Calls visit(i) for every point i in the cells that the cube of half-width `radius`
  /// around x touches (a superset of the points within radius).
  template <class Visit>
  void for_each_near(const Vec3& x, double radius, Visit&& visit) const {
    if (indices_.empty()) return;
    const Eigen::Vector3i lo = cell_of(x - Vec3::Constant(radius));
    const Eigen::Vector3i hi = cell_of(x + Vec3::Constant(radius));
    if ((hi.array() < 0).any() || (lo.array() >= dims_.array()).any()) return;
    const Eigen::Vector3i from = clamp(lo);
    const Eigen::Vector3i to = clamp(hi);
    for (int i = from.x(); i <= to.x(); ++i) {
      for (int j = from.y(); j <= to.y(); ++j) {
        const int row = flat(Eigen::Vector3i(i, j, 0));
        const int begin = offsets_[static_cast<std::size_t>(row + from.z())];
        const int end = offsets_[static_cast<std::size_t>(row + to.z()) + 1];
        for (int p = begin; p < end; ++p) visit(indices_[static_cast<std::size_t>(p)]);
      }
    }
  }

 private:
  static constexpr int max_cells = 1 << 22;

  Eigen::Vector3i cell_of(const Vec3& x) const {
    const Eigen::Array3d c = ((x - lo_) / cell_).array().floor();
    // Far-away queries saturate instead of overflowing int.
    return c.max(-1.0).min(dims_.cast<double>().array()).cast<int>().matrix();
  }
  Eigen::Vector3i clamp(const Eigen::Vector3i& c) const {
    return c.cwiseMax(0).cwiseMin(dims_ - Eigen::Vector3i::Ones());
  }
  int flat(const Eigen::Vector3i& c) const {
    return (c.x() * dims_.y() + c.y()) * dims_.z() + c.z();
  }

  double cell_ = 1.0;
  Vec3 lo_ = Vec3::Zero();
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  std::vector<int> offsets_;
  std::vector<int> indices_;
};

/// The spheres a point of the SAS lies on: one on a sphere patch, two on a crease (the circle
/// where they meet), three at a vertex; ascending, unused slots -1 at the end.
using Spheres = std::array<int, 3>;

Spheres sorted_spheres(int a, int b = -1, int c = -1) {
  Spheres s{a, b, c};
  std::sort(s.begin(), s.end(), [](int x, int y) { return y < 0 || (x >= 0 && x < y); });
  return s;
}

int sphere_count(const Spheres& s) {
  return static_cast<int>(std::count_if(s.begin(), s.end(), [](int x) { return x >= 0; }));
}

/// True when points labelled a and b lie on a common sphere (no crease between them).
bool share_sphere(const Spheres& a, const Spheres& b) {
  for (const int x : a) {
    if (x >= 0 && std::find(b.begin(), b.end(), x) != b.end()) return true;
  }
  return false;
}

/// What the nearest point of the SAS boundary lies on.
enum class Feature : std::uint8_t { none, sphere, circle, vertex };

struct NearestPoint {
  double distance = std::numeric_limits<double>::infinity();
  Vec3 point = Vec3::Zero();
  Feature feature = Feature::none;
  int index = -1;  ///< sphere, circle or vertex index
};

/// The union U of spheres R_i = r_i + probe (the SAS region) and the exact distance from a point
/// inside U to its boundary, whose pieces are sphere patches, arcs of the circles where two
/// spheres meet and the vertices where three meet (each kept only where no other sphere
/// buries it). The SES is the set of points at distance `probe` inside U: the probe, centred
/// on the boundary of U, touches but does not enter the atoms.
class SasGeometry {
 public:
  SasGeometry(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
              const Eigen::Ref<const Eigen::VectorXd>& radii, double probe)
      : probe_(probe) {
    for (Eigen::Index i = 0; i < centers.rows(); ++i) {
      centers_.emplace_back(centers.row(i).transpose());
      big_.push_back(radii(i) + probe);
      atom_.push_back(radii(i));
    }
    max_big_ = *std::max_element(big_.begin(), big_.end());
    spheres_ = CellIndex(centers_, sphere_cell);
    find_neighbours();
    find_circles();
  }

  double probe() const { return probe_; }
  double radius(int i) const { return big_[static_cast<std::size_t>(i)]; }
  double atom_radius(int i) const { return atom_[static_cast<std::size_t>(i)]; }
  const Vec3& center(int i) const { return centers_[static_cast<std::size_t>(i)]; }

  /// The spheres and vertices that can matter within `radius` of `centre` when features are
  /// searched up to `limit`: spheres with |x - c_i| - R_i < limit somewhere in the ball
  /// and vertices within limit + radius, in CellIndex order.
  struct Candidates {
    std::vector<int> spheres;
    std::vector<int> vertices;
  };
  void gather(const Vec3& centre, double radius, double limit, Candidates& out) const {
    out.spheres.clear();
    out.vertices.clear();
    spheres_.for_each_near(centre, max_big_ + limit + radius, [&](int i) {
      if ((centre - center(i)).norm() - this->radius(i) < limit + radius) out.spheres.push_back(i);
    });
    vertex_index_.for_each_near(centre, limit + radius, [&](int v) {
      if ((centre - vertices_[static_cast<std::size_t>(v)]).norm() < limit + radius) {
        out.vertices.push_back(v);
      }
    });
  }

  /// min_i (|x - c_i| - R_i) over the candidates, at most `limit`: the CSG union, exact
  /// outside U and never deeper than the true depth inside. Sets *which (the first candidate
  /// on ties).
  double union_value(const Vec3& x, double limit, const Candidates& candidates,
                     int* which = nullptr) const {
    double best = limit;
    for (const int i : candidates.spheres) {
      const double v = (x - center(i)).norm() - radius(i);
      if (v < best) {
        best = v;
        if (which != nullptr) *which = i;
      }
    }
    return best;
  }
  double union_value(const Vec3& x, double limit) const {
    thread_local Candidates candidates;
    gather(x, 0.0, limit, candidates);
    return union_value(x, limit, candidates);
  }

  /// The nearest point of the boundary of U to x (inside U), searched up to `limit` among the
  /// candidates; feature none and distance `limit` when it is farther. Spheres are visited by
  /// increasing gap |R_i - |x - c_i||, a lower bound of the distance to every feature on them.
  NearestPoint nearest_boundary_point(const Vec3& x, double limit,
                                      const Candidates& candidates) const {
    NearestPoint best;
    best.distance = limit;
    thread_local std::vector<std::pair<double, int>> near;
    thread_local std::vector<double> gap_of;
    near.clear();
    if (gap_of.size() != centers_.size()) gap_of.assign(centers_.size(), limit_none);
    for (const int i : candidates.spheres) {
      const double gap = std::abs(radius(i) - (x - center(i)).norm());
      if (gap < limit) near.emplace_back(gap, i);
    }
    std::sort(near.begin(), near.end());
    for (const auto& [gap, i] : near) gap_of[static_cast<std::size_t>(i)] = gap;
    for (const auto& [gap, i] : near) {
      if (gap >= best.distance) break;
      const Vec3 d = x - center(i);
      const double length = d.norm();
      if (length == 0.0 || !exposed_sphere_[static_cast<std::size_t>(i)]) continue;
      const Vec3 p = center(i) + radius(i) / length * d;
      if (!buried(p, neighbours_[static_cast<std::size_t>(i)], i)) {
        best = NearestPoint{gap, p, Feature::sphere, i};
        break;
      }
    }
    for (const auto& [gap, i] : near) {
      if (gap >= best.distance) break;
      for (const int c : circles_of_[static_cast<std::size_t>(i)]) {
        const Circle& circle = circles_[static_cast<std::size_t>(c)];
        const int other = circle.i == i ? circle.j : circle.i;
        const double other_gap = gap_of[static_cast<std::size_t>(other)];
        // Visit each circle once, from the sphere with the smaller gap.
        if (other_gap >= best.distance || other_gap < gap || (other_gap == gap && other < i))
          continue;
        const Vec3 v = x - circle.center;
        const double along = v.dot(circle.normal);
        const Vec3 radial = v - along * circle.normal;
        const double r = radial.norm();
        const double distance = std::hypot(along, r - circle.radius);
        if (distance >= best.distance) continue;
        double angle = r > 0.0 ? std::atan2(radial.dot(circle.w), radial.dot(circle.u)) : 0.0;
        if (angle < 0.0) angle += 2.0 * M_PI;
        if (circle.exposed_at(angle)) {
          const Vec3 p = circle.center +
                         circle.radius * (std::cos(angle) * circle.u + std::sin(angle) * circle.w);
          best = NearestPoint{distance, p, Feature::circle, c};
        }
      }
    }
    for (const auto& entry : near) gap_of[static_cast<std::size_t>(entry.second)] = limit_none;
    for (const int v : candidates.vertices) {
      const double distance = (x - vertices_[static_cast<std::size_t>(v)]).norm();
      if (distance < best.distance) {
        best = NearestPoint{distance, vertices_[static_cast<std::size_t>(v)], Feature::vertex, v};
      }
    }
    return best;
  }

  /// Signed distance-like value of the SES (negative inside, 1-Lipschitz), exact where its
  /// magnitude is below `clamp` and clamped to [-clamp, clamp] beyond. `candidates` must come
  /// from gather() with limit >= probe + clamp around a ball containing x.
  double ses_value(const Vec3& x, double clamp, const Candidates& candidates) const {
    const double outside = union_value(x, probe_ + clamp, candidates);
    if (outside >= 0.0) return std::min(probe_ + outside, clamp);
    // dist(x, boundary) >= the depth in any one sphere, so this bounds the value from above.
    if (probe_ + outside <= -clamp) return -clamp;
    const NearestPoint q = nearest_boundary_point(x, probe_ + clamp, candidates);
    return std::clamp(probe_ - q.distance, -clamp, clamp);
  }

  /// Signed distance-like value of the SAS (negative inside, 1-Lipschitz), clamped.
  double sas_value(const Vec3& x, double clamp, const Candidates& candidates) const {
    return std::clamp(union_value(x, clamp, candidates), -clamp, clamp);
  }

  /// Moves x, which lies within `reach` of the SES, onto it; returns the outward unit normal
  /// and the mean curvature there (unchanged if no surface is within reach).
  void project_to_ses(Vec3& x, double reach, Vec3& normal, double& mean_curvature) const {
    const double limit = probe_ + reach;
    thread_local Candidates candidates;
    gather(x, reach, limit, candidates);
    for (int round = 0; round < projection_rounds; ++round) {
      if (union_value(x, limit, candidates) >= 0.0) {
        // Outside U: on the surface itself only for a zero probe (the SES is then U's boundary).
        if (probe_ == 0.0) project_to_sas(x, reach, normal, mean_curvature);
        return;
      }
      const NearestPoint q = nearest_boundary_point(x, limit, candidates);
      if (q.feature == Feature::none || q.distance == 0.0) return;
      const Vec3 away = (q.point - x) / q.distance;  // outward normal of the SES
      const Vec3 moved = q.point - probe_ * away;
      normal = away;
      mean_curvature = curvature_at(moved, normal, q);
      // Moving towards q keeps q the nearest boundary point, so x is then exact; moving
      // away from q (x was outside the SES) may not, and is checked by another round.
      const bool done = q.distance >= probe_ || (moved - x).norm() < convergence;
      x = moved;
      if (done) return;
    }
  }

  /// Moves x, which lies within `reach` of the SAS, onto its nearest point of the SAS: the
  /// nearest sphere from outside U; from inside, the nearest sphere patch, crease or vertex.
  /// Returns the spheres the point lies on (all -1, x unchanged, if none is within reach).
  Spheres nearest_sas_point(Vec3& x, double reach) const {
    thread_local Candidates candidates;
    gather(x, reach, reach, candidates);
    int which = -1;
    if (union_value(x, reach, candidates, &which) >= 0.0) {
      if (which < 0) return Spheres{-1, -1, -1};
      const Vec3 d = x - center(which);
      if (d.norm() == 0.0) return Spheres{-1, -1, -1};
      x = center(which) + radius(which) / d.norm() * d;
      return sorted_spheres(which);
    }
    const NearestPoint q = nearest_boundary_point(x, reach, candidates);
    switch (q.feature) {
      case Feature::none:
        return Spheres{-1, -1, -1};
      case Feature::sphere:
        x = q.point;
        return sorted_spheres(q.index);
      case Feature::circle: {
        const Circle& c = circles_[static_cast<std::size_t>(q.index)];
        x = q.point;
        return sorted_spheres(c.i, c.j);
      }
      case Feature::vertex:
        x = q.point;
        return vertex_spheres_[static_cast<std::size_t>(q.index)];
    }
    return Spheres{-1, -1, -1};
  }

  /// The point of the exposed crease between spheres i and j (an arc of their circle) nearest
  /// to `near`, if the circle exists and is exposed there.
  bool crease_point(int i, int j, const Vec3& near, Vec3& out) const {
    for (const int c : circles_of_[static_cast<std::size_t>(i)]) {
      const Circle& circle = circles_[static_cast<std::size_t>(c)];
      if (circle.i != j && circle.j != j) continue;
      const Vec3 v = near - circle.center;
      const Vec3 radial = v - v.dot(circle.normal) * circle.normal;
      if (radial.norm() == 0.0) return false;
      double angle = std::atan2(radial.dot(circle.w), radial.dot(circle.u));
      if (angle < 0.0) angle += 2.0 * M_PI;
      if (!circle.exposed_at(angle)) return false;
      out = circle.center + circle.radius / radial.norm() * radial;
      return true;
    }
    return false;
  }

  /// The SAS vertex of spheres s nearest to `near`, if one exists within `limit` of it.
  bool vertex_point(const Spheres& s, const Vec3& near, double limit, Vec3& out) const {
    bool found = false;
    vertex_index_.for_each_near(near, limit, [&](int v) {
      const Vec3& p = vertices_[static_cast<std::size_t>(v)];
      if (vertex_spheres_[static_cast<std::size_t>(v)] == s && (p - near).norm() < limit &&
          (!found || (p - near).norm() < (out - near).norm())) {
        out = p;
        found = true;
      }
    });
    return found;
  }

  /// Moves x, which lies within `reach` of the SAS, onto it; returns the outward unit normal
  /// and the mean curvature there (unchanged if no surface is within reach).
  void project_to_sas(Vec3& x, double reach, Vec3& normal, double& mean_curvature) const {
    thread_local Candidates candidates;
    gather(x, reach, reach, candidates);
    for (int round = 0; round < projection_rounds; ++round) {
      int which = -1;
      union_value(x, reach, candidates, &which);
      if (which < 0) return;
      const Vec3 d = x - center(which);
      if (d.norm() == 0.0) return;
      normal = d.normalized();
      const Vec3 moved = center(which) + radius(which) * normal;
      mean_curvature = 1.0 / radius(which);
      const bool done = (moved - x).norm() < convergence;
      x = moved;
      if (done) return;
    }
  }

 private:
  /// A circle where spheres i < j meet, with the arcs of it that no third sphere buries.
  struct Circle {
    Vec3 center;
    Vec3 normal;  ///< unit, from sphere i to sphere j
    Vec3 u;       ///< in-plane basis: a point is center + radius (cos t u + sin t w)
    Vec3 w;
    double radius;
    int i;
    int j;
    std::vector<std::pair<double, double>> exposed;  ///< angle intervals within [0, 2 pi]

    bool exposed_at(double angle) const {
      for (const auto& [start, end] : exposed) {
        if (angle >= start && angle <= end) return true;
      }
      return false;
    }
  };

  bool buried(const Vec3& p, const std::vector<int>& others, int a) const {
    for (const int k : others) {
      if (k == a) continue;
      if ((p - center(k)).squaredNorm() <
          (radius(k) - burial_tolerance) * (radius(k) - burial_tolerance)) {
        return true;
      }
    }
    return false;
  }

  void find_neighbours() {
    neighbours_.resize(centers_.size());
    for (std::size_t i = 0; i < centers_.size(); ++i) {
      spheres_.for_each_near(centers_[i], 2.0 * max_big_, [&](int j) {
        if (static_cast<std::size_t>(j) != i &&
            (centers_[i] - center(j)).norm() < big_[i] + radius(j)) {
          neighbours_[i].push_back(j);
        }
      });
      std::sort(neighbours_[i].begin(), neighbours_[i].end());
    }
  }

  /// Finds every circle where two spheres meet and its exposed arcs; keeps the circles with an
  /// exposed arc, their arc ends (the SAS vertices) and which spheres keep exposed area.
  void find_circles() {
    constexpr double two_pi = 2.0 * M_PI;
    const std::size_t n = centers_.size();
    circles_of_.resize(n);
    std::vector<bool> contained(n, false);
    std::vector<bool> has_circle(n, false);
    std::vector<bool> has_exposed_circle(n, false);
    for (std::size_t a = 0; a < n; ++a) {
      const int i = static_cast<int>(a);
      for (const int j : neighbours_[a]) {
        const Vec3 axis = center(j) - center(i);
        const double d = axis.norm();
        if (d <= radius(j) - radius(i)) contained[a] = true;
        if (j <= i || d <= std::abs(radius(i) - radius(j))) continue;
        const double x0 = (d * d + radius(i) * radius(i) - radius(j) * radius(j)) / (2.0 * d);
        const double rho2 = radius(i) * radius(i) - x0 * x0;
        if (rho2 <= 0.0) continue;
        has_circle[a] = has_circle[static_cast<std::size_t>(j)] = true;
        Circle circle;
        circle.center = center(i) + x0 / d * axis;
        circle.normal = axis / d;
        circle.u = circle.normal.unitOrthogonal();
        circle.w = circle.normal.cross(circle.u);
        circle.radius = std::sqrt(rho2);
        circle.i = i;
        circle.j = j;
        // Sphere k buries the points where |p - c_k| < R_k: with a = (o - c_k).u,
        // b = (o - c_k).w, that is a cos t + b sin t < (R_k^2 - |o - c_k|^2 - rho^2) / (2 rho).
        std::vector<std::tuple<double, double, int>> buried_arcs;  ///< start, end, sphere
        bool all_buried = false;
        for (const int k : neighbours_[a]) {
          if (k == j) continue;
          const Vec3 offset = circle.center - center(k);
          const double ca = offset.dot(circle.u);
          const double cb = offset.dot(circle.w);
          const double m = std::hypot(ca, cb);
          const double t =
              (radius(k) * radius(k) - offset.squaredNorm() - rho2) / (2.0 * circle.radius);
          if (t <= -m) continue;
          if (t >= m) {
            all_buried = true;
            break;
          }
          double middle = std::atan2(cb, ca) + M_PI;
          if (middle >= two_pi) middle -= two_pi;
          const double half_width = M_PI - std::acos(t / m);
          const double start = middle - half_width;
          const double end = middle + half_width;
          if (start < 0.0) {
            buried_arcs.emplace_back(start + two_pi, two_pi, k);
            buried_arcs.emplace_back(0.0, end, k);
          } else if (end > two_pi) {
            buried_arcs.emplace_back(start, two_pi, k);
            buried_arcs.emplace_back(0.0, end - two_pi, k);
          } else {
            buried_arcs.emplace_back(start, end, k);
          }
        }
        if (all_buried) continue;
        std::sort(buried_arcs.begin(), buried_arcs.end());
        double covered = 0.0;  // [0, covered] is buried, by sphere `cover` at its end
        int cover = -1;
        for (const auto& [start, end, k] : buried_arcs) {
          if (start > covered) {
            circle.exposed.emplace_back(covered, start);
            add_arc_end(circle, covered, cover);
            add_arc_end(circle, start, k);
          }
          if (end > covered) {
            covered = end;
            cover = k;
          }
        }
        if (covered < two_pi) {
          circle.exposed.emplace_back(covered, two_pi);
          add_arc_end(circle, covered, cover);
        }
        if (circle.exposed.empty()) continue;
        has_exposed_circle[a] = has_exposed_circle[static_cast<std::size_t>(j)] = true;
        circles_of_[a].push_back(static_cast<int>(circles_.size()));
        circles_of_[static_cast<std::size_t>(j)].push_back(static_cast<int>(circles_.size()));
        circles_.push_back(std::move(circle));
      }
    }
    exposed_sphere_.resize(n);
    for (std::size_t a = 0; a < n; ++a) {
      exposed_sphere_[a] = has_exposed_circle[a] || (!has_circle[a] && !contained[a]);
    }
    vertex_index_ = CellIndex(vertices_, sphere_cell);
  }

  /// Records the SAS vertex at `angle` on `circle` (an end of a buried arc; 0 and 2 pi are
  /// where the angle wraps, not vertices).
  void add_arc_end(const Circle& circle, double angle, int k) {
    if (angle <= 0.0 || angle >= 2.0 * M_PI) return;
    vertices_.push_back(circle.center +
                        circle.radius * (std::cos(angle) * circle.u + std::sin(angle) * circle.w));
    vertex_spheres_.push_back(sorted_spheres(circle.i, circle.j, k));
  }

  /// Mean curvature of the SES at x (positive where convex) given its nearest SAS feature q.
  double curvature_at(const Vec3& x, const Vec3& normal, const NearestPoint& q) const {
    switch (q.feature) {
      case Feature::sphere:
        return 1.0 / atom_radius(q.index);
      case Feature::vertex:
        return -1.0 / probe_;
      case Feature::circle: {
        // Torus: -1/probe along the probe's arc; around the axis, the parallel circle of
        // radius y has normal curvature (w . n) / y, w the unit vector away from the axis.
        const Circle& circle = circles_[static_cast<std::size_t>(q.index)];
        const Vec3 v = x - circle.center;
        const Vec3 radial = v - v.dot(circle.normal) * circle.normal;
        const double y = radial.norm();
        const double parallel = y > 0.0 ? radial.dot(normal) / (y * y) : 0.0;
        return 0.5 * (-1.0 / probe_ + std::min(parallel, 1.0 / probe_));
      }
      case Feature::none:
        break;
    }
    return 0.0;
  }

  double probe_;
  std::vector<Vec3> centers_;
  std::vector<double> big_;
  std::vector<double> atom_;
  double max_big_ = 0.0;
  CellIndex spheres_;
  std::vector<std::vector<int>> neighbours_;
  std::vector<Circle> circles_;
  std::vector<std::vector<int>> circles_of_;
  std::vector<bool> exposed_sphere_;
  std::vector<Vec3> vertices_;
  std::vector<Spheres> vertex_spheres_;  ///< the three spheres meeting at each vertex
  CellIndex vertex_index_;
};

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

/// Samples field.value(x, clamp) on the grid nodes ijk * voxel near its zero level set,
/// refining boxes of nodes adaptively: a box whose centre value exceeds its half-diagonal plus
/// the band in magnitude lies wholly outside (background) or inside (an inactive negative
/// fill), since the field is 1-Lipschitz; the cheap upper bound decides large boxes. Only root
/// boxes within `reach` of an atom are visited. They are processed in parallel into separate
/// slots and written in a fixed order, so the grid does not depend on the thread count.
template <class Field>
openvdb::FloatGrid::Ptr sample_band(const Field& field,
                                    const Eigen::Ref<const Eigen::MatrixX3d>& centers, double reach,
                                    double voxel) {
  const auto band = static_cast<float>(band_voxels * voxel);
  auto grid = openvdb::FloatGrid::create(band);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
  grid->setGridClass(openvdb::GRID_LEVEL_SET);

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
    std::vector<std::pair<openvdb::Coord, float>> values;
    std::vector<std::pair<openvdb::Coord, int>> inside_boxes;  ///< origin, size
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
      const openvdb::Coord corner(origin.x(), origin.y(), origin.z());
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
              out.values.emplace_back(openvdb::Coord(c.x(), c.y(), c.z()), static_cast<float>(v));
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
  auto accessor = grid->getAccessor();
  for (const Samples& s : slots) {
    for (const auto& [origin, size] : s.inside_boxes) {
      grid->tree().fill(openvdb::CoordBBox::createCube(origin, size), -band, false);
    }
  }
  for (const Samples& s : slots) {
    for (const auto& [coord, value] : s.values) accessor.setValue(coord, value);
  }
  return grid;
}

struct TriangleSoup {
  Eigen::MatrixX3d positions;  ///< #V by 3, A
  Eigen::MatrixX3i faces;      ///< #F by 3, counter-clockwise seen from outside
};

/// Meshes the zero isosurface of `grid` (dual contouring; each quad split along its shorter
/// diagonal). Vertices are sorted by coordinates and faces by indices, so the arrays do not
/// depend on the order in which OpenVDB's threads produced them.
TriangleSoup extract_isosurface(const openvdb::FloatGrid& grid) {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(grid, points, quads, 0.0);

  std::vector<std::uint32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0U);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const auto& p = points[a];
    const auto& q = points[b];
    if (p[0] != q[0]) return p[0] < q[0];
    if (p[1] != q[1]) return p[1] < q[1];
    if (p[2] != q[2]) return p[2] < q[2];
    return a < b;
  });
  std::vector<int> rank(points.size());
  TriangleSoup soup;
  soup.positions.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < order.size(); ++i) {
    rank[order[i]] = static_cast<int>(i);
    const auto& p = points[order[i]];
    soup.positions.row(static_cast<Eigen::Index>(i)) << p[0], p[1], p[2];
  }
  // OpenVDB winds quads clockwise seen from the positive (outer) side: reverse them.
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(2 * quads.size());
  for (const auto& q : quads) {
    const int a = rank[q[3]], b = rank[q[2]], c = rank[q[1]], d = rank[q[0]];
    const double ac = (soup.positions.row(a) - soup.positions.row(c)).squaredNorm();
    const double bd = (soup.positions.row(b) - soup.positions.row(d)).squaredNorm();
    if (ac <= bd) {
      triangles.push_back({a, b, c});
      triangles.push_back({a, c, d});
    } else {
      triangles.push_back({a, b, d});
      triangles.push_back({b, c, d});
    }
  }
  for (auto& t : triangles) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::sort(triangles.begin(), triangles.end());
  soup.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    soup.faces.row(static_cast<Eigen::Index>(f)) << triangles[f][0], triangles[f][1],
        triangles[f][2];
  }
  return soup;
}

int find_root(std::vector<int>& parent, int v) {
  while (parent[static_cast<std::size_t>(v)] != v) {
    auto& p = parent[static_cast<std::size_t>(v)];
    p = parent[static_cast<std::size_t>(p)];
    v = p;
  }
  return v;
}

/// The smallest volumes (A^3) a component of the grid mesh must enclose to be kept.
struct ComponentVolumes {
  double outward = 0.0;  ///< an outward component (a body of the molecule)
  double cavity = 0.0;   ///< an inward one (a cavity), when cavities are kept at all
  bool keep_cavities = false;
};

/// The vertex-connected components of `soup` that are kept: outward-facing ones (positive
/// enclosed volume) of at least `limits.outward`, and with `limits.keep_cavities` inward-facing
/// ones (they line cavities) of at least `limits.cavity` in absolute value. The outward
/// component of largest volume is always kept. Vertex and face order are preserved.
TriangleSoup kept_components(const TriangleSoup& soup, const ComponentVolumes& limits) {
  const auto n = static_cast<std::size_t>(soup.positions.rows());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (Eigen::Index f = 0; f < soup.faces.rows(); ++f) {
    for (int k = 1; k < 3; ++k) {
      const int a = find_root(parent, soup.faces(f, 0));
      const int b = find_root(parent, soup.faces(f, k));
      parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  }
  std::vector<double> volume(n, 0.0);
  for (Eigen::Index f = 0; f < soup.faces.rows(); ++f) {
    const Vec3 a = soup.positions.row(soup.faces(f, 0));
    const Vec3 b = soup.positions.row(soup.faces(f, 1));
    const Vec3 c = soup.positions.row(soup.faces(f, 2));
    volume[static_cast<std::size_t>(find_root(parent, soup.faces(f, 0)))] +=
        a.dot(b.cross(c)) / 6.0;
  }
  // Roots are the lowest vertex of their component, so a tie goes to the lowest index.
  const auto largest = static_cast<std::size_t>(
      std::distance(volume.begin(), std::max_element(volume.begin(), volume.end())));
  std::vector<bool> kept_root(n, false);
  for (std::size_t root = 0; root < n; ++root) {
    const double v = volume[root];
    kept_root[root] = v > 0.0 ? v >= limits.outward || root == largest
                              : limits.keep_cavities && -v >= limits.cavity;
  }
  std::vector<int> new_index(n, -1);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index f = 0; f < soup.faces.rows(); ++f) {
    if (!kept_root[static_cast<std::size_t>(find_root(parent, soup.faces(f, 0)))]) continue;
    kept.push_back(f);
    for (int k = 0; k < 3; ++k) new_index[static_cast<std::size_t>(soup.faces(f, k))] = 0;
  }
  int next = 0;
  for (auto& index : new_index) {
    if (index == 0) index = next++;
  }
  TriangleSoup out;
  out.positions.resize(next, 3);
  for (std::size_t v = 0; v < n; ++v) {
    if (new_index[v] >= 0)
      out.positions.row(new_index[v]) = soup.positions.row(static_cast<Eigen::Index>(v));
  }
  out.faces.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t f = 0; f < kept.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      out.faces(static_cast<Eigen::Index>(f), k) =
          new_index[static_cast<std::size_t>(soup.faces(kept[f], k))];
    }
  }
  return out;
}

void compensate_chord_gaps(Surface& surface, const Eigen::MatrixX3d& normals,
                           const Eigen::VectorXd& curvature);

/// Projects every vertex onto the exact surface and sets the exact outward normals. With
/// `compensate`, then moves each vertex along its normal by the mean gap between its flat
/// triangles and the curved surface, H * (a^2 + b^2 + c^2) / 24 averaged over its triangles
/// (the mean height of a sphere of mean curvature H over a chord triangle with sides a, b, c:
/// the circumcentre-centred cap height (rho^2 - t^2) / (2 / H) averaged over the triangle), so
/// that area and volume are unbiased instead of those of an inscribed polyhedron.
template <class Project>
void place_vertices(Surface& surface, const Project& project, bool compensate) {
  TriMesh& mesh = tri_mesh(surface);
  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  Eigen::MatrixX3d positions = surface.positions();
  Eigen::MatrixX3d normals(n, 3);
  Eigen::VectorXd curvature(n);
  tbb::parallel_for(Eigen::Index{0}, n, [&](Eigen::Index v) {
    Vec3 x = positions.row(v).transpose();
    Vec3 normal = Vec3::Zero();
    double h = 0.0;
    project(x, normal, h);
    positions.row(v) = x.transpose();
    normals.row(v) = normal.transpose();
    curvature(v) = h;
  });
  for (auto vh : mesh.vertices()) {
    const Eigen::Index v = vh.idx();
    mesh.set_point(vh, TriMesh::Point(positions(v, 0), positions(v, 1), positions(v, 2)));
  }
  if ((normals.rowwise().squaredNorm().array() == 0.0).any()) {
    // A vertex with no surface point within reach keeps its place and the mesh normal.
    surface.compute_normals();
    const Eigen::MatrixX3d mesh_normals = surface.normals();
    for (Eigen::Index v = 0; v < n; ++v) {
      if (normals.row(v).squaredNorm() == 0.0) normals.row(v) = mesh_normals.row(v);
    }
  }
  surface.set_normals(normals);
  if (compensate) compensate_chord_gaps(surface, normals, curvature);
}

/// Moves each vertex along its unit normal by the mean gap between its flat triangles and the
/// curved surface of mean curvature curvature(v), H * (a^2 + b^2 + c^2) / 24 averaged over
/// its triangles (see place_vertices).
void compensate_chord_gaps(Surface& surface, const Eigen::MatrixX3d& normals,
                           const Eigen::VectorXd& curvature) {
  TriMesh& mesh = tri_mesh(surface);
  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  Eigen::MatrixX3d positions = surface.positions();
  Eigen::VectorXd squared_edges = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd face_count = Eigen::VectorXd::Zero(n);
  for (auto f : mesh.faces()) {
    double sum = 0.0;
    for (auto h : mesh.fh_range(f)) sum += mesh.calc_edge_sqr_length(h);
    for (auto v : mesh.fv_range(f)) {
      squared_edges(v.idx()) += sum;
      face_count(v.idx()) += 1.0;
    }
  }
  for (auto vh : mesh.vertices()) {
    const Eigen::Index v = vh.idx();
    if (face_count(v) == 0.0 || normals.row(v).squaredNorm() == 0.0) continue;
    const double gap = curvature(v) * squared_edges(v) / face_count(v) / 24.0;
    positions.row(v) += gap * normals.row(v);
    mesh.set_point(vh, TriMesh::Point(positions(v, 0), positions(v, 1), positions(v, 2)));
  }
}

Vec3 to_vec(const TriMesh::Point& p) { return Vec3(p[0], p[1], p[2]); }
TriMesh::Point to_point(const Vec3& x) { return TriMesh::Point(x.x(), x.y(), x.z()); }

/// True when moving vertex v to p keeps every triangle around it (except those that also hold
/// `ignore`, which a collapse removes) turning the same way, with an area above `min_area`.
bool move_keeps_orientation(const TriMesh& mesh, TriMesh::VertexHandle v, const Vec3& p,
                            TriMesh::VertexHandle ignore, double min_area) {
  for (auto h : mesh.voh_range(v)) {
    if (mesh.is_boundary(h)) return false;
    const auto b = mesh.to_vertex_handle(h);
    const auto c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
    if (b == ignore || c == ignore) continue;
    const Vec3 pb = to_vec(mesh.point(b));
    const Vec3 pc = to_vec(mesh.point(c));
    const Vec3 before = (pb - to_vec(mesh.point(v))).cross(pc - to_vec(mesh.point(v)));
    const Vec3 after = (pb - p).cross(pc - p);
    if (0.5 * after.norm() <= min_area || after.dot(before) <= 0.0) return false;
  }
  return true;
}

/// Projects every vertex onto its nearest point of the SAS and makes the mesh follow the
/// creases, the concave circle arcs where two spheres meet, which chord triangles would
/// otherwise cut across (losing area): every edge whose ends lie on no common sphere is split
/// at the exact crease point nearest its midpoint, or its nearer end is moved there when that
/// is close (crease_rounds passes); short edges left by the splits are then collapsed onto
/// the crease vertices. Sets the exact normals (the mean of the spheres' at a crease) and, with
/// `compensate`, moves the vertices on one sphere by the chord gap (crease vertices stay on
/// their crease). Sequential after the parallel projection: deterministic.
void place_sas_vertices(Surface& surface, const SasGeometry& sas, double reach, double edge_length,
                        bool compensate) {
  TriMesh& mesh = tri_mesh(surface);
  const Spheres none{-1, -1, -1};
  OpenMesh::VPropHandleT<Spheres> label;
  mesh.add_property(label);
  {
    const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
    Eigen::MatrixX3d positions = surface.positions();
    std::vector<Spheres> on(static_cast<std::size_t>(n));
    tbb::parallel_for(Eigen::Index{0}, n, [&](Eigen::Index v) {
      Vec3 x = positions.row(v).transpose();
      on[static_cast<std::size_t>(v)] = sas.nearest_sas_point(x, reach);
      positions.row(v) = x.transpose();
    });
    for (auto v : mesh.vertices()) {
      mesh.set_point(v, to_point(positions.row(v.idx()).transpose()));
      mesh.property(label, v) = on[static_cast<std::size_t>(v.idx())];
    }
  }
  const double min_area = crease_min_area * edge_length * edge_length;
  for (int round = 0; round < crease_rounds; ++round) {
    std::vector<TriMesh::EdgeHandle> crossing;
    for (auto e : mesh.edges()) {
      const Spheres& a = mesh.property(label, mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)));
      const Spheres& b = mesh.property(label, mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)));
      if (a != none && b != none && !share_sphere(a, b)) crossing.push_back(e);
    }
    if (crossing.empty()) break;
    for (const auto e : crossing) {
      const auto va = mesh.from_vertex_handle(mesh.halfedge_handle(e, 0));
      const auto vb = mesh.to_vertex_handle(mesh.halfedge_handle(e, 0));
      const Spheres a = mesh.property(label, va);
      const Spheres b = mesh.property(label, vb);
      if (share_sphere(a, b)) continue;  // an earlier move fixed it
      const Vec3 pa = to_vec(mesh.point(va));
      const Vec3 pb = to_vec(mesh.point(vb));
      const Vec3 middle = 0.5 * (pa + pb);
      const double length = (pb - pa).norm();
      // The nearest crease point or vertex of a sphere of a with a sphere of b.
      Vec3 point = middle;
      Spheres spheres = none;
      double best = length;
      const auto consider = [&](const Vec3& p, const Spheres& s) {
        const double d = (p - middle).norm();
        if (d < best) {
          best = d;
          point = p;
          spheres = s;
        }
      };
      std::vector<int> all;
      for (const int x : a) {
        if (x < 0) continue;
        all.push_back(x);
        for (const int y : b) {
          Vec3 p;
          if (y >= 0 && sas.crease_point(x, y, middle, p)) consider(p, sorted_spheres(x, y));
        }
      }
      for (const int y : b) {
        if (y >= 0) all.push_back(y);
      }
      for (std::size_t i = 0; i < all.size(); ++i) {
        for (std::size_t j = i + 1; j < all.size(); ++j) {
          for (std::size_t k = j + 1; k < all.size(); ++k) {
            const Spheres s = sorted_spheres(all[i], all[j], all[k]);
            Vec3 p;
            if (sas.vertex_point(s, middle, best, p)) consider(p, s);
          }
        }
      }
      if (spheres == none) {
        // No crease of these spheres nearby: a third sphere lies between; split at the
        // surface point nearest the midpoint, a later round finds the creases on each side.
        spheres = sas.nearest_sas_point(point, reach);
        if (spheres == none) continue;
      }
      const double da = (point - pa).norm();
      const double db = (point - pb).norm();
      const auto nearer = da <= db ? va : vb;
      if (std::min(da, db) < snap_fraction * edge_length &&
          move_keeps_orientation(mesh, nearer, point, TriMesh::VertexHandle(), min_area)) {
        mesh.set_point(nearer, to_point(point));
        mesh.property(label, nearer) = spheres;
        continue;
      }
      if (std::min(da, db) < snap_fraction * edge_length) continue;
      const auto v = mesh.split(e, to_point(point));
      mesh.property(label, v) = spheres;
    }
  }
  // Collapse the short edges the splits left, keeping the vertex on more spheres; a collapse
  // can shorten edges already visited, so pass again while any changes.
  const double shortest = collapse_fraction * edge_length;
  for (int pass = 0; pass < collapse_passes; ++pass) {
    bool changed = false;
    for (auto e : mesh.edges()) {
      if (mesh.status(e).deleted()) continue;
      const double length = mesh.calc_edge_length(e);
      if (length >= shortest) continue;
      auto h = mesh.halfedge_handle(e, 0);
      const Spheres& a = mesh.property(label, mesh.from_vertex_handle(h));
      const Spheres& b = mesh.property(label, mesh.to_vertex_handle(h));
      if (a == none || b == none) continue;
      if (sphere_count(a) > sphere_count(b)) {
        h = mesh.opposite_halfedge_handle(h);
      } else if (sphere_count(a) == sphere_count(b) && a != b) {
        continue;
      }
      const auto removed = mesh.from_vertex_handle(h);
      const auto kept = mesh.to_vertex_handle(h);
      if (!mesh.is_collapse_ok(h)) continue;
      bool compatible = true;
      for (auto w : mesh.vv_range(removed)) {
        if (!share_sphere(mesh.property(label, w), mesh.property(label, kept))) compatible = false;
      }
      // Coincident ends (two vertices projected onto one SAS vertex) collapse unconditionally.
      if (length > 0.0 &&
          (!compatible ||
           !move_keeps_orientation(mesh, removed, to_vec(mesh.point(kept)), kept, min_area))) {
        continue;
      }
      mesh.collapse(h);
      changed = true;
    }
    if (!changed) break;
  }
  mesh.garbage_collection();

  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  Eigen::MatrixX3d normals = Eigen::MatrixX3d::Zero(n, 3);
  Eigen::VectorXd curvature = Eigen::VectorXd::Zero(n);
  for (auto v : mesh.vertices()) {
    const Spheres& s = mesh.property(label, v);
    const Vec3 p = to_vec(mesh.point(v));
    Vec3 sum = Vec3::Zero();
    for (const int i : s) {
      if (i >= 0) sum += (p - sas.center(i)).normalized();
    }
    if (sum.squaredNorm() > 0.0) normals.row(v.idx()) = sum.normalized().transpose();
    if (sphere_count(s) == 1) curvature(v.idx()) = 1.0 / sas.radius(s[0]);
  }
  mesh.remove_property(label);
  if ((normals.rowwise().squaredNorm().array() == 0.0).any()) {
    surface.compute_normals();
    const Eigen::MatrixX3d mesh_normals = surface.normals();
    for (Eigen::Index v = 0; v < n; ++v) {
      if (normals.row(v).squaredNorm() == 0.0) normals.row(v) = mesh_normals.row(v);
    }
  }
  surface.set_normals(normals);
  if (compensate) compensate_chord_gaps(surface, normals, curvature);
}

void validate(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
              const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options,
              const std::string& what) {
  if (centers.rows() == 0) throw InputError(what + ": no atoms; expected at least one");
  if (centers.rows() != radii.size()) {
    throw InputError(what + ": " + std::to_string(centers.rows()) + " centres but " +
                     std::to_string(radii.size()) + " radii; expected one radius per centre");
  }
  for (Eigen::Index i = 0; i < centers.rows(); ++i) {
    if (!centers.row(i).allFinite()) {
      throw InputError(what + ": atom " + std::to_string(i) +
                       " has a non-finite centre; expected finite coordinates");
    }
    if (!std::isfinite(radii(i)) || radii(i) <= 0.0) {
      throw InputError(what + ": atom " + std::to_string(i) + " has radius " +
                       std::to_string(radii(i)) + "; expected a finite radius > 0 A");
    }
  }
  if (!std::isfinite(options.probe_radius) || options.probe_radius < 0.0) {
    throw OptionError(what + ": probe radius " + std::to_string(options.probe_radius) +
                      " A; expected a finite value >= 0");
  }
  if (!(options.min_component_volume_fraction >= 0.0 &&
        options.min_component_volume_fraction <= 1.0)) {
    throw OptionError(what + ": min_component_volume_fraction " +
                      std::to_string(options.min_component_volume_fraction) +
                      "; expected a value in [0, 1]");
  }
  if (!std::isfinite(options.voxel_size) || options.voxel_size < 0.0) {
    throw OptionError(what + ": voxel size " + std::to_string(options.voxel_size) +
                      " A; expected a finite value > 0, or 0 for automatic");
  }
}

/// options.voxel_size, or the automatic choice documented in SesOptions.
double choose_voxel_size(const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options,
                         double edge_length, const std::string& what) {
  const double smallest = radii.minCoeff();
  if (options.voxel_size == 0.0) {
    return std::min(auto_voxel_per_edge * edge_length, smallest / min_atom_voxels);
  }
  if (smallest < min_atom_voxels * options.voxel_size) {
    throw OptionError(what + ": voxel size " + std::to_string(options.voxel_size) +
                      " A is too coarse for the smallest atom (radius " + std::to_string(smallest) +
                      " A); expected at most " + std::to_string(smallest / min_atom_voxels) + " A");
  }
  return options.voxel_size;
}

Surface build_surface(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                      const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options,
                      bool excluded, const std::string& what) {
  validate(centers, radii, options, what);
  const double edge_length = edge_length_for_density(options.vertex_density);
  const double voxel = choose_voxel_size(radii, options, edge_length, what);
  const SasGeometry sas(centers, radii, options.probe_radius);

  // Both surfaces lie inside the spheres R_i (SAS on them), the band a little beyond.
  const double reach = radii.maxCoeff() + options.probe_radius + 2.0 * voxel;
  const openvdb::FloatGrid::Ptr grid = excluded ? sample_band(SesField{sas}, centers, reach, voxel)
                                                : sample_band(SasField{sas}, centers, reach, voxel);
  TriangleSoup soup = extract_isosurface(*grid);
  // A component holding an atom holds its whole van der Waals ball, and a cavity the probe's.
  const double fraction = options.min_component_volume_fraction;
  ComponentVolumes limits;
  limits.outward = fraction * 4.0 / 3.0 * M_PI * std::pow(radii.minCoeff(), 3);
  limits.cavity = fraction * 4.0 / 3.0 * M_PI * std::pow(options.probe_radius, 3);
  limits.keep_cavities = options.keep_cavities;
  soup = kept_components(soup, limits);
  if (soup.faces.rows() == 0) {
    throw TopologyError(what + ": the isosurface is empty at voxel size " + std::to_string(voxel) +
                        " A");
  }
  Surface surface = Surface::from_arrays(soup.positions, soup.faces, what);
  if (options.remesh) surface = isotropic_remesh(surface, edge_length, remesh_iterations, false);
  // Grid and remeshed vertices lie within a voxel of the surface; search a little wider.
  const double projection_reach = reach_voxels * voxel;
  if (excluded) {
    place_vertices(
        surface,
        [&](Vec3& x, Vec3& n, double& h) { sas.project_to_ses(x, projection_reach, n, h); },
        options.compensate_chords);
  } else {
    place_sas_vertices(surface, sas, projection_reach, edge_length, options.compensate_chords);
  }
  require_closed_manifold(surface);
  return surface;
}

}  // namespace

Surface build_ses(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                  const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options) {
  return build_surface(centers, radii, options, true, "<ses>");
}

Surface build_sas(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                  const Eigen::Ref<const Eigen::VectorXd>& radii, const SesOptions& options) {
  return build_surface(centers, radii, options, false, "<sas>");
}

}  // namespace surfcomp::mesh
