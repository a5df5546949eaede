#include "dual_marching_cubes.hpp"

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace surfcomp::molsurf::detail {
namespace {

/// The corner with offsets (x, y, z) in {0, 1}.
constexpr int corner_at(int x, int y, int z) { return x | (y << 1) | (z << 2); }

/// The corner with offset `along_a` along axis a, `along_b` along (a + 1) % 3 and `along_c`
/// along (a + 2) % 3.
constexpr int corner_on_axes(int a, int along_a, int along_b, int along_c) {
  std::array<int, 3> offset{};
  offset[static_cast<std::size_t>(a)] = along_a;
  offset[static_cast<std::size_t>((a + 1) % 3)] = along_b;
  offset[static_cast<std::size_t>((a + 2) % 3)] = along_c;
  return corner_at(offset[0], offset[1], offset[2]);
}

/// The cube's edges and faces in the numbering of CellTopology, derived from it.
struct CubeGeometry {
  std::array<std::array<int, 2>, 12> edge_corners{};  ///< the ends of edge e, lower first
  std::array<std::array<int, 4>, 6> face_corners{};   ///< face f's corners in cyclic order
  std::array<std::array<int, 4>, 6> face_edges{};     ///< edge i joins face corners i, i + 1
};

constexpr CubeGeometry make_cube_geometry() {
  CubeGeometry g{};
  for (int a = 0; a < 3; ++a) {
    for (int u = 0; u < 2; ++u) {
      for (int v = 0; v < 2; ++v) {
        auto& ends =
            g.edge_corners[static_cast<std::size_t>(a) * 4 + static_cast<std::size_t>(u + 2 * v)];
        ends[0] = corner_on_axes(a, 0, u, v);
        ends[1] = corner_on_axes(a, 1, u, v);
      }
    }
  }
  constexpr std::array<std::array<int, 2>, 4> square = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  for (int a = 0; a < 3; ++a) {
    for (int s = 0; s < 2; ++s) {
      const std::size_t f = static_cast<std::size_t>(a) * 2 + static_cast<std::size_t>(s);
      auto& corners = g.face_corners[f];
      auto& edges = g.face_edges[f];
      for (std::size_t i = 0; i < 4; ++i) {
        corners[i] = corner_on_axes(a, s, square[i][0], square[i][1]);
      }
      for (std::size_t i = 0; i < 4; ++i) {
        const int p = corners[i];
        const int q = corners[(i + 1) % 4];
        for (int e = 0; e < 12; ++e) {
          const auto& ends = g.edge_corners[static_cast<std::size_t>(e)];
          if ((ends[0] == p && ends[1] == q) || (ends[0] == q && ends[1] == p)) edges[i] = e;
        }
      }
    }
  }
  return g;
}

constexpr CubeGeometry cube = make_cube_geometry();

constexpr bool is_inside(std::uint8_t inside, int corner) { return ((inside >> corner) & 1U) != 0; }

constexpr int find_root(const std::array<int, 12>& parent, int e) {
  while (parent[static_cast<std::size_t>(e)] != e) e = parent[static_cast<std::size_t>(e)];
  return e;
}

constexpr void join(std::array<int, 12>& parent, int a, int b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
}

/// Segments on one face of a cell: pairs of face-edge positions (0-3, see
/// CubeGeometry::face_edges).
struct FaceSegments {
  int count = 0;
  std::array<std::array<int, 2>, 2> segment{};
};

/// The segments the marching-cubes surface draws on face f of a cell. Two crossings give one
/// segment; four (an ambiguous face) give two, each cutting off an outside corner, so that the
/// face joins its inside corners.
constexpr FaceSegments face_segments(std::uint8_t inside, int f) {
  const auto& corners = cube.face_corners[static_cast<std::size_t>(f)];
  std::array<int, 4> crossed{};
  FaceSegments out;
  int crossings = 0;
  for (int i = 0; i < 4; ++i) {
    if (is_inside(inside, corners[static_cast<std::size_t>(i)]) !=
        is_inside(inside, corners[static_cast<std::size_t>((i + 1) % 4)])) {
      crossed[static_cast<std::size_t>(crossings++)] = i;
    }
  }
  if (crossings == 2) {
    out.count = 1;
    out.segment[0] = {crossed[0], crossed[1]};
  } else if (crossings == 4) {
    for (int i = 0; i < 4; ++i) {
      if (!is_inside(inside, corners[static_cast<std::size_t>(i)])) {
        out.segment[static_cast<std::size_t>(out.count++)] = {(i + 3) % 4, i};
      }
    }
  }
  return out;
}

/// The one ambiguous face of a cell with two or three inside corners, or -1 when it has none
/// or several.
constexpr int lone_ambiguous_face(std::uint8_t inside) {
  int inside_corners = 0;
  for (int c = 0; c < 8; ++c) inside_corners += is_inside(inside, c) ? 1 : 0;
  if (inside_corners < 2 || inside_corners > 3) return -1;
  int face = -1;
  for (int f = 0; f < 6; ++f) {
    if (face_segments(inside, f).count != 2) continue;
    if (face >= 0) return -1;
    face = f;
  }
  return face;
}

/// The loops of the cell whose corner c is inside iff bit c of `inside` is set: the classes of
/// crossed edges joined by the face segments.
constexpr CellTopology compute_cell_topology(std::uint8_t inside) {
  std::array<int, 12> parent{};
  for (int e = 0; e < 12; ++e) parent[static_cast<std::size_t>(e)] = e;
  for (int f = 0; f < 6; ++f) {
    const auto& edges = cube.face_edges[static_cast<std::size_t>(f)];
    const FaceSegments segments = face_segments(inside, f);
    for (int s = 0; s < segments.count; ++s) {
      const auto& ends = segments.segment[static_cast<std::size_t>(s)];
      join(parent, edges[static_cast<std::size_t>(ends[0])],
           edges[static_cast<std::size_t>(ends[1])]);
    }
  }
  // Loops numbered in the order of their lowest edge.
  CellTopology out;
  std::array<int, 12> loop_of_root{};
  for (auto& loop : loop_of_root) loop = -1;
  for (std::size_t e = 0; e < 12; ++e) {
    out.loop[e] = -1;
    const auto& ends = cube.edge_corners[e];
    if (is_inside(inside, ends[0]) == is_inside(inside, ends[1])) continue;
    auto& loop = loop_of_root[static_cast<std::size_t>(find_root(parent, static_cast<int>(e)))];
    if (loop < 0) loop = out.loops++;
    out.loop[e] = loop;
  }
  for (int f = 0; f < 6; ++f) {
    const auto& edges = cube.face_edges[static_cast<std::size_t>(f)];
    const FaceSegments segments = face_segments(inside, f);
    if (segments.count != 2) continue;
    const auto first =
        static_cast<std::size_t>(edges[static_cast<std::size_t>(segments.segment[0][0])]);
    const auto second =
        static_cast<std::size_t>(edges[static_cast<std::size_t>(segments.segment[1][0])]);
    if (out.loop[first] == out.loop[second]) {
      out.one_loop_faces = static_cast<std::uint8_t>(out.one_loop_faces | (1U << f));
    }
  }
  out.lone_ambiguous_face = lone_ambiguous_face(inside);
  return out;
}

constexpr std::array<CellTopology, 256> make_cell_table() {
  std::array<CellTopology, 256> table{};
  for (int inside = 0; inside < 256; ++inside) {
    table[static_cast<std::size_t>(inside)] =
        compute_cell_topology(static_cast<std::uint8_t>(inside));
  }
  return table;
}

/// The case table: the loops of each of the 256 sign configurations of a cell.
constexpr std::array<CellTopology, 256> cell_table = make_cell_table();

constexpr int most_loops() {
  int most = 0;
  for (const CellTopology& t : cell_table) most = std::max(most, t.loops);
  return most;
}

/// The most loops a cell has (marching cubes: four, in the checkerboard configurations).
constexpr std::size_t max_loops = 4;
static_assert(most_loops() == max_loops, "a cell has at most four loops");

constexpr int lone_face_patterns() {
  int count = 0;
  for (const CellTopology& t : cell_table) count += t.lone_ambiguous_face >= 0 ? 1 : 0;
  return count;
}

/// Twelve patterns of two inside corners on a face diagonal, 24 with a third inside corner that
/// leaves the face the only ambiguous one: the 36 of OpenVDB's table of such patterns.
static_assert(lone_face_patterns() == 36, "36 patterns have one ambiguous face");

/// A cell the surface passes through.
struct ActiveCell {
  GridCoord coord;
  std::uint8_t inside = 0;    ///< its sign pattern
  std::uint8_t topology = 0;  ///< the pattern whose cell_table entry it takes (see cut_faces)
  int first_vertex = 0;       ///< its loops' vertices are first_vertex + loop
  std::array<float, 8> values{};
};

/// The crossing point (index space) on edge e of the cell at `coord` with corner values `v`.
Eigen::Vector3d crossing_point(const GridCoord& coord, int e, const std::array<float, 8>& v) {
  const auto& ends = cube.edge_corners[static_cast<std::size_t>(e)];
  const double v0 = v[static_cast<std::size_t>(ends[0])];
  const double v1 = v[static_cast<std::size_t>(ends[1])];
  const double t = v0 / (v0 - v1);
  Eigen::Vector3d p(coord[0] + (ends[0] & 1), coord[1] + ((ends[0] >> 1) & 1),
                    coord[2] + (ends[0] >> 2));
  p[e / 4] += t;
  return p;
}

/// Active cells and their vertices, with a lookup by cell coordinate.
class CellIndex {
 public:
  void add(const ActiveCell& cell) {
    const GridCoord block = SparseGrid::block_of(cell.coord);
    const GridCoord local = SparseGrid::offset_in_block(cell.coord);
    const auto [it, inserted] = tables_.try_emplace(block, slots_.size());
    if (inserted) slots_.emplace_back().fill(-1);
    slots_[it->second][slot(local)] = static_cast<int>(cells_.size());
    cells_.push_back(cell);
  }

  /// The active cell at `coord`; it must exist.
  const ActiveCell& at(const GridCoord& coord) const {
    const GridCoord local = SparseGrid::offset_in_block(coord);
    const int index = slots_[tables_.at(SparseGrid::block_of(coord))][slot(local)];
    return cells_[static_cast<std::size_t>(index)];
  }

  const std::vector<ActiveCell>& cells() const { return cells_; }
  std::vector<ActiveCell>& cells() { return cells_; }

 private:
  static std::size_t slot(const GridCoord& local) {
    return SparseGrid::Block::index(local[0], local[1], local[2]);
  }

  std::vector<ActiveCell> cells_;
  std::unordered_map<GridCoord, std::size_t, GridCoordHash> tables_;
  std::vector<std::array<int, SparseGrid::block_nodes>> slots_;
};

GridCoord plus(const GridCoord& a, int dx, int dy, int dz) {
  return {a[0] + dx, a[1] + dy, a[2] + dz};
}

/// The blocks whose cells may touch a stored block: each stored block and its neighbours below
/// (a cell reads the nodes of its own block and of the blocks above it), sorted.
std::vector<GridCoord> candidate_blocks(const SparseGrid& grid) {
  std::vector<GridCoord> out;
  out.reserve(8 * grid.block_coords().size());
  for (const GridCoord& b : grid.block_coords()) {
    for (int d = 0; d < 8; ++d) out.push_back(plus(b, -(d & 1), -((d >> 1) & 1), -(d >> 2)));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// Finds the active cells of the cells whose lowest corner lies in block `block`, appending
/// them to `index`.
void scan_block(const SparseGrid& grid, const GridCoord& block, CellIndex& index) {
  constexpr int w = SparseGrid::block_width;
  std::array<const SparseGrid::Block*, 8> near{};
  bool mixed = false;
  bool any_inside = false;
  bool any_outside = false;
  for (int d = 0; d < 8; ++d) {
    near[static_cast<std::size_t>(d)] = grid.find_block(plus(block, d & 1, (d >> 1) & 1, d >> 2));
    const SparseGrid::Block* b = near[static_cast<std::size_t>(d)];
    if (b != nullptr && !b->uniform) {
      mixed = true;
    } else {
      const float v = b == nullptr ? grid.background() : b->uniform_value;
      (v < 0.0F ? any_inside : any_outside) = true;
    }
  }
  if (!mixed && !(any_inside && any_outside)) return;

  // The block's nodes and the first layer of the blocks above, (w + 1)^3 values.
  constexpr int n = w + 1;
  const auto at = [](int i, int j, int k) {
    constexpr auto m = static_cast<std::size_t>(n);
    return (static_cast<std::size_t>(i) * m + static_cast<std::size_t>(j)) * m +
           static_cast<std::size_t>(k);
  };
  std::array<float, static_cast<std::size_t>(n) * n * n> values{};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        const int d = (i / w) | ((j / w) << 1) | ((k / w) << 2);
        const SparseGrid::Block* b = near[static_cast<std::size_t>(d)];
        values[at(i, j, k)] = b == nullptr ? grid.background() : b->at(i % w, j % w, k % w);
      }
    }
  }
  const GridCoord origin = {w * block[0], w * block[1], w * block[2]};
  for (int i = 0; i < w; ++i) {
    for (int j = 0; j < w; ++j) {
      for (int k = 0; k < w; ++k) {
        std::array<float, 8> v{};
        std::uint8_t inside = 0;
        for (int c = 0; c < 8; ++c) {
          v[static_cast<std::size_t>(c)] =
              values[at(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2))];
          if (v[static_cast<std::size_t>(c)] < 0.0F) inside |= static_cast<std::uint8_t>(1U << c);
        }
        if (inside == 0 || inside == 0xFF) continue;
        ActiveCell cell;
        cell.coord = plus(origin, i, j, k);
        cell.inside = inside;
        cell.topology = inside;
        cell.values = v;
        index.add(cell);
      }
    }
  }
}

/// The face rule's exception (OpenVDB's): where two cells share an ambiguous face that is the
/// only one of each and each has two or three inside corners, both take the complement's loops,
/// which separate that face's inside corners. A bridge of the solid thinner than a voxel, with
/// nothing else ambiguous around it, is cut there rather than kept as a handle; and these are the
/// faces where both cells would otherwise put both segments in one loop (dual_marching_cubes).
void cut_faces(CellIndex& index) {
  for (ActiveCell& cell : index.cells()) {
    const int face = cell_table[cell.inside].lone_ambiguous_face;
    if (face < 0) continue;
    const int axis = face / 2;
    const int side = face % 2;
    GridCoord across = cell.coord;
    across[static_cast<std::size_t>(axis)] += side == 1 ? 1 : -1;
    if (cell_table[index.at(across).inside].lone_ambiguous_face == (face ^ 1)) {
      cell.topology = static_cast<std::uint8_t>(~cell.inside);
    }
  }
}

/// Each cell's loop vertices (index space), appended to `points`: the mean of the loop's edge
/// crossings.
void place_vertices(CellIndex& index, std::vector<Eigen::Vector3d>& points) {
  for (ActiveCell& cell : index.cells()) {
    const CellTopology& topology = cell_table[cell.topology];
    cell.first_vertex = static_cast<int>(points.size());
    std::array<Eigen::Vector3d, max_loops> sum{};
    std::array<int, max_loops> count{};
    for (auto& s : sum) s.setZero();
    for (int e = 0; e < 12; ++e) {
      const int loop = topology.loop[static_cast<std::size_t>(e)];
      if (loop < 0) continue;
      sum[static_cast<std::size_t>(loop)] += crossing_point(cell.coord, e, cell.values);
      ++count[static_cast<std::size_t>(loop)];
    }
    for (std::size_t l = 0; l < static_cast<std::size_t>(topology.loops); ++l) {
      points.push_back(sum[l] / count[l]);
    }
  }
}

/// Appends the two triangles of quad a b c d (counter-clockwise), split along its shorter
/// diagonal.
void split_quad(const std::array<int, 4>& quad, const std::vector<Eigen::Vector3d>& points,
                std::vector<std::array<int, 3>>& triangles) {
  const auto [a, b, c, d] = quad;
  const double ac =
      (points[static_cast<std::size_t>(a)] - points[static_cast<std::size_t>(c)]).squaredNorm();
  const double bd =
      (points[static_cast<std::size_t>(b)] - points[static_cast<std::size_t>(d)]).squaredNorm();
  if (ac <= bd) {
    triangles.push_back({a, b, c});
    triangles.push_back({a, c, d});
  } else {
    triangles.push_back({a, b, d});
    triangles.push_back({b, c, d});
  }
}

/// The triangles of the quads around every grid edge whose ends differ in sign.
std::vector<std::array<int, 3>> edge_quads(const CellIndex& index,
                                           const std::vector<Eigen::Vector3d>& points) {
  // The four cells around an edge along axis a, counter-clockwise seen from its positive end:
  // offsets (along (a + 1) % 3, along (a + 2) % 3) subtracted from the edge's lower node.
  constexpr std::array<std::array<int, 2>, 4> ring = {{{1, 1}, {0, 1}, {0, 0}, {1, 0}}};
  std::vector<std::array<int, 3>> triangles;
  for (const ActiveCell& cell : index.cells()) {
    for (int a = 0; a < 3; ++a) {
      const bool lower_inside = is_inside(cell.inside, 0);
      if (lower_inside == is_inside(cell.inside, 1 << a)) continue;
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      std::array<int, 4> quad{};
      for (std::size_t r = 0; r < 4; ++r) {
        GridCoord around = cell.coord;
        around[static_cast<std::size_t>(b)] -= ring[r][0];
        around[static_cast<std::size_t>(c)] -= ring[r][1];
        const ActiveCell& owner = index.at(around);
        const int e = 4 * a + ring[r][0] + 2 * ring[r][1];
        quad[r] = owner.first_vertex + cell_table[owner.topology].loop[static_cast<std::size_t>(e)];
      }
      if (!lower_inside) std::reverse(quad.begin(), quad.end());
      split_quad(quad, points, triangles);
    }
  }
  return triangles;
}

}  // namespace

CellTopology cell_topology(std::uint8_t inside) { return cell_table[inside]; }

TriangleSoup dual_marching_cubes(const SparseGrid& grid, double spacing) {
  CellIndex index;
  std::vector<Eigen::Vector3d> points;
  for (const GridCoord& block : candidate_blocks(grid)) scan_block(grid, block, index);
  cut_faces(index);
  place_vertices(index, points);
  std::vector<std::array<int, 3>> triangles = edge_quads(index, points);

  // Canonical order: vertices by coordinates, faces by indices.
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Eigen::Vector3d& p = points[static_cast<std::size_t>(a)];
    const Eigen::Vector3d& q = points[static_cast<std::size_t>(b)];
    return std::tie(p[0], p[1], p[2], a) < std::tie(q[0], q[1], q[2], b);
  });
  std::vector<int> rank(points.size());
  TriangleSoup soup;
  soup.positions.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < order.size(); ++i) {
    rank[static_cast<std::size_t>(order[i])] = static_cast<int>(i);
    soup.positions.row(static_cast<Eigen::Index>(i)) =
        spacing * points[static_cast<std::size_t>(order[i])].transpose();
  }
  for (auto& t : triangles) {
    for (int& v : t) v = rank[static_cast<std::size_t>(v)];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  }
  std::sort(triangles.begin(), triangles.end());
  soup.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    soup.faces.row(static_cast<Eigen::Index>(f)) << triangles[f][0], triangles[f][1],
        triangles[f][2];
  }
  return soup;
}

}  // namespace surfcomp::molsurf::detail
