#include "sas_geometry.hpp"

#include <cmath>
#include <tuple>

namespace surfcomp::molsurf::detail {
namespace {

/// Projections of a vertex onto the exact surface (the nearest feature can change once).
constexpr int projection_rounds = 3;
/// A projection has converged when it moves a vertex less than this, A.
constexpr double convergence = 1e-12;
/// Marks "not a candidate" in the per-thread gap table.
constexpr double limit_none = std::numeric_limits<double>::infinity();
/// Tolerance for "a point on sphere i lies inside sphere j", A.
constexpr double burial_tolerance = 1e-9;
/// Cell size of the sphere and vertex grids, A.
constexpr double sphere_cell = 1.5;

/// `points` as the 3 by #P matrix SpatialGrid takes (a view, no copy).
Eigen::Map<const Eigen::Matrix3Xd> columns(const std::vector<Vec3>& points) {
  return {points.empty() ? nullptr : points.front().data(), 3,
          static_cast<Eigen::Index>(points.size())};
}

}  // namespace

SasGeometry::SasGeometry(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                         const Eigen::Ref<const Eigen::VectorXd>& radii, double probe)
    : probe_(probe) {
  for (Eigen::Index i = 0; i < centers.rows(); ++i) {
    centers_.emplace_back(centers.row(i).transpose());
    big_.push_back(radii(i) + probe);
    atom_.push_back(radii(i));
  }
  max_big_ = *std::max_element(big_.begin(), big_.end());
  spheres_ = mesh::SpatialGrid(columns(centers_), sphere_cell);
  find_neighbours();
  find_circles();
}

double SasGeometry::union_value(const Vec3& x, double limit) const {
  // The spheres gather() would keep are those with a value below `limit`; the others cannot
  // lower the minimum, so the spheres near x are taken as they come.
  double best = limit;
  spheres_.for_each_near(x, max_big_ + limit, [&](int i) {
    const double v = (x - center(i)).norm() - radius(i);
    if (v < best) best = v;
  });
  return best;
}

NearestPoint SasGeometry::nearest_boundary_point(const Vec3& x, double limit,
                                                 const Candidates& candidates) const {
  NearestPoint best;
  best.distance = limit;
  thread_local std::vector<std::pair<double, int>> near;
  thread_local std::vector<double> gap_of;
  thread_local std::vector<std::pair<double, int>> arcs;  ///< distance, discovery order
  thread_local std::vector<int> arc_circles;              ///< circle of each arc found
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
    if (!buried(p, i)) {
      best = NearestPoint{gap, p, Feature::sphere, i};
      break;
    }
  }
  // The nearest SAS vertex: the first of the nearest candidates, which wins if it is nearer
  // than the sphere point and than every exposed circle point (a circle point at the same
  // distance comes first).
  int vertex = -1;
  double vertex_distance = std::numeric_limits<double>::infinity();
  for (const int v : candidates.vertices) {
    const double distance = (x - vertices_[static_cast<std::size_t>(v)]).norm();
    if (distance < vertex_distance) {
      vertex_distance = distance;
      vertex = v;
    }
  }
  // Circles can win only within the sphere point's distance (strictly) and the vertex's (ties
  // go to the circle). Each is reached once, from the sphere with the smaller gap, a lower bound
  // of the distance to every point on that sphere; those within reach are tried by increasing
  // distance (ties in the order they were found), and the first whose nearest point lies on an
  // exposed arc is the nearest circle point.
  const auto within_reach = [&](double d) { return d < best.distance && d <= vertex_distance; };
  arcs.clear();
  arc_circles.clear();
  for (const auto& [gap, i] : near) {
    if (!within_reach(gap)) break;
    for (const int c : circles_of_[static_cast<std::size_t>(i)]) {
      const Circle& circle = circles_[static_cast<std::size_t>(c)];
      const int other = circle.i == i ? circle.j : circle.i;
      const double other_gap = gap_of[static_cast<std::size_t>(other)];
      if (!within_reach(other_gap) || other_gap < gap || (other_gap == gap && other < i)) continue;
      const Vec3 v = x - circle.center;
      const double along = v.dot(circle.normal);
      const double off = (v - along * circle.normal).norm() - circle.radius;
      // Lengths of a few A: the square root needs no guard against overflow (hypot's).
      const double distance = std::sqrt(along * along + off * off);
      if (!within_reach(distance)) continue;
      arcs.emplace_back(distance, static_cast<int>(arc_circles.size()));
      arc_circles.push_back(c);
    }
  }
  for (const auto& entry : near) gap_of[static_cast<std::size_t>(entry.second)] = limit_none;
  std::sort(arcs.begin(), arcs.end());
  for (const auto& [distance, found] : arcs) {
    const int c = arc_circles[static_cast<std::size_t>(found)];
    const Circle& circle = circles_[static_cast<std::size_t>(c)];
    const Vec3 v = x - circle.center;
    const Vec3 radial = v - v.dot(circle.normal) * circle.normal;
    const double a = radial.dot(circle.u), b = radial.dot(circle.w);
    const bool on_axis = !(radial.norm() > 0.0);  // every point of the circle is as near
    if (on_axis ? circle.exposed_at(0.0) : circle.exposed_towards(a, b)) {
      double angle = on_axis ? 0.0 : std::atan2(b, a);
      if (angle < 0.0) angle += 2.0 * M_PI;
      const Vec3 p =
          circle.center + circle.radius * (std::cos(angle) * circle.u + std::sin(angle) * circle.w);
      return NearestPoint{distance, p, Feature::circle, c};
    }
  }
  if (vertex >= 0 && vertex_distance < best.distance) {
    best = NearestPoint{vertex_distance, vertices_[static_cast<std::size_t>(vertex)],
                        Feature::vertex, vertex};
  }
  return best;
}

void SasGeometry::project_to_ses(Vec3& x, double reach, Vec3& normal,
                                 double& mean_curvature) const {
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

Spheres SasGeometry::nearest_sas_point(Vec3& x, double reach) const {
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

bool SasGeometry::crease_point(int i, int j, const Vec3& near, Vec3& out) const {
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

bool SasGeometry::vertex_point(const Spheres& s, const Vec3& near, double limit, Vec3& out) const {
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

void SasGeometry::project_to_sas(Vec3& x, double reach, Vec3& normal,
                                 double& mean_curvature) const {
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

bool SasGeometry::buried(const Vec3& p, int i) const {
  const auto first = static_cast<std::size_t>(burial_offsets_[static_cast<std::size_t>(i)]);
  const auto last = static_cast<std::size_t>(burial_offsets_[static_cast<std::size_t>(i) + 1]);
  for (std::size_t k = first; k < last; ++k) {
    const Burial& b = burials_[k];
    const double dx = p.x() - b.center[0], dy = p.y() - b.center[1], dz = p.z() - b.center[2];
    if (dx * dx + dy * dy + dz * dz < b.squared_radius) return true;
  }
  return false;
}

void SasGeometry::find_neighbours() {
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
  burial_offsets_.assign(1, 0);
  for (std::size_t i = 0; i < centers_.size(); ++i) {
    for (const int j : neighbours_[i]) {
      const double r = radius(j) - burial_tolerance;
      burials_.push_back(Burial{{center(j).x(), center(j).y(), center(j).z()}, r * r});
    }
    burial_offsets_.push_back(static_cast<int>(burials_.size()));
  }
}

void SasGeometry::find_circles() {
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
      add_pieces(circle);
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
  vertex_index_ = mesh::SpatialGrid(columns(vertices_), sphere_cell);
}

void SasGeometry::add_pieces(Circle& circle) {
  for (const auto& [start, end] : circle.exposed) {
    const int count = std::max(1, static_cast<int>(std::ceil((end - start) / (0.5 * M_PI))));
    double from_u = std::cos(start), from_w = std::sin(start);
    for (int k = 1; k <= count; ++k) {
      const double angle = k == count ? end : start + (end - start) * k / count;
      const double to_u = std::cos(angle), to_w = std::sin(angle);
      circle.pieces.push_back(Circle::Piece{from_u, from_w, to_u, to_w});
      from_u = to_u;
      from_w = to_w;
    }
  }
}

void SasGeometry::add_arc_end(const Circle& circle, double angle, int k) {
  if (angle <= 0.0 || angle >= 2.0 * M_PI) return;
  vertices_.push_back(circle.center +
                      circle.radius * (std::cos(angle) * circle.u + std::sin(angle) * circle.w));
  vertex_spheres_.push_back(sorted_spheres(circle.i, circle.j, k));
}

double SasGeometry::curvature_at(const Vec3& x, const Vec3& normal, const NearestPoint& q) const {
  // With a zero probe the re-entrant patches shrink to the creases and corners of the van der
  // Waals surface, where the curvature is concentrated (unbounded): like the SAS's crease
  // vertices, they get 0 and so no chord compensation.
  if (probe_ == 0.0 && q.feature != Feature::sphere) return 0.0;
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
}  // namespace surfcomp::molsurf::detail
