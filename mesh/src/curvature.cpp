#include "surfcomp/mesh/curvature.hpp"

#include "pivoted_qr.hpp"
#include "surface_mesh.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"

#include <CGAL/Eigen_svd.h>
#include <CGAL/Monge_via_jet_fitting.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Dense>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::mesh {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using JetFitter = CGAL::Monge_via_jet_fitting<Kernel, Kernel, CGAL::Eigen_svd>;
using detail::apply_reflectors;
using detail::apply_reflectors_to_columns;
using detail::back_substitute;
using detail::pivoted_least_squares;
using detail::pivoted_qr;
using detail::PivotedQr;
using detail::well_conditioned;

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Coefficients of the sphere fitted to a component of fewer than min_points vertices.
constexpr std::size_t sphere_coefficients = 4;

/// Number of coefficients the chosen fit determines (the minimum number of points).
std::size_t fitted_coefficients(const CurvatureOptions& o) {
  if (o.method == CurvatureMethod::quadric) return 9;
  const auto d = static_cast<std::size_t>(o.jet_degree);
  return (d + 1) * (d + 2) / 2;
}

void check_options(const CurvatureOptions& o) {
  constexpr const char* caller = "principal_curvatures: ";
  if (o.rings < 1) {
    throw OptionError(caller + std::string("rings is ") + std::to_string(o.rings) +
                      "; expected >= 1");
  }
  if (!(o.radius >= 0.0) || !std::isfinite(o.radius)) {
    throw OptionError(caller + std::string("radius is ") + format_number(o.radius) +
                      " A; expected a finite value >= 0 (0 = use rings)");
  }
  if (o.quadric_passes < 0 || o.quadric_passes > 20) {
    throw OptionError(caller + std::string("quadric_passes is ") +
                      std::to_string(o.quadric_passes) + "; expected 0..20");
  }
  if (!(o.quadric_ridge >= 0.0) || !std::isfinite(o.quadric_ridge)) {
    throw OptionError(caller + std::string("quadric_ridge is ") + format_number(o.quadric_ridge) +
                      "; expected a finite value >= 0");
  }
  if (o.jet_degree < 2 || o.jet_degree > 4) {
    throw OptionError(caller + std::string("jet_degree is ") + std::to_string(o.jet_degree) +
                      "; expected 2, 3 or 4");
  }
  const std::size_t coefficients = fitted_coefficients(o);
  if (o.min_points < 0 || static_cast<std::size_t>(o.min_points) < coefficients) {
    throw OptionError(caller + std::string("min_points is ") + std::to_string(o.min_points) +
                      "; the fit determines " + std::to_string(coefficients) +
                      " coefficients and needs at least as many points");
  }
  if (o.max_points < o.min_points || o.max_points > 100000) {
    throw OptionError(caller + std::string("max_points is ") + std::to_string(o.max_points) +
                      "; expected min_points (" + std::to_string(o.min_points) + ") to 100000");
  }
}

/// Vertex adjacency in compressed rows: the neighbours of v are
/// neighbours[offsets[v] .. offsets[v+1]), in OpenMesh's circulation order.
struct Adjacency {
  std::vector<int> offsets;
  std::vector<int> neighbours;
};

Adjacency vertex_adjacency(const TriMesh& mesh) {
  Adjacency a;
  a.offsets.reserve(mesh.n_vertices() + 1);
  a.offsets.push_back(0);
  for (auto v : mesh.vertices()) {
    for (auto u : mesh.vv_range(v)) a.neighbours.push_back(u.idx());
    a.offsets.push_back(static_cast<int>(a.neighbours.size()));
  }
  return a;
}

/// Area-weighted vertex normals (#V by 3, unit or zero) of the surface's triangles.
Eigen::MatrixX3d area_weighted_normals(const Surface& surface) {
  const TriMesh& mesh = tri_mesh(surface);
  Eigen::MatrixX3d normals =
      Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (auto f : mesh.faces()) {
    auto h = mesh.halfedge_handle(f);
    const auto& a = mesh.point(mesh.from_vertex_handle(h));
    const auto& b = mesh.point(mesh.to_vertex_handle(h));
    const auto& c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    const OpenMesh::Vec3d area_normal = OpenMesh::cross(b - a, c - a);
    for (auto v : mesh.fv_range(f)) {
      normals.row(v.idx()) += Eigen::RowVector3d(area_normal[0], area_normal[1], area_normal[2]);
    }
  }
  for (Eigen::Index v = 0; v < normals.rows(); ++v) {
    const double length = normals.row(v).norm();
    if (length > 0) normals.row(v) /= length;
  }
  return normals;
}

/// Per-thread scratch: a visit stamp per vertex (so that marking needs no clearing) and the
/// neighbourhood under construction.
struct Scratch {
  std::vector<std::uint32_t> stamp;
  std::uint32_t current = 0;
  std::vector<int> members;
  std::vector<int> layer;
  std::vector<int> next;
};

/// A neighbourhood grows by whole rings until it has visited this many times
/// CurvatureOptions::max_points vertices (whatever its radius), then is sampled down to it.
constexpr std::size_t max_visited_factor = 4;

/// The vertices whose points are fitted at `vertex`, the vertex itself first (CGAL's jet
/// fitting puts its origin at the first point). Layers are added whole, in a fixed order.
void collect_neighbourhood(int vertex, const Adjacency& adj, const Eigen::MatrixX3d& positions,
                           const CurvatureOptions& options, Scratch& s) {
  if (++s.current == 0) {  // stamp wrapped around: clear the marks
    std::fill(s.stamp.begin(), s.stamp.end(), 0u);
    s.current = 1;
  }
  s.members.assign(1, vertex);
  s.layer.assign(1, vertex);
  s.stamp[static_cast<std::size_t>(vertex)] = s.current;
  const Eigen::RowVector3d centre = positions.row(vertex);
  const double radius2 = options.radius * options.radius;
  const bool by_radius = options.radius > 0.0;
  const auto min_points = static_cast<std::size_t>(options.min_points);
  const auto max_points = static_cast<std::size_t>(options.max_points);
  const std::size_t max_visited = max_visited_factor * max_points;
  for (int ring = 1; s.members.size() < max_visited; ++ring) {
    const bool grow_freely = by_radius ? false : ring <= options.rings;
    s.next.clear();
    for (int u : s.layer) {
      for (int k = adj.offsets[static_cast<std::size_t>(u)];
           k < adj.offsets[static_cast<std::size_t>(u) + 1]; ++k) {
        const int w = adj.neighbours[static_cast<std::size_t>(k)];
        if (s.stamp[static_cast<std::size_t>(w)] == s.current) continue;
        if (by_radius && (positions.row(w) - centre).squaredNorm() > radius2) continue;
        if (!by_radius && !grow_freely) continue;
        s.stamp[static_cast<std::size_t>(w)] = s.current;
        s.next.push_back(w);
      }
    }
    if (s.next.empty()) break;
    s.members.insert(s.members.end(), s.next.begin(), s.next.end());
    s.layer.swap(s.next);
  }
  // Too few points: add whole rings around everything collected until there are enough.
  while (s.members.size() < min_points) {
    s.next.clear();
    for (int u : s.members) {
      for (int k = adj.offsets[static_cast<std::size_t>(u)];
           k < adj.offsets[static_cast<std::size_t>(u) + 1]; ++k) {
        const int w = adj.neighbours[static_cast<std::size_t>(k)];
        if (s.stamp[static_cast<std::size_t>(w)] == s.current) continue;
        s.stamp[static_cast<std::size_t>(w)] = s.current;
        s.next.push_back(w);
      }
    }
    if (s.next.empty()) break;
    s.members.insert(s.members.end(), s.next.begin(), s.next.end());
  }
  // Too many: an even sample of them in their order (ring by ring), the vertex itself first, so
  // that the fit keeps the neighbourhood's extent at a bounded cost.
  if (s.members.size() > max_points) {
    const std::size_t others = s.members.size() - 1;
    for (std::size_t k = 1; k < max_points; ++k)
      s.members[k] = s.members[1 + (k - 1) * others / (max_points - 1)];
    s.members.resize(max_points);
  }
}

enum class FitStatus : std::uint8_t { ok, too_few_points, no_normal, not_finite };

/// Principal curvatures (k1 >= k2, seed sign: negative where the surface bends away from
/// `normal`) at the first of `members`, from CGAL's jet fitting.
std::pair<double, double> jet_curvatures(const Eigen::MatrixX3d& positions,
                                         const std::vector<int>& members,
                                         const Eigen::RowVector3d& normal, std::size_t degree) {
  std::vector<Kernel::Point_3> points;
  points.reserve(members.size());
  for (int m : members) points.emplace_back(positions(m, 0), positions(m, 1), positions(m, 2));
  JetFitter fitter;
  JetFitter::Monge_form monge = fitter(points.begin(), points.end(), degree, 2);
  monge.comply_wrt_given_normal(Kernel::Vector_3(normal(0), normal(1), normal(2)));
  // CGAL's Monge form is z = (k1 x^2 + k2 y^2) / 2 with z along the normal: a convex surface
  // bends away from an outward normal, so its k are negative, the seed's sign.
  return {monge.principal_curvatures(0), monge.principal_curvatures(1)};
}

/// Principal curvatures (both equal, seed sign as above) at the first of `members` from the
/// sphere fitted to all of them: the algebraic least-squares fit |p|^2 = 2 c.p + k (4
/// coefficients; radius sqrt(k + |c|^2)), negative when `normal` points away from the centre.
/// Coplanar points (rank < 4) are a plane, curvature 0. Needs at least 4 points.
std::pair<double, double> sphere_curvatures(const Eigen::MatrixX3d& positions,
                                            const std::vector<int>& members,
                                            const Eigen::RowVector3d& normal) {
  const auto count = static_cast<Eigen::Index>(members.size());
  Eigen::MatrixX3d points(count, 3);
  for (Eigen::Index k = 0; k < count; ++k) {
    points.row(k) = positions.row(members[static_cast<std::size_t>(k)]);
  }
  // Centred and in units of the points' spread, so that the system is well scaled and the
  // result scales exactly as 1/length.
  const Eigen::RowVector3d centroid = points.colwise().mean();
  points.rowwise() -= centroid;
  const double scale = std::sqrt(points.squaredNorm() / static_cast<double>(count));
  if (!(scale > 0.0)) return {std::nan(""), std::nan("")};
  points /= scale;
  Eigen::MatrixXd design(count, 4);
  design.leftCols(3) = 2.0 * points;
  design.col(3).setOnes();
  const Eigen::VectorXd target = points.rowwise().squaredNorm();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
  if (qr.rank() < 4) return {0.0, 0.0};
  const Eigen::Vector4d solution = qr.solve(target);
  const Eigen::Vector3d centre = solution.head<3>();
  const double radius = std::sqrt(solution(3) + centre.squaredNorm()) * scale;
  const Eigen::Vector3d outward = points.row(0).transpose() - centre;
  const double k = outward.dot(normal.transpose()) > 0.0 ? -1.0 / radius : 1.0 / radius;
  return {k, k};
}

/// A height function's value, gradient and Hessian at the origin of the tangent plane.
struct HeightJet {
  double value = 0.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  Eigen::Matrix2d hessian = Eigen::Matrix2d::Zero();
};

/// The value, gradient and Hessian at the origin of a pass's P = Q(x, y) + g P'^2 + (h x + i y) P'
/// (q = a..f, g, h, i of quadric_fit) by the chain rule, from `previous`, the jet of P'.
HeightJet next_jet(const Eigen::Matrix<double, 9, 1>& q, const HeightJet& previous) {
  const double g = q(6), h = q(7), i = q(8);
  const double p0 = previous.value;
  const Eigen::Vector2d dp = previous.gradient;
  HeightJet next;
  next.value = q(5) + g * p0 * p0;
  next.gradient << q(3) + 2 * g * p0 * dp(0) + h * p0, q(4) + 2 * g * p0 * dp(1) + i * p0;
  next.hessian << 2 * q(0), q(1), q(1), 2 * q(2);
  next.hessian += 2 * g * (dp * dp.transpose() + p0 * previous.hessian);
  const Eigen::Vector2d ex = Eigen::Vector2d::UnitX(), ey = Eigen::Vector2d::UnitY();
  next.hessian += h * (ex * dp.transpose() + dp * ex.transpose());
  next.hessian += i * (ey * dp.transpose() + dp * ey.transpose());
  return next;
}

/// The principal curvatures (k1 >= k2) at the origin of the graph z = P(x, y) of `jet`, fitted
/// in units of `scale` (the results are per length). With the upward normal (the vertex
/// normal): first fundamental form I = 1 + p p^T, second II = Hessian / sqrt(1 + |p|^2);
/// z = k x^2 / 2 bends towards the normal for k > 0, so a convex surface under an outward normal
/// has k < 0 (the seed's sign).
std::pair<double, double> graph_curvatures(const HeightJet& jet, double scale) {
  const Eigen::Vector2d p = jet.gradient;
  const Eigen::Matrix2d first = Eigen::Matrix2d::Identity() + p * p.transpose();
  const Eigen::Matrix2d shape = first.inverse() * jet.hessian / std::sqrt(1.0 + p.squaredNorm());
  const double mean = 0.5 * shape.trace();
  const double root = std::sqrt(std::max(0.0, mean * mean - shape.determinant()));
  return {(mean + root) / scale, (mean - root) / scale};
}

/// Principal curvatures (k1 >= k2, seed sign as above) at the first of `members` from a
/// quadric fitted in the tangent frame (t1, t2, n) of the vertex normal. The implicit quadric
///   z = a x^2 + b xy + c y^2 + d x + e y + f + g z^2 + h xz + i yz
/// holds every quadric exactly (a sphere is z = -(x^2 + y^2 + z^2) / (2r)), so large
/// neighbourhoods on coarse meshes add no bias on spheres, cylinders and ellipsoids, where a
/// height paraboloid overestimates |k|. Putting the measured z into the regressors z^2, xz, yz
/// would make noise blow up on flat patches (errors in variables), so they use the previous
/// pass's prediction P(x, y) instead: pass 0 fits the paraboloid P = a x^2 + ... + f, and each
/// of `passes` further passes fits z = Q(x, y) + g P^2 + (h x + i y) P and takes it as the new
/// P, a fixed-point iteration whose fixed point on a quadric is the quadric. The value,
/// gradient and Hessian of P at the origin follow by the chain rule; the curvatures are those
/// of the graph z = P(x, y) there. Where P^2, xP, yP are tiny (flat or noisy patches, one-sided
/// boundary neighbourhoods) g, h, i are poorly determined, so a ridge term
/// ridge_weight * #points * ((g - (a + c) / 2)^2 + h^2 + i^2) pulls them towards the sphere's
/// values, exact for spheres and harmless where the P columns are well determined.
/// `MaxRows` bounds the rows of the least-squares system (#members + 3), or is Eigen::Dynamic.
template <int MaxRows>
std::pair<double, double> quadric_fit(const Eigen::MatrixX3d& positions,
                                      const std::vector<int>& members,
                                      const Eigen::RowVector3d& normal, int passes,
                                      double ridge_weight) {
  using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, MaxRows, 1>;
  using Design = Eigen::Matrix<double, Eigen::Dynamic, 9, Eigen::ColMajor, MaxRows, 9>;
  using Paraboloid = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::ColMajor, MaxRows, 6>;
  const Eigen::Vector3d n = normal.transpose().normalized();
  // Tangent basis: t1 perpendicular to n and to the coordinate axis least aligned with n.
  Eigen::Index axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d t1 = n.cross(Eigen::Vector3d::Unit(axis)).normalized();
  const Eigen::Vector3d t2 = n.cross(t1);
  const Eigen::Vector3d origin = positions.row(members.front()).transpose();
  const auto count = static_cast<Eigen::Index>(members.size());
  Column x(count), y(count), z(count);
  for (Eigen::Index k = 0; k < count; ++k) {
    const Eigen::Vector3d d =
        positions.row(members[static_cast<std::size_t>(k)]).transpose() - origin;
    x(k) = d.dot(t1);
    y(k) = d.dot(t2);
    z(k) = d.dot(n);
  }
  // Work in units of the neighbourhood's size so that the system is well scaled and the result
  // scales exactly as 1/length.
  const double scale =
      std::sqrt((x.squaredNorm() + y.squaredNorm() + z.squaredNorm()) / static_cast<double>(count));
  if (!(scale > 0.0)) return {std::nan(""), std::nan("")};
  x /= scale;
  y /= scale;
  z /= scale;

  // Three extra rows hold the ridge penalty that pulls g towards (a + c) / 2 and h, i towards 0,
  // the values of a sphere in any tangent frame.
  const double ridge = std::sqrt(ridge_weight * static_cast<double>(count));
  Design design = Design::Zero(count + 3, 9);
  design(count, 6) = ridge;
  design(count, 0) = -0.5 * ridge;
  design(count, 2) = -0.5 * ridge;
  design(count + 1, 7) = ridge;
  design(count + 2, 8) = ridge;
  Column target = Column::Zero(count + 3);
  target.head(count) = z;
  auto rows = design.topRows(count);
  rows.col(0) = x.cwiseProduct(x);
  rows.col(1) = x.cwiseProduct(y);
  rows.col(2) = y.cwiseProduct(y);
  rows.col(3) = x;
  rows.col(4) = y;
  rows.col(5).setOnes();
  // Pass 0: the paraboloid.
  Paraboloid system = rows.template leftCols<6>();
  const PivotedQr<6> first_qr = pivoted_qr<6>(system);
  Column right = z;
  apply_reflectors(system, first_qr, first_qr.pivots, right);
  Eigen::Matrix<double, 9, 1> q = Eigen::Matrix<double, 9, 1>::Zero();
  q.head<6>() = back_substitute<6>(system, first_qr, right.template head<6>());
  Column predicted = rows.template leftCols<6>() * q.head<6>();
  HeightJet jet;
  jet.value = q(5);
  jet.gradient << q(3), q(4);
  jet.hessian << 2 * q(0), q(1), q(1), 2 * q(2);
  // Every pass solves [A | B] (g, h, i) = target for the same first six columns A (the
  // paraboloid's, with the first ridge row below) and new columns B (P^2, xP, yP and the ridge
  // rows). A's factorisation is pass 0's with the ridge row rotated into its R (Givens
  // rotations); a pass applies A's Q^T to B and factorises the three columns left. When either
  // block is near rank deficiency, the pass solves the whole system as one pivoted QR instead,
  // whose basic solution the blocks would not give.
  using Rest = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::ColMajor, MaxRows, 3>;
  Eigen::Matrix<double, 6, 6> upper_r = system.template topRows<6>();
  upper_r.template triangularView<Eigen::StrictlyLower>().setZero();
  std::array<double, 6> cosine{}, sine{};
  double first_largest = 0.0;  // the largest column norm of [A; ridge row]
  {
    Eigen::Matrix<double, 6, 1> ridge_row;
    for (int k = 0; k < 6; ++k) {
      const int column = first_qr.order[static_cast<std::size_t>(k)];
      ridge_row(k) = design(count, column);
      first_largest = std::max(first_largest, std::hypot(rows.col(column).norm(), ridge_row(k)));
    }
    for (int k = 0; k < 6; ++k) {
      const double a = upper_r(k, k), b = ridge_row(k);
      const double length = std::hypot(a, b);
      cosine[k] = length > 0.0 ? a / length : 1.0;
      sine[k] = length > 0.0 ? b / length : 0.0;
      for (int j = k; j < 6; ++j) {
        const double top = upper_r(k, j), bottom = ridge_row(j);
        upper_r(k, j) = cosine[k] * top + sine[k] * bottom;
        ridge_row(j) = cosine[k] * bottom - sine[k] * top;
      }
    }
  }
  PivotedQr<6> first_r = first_qr;  // R of [A; ridge row], in pass 0's column order
  first_r.largest_norm = first_largest;
  const bool first_well = first_qr.pivots == 6 && well_conditioned(upper_r, first_r);
  // Q^T of [A; ridge row] on the rows of a column: pass 0's reflectors on the data rows, then
  // the rotations between each of the first six rows and the ridge row.
  const auto rotate = [&](auto&& column) {
    for (int k = 0; k < 6; ++k) {
      const double top = column(k), bottom = column(count);
      column(k) = cosine[k] * top + sine[k] * bottom;
      column(count) = cosine[k] * bottom - sine[k] * top;
    }
  };
  Column rotated_target = target;  // Q^T target, the same in every pass
  if (first_well) {
    apply_reflectors(system, first_qr, 6, rotated_target.head(count));
    rotate(rotated_target);
  }
  Rest rest(count + 3, 3);
  Design work;
  for (int pass = 0; pass < passes; ++pass) {
    rows.col(6) = predicted.cwiseProduct(predicted);
    rows.col(7) = x.cwiseProduct(predicted);
    rows.col(8) = y.cwiseProduct(predicted);
    bool solved = false;
    if (first_well) {
      rest = design.template rightCols<3>();
      apply_reflectors_to_columns<6, 3>(system, first_qr, 6, rest.topRows(count));
      for (int c = 0; c < 3; ++c) rotate(rest.col(c));
      Rest second = rest.bottomRows(count - 3);
      const PivotedQr<3> second_qr = pivoted_qr<3>(second);
      if (well_conditioned(second, second_qr)) {
        Column lower = rotated_target.tail(count - 3);
        apply_reflectors(second, second_qr, 3, lower);
        const Eigen::Vector3d tail =
            back_substitute<3>(second, second_qr, lower.template head<3>());
        // R12 holds B's first six rows in the factorisation's column order of A.
        Eigen::Matrix<double, 6, 1> upper = rotated_target.template head<6>();
        upper -= rest.template topRows<6>() * tail;
        q.head<6>() = back_substitute<6>(upper_r, first_r, upper);
        q.tail<3>() = tail;
        solved = true;
      }
    }
    if (!solved) {
      work = design;
      right = target;
      q = pivoted_least_squares<9>(work, right);
    }
    predicted = rows * q;
    jet = next_jet(q, jet);
  }
  return graph_curvatures(jet, scale);
}

/// Neighbourhoods of up to this many points are fitted in matrices of a fixed capacity, which
/// need no heap memory and let Eigen unroll the loops over the 9 columns; larger ones (a large
/// options.radius) in heap matrices.
constexpr std::size_t fixed_capacity_points = 61;

/// quadric_fit in matrices of a fixed capacity when `members` fits in them.
std::pair<double, double> quadric_curvatures(const Eigen::MatrixX3d& positions,
                                             const std::vector<int>& members,
                                             const Eigen::RowVector3d& normal, int passes,
                                             double ridge_weight) {
  if (members.size() <= fixed_capacity_points) {
    return quadric_fit<static_cast<int>(fixed_capacity_points) + 3>(positions, members, normal,
                                                                    passes, ridge_weight);
  }
  return quadric_fit<Eigen::Dynamic>(positions, members, normal, passes, ridge_weight);
}

}  // namespace

PrincipalCurvatures principal_curvatures(const Surface& surface, const CurvatureOptions& options) {
  check_options(options);
  const TriMesh& mesh = tri_mesh(surface);
  if (mesh.n_faces() == 0) {
    throw TopologyError(surface.source() +
                        ": principal_curvatures needs a surface with "
                        "triangles; this one has none");
  }
  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  const Eigen::MatrixX3d positions = surface.positions();
  const Eigen::MatrixX3d normals =
      surface.has_normals() ? surface.normals() : area_weighted_normals(surface);
  const Adjacency adjacency = vertex_adjacency(mesh);
  const auto min_points = static_cast<std::size_t>(options.min_points);

  PrincipalCurvatures out;
  out.cc1.resize(n);
  out.cc2.resize(n);
  out.shape_index.resize(n);
  out.curvedness.resize(n);
  std::vector<FitStatus> status(static_cast<std::size_t>(n), FitStatus::ok);
  tbb::enumerable_thread_specific<Scratch> scratches([&] {
    Scratch s;
    s.stamp.assign(static_cast<std::size_t>(n), 0u);
    return s;
  });

  std::atomic<std::int64_t> fitted{0};
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n, 64), [&](const auto& range) {
    if (options.progress) {
      options.progress(fitted.fetch_add(static_cast<std::int64_t>(range.size())), n);
    }
    Scratch& scratch = scratches.local();
    for (Eigen::Index v = range.begin(); v != range.end(); ++v) {
      const auto vi = static_cast<std::size_t>(v);
      const Eigen::RowVector3d normal = normals.row(v);
      if (!(normal.norm() > 0.5) || !normal.allFinite()) {
        status[vi] = FitStatus::no_normal;
        continue;
      }
      collect_neighbourhood(static_cast<int>(v), adjacency, positions, options, scratch);
      // Fewer than min_points: the neighbourhood is the vertex's whole component, whose far
      // side a height fit would take for noise.
      const bool tiny_component = scratch.members.size() < min_points;
      if (tiny_component && scratch.members.size() < sphere_coefficients) {
        status[vi] = FitStatus::too_few_points;
        continue;
      }
      const auto [k1, k2] = tiny_component ? sphere_curvatures(positions, scratch.members, normal)
                            : options.method == CurvatureMethod::jet
                                ? jet_curvatures(positions, scratch.members, normal,
                                                 static_cast<std::size_t>(options.jet_degree))
                                : quadric_curvatures(positions, scratch.members, normal,
                                                     options.quadric_passes, options.quadric_ridge);
      if (!std::isfinite(k1) || !std::isfinite(k2)) {
        status[vi] = FitStatus::not_finite;
        continue;
      }
      const bool first_larger = std::abs(k1) >= std::abs(k2);
      out.cc1(v) = first_larger ? k1 : k2;
      out.cc2(v) = first_larger ? k2 : k1;
      // Convex-positive principal curvatures, k_max >= k_min.
      const double k_max = -std::min(k1, k2);
      const double k_min = -std::max(k1, k2);
      // atan2 equals atan((k_max + k_min) / (k_max - k_min)) for k_max > k_min and gives
      // +-pi/2 (S = +-1) for umbilics, 0 for a plane.
      out.shape_index(v) = 2.0 / M_PI * std::atan2(k_max + k_min, k_max - k_min);
      out.curvedness(v) = std::sqrt((k1 * k1 + k2 * k2) / 2.0);
    }
  });

  if (options.progress) options.progress(n, n);
  // Report the lowest failing vertex, whatever the thread schedule was.
  for (std::size_t v = 0; v < status.size(); ++v) {
    const std::string where = surface.source() + ": curvature: vertex " + std::to_string(v);
    switch (status[v]) {
      case FitStatus::ok:
        continue;
      case FitStatus::no_normal:
        throw NumericError(where + " has no defined normal (no triangle of non-zero area; " +
                           options::named("repair") +
                           " "
                           "removes isolated vertices and degenerate faces)");
      case FitStatus::too_few_points:
        throw TopologyError(where + " is connected to fewer than " +
                            std::to_string(sphere_coefficients - 1) +
                            " other vertices; the smallest fit (a sphere) needs " +
                            std::to_string(sphere_coefficients) + " points (" +
                            options::named("repair") + " keeps the largest component)");
      case FitStatus::not_finite:
        throw NumericError(where + ": the local fit is degenerate (non-finite curvature)");
    }
  }
  return out;
}

Eigen::VectorXd angle_defects(const Surface& surface) {
  const TriMesh& mesh = tri_mesh(surface);
  if (mesh.n_faces() == 0) {
    throw TopologyError(surface.source() + ": the surface has no triangles");
  }
  Eigen::VectorXd angle_sum = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.n_vertices()));
  for (auto f : mesh.faces()) {
    for (auto h : mesh.fh_range(f)) {
      // The angle at the tip of h, between the edges to its predecessor and successor.
      const auto v = mesh.to_vertex_handle(h);
      const auto& p = mesh.point(v);
      const OpenMesh::Vec3d a = mesh.point(mesh.from_vertex_handle(h)) - p;
      const OpenMesh::Vec3d b = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h))) - p;
      angle_sum(v.idx()) += std::atan2(OpenMesh::cross(a, b).norm(), OpenMesh::dot(a, b));
    }
  }
  Eigen::VectorXd defects(angle_sum.size());
  for (auto v : mesh.vertices()) {
    const double full = !mesh.is_isolated(v) && mesh.is_boundary(v) ? M_PI : 2.0 * M_PI;
    defects(v.idx()) = full - angle_sum(v.idx());
  }
  return defects;
}

}  // namespace surfcomp::mesh
