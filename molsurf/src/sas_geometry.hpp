// Internal to the molsurf module (not installed): the union of the atoms' probe-inflated spheres
// (the SAS region) and the exact distance to its boundary, from which build_ses and build_sas
// sample their fields and onto which they project their vertices.
#pragma once

#include "surfcomp/mesh/spatial_grid.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace surfcomp::molsurf::detail {

using Vec3 = Eigen::Vector3d;

/// The spheres a point of the SAS lies on: one on a sphere patch, two on a crease (the circle
/// where they meet), three at a vertex; ascending, unused slots -1 at the end.
using Spheres = std::array<int, 3>;

inline Spheres sorted_spheres(int a, int b = -1, int c = -1) {
  Spheres s{a, b, c};
  std::sort(s.begin(), s.end(), [](int x, int y) { return y < 0 || (x >= 0 && x < y); });
  return s;
}

inline int sphere_count(const Spheres& s) {
  return static_cast<int>(std::count_if(s.begin(), s.end(), [](int x) { return x >= 0; }));
}

/// True when points labelled a and b lie on a common sphere (no crease between them).
inline bool share_sphere(const Spheres& a, const Spheres& b) {
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
/// on the boundary of U, touches but does not enter the atoms. Lengths in A. Const member
/// functions may run from any number of threads.
class SasGeometry {
 public:
  /// `centers` #A by 3, `radii` #A van der Waals radii (validated by the caller: at least one
  /// atom, finite, radii > 0, probe >= 0).
  SasGeometry(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
              const Eigen::Ref<const Eigen::VectorXd>& radii, double probe);

  double probe() const { return probe_; }
  double radius(int i) const { return big_[static_cast<std::size_t>(i)]; }
  double atom_radius(int i) const { return atom_[static_cast<std::size_t>(i)]; }
  const Vec3& center(int i) const { return centers_[static_cast<std::size_t>(i)]; }

  /// The spheres and vertices that can matter within `radius` of `centre` when features are
  /// searched up to `limit`: spheres with |x - c_i| - R_i < limit somewhere in the ball
  /// and vertices within limit + radius, in SpatialGrid order.
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
  /// The same over the spheres gathered around x.
  double union_value(const Vec3& x, double limit) const;

  /// The nearest point of the boundary of U to x (inside U), searched up to `limit` among the
  /// candidates; feature none and distance `limit` when it is farther. Spheres are visited by
  /// increasing gap |R_i - |x - c_i||, a lower bound of the distance to every feature on them.
  NearestPoint nearest_boundary_point(const Vec3& x, double limit,
                                      const Candidates& candidates) const;

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
  void project_to_ses(Vec3& x, double reach, Vec3& normal, double& mean_curvature) const;

  /// Moves x, which lies within `reach` of the SAS, onto its nearest point of the SAS: the
  /// nearest sphere from outside U; from inside, the nearest sphere patch, crease or vertex.
  /// Returns the spheres the point lies on (all -1, x unchanged, if none is within reach).
  Spheres nearest_sas_point(Vec3& x, double reach) const;

  /// The point of the exposed crease between spheres i and j (an arc of their circle) nearest
  /// to `near`, if the circle exists and is exposed there.
  bool crease_point(int i, int j, const Vec3& near, Vec3& out) const;

  /// The SAS vertex of spheres s nearest to `near`, if one exists within `limit` of it.
  bool vertex_point(const Spheres& s, const Vec3& near, double limit, Vec3& out) const;

  /// Moves x, which lies within `reach` of the SAS, onto it; returns the outward unit normal
  /// and the mean curvature there (unchanged if no surface is within reach).
  void project_to_sas(Vec3& x, double reach, Vec3& normal, double& mean_curvature) const;

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

    /// The exposed intervals cut into pieces of at most a quarter turn, each by the directions
    /// (cos, sin) of its ends in the (u, w) plane; one piece's end is the next one's start.
    struct Piece {
      double start_u, start_w, end_u, end_w;
    };
    std::vector<Piece> pieces;

    bool exposed_at(double angle) const {
      for (const auto& [start, end] : exposed) {
        if (angle >= start && angle <= end) return true;
      }
      return false;
    }

    /// exposed_at for the angle of the in-plane direction a u + b w ((a, b) != 0), decided by
    /// cross products with the pieces' ends instead of the angle: the same answer but within
    /// rounding of an interval's end, without an arctangent.
    bool exposed_towards(double a, double b) const {
      for (const Piece& p : pieces) {
        if (p.start_u * b - p.start_w * a >= 0.0 && a * p.end_w - b * p.end_u >= 0.0 &&
            a * (p.start_u + p.end_u) + b * (p.start_w + p.end_w) > 0.0) {
          return true;
        }
      }
      return false;
    }
  };

  /// True when a neighbour of sphere i buries p: |p - c_k| < R_k - burial tolerance.
  bool buried(const Vec3& p, int i) const;
  void find_neighbours();
  /// Finds every circle where two spheres meet and its exposed arcs; keeps the circles with an
  /// exposed arc, their arc ends (the SAS vertices) and which spheres keep exposed area.
  void find_circles();
  /// Fills circle.pieces from circle.exposed.
  static void add_pieces(Circle& circle);
  /// Records the SAS vertex at `angle` on `circle` (an end of a buried arc; 0 and 2 pi are
  /// where the angle wraps, not vertices).
  void add_arc_end(const Circle& circle, double angle, int k);
  /// Mean curvature of the SES at x (positive where convex) given its nearest SAS feature q.
  double curvature_at(const Vec3& x, const Vec3& normal, const NearestPoint& q) const;

  double probe_;
  std::vector<Vec3> centers_;
  std::vector<double> big_;
  std::vector<double> atom_;
  double max_big_ = 0.0;
  mesh::SpatialGrid spheres_;  ///< the centres, binned (reach 0)
  std::vector<std::vector<int>> neighbours_;
  /// A neighbour's centre and squared burial radius (R_k - burial tolerance)^2, packed so that
  /// the burial test of a sphere reads one contiguous run.
  struct Burial {
    std::array<double, 3> center;
    double squared_radius;
  };
  std::vector<Burial> burials_;      ///< the neighbours of sphere i, each as a Burial
  std::vector<int> burial_offsets_;  ///< sphere i's run: burials_[offsets[i] .. offsets[i + 1])
  std::vector<Circle> circles_;
  std::vector<std::vector<int>> circles_of_;
  std::vector<bool> exposed_sphere_;
  std::vector<Vec3> vertices_;
  std::vector<Spheres> vertex_spheres_;  ///< the three spheres meeting at each vertex
  mesh::SpatialGrid vertex_index_;       ///< the vertices, binned (reach 0)
};

}  // namespace surfcomp::molsurf::detail
