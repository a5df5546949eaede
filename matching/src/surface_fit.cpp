#include "surfcomp/matching/surface_fit.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/spatial_grid.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace surfcomp::matching {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 to_cgal(const Eigen::Vector3d& x) { return {x.x(), x.y(), x.z()}; }
Eigen::Vector3d to_eigen(const Kernel::Point_3& p) { return {p.x(), p.y(), p.z()}; }

/// The longest edge, against the mean, up to which `Side::within` tests the corners first.
constexpr double kCornerTestEdgeRatio = 4.0;

/// One surface as the fit measures it: its kept triangles, indexed, and the vertices it is
/// measured at.
struct Side {
  Triangles triangles;
  std::vector<Eigen::Vector3d> unit_normals;  ///< of the triangles, by the faces' orientation
  /// The unit vertex normals at each triangle's corners, for a normal that varies smoothly
  /// over the surface (closest points often fall on an edge or a corner, which two or more
  /// triangles share).
  std::vector<Eigen::Matrix3d> corner_normals;
  Tree tree;
  /// The kept triangles' corners, gridded (none when an edge is far longer than the mean), and
  /// the longest edge: a first answer to `within`.
  Eigen::Matrix3Xd corner_points;
  mesh::SpatialGrid corner_grid;
  double longest_edge = 0.0;
  bool corner_test = false;
  Eigen::Matrix3Xd points;   ///< the measured vertices
  Eigen::Matrix3Xd normals;  ///< their unit normals
  Eigen::VectorXd weights;   ///< their barycentric areas
  double area = 0.0;         ///< of the kept triangles

  Side(const mesh::Surface& surface, const std::vector<bool>* mask, std::size_t max_points) {
    const auto n = surface.n_vertices();
    if (mask && mask->size() != n) {
      throw InputError(surface.source() + ": surface fit: the vertex mask has " +
                       std::to_string(mask->size()) + " flags for " + std::to_string(n) +
                       " vertices");
    }
    const auto kept = [&](int v) { return !mask || (*mask)[static_cast<std::size_t>(v)]; };
    std::vector<int> corner_vertices;
    double edge_sum = 0.0;
    const Eigen::MatrixX3d positions = surface.positions();
    const Eigen::MatrixX3i faces = surface.faces();
    mesh::Surface with_normals = surface;
    if (!with_normals.has_normals()) with_normals.compute_normals();
    const Eigen::MatrixX3d vertex_normals = with_normals.normals();
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      if (!kept(faces(f, 0)) || !kept(faces(f, 1)) || !kept(faces(f, 2))) continue;
      const Eigen::Vector3d a = positions.row(faces(f, 0)).transpose();
      const Eigen::Vector3d b = positions.row(faces(f, 1)).transpose();
      const Eigen::Vector3d c = positions.row(faces(f, 2)).transpose();
      const Eigen::Vector3d cross = (b - a).cross(c - a);
      const double norm = cross.norm();
      if (!(norm > 0.0)) continue;  // a degenerate triangle has no plane to measure to
      triangles.emplace_back(to_cgal(a), to_cgal(b), to_cgal(c));
      for (int k = 0; k < 3; ++k) corner_vertices.push_back(faces(f, k));
      longest_edge = std::max({longest_edge, (b - a).norm(), (c - b).norm(), (a - c).norm()});
      edge_sum += (b - a).norm() + (c - b).norm() + (a - c).norm();
      unit_normals.push_back(cross / norm);
      Eigen::Matrix3d corners;
      for (int k = 0; k < 3; ++k) corners.col(k) = vertex_normals.row(faces(f, k)).transpose();
      corner_normals.push_back(corners);
      area += 0.5 * norm;
    }
    if (triangles.empty()) {
      throw InputError(surface.source() + ": surface fit: no triangle of positive area" +
                       (mask ? " within the compared part" : ""));
    }
    std::sort(corner_vertices.begin(), corner_vertices.end());
    corner_vertices.erase(std::unique(corner_vertices.begin(), corner_vertices.end()),
                          corner_vertices.end());
    corner_points.resize(3, static_cast<Eigen::Index>(corner_vertices.size()));
    for (std::size_t k = 0; k < corner_vertices.size(); ++k)
      corner_points.col(static_cast<Eigen::Index>(k)) =
          positions.row(corner_vertices[k]).transpose();
    // A mesh with an edge far longer than most would make a corner search visit most corners:
    // the tree alone answers there.
    const double mean_edge = edge_sum / (3.0 * static_cast<double>(triangles.size()));
    corner_test = longest_edge <= kCornerTestEdgeRatio * mean_edge;
    if (corner_test) corner_grid = mesh::SpatialGrid(corner_points, longest_edge);
    tree.insert(triangles.begin(), triangles.end());
    tree.build();
    tree.accelerate_distance_queries();
    (void)tree.squared_distance(triangles.front()[0]);  // builds the search tree before threads

    const Eigen::VectorXd areas = mesh::vertex_areas(surface);
    std::vector<int> vertices;
    for (int v = 0; v < static_cast<int>(n); ++v) {
      if (kept(v) && areas(v) > 0.0) vertices.push_back(v);
    }
    const std::size_t stride = std::max<std::size_t>(
        1, (vertices.size() + max_points - 1) / std::max<std::size_t>(1, max_points));
    const auto count = static_cast<Eigen::Index>((vertices.size() + stride - 1) / stride);
    points.resize(3, count);
    normals.resize(3, count);
    weights.resize(count);
    for (Eigen::Index k = 0; k < count; ++k) {
      const int v = vertices[static_cast<std::size_t>(k) * stride];
      points.col(k) = positions.row(v).transpose();
      normals.col(k) = vertex_normals.row(v).transpose();
      weights(k) = areas(v);
    }
  }

  /// Whether a triangle lies within `distance` of x. The corners answer first: one within
  /// `distance` is a point of the surface that near; with none within distance + the longest
  /// edge, no triangle is that near (a triangle's points lie within its longest edge of each of
  /// its corners). Between the two, the tree's search starts from a made-up closest point just
  /// beyond `distance` (its hint), so that it descends only into boxes nearer than that.
  bool within(const Eigen::Vector3d& x, double distance) const {
    const double squared = distance * distance;
    const double reach = (distance + longest_edge) * (1.0 + 1e-9);  // rounding kept inside
    if (corner_test) {
      bool corner_within = false, corner_in_reach = false;
      corner_grid.for_each_near(x, reach, [&](int k) {
        const double d2 = (corner_points.col(k) - x).squaredNorm();
        corner_within = corner_within || d2 <= squared;
        corner_in_reach = corner_in_reach || d2 <= reach * reach;
      });
      if (corner_within) return true;
      if (!corner_in_reach) return false;
    }
    const Kernel::Point_3 hint = to_cgal(x + Eigen::Vector3d(distance * (1.0 + 1e-9), 0.0, 0.0));
    return tree.squared_distance(to_cgal(x), hint) <= squared;
  }

  /// The unit normal at `q`, a point of triangle `face`: its corners' vertex normals
  /// interpolated barycentrically, or the triangle's own where they cancel.
  Eigen::Vector3d normal_at(std::size_t face, const Eigen::Vector3d& q) const {
    const Kernel::Triangle_3& t = triangles[face];
    const Eigen::Vector3d a = to_eigen(t[0]), b = to_eigen(t[1]), c = to_eigen(t[2]);
    const Eigen::Vector3d& n = unit_normals[face];
    const double total = (b - a).cross(c - a).dot(n);
    const Eigen::Vector3d barycentric((b - q).cross(c - q).dot(n) / total,
                                      (c - q).cross(a - q).dot(n) / total,
                                      (a - q).cross(b - q).dot(n) / total);
    const Eigen::Vector3d blended = corner_normals[face] * barycentric;
    const double length = blended.norm();
    return length > 1e-12 ? Eigen::Vector3d(blended / length) : n;
  }

  /// The fraction of the measured weight whose points, moved by `transform`, lie within
  /// `distance` of `other`'s triangles.
  double covered_by(const Side& other, const RigidTransform& transform, double distance) const {
    double covered = 0.0;
    for (Eigen::Index k = 0; k < points.cols(); ++k) {
      const Eigen::Vector3d x = transform.rotation * points.col(k) + transform.translation;
      if (other.within(x, distance)) covered += weights(k);
    }
    return covered / weights.sum();
  }
};

}  // namespace

struct SurfaceFit::Impl {
  Side reference, probe;
  Impl(const mesh::Surface& ref, const mesh::Surface& prb, const std::vector<bool>* ref_mask,
       const std::vector<bool>* prb_mask, std::size_t max_points)
      : reference(ref, ref_mask, max_points), probe(prb, prb_mask, max_points) {}
};

SurfaceFit::SurfaceFit(const mesh::Surface& reference, const mesh::Surface& probe,
                       const std::vector<bool>* reference_mask, const std::vector<bool>* probe_mask,
                       std::size_t max_points)
    : impl_(
          std::make_unique<const Impl>(reference, probe, reference_mask, probe_mask, max_points)) {}
SurfaceFit::SurfaceFit(SurfaceFit&&) noexcept = default;
SurfaceFit& SurfaceFit::operator=(SurfaceFit&&) noexcept = default;
SurfaceFit::~SurfaceFit() = default;

double SurfaceFit::reference_area() const { return impl_->reference.area; }
double SurfaceFit::probe_area() const { return impl_->probe.area; }

CoverageScore SurfaceFit::coverage(const RigidTransform& transform, double distance) const {
  if (!(std::isfinite(distance) && distance > 0.0)) {
    throw OptionError("coverage distance " + std::to_string(distance) +
                      ": expected a finite distance > 0");
  }
  CoverageScore out;
  out.probe = impl_->probe.covered_by(impl_->reference, transform, distance);
  out.reference = impl_->reference.covered_by(impl_->probe, transform.inverse(), distance);
  out.score = std::max(out.probe, out.reference);
  return out;
}

RigidTransform SurfaceFit::icp(const RigidTransform& start, const IcpOptions& options) const {
  if (!(std::isfinite(options.max_distance) && options.max_distance > 0.0)) {
    throw OptionError("ICP max distance " + std::to_string(options.max_distance) +
                      ": expected a finite distance > 0");
  }
  if (options.iterations < 1)
    throw OptionError("ICP iterations " + std::to_string(options.iterations) + ": expected >= 1");
  if (!(std::isfinite(options.tolerance) && options.tolerance >= 0.0)) {
    throw OptionError("ICP tolerance " + std::to_string(options.tolerance) +
                      ": expected a finite value >= 0");
  }
  const Side& probe = impl_->probe;
  const Side& reference = impl_->reference;
  const double limit = options.max_distance * options.max_distance;
  const double reach = options.max_distance * (1.0 + 1e-9);
  RigidTransform pose = start;
  for (int step = 0; step < options.iterations; ++step) {
    const Eigen::Matrix3Xd moved = pose.apply(probe.points);
    // The pairs first, so that the motion is linearised about their weighted centroid.
    std::vector<Eigen::Index> kept;
    std::vector<Eigen::Vector3d> planes;  // the pair's normal, scaled by nothing
    std::vector<double> offsets;          // signed distance of the vertex above the plane
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    double total = 0.0;
    for (Eigen::Index k = 0; k < moved.cols(); ++k) {
      const Eigen::Vector3d x = moved.col(k);
      // Searched only nearer than max_distance (the hint, as in Side::within).
      const Tree::Point_and_primitive_id hint(to_cgal(x + Eigen::Vector3d(reach, 0.0, 0.0)),
                                              reference.triangles.begin());
      const auto [nearest, triangle] = reference.tree.closest_point_and_primitive(to_cgal(x), hint);
      const Eigen::Vector3d q = to_eigen(nearest);
      if ((x - q).squaredNorm() > limit) continue;
      const auto face = static_cast<std::size_t>(triangle - reference.triangles.begin());
      const Eigen::Vector3d n = reference.normal_at(face, q);
      if (n.dot(pose.rotation * probe.normals.col(k)) <= 0.0) continue;  // facing away
      kept.push_back(k);
      planes.push_back(n);
      offsets.push_back((x - q).dot(n));
      centroid += probe.weights(k) * x;
      total += probe.weights(k);
    }
    if (kept.size() < 6 || !(total > 0.0)) break;
    centroid /= total;
    // x' = dR (x - c) + c + t with dR ~ I + [w]x: the residual of pair i is
    // (x_i - q_i).n + w.((x_i - c) x n) + t.n, minimised in weighted least squares.
    Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    for (std::size_t i = 0; i < kept.size(); ++i) {
      const Eigen::Vector3d x = moved.col(kept[i]);
      Eigen::Matrix<double, 6, 1> row;
      row << (x - centroid).cross(planes[i]), planes[i];
      const double w = probe.weights(kept[i]);
      normal += w * row * row.transpose();
      rhs -= w * offsets[i] * row;
    }
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solver(normal);
    if (solver.info() != Eigen::Success) break;
    const Eigen::Matrix<double, 6, 1> motion = solver.solve(rhs);
    if (!motion.allFinite()) break;
    const Eigen::Vector3d w = motion.head<3>();
    const double angle = w.norm();
    const Eigen::Matrix3d turn = angle > 0.0
                                     ? Eigen::AngleAxisd(angle, w / angle).toRotationMatrix()
                                     : Eigen::Matrix3d::Identity();
    RigidTransform next;
    next.rotation = turn * pose.rotation;
    next.translation = turn * (pose.translation - centroid) + centroid + motion.tail<3>();
    const double largest = (next.apply(probe.points) - moved).colwise().norm().maxCoeff();
    pose = next;
    if (largest <= options.tolerance) break;
  }
  return pose;
}

}  // namespace surfcomp::matching
