#include "surfcomp/harmonic/disk_map.hpp"

#include "surfcomp/core/error.hpp"

#include <Eigen/Geometry>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <cmath>
#include <sstream>
#include <string>

namespace surfcomp::harmonic {
namespace {

constexpr double two_pi = 6.283185307179586476925286766559;

std::string format_number(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

std::string vertex_range(Eigen::Index n_vertices) {
  return "0.." + std::to_string(static_cast<long long>(n_vertices) - 1);
}

/// The halfedges of a face list, grouped by source vertex (compressed rows): halfedge h of
/// vertex a runs a -> target[h] inside a face whose third vertex is apex[h].
struct Halfedges {
  std::vector<int> first;  ///< #V + 1 offsets into target / apex
  std::vector<int> target;
  std::vector<int> apex;

  /// The halfedge a -> b, or -1 when no face traverses a -> b.
  int find(int a, int b) const {
    for (int h = first[static_cast<std::size_t>(a)]; h < first[static_cast<std::size_t>(a) + 1];
         ++h) {
      if (target[static_cast<std::size_t>(h)] == b) return h;
    }
    return -1;
  }
};

/// A checked patch: its halfedges and, per vertex, the border edges through it (-1 if none):
/// next_on_border[a] = b when a -> b is traversed by a face and b -> a is not (then a's
/// previous border vertex is the p with next_on_border[p] == a, kept in prev_on_border).
struct PatchTopology {
  Halfedges halfedges;
  std::vector<int> next_on_border;
  std::vector<int> prev_on_border;
};

PatchTopology check_and_build(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                              const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                              const std::vector<int>& outer_boundary, const char* caller) {
  const std::string where = std::string(caller) + ": ";
  const Eigen::Index n_vertices = positions.rows();
  if (n_vertices == 0) throw InputError(where + "positions is empty, expected #V >= 3 rows");
  for (Eigen::Index v = 0; v < n_vertices; ++v) {
    if (!positions.row(v).allFinite()) {
      throw InputError(where + "position of vertex " + std::to_string(v) +
                       " is not finite, expected finite coordinates (A)");
    }
  }
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int v = faces(f, c);
      if (v < 0 || v >= n_vertices) {
        throw InputError(where + "face " + std::to_string(f) + " has vertex index " +
                         std::to_string(v) + ", expected " + vertex_range(n_vertices));
      }
    }
    if (faces(f, 0) == faces(f, 1) || faces(f, 1) == faces(f, 2) || faces(f, 0) == faces(f, 2)) {
      throw InputError(where + "face " + std::to_string(f) + " (" + std::to_string(faces(f, 0)) +
                       ", " + std::to_string(faces(f, 1)) + ", " + std::to_string(faces(f, 2)) +
                       ") repeats a vertex, expected three distinct vertices");
    }
  }
  const std::size_t n_boundary = outer_boundary.size();
  if (n_boundary < 3) {
    throw TopologyError(where + "the outer boundary has " + std::to_string(n_boundary) +
                        " vertices, expected at least 3");
  }
  const auto nv = static_cast<std::size_t>(n_vertices);
  std::vector<char> on_outer(nv, 0);
  for (const int v : outer_boundary) {
    if (v < 0 || v >= n_vertices) {
      throw InputError(where + "outer boundary vertex index " + std::to_string(v) + " is outside " +
                       vertex_range(n_vertices));
    }
    if (on_outer[static_cast<std::size_t>(v)]) {
      throw InputError(where + "outer boundary vertex " + std::to_string(v) +
                       " appears twice, expected each vertex once");
    }
    on_outer[static_cast<std::size_t>(v)] = 1;
  }

  PatchTopology topology;
  Halfedges& he = topology.halfedges;
  he.first.assign(nv + 1, 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) ++he.first[static_cast<std::size_t>(faces(f, c)) + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) he.first[v + 1] += he.first[v];
  he.target.assign(static_cast<std::size_t>(3 * faces.rows()), -1);  // -1: slot not filled yet
  he.apex.resize(he.target.size());
  std::vector<int> fill(he.first.begin(), he.first.end() - 1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int a = faces(f, c), b = faces(f, (c + 1) % 3), apex = faces(f, (c + 2) % 3);
      if (he.find(a, b) >= 0) {
        throw TopologyError(where + "edge " + std::to_string(a) + " -> " + std::to_string(b) +
                            " is traversed by two faces (face " + std::to_string(f) +
                            " is the second), expected a consistently oriented 2-manifold");
      }
      const auto slot = static_cast<std::size_t>(fill[static_cast<std::size_t>(a)]++);
      he.target[slot] = b;
      he.apex[slot] = apex;
    }
  }

  // Border edges, and every vertex's fan of triangles must be a single fan.
  topology.next_on_border.assign(nv, -1);
  topology.prev_on_border.assign(nv, -1);
  for (int a = 0; a < n_vertices; ++a) {
    int border_start = -1;
    for (int h = he.first[static_cast<std::size_t>(a)];
         h < he.first[static_cast<std::size_t>(a) + 1]; ++h) {
      const int b = he.target[static_cast<std::size_t>(h)];
      if (he.find(b, a) >= 0) continue;
      if (border_start >= 0) {
        throw TopologyError(where + "vertex " + std::to_string(a) +
                            " lies on two border edges leaving it (a bow-tie), expected a "
                            "manifold patch whose border passes each vertex once");
      }
      border_start = h;
      topology.next_on_border[static_cast<std::size_t>(a)] = b;
      topology.prev_on_border[static_cast<std::size_t>(b)] = a;
    }
    const int degree =
        he.first[static_cast<std::size_t>(a) + 1] - he.first[static_cast<std::size_t>(a)];
    if (degree == 0) continue;
    // Rotate from the leaving halfedge a -> b to a -> apex (the face across edge a-apex);
    // a single fan visits every leaving halfedge once.
    const int start = border_start >= 0 ? border_start : he.first[static_cast<std::size_t>(a)];
    int visited = 0;
    for (int h = start; h >= 0 && visited <= degree;) {
      ++visited;
      h = he.find(a, he.apex[static_cast<std::size_t>(h)]);
      if (h == start) break;
    }
    if (visited != degree) {
      throw TopologyError(where + "the triangles around vertex " + std::to_string(a) +
                          " form more than one fan, expected a manifold vertex");
    }
  }

  for (std::size_t k = 0; k < n_boundary; ++k) {
    const int a = outer_boundary[k], b = outer_boundary[(k + 1) % n_boundary];
    if (topology.next_on_border[static_cast<std::size_t>(a)] != b) {
      throw TopologyError(where + "outer boundary step " + std::to_string(k) + " (" +
                          std::to_string(a) + " -> " + std::to_string(b) +
                          ") is not a border edge walked with the patch on its left, expected "
                          "the outer border loop counter-clockwise seen from outside");
    }
  }

  // Every vertex must be reachable from the outer boundary (faces are directed cycles, so
  // following leaving halfedges reaches every vertex of the faces' connected set).
  std::vector<char> reached(nv, 0);
  std::vector<int> stack(outer_boundary.begin(), outer_boundary.end());
  for (const int v : outer_boundary) reached[static_cast<std::size_t>(v)] = 1;
  while (!stack.empty()) {
    const int a = stack.back();
    stack.pop_back();
    for (int h = he.first[static_cast<std::size_t>(a)];
         h < he.first[static_cast<std::size_t>(a) + 1]; ++h) {
      const auto b = static_cast<std::size_t>(he.target[static_cast<std::size_t>(h)]);
      if (!reached[b]) {
        reached[b] = 1;
        stack.push_back(static_cast<int>(b));
      }
    }
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (!reached[v]) {
      throw TopologyError(where + "vertex " + std::to_string(v) +
                          " is not joined to the outer boundary by edges, expected one "
                          "connected patch");
    }
  }
  return topology;
}

Eigen::Vector3d point(const Eigen::Ref<const Eigen::MatrixX3d>& positions, int v) {
  return positions.row(v).transpose();
}

/// cot of the angle at `k` in triangle (i, j, k); 0 for a degenerate triangle (as CGAL).
double cotangent_at(const Eigen::Vector3d& i, const Eigen::Vector3d& j, const Eigen::Vector3d& k) {
  const Eigen::Vector3d a = j - k, b = i - k;
  const double sine = a.cross(b).norm();
  return sine != 0.0 ? a.dot(b) / sine : 0.0;
}

/// tan(gamma / 2) of the angle gamma at `i` between the edges to `j` and to `k`.
double half_angle_tangent(const Eigen::Vector3d& i, const Eigen::Vector3d& j,
                          const Eigen::Vector3d& k) {
  const Eigen::Vector3d a = j - i, b = k - i;
  return a.cross(b).norm() / (a.norm() * b.norm() + a.dot(b));
}

/// The spring constant k_ij of row i for the edge to j, whose opposite vertices are `left`
/// (apex of the face traversing i -> j) and `right` (apex of the face traversing j -> i).
double spring_constant(SpringWeights weights, const Eigen::Vector3d& pi, const Eigen::Vector3d& pj,
                       const Eigen::Vector3d& left, const Eigen::Vector3d& right) {
  switch (weights) {
    case SpringWeights::inverse_length:
      return 1.0 / (pj - pi).norm();
    case SpringWeights::uniform:
      return 1.0;
    case SpringWeights::cotangent:
      return cotangent_at(pi, pj, left) + cotangent_at(pi, pj, right);
    case SpringWeights::mean_value:
      return (half_angle_tangent(pi, pj, left) + half_angle_tangent(pi, pj, right)) /
             (pj - pi).norm();
  }
  return 0.0;
}

/// The message for a factorisation `method` that failed on the n by n system, for `reason`.
std::string factorisation_failure(const char* caller, const char* method, Eigen::Index n,
                                  const DiskMapOptions& options, const std::string& reason) {
  return std::string(caller) + ": the " + method + " factorisation of the " + std::to_string(n) +
         " by " + std::to_string(n) + " " + to_string(options.weights) + " system failed (" +
         reason + "), expected a non-singular system";
}

/// Throws NumericError unless the solve succeeded and gave finite coordinates.
void require_finite(const Eigen::MatrixX2d& solution, bool solved, const DiskMapOptions& options,
                    const char* caller) {
  if (!solved || !solution.allFinite()) {
    throw NumericError(std::string(caller) + ": solving the " + to_string(options.weights) +
                       " system gave non-finite coordinates, expected a non-singular system");
  }
}

/// Eigen's approximate minimum degree ordering of a matrix whose pattern is symmetric already,
/// as Eigen::SimplicialLDLT hands it over (both halves filled in): Eigen::AMDOrdering would first
/// add the transpose to the pattern, at about the cost of the ordering itself.
struct SymmetricAmdOrdering {
  using PermutationType = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;
  void operator()(const Eigen::SparseMatrix<double>& symmetric, PermutationType& inverse) const {
    Eigen::SparseMatrix<double> pattern = symmetric;  // the ordering works in its input
    Eigen::internal::minimum_degree_ordering(pattern, inverse);
  }
};

/// The solution of a symmetric positive-definite system (positive symmetric weights: every
/// free vertex is joined to the fixed border through its edges, so the matrix is an
/// irreducibly diagonally dominant M-matrix), by a sparse Cholesky (LDL^T) factorisation with
/// a fill-reducing ordering: the same solution as a general LU, for a fraction of the cost.
Eigen::MatrixX2d solve_positive_definite(const Eigen::SparseMatrix<double>& matrix,
                                         const Eigen::MatrixX2d& rhs, const DiskMapOptions& options,
                                         const char* caller) {
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, SymmetricAmdOrdering>
      solver(matrix);
  if (solver.info() != Eigen::Success) {
    throw NumericError(
        factorisation_failure(caller, "sparse LDL^T", matrix.rows(), options, "not positive"));
  }
  Eigen::MatrixX2d solution = solver.solve(rhs);
  require_finite(solution, solver.info() == Eigen::Success, options, caller);
  return solution;
}

/// The solution of a general (possibly unsymmetric or indefinite) system by sparse LU.
Eigen::MatrixX2d solve_general(const Eigen::SparseMatrix<double>& matrix,
                               const Eigen::MatrixX2d& rhs, const DiskMapOptions& options,
                               const char* caller) {
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> solver;
  solver.compute(matrix);
  if (solver.info() != Eigen::Success) {
    throw NumericError(factorisation_failure(caller, "sparse LU", matrix.rows(), options,
                                             solver.lastErrorMessage()));
  }
  Eigen::MatrixX2d solution = solver.solve(rhs);
  require_finite(solution, solver.info() == Eigen::Success, options, caller);
  return solution;
}

}  // namespace

const char* to_string(SpringWeights weights) {
  return spring_weights_names[static_cast<std::size_t>(weights)];
}

std::optional<SpringWeights> spring_weights_from_name(const std::string& name) {
  for (std::size_t i = 0; i < spring_weights_names.size(); ++i) {
    if (name == spring_weights_names[i]) return static_cast<SpringWeights>(i);
  }
  return std::nullopt;
}

void check_disk_map_input(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                          const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                          const std::vector<int>& outer_boundary) {
  check_and_build(positions, faces, outer_boundary, "check_disk_map_input");
}

DiskMap harmonic_disk_map(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                          const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                          const std::vector<int>& outer_boundary, const DiskMapOptions& options) {
  const char* caller = "harmonic_disk_map";
  const PatchTopology topology = check_and_build(positions, faces, outer_boundary, caller);
  const Halfedges& he = topology.halfedges;
  const Eigen::Index n_vertices = positions.rows();
  const auto nv = static_cast<std::size_t>(n_vertices);

  DiskMap map;
  map.uv.setZero(n_vertices, 2);

  // Border: cumulative arc length from outer_boundary[0], counter-clockwise.
  const std::size_t n_boundary = outer_boundary.size();
  std::vector<double> arc(n_boundary + 1, 0.0);
  for (std::size_t k = 0; k < n_boundary; ++k) {
    const Eigen::Vector3d step = point(positions, outer_boundary[(k + 1) % n_boundary]) -
                                 point(positions, outer_boundary[k]);
    arc[k + 1] = arc[k] + step.norm();
  }
  const double perimeter = arc[n_boundary];
  if (!(perimeter > 0.0)) {
    throw NumericError(std::string(caller) + ": the outer boundary has length " +
                       format_number(perimeter) + " A, expected > 0");
  }
  std::vector<int> free_index(nv, -1);
  std::vector<char> fixed(nv, 0);
  for (std::size_t k = 0; k < n_boundary; ++k) {
    const double angle = arc[k] * (two_pi / perimeter);
    map.uv.row(outer_boundary[k]) << std::cos(angle), std::sin(angle);
    fixed[static_cast<std::size_t>(outer_boundary[k])] = 1;
  }
  int n_free = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!fixed[v]) free_index[v] = n_free++;
  }
  if (n_free == 0) return map;

  // Row i: sum_j k_ij (u_i - u_j) = 0, fixed neighbours moved to the right-hand side.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(he.target.size() + 2 * nv);
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n_free, 2);
  for (int i = 0; i < n_vertices; ++i) {
    const int row = free_index[static_cast<std::size_t>(i)];
    if (row < 0) continue;
    const Eigen::Vector3d pi = point(positions, i);
    // On a hole, the missing triangle beside a border edge is the wedge (i, next, previous).
    const int next = topology.next_on_border[static_cast<std::size_t>(i)];
    const int previous = topology.prev_on_border[static_cast<std::size_t>(i)];
    double diagonal = 0.0;
    auto add_neighbour = [&](int j, int left, int right) {
      const double k_ij = spring_constant(options.weights, pi, point(positions, j),
                                          point(positions, left), point(positions, right));
      if (!std::isfinite(k_ij)) {
        throw NumericError(std::string(caller) + ": the " + to_string(options.weights) +
                           " spring constant of edge " + std::to_string(i) + "-" +
                           std::to_string(j) + " is " + format_number(k_ij) +
                           ", expected a finite number (coincident vertices or a degenerate "
                           "triangle)");
      }
      diagonal += k_ij;
      const int column = free_index[static_cast<std::size_t>(j)];
      if (column >= 0) {
        entries.emplace_back(row, column, -k_ij);
      } else {
        rhs.row(row) += k_ij * map.uv.row(j);
      }
    };
    for (int h = he.first[static_cast<std::size_t>(i)];
         h < he.first[static_cast<std::size_t>(i) + 1]; ++h) {
      const int j = he.target[static_cast<std::size_t>(h)];
      const int back = he.find(j, i);
      const int right = back >= 0 ? he.apex[static_cast<std::size_t>(back)] : previous;
      add_neighbour(j, he.apex[static_cast<std::size_t>(h)], right);
    }
    if (previous >= 0) {
      // previous -> i is a border edge: no face traverses i -> previous.
      const int back = he.find(previous, i);
      add_neighbour(previous, next, he.apex[static_cast<std::size_t>(back)]);
    }
    entries.emplace_back(row, row, diagonal);
  }
  Eigen::SparseMatrix<double> matrix(n_free, n_free);
  matrix.setFromTriplets(entries.begin(), entries.end());
  const Eigen::MatrixX2d solution =
      options.weights == SpringWeights::inverse_length || options.weights == SpringWeights::uniform
          ? solve_positive_definite(matrix, rhs, options, caller)
          : solve_general(matrix, rhs, options, caller);
  for (std::size_t v = 0; v < nv; ++v) {
    if (free_index[v] >= 0) map.uv.row(static_cast<Eigen::Index>(v)) = solution.row(free_index[v]);
  }
  return map;
}

int count_flipped_triangles(const Eigen::Ref<const Eigen::MatrixX2d>& uv,
                            const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
  int flipped = 0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      if (faces(f, c) < 0 || faces(f, c) >= uv.rows()) {
        throw InputError("map distortion: face " + std::to_string(f) + " has vertex index " +
                         std::to_string(faces(f, c)) + ", expected " + vertex_range(uv.rows()));
      }
    }
    const Eigen::Vector2d a = uv.row(faces(f, 0)).transpose();
    const Eigen::Vector2d b = uv.row(faces(f, 1)).transpose();
    const Eigen::Vector2d c = uv.row(faces(f, 2)).transpose();
    const double twice_area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (!(twice_area > 0.0)) ++flipped;
  }
  return flipped;
}

}  // namespace surfcomp::harmonic
