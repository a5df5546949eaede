// Test patches for the harmonic disk map (tests/harmonic/disk_map_test.cpp,
// bench/disk_map_bench.cpp): analytic meshes cut the way a patch extractor does (method §3: a ball
// of vertices, dangling triangles removed, border loops walked with the patch on their left, the
// longest outer).
#pragma once

#include "analytic_meshes.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::test {

/// A test patch: patch-local arrays and its border loops, found as a patch extractor would.
struct TestPatch {
  std::string name;
  Eigen::MatrixX3d positions;
  Eigen::MatrixX3i faces;
  std::vector<int> outer_boundary;  ///< counter-clockwise seen from outside, lowest index first
  std::size_t n_holes = 0;
};

inline MeshArrays arrays_of(const mesh::Surface& surface) {
  return {surface.positions(), surface.faces()};
}

/// The patch made of the faces of `mesh` with keep[f] set: dangling triangles (two or more
/// border edges) are removed until none is left, vertices are renumbered in increasing
/// order, and the border loops are walked with the patch on their left; the longest is the
/// outer boundary, started at its lowest vertex index.
inline TestPatch cut_patch(const std::string& name, const MeshArrays& mesh,
                           std::vector<char> keep) {
  auto edge_key = [&](int a, int b) {
    return static_cast<long long>(a) * mesh.positions.rows() + b;
  };
  for (bool changed = true; changed;) {
    changed = false;
    std::map<long long, int> directed;
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
      if (!keep[static_cast<std::size_t>(f)]) continue;
      for (int c = 0; c < 3; ++c)
        ++directed[edge_key(mesh.faces(f, c), mesh.faces(f, (c + 1) % 3))];
    }
    for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
      if (!keep[static_cast<std::size_t>(f)]) continue;
      int border_edges = 0;
      for (int c = 0; c < 3; ++c) {
        border_edges += directed.count(edge_key(mesh.faces(f, (c + 1) % 3), mesh.faces(f, c))) == 0;
      }
      if (border_edges >= 2) {
        keep[static_cast<std::size_t>(f)] = 0;
        changed = true;
      }
    }
  }
  std::vector<int> local(static_cast<std::size_t>(mesh.positions.rows()), -1);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    if (!keep[static_cast<std::size_t>(f)]) continue;
    for (int c = 0; c < 3; ++c) local[static_cast<std::size_t>(mesh.faces(f, c))] = 0;
  }
  TestPatch patch;
  patch.name = name;
  std::vector<int> global;
  for (std::size_t v = 0; v < local.size(); ++v) {
    if (local[v] < 0) continue;
    local[v] = static_cast<int>(global.size());
    global.push_back(static_cast<int>(v));
  }
  patch.positions.resize(static_cast<Eigen::Index>(global.size()), 3);
  for (std::size_t v = 0; v < global.size(); ++v) {
    patch.positions.row(static_cast<Eigen::Index>(v)) = mesh.positions.row(global[v]);
  }
  std::vector<Eigen::Vector3i> faces;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    if (!keep[static_cast<std::size_t>(f)]) continue;
    faces.emplace_back(local[static_cast<std::size_t>(mesh.faces(f, 0))],
                       local[static_cast<std::size_t>(mesh.faces(f, 1))],
                       local[static_cast<std::size_t>(mesh.faces(f, 2))]);
  }
  patch.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    patch.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();

  std::map<std::pair<int, int>, int> directed;
  for (const auto& face : faces) {
    for (int c = 0; c < 3; ++c) directed[{face[c], face[(c + 1) % 3]}] = 1;
  }
  std::map<int, int> next;
  for (const auto& [edge, unused] : directed) {
    if (directed.count({edge.second, edge.first}) == 0) {
      if (next.count(edge.first) != 0) {
        throw std::logic_error(name + ": bow-tie at vertex " + std::to_string(edge.first));
      }
      next[edge.first] = edge.second;
    }
  }
  std::vector<std::vector<int>> loops;
  while (!next.empty()) {
    std::vector<int> loop = {next.begin()->first};  // lowest remaining index
    for (int v = next.at(loop.front()); v != loop.front(); v = next.at(v)) loop.push_back(v);
    for (const int v : loop) next.erase(v);
    loops.push_back(loop);
  }
  auto perimeter = [&](const std::vector<int>& loop) {
    double length = 0.0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Eigen::RowVector3d step =
          patch.positions.row(loop[(k + 1) % loop.size()]) - patch.positions.row(loop[k]);
      length += step.norm();
    }
    return length;
  };
  std::size_t outer = 0;
  for (std::size_t l = 1; l < loops.size(); ++l) {
    if (perimeter(loops[l]) > perimeter(loops[outer])) outer = l;
  }
  patch.outer_boundary = loops.at(outer);
  patch.n_holes = loops.size() - 1;
  return patch;
}

/// The faces of `mesh` whose three vertices lie within Euclidean distance `radius` of vertex
/// `center`.
inline std::vector<char> faces_within(const MeshArrays& mesh, int center, double radius) {
  std::vector<char> keep(static_cast<std::size_t>(mesh.faces.rows()), 0);
  const Eigen::RowVector3d c = mesh.positions.row(center);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    bool inside = true;
    for (int k = 0; k < 3; ++k)
      inside = inside && (mesh.positions.row(mesh.faces(f, k)) - c).norm() <= radius;
    keep[static_cast<std::size_t>(f)] = inside;
  }
  return keep;
}

/// The vertex of `mesh` nearest to `point`.
inline int nearest_vertex(const MeshArrays& mesh, const Eigen::Vector3d& point) {
  Eigen::Index best = 0;
  (mesh.positions.rowwise() - point.transpose()).rowwise().squaredNorm().minCoeff(&best);
  return static_cast<int>(best);
}

/// (a) A cap of a sphere of radius 5 A (frequency 12), 170 vertices.
inline TestPatch sphere_cap_patch() {
  MeshArrays sphere = unit_icosphere_arrays(12);
  sphere.positions *= 5.0;
  const int center = nearest_vertex(sphere, 5.0 * Eigen::Vector3d(0.3, 0.5, 0.8).normalized());
  return cut_patch("sphere cap", sphere, faces_within(sphere, center, 3.5));
}

/// (b) A patch of the ellipsoid with semi-axes 6, 4, 3 A (frequency 14) away from its axes,
/// where the principal curvatures differ; 173 vertices.
inline TestPatch ellipsoid_patch() {
  MeshArrays ellipsoid_mesh = arrays_of(ellipsoid(6.0, 4.0, 3.0, 14));
  const int center = nearest_vertex(ellipsoid_mesh, Eigen::Vector3d(4.0, 2.2, 1.5));
  return cut_patch("ellipsoid", ellipsoid_mesh, faces_within(ellipsoid_mesh, center, 2.4));
}

/// (c) A torus patch (major radius 4 A, tube 1.5 A) over theta in [0, 2 pi 14/48] and phi
/// from the outer equator over the top to the inner side, with a hole: the triangles around
/// two neighbouring vertices are left out.
inline TestPatch torus_patch_with_hole() {
  const int n_major = 48, n_minor = 24;
  MeshArrays torus_mesh = arrays_of(torus(4.0, 1.5, n_major, n_minor));
  std::vector<char> keep(static_cast<std::size_t>(torus_mesh.faces.rows()), 0);
  const std::vector<int> hole_vertices = {6 * n_minor + 5, 7 * n_minor + 5};
  for (int i = 0; i < 14; ++i) {
    for (int j = 0; j < 12; ++j) {
      for (int half = 0; half < 2; ++half) {
        const int f = 2 * (i * n_minor + j) + half;
        bool touches_hole = false;
        for (int c = 0; c < 3; ++c) {
          touches_hole = touches_hole || std::count(hole_vertices.begin(), hole_vertices.end(),
                                                    torus_mesh.faces(f, c)) > 0;
        }
        keep[static_cast<std::size_t>(f)] = !touches_hole;
      }
    }
  }
  return cut_patch("torus with hole", torus_mesh, keep);
}

inline std::vector<TestPatch> analytic_patches() {
  return {sphere_cap_patch(), ellipsoid_patch(), torus_patch_with_hole()};
}

}  // namespace surfcomp::test
