// Test-only analytic surfaces with known geometry: an icosphere (geodesic subdivision of the
// icosahedron projected to a sphere), an ellipsoid (a scaled icosphere), a torus, a planar
// disk, and the regular tetrahedron and octahedron. Each returns a mesh::Surface built with
// Surface::from_arrays (no normals set), faces counter-clockwise seen from outside (the disk:
// seen from +z).
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::test {

/// Vertex positions (#V by 3) and triangles (#F by 3) before they become a Surface.
struct MeshArrays {
  Eigen::MatrixX3d positions;
  Eigen::MatrixX3i faces;
};

/// The unit icosphere of class I geodesic frequency `frequency` (>= 1): every icosahedron edge
/// is split into `frequency` segments, every face into frequency^2 triangles, and the vertices
/// are projected onto the unit sphere. #V = 10 * frequency^2 + 2, #F = 20 * frequency^2.
inline MeshArrays unit_icosphere_arrays(int frequency) {
  if (frequency < 1) throw std::invalid_argument("icosphere frequency must be >= 1");
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  const std::array<Eigen::Vector3d, 12> corners = {
      Eigen::Vector3d(-1, phi, 0),  Eigen::Vector3d(1, phi, 0),   Eigen::Vector3d(-1, -phi, 0),
      Eigen::Vector3d(1, -phi, 0),  Eigen::Vector3d(0, -1, phi),  Eigen::Vector3d(0, 1, phi),
      Eigen::Vector3d(0, -1, -phi), Eigen::Vector3d(0, 1, -phi),  Eigen::Vector3d(phi, 0, -1),
      Eigen::Vector3d(phi, 0, 1),   Eigen::Vector3d(-phi, 0, -1), Eigen::Vector3d(-phi, 0, 1)};
  const std::array<std::array<int, 3>, 20> icosahedron = {
      {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
       {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
       {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}}};
  const int n = frequency;
  // A point (i*A + j*B + k*C) / n is keyed by its corners and weights, sorted by corner, so
  // that the faces sharing an edge or a corner share the vertex.
  std::map<std::array<int, 6>, int> index_of;
  std::vector<Eigen::Vector3d> points;
  auto vertex = [&](const std::array<int, 3>& face, int i, int j) {
    std::array<std::pair<int, int>, 3> terms = {{{face[0], i}, {face[1], j}, {face[2], n - i - j}}};
    std::sort(terms.begin(), terms.end());
    std::array<int, 6> key{};
    int slot = 0;
    for (const auto& [corner, weight] : terms) {
      if (weight == 0) continue;
      key[static_cast<std::size_t>(slot++)] = corner + 1;
      key[static_cast<std::size_t>(slot++)] = weight;
    }
    const auto found = index_of.find(key);
    if (found != index_of.end()) return found->second;
    const Eigen::Vector3d p = (i * corners[static_cast<std::size_t>(face[0])] +
                               j * corners[static_cast<std::size_t>(face[1])] +
                               (n - i - j) * corners[static_cast<std::size_t>(face[2])]) /
                              static_cast<double>(n);
    points.push_back(p.normalized());
    const int id = static_cast<int>(points.size()) - 1;
    index_of.emplace(key, id);
    return id;
  };
  std::vector<std::array<int, 3>> triangles;
  for (const auto& face : icosahedron) {
    // Lattice (i, j): weight i on corner 0, j on corner 1, the rest on corner 2. Moving from
    // corner 2 towards corner 0 then corner 1 keeps the face's counter-clockwise order.
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        const int a = vertex(face, i, j);
        const int b = vertex(face, i + 1, j);
        const int c = vertex(face, i, j + 1);
        triangles.push_back({c, a, b});
        if (i + j + 1 < n) {
          const int d = vertex(face, i + 1, j + 1);
          triangles.push_back({c, b, d});
        }
      }
    }
  }
  MeshArrays out;
  out.positions.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v) {
    out.positions.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
  }
  out.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    out.faces.row(static_cast<Eigen::Index>(f)) << triangles[f][0], triangles[f][1],
        triangles[f][2];
  }
  // Orient outward: the signed volume of a face with a corner at the origin is positive.
  for (Eigen::Index f = 0; f < out.faces.rows(); ++f) {
    const Eigen::Vector3d a = out.positions.row(out.faces(f, 0));
    const Eigen::Vector3d b = out.positions.row(out.faces(f, 1));
    const Eigen::Vector3d c = out.positions.row(out.faces(f, 2));
    if (a.dot(b.cross(c)) < 0) std::swap(out.faces(f, 1), out.faces(f, 2));
  }
  return out;
}

/// Sphere of radius `radius` (A) centred at `centre`, geodesic frequency `frequency`.
inline mesh::Surface icosphere(double radius, int frequency,
                               const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  MeshArrays m = unit_icosphere_arrays(frequency);
  m.positions *= radius;
  m.positions.rowwise() += centre.transpose();
  return mesh::Surface::from_arrays(m.positions, m.faces, "icosphere");
}

/// The geodesic frequency whose icosphere of radius `radius` has about `vertices_per_a2`
/// vertices per A^2 (at least 1).
inline int icosphere_frequency_for_density(double radius, double vertices_per_a2) {
  const double vertices = vertices_per_a2 * 4.0 * M_PI * radius * radius;
  return std::max(1, static_cast<int>(std::lround(std::sqrt(std::max(0.0, vertices - 2) / 10))));
}

/// Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 (semi-axes in A): the unit icosphere scaled.
inline mesh::Surface ellipsoid(double a, double b, double c, int frequency) {
  MeshArrays m = unit_icosphere_arrays(frequency);
  m.positions.col(0) *= a;
  m.positions.col(1) *= b;
  m.positions.col(2) *= c;
  return mesh::Surface::from_arrays(m.positions, m.faces, "ellipsoid");
}

/// Principal curvatures (convex positive, k_max >= k_min, 1/A) of the ellipsoid with semi-axes
/// (a, b, c) at its point p, from the closed forms of the Gaussian and mean curvature.
inline std::pair<double, double> ellipsoid_principal_curvatures(double a, double b, double c,
                                                                const Eigen::Vector3d& p) {
  const double a2 = a * a, b2 = b * b, c2 = c * c;
  const double s =
      p.x() * p.x() / (a2 * a2) + p.y() * p.y() / (b2 * b2) + p.z() * p.z() / (c2 * c2);
  const double gaussian = 1.0 / (a2 * b2 * c2 * s * s);
  const double mean =
      std::abs(p.squaredNorm() - a2 - b2 - c2) / (2.0 * a2 * b2 * c2 * std::pow(s, 1.5));
  const double root = std::sqrt(std::max(0.0, mean * mean - gaussian));
  return {mean + root, mean - root};
}

/// Torus around the z axis with major radius `major` and tube radius `minor` (A), sampled on
/// an n_major by n_minor grid of the angles (theta around the axis, phi around the tube; phi = 0
/// is the outer equator, phi = pi the inner one). Vertex theta_i, phi_j has index i*n_minor + j.
inline mesh::Surface torus(double major, double minor, int n_major, int n_minor) {
  MeshArrays m;
  m.positions.resize(n_major * n_minor, 3);
  for (int i = 0; i < n_major; ++i) {
    const double theta = 2.0 * M_PI * i / n_major;
    for (int j = 0; j < n_minor; ++j) {
      const double phi = 2.0 * M_PI * j / n_minor;
      const double rho = major + minor * std::cos(phi);
      m.positions.row(i * n_minor + j) << rho * std::cos(theta), rho * std::sin(theta),
          minor * std::sin(phi);
    }
  }
  m.faces.resize(2 * n_major * n_minor, 3);
  for (int i = 0; i < n_major; ++i) {
    for (int j = 0; j < n_minor; ++j) {
      const int v00 = i * n_minor + j;
      const int v10 = ((i + 1) % n_major) * n_minor + j;
      const int v01 = i * n_minor + (j + 1) % n_minor;
      const int v11 = ((i + 1) % n_major) * n_minor + (j + 1) % n_minor;
      // d/dtheta x d/dphi points outward, so (v00, v10, v11) is counter-clockwise from outside.
      const int f = 2 * (i * n_minor + j);
      m.faces.row(f) << v00, v10, v11;
      m.faces.row(f + 1) << v00, v11, v01;
    }
  }
  return mesh::Surface::from_arrays(m.positions, m.faces, "torus");
}

/// Planar disk of radius `radius` (A) in the z = 0 plane: a centre vertex and `rings`
/// concentric rings, ring k with 6k vertices at radius k * radius / rings; normal +z.
inline mesh::Surface disk(double radius, int rings) {
  std::vector<Eigen::Vector3d> points = {Eigen::Vector3d::Zero()};
  std::vector<std::vector<int>> ring_ids = {{0}};
  std::vector<std::vector<double>> ring_angles = {{0.0}};
  for (int k = 1; k <= rings; ++k) {
    std::vector<int> ids;
    std::vector<double> angles;
    for (int s = 0; s < 6 * k; ++s) {
      const double angle = 2.0 * M_PI * s / (6 * k);
      const double rho = radius * k / rings;
      ids.push_back(static_cast<int>(points.size()));
      angles.push_back(angle);
      points.emplace_back(rho * std::cos(angle), rho * std::sin(angle), 0.0);
    }
    ring_ids.push_back(ids);
    ring_angles.push_back(angles);
  }
  std::vector<std::array<int, 3>> triangles;
  for (int s = 0; s < 6; ++s) triangles.push_back({0, ring_ids[1][s], ring_ids[1][(s + 1) % 6]});
  for (int k = 2; k <= rings; ++k) {
    // Zip the inner ring (6(k-1) vertices) and the outer ring (6k) by angle.
    const auto& in = ring_ids[k - 1];
    const auto& out = ring_ids[k];
    const std::size_t n_in = in.size(), n_out = out.size();
    std::size_t a = 0, b = 0;
    while (a < n_in || b < n_out) {
      const double next_in = a + 1 <= n_in ? 2.0 * M_PI * (a + 1) / n_in : 1e9;
      const double next_out = b + 1 <= n_out ? 2.0 * M_PI * (b + 1) / n_out : 1e9;
      if (b < n_out && (next_out <= next_in || a == n_in)) {
        triangles.push_back({in[a % n_in], out[b], out[(b + 1) % n_out]});
        ++b;
      } else {
        triangles.push_back({in[a], out[b % n_out], in[(a + 1) % n_in]});
        ++a;
      }
    }
  }
  MeshArrays m;
  m.positions.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v) {
    m.positions.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
  }
  m.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    m.faces.row(static_cast<Eigen::Index>(f)) << triangles[f][0], triangles[f][1], triangles[f][2];
  }
  return mesh::Surface::from_arrays(m.positions, m.faces, "disk");
}

/// The regular tetrahedron (4 vertices) inscribed in the sphere of radius `radius` (A) about
/// `centre`: the smallest closed triangle mesh.
inline mesh::Surface tetrahedron(double radius,
                                 const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  Eigen::MatrixX3d p(4, 3);
  p << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  p *= radius / std::sqrt(3.0);
  p.rowwise() += centre.transpose();
  Eigen::MatrixX3i f(4, 3);
  f << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
  return mesh::Surface::from_arrays(p, f, "tetrahedron");
}

/// The regular octahedron (6 vertices) inscribed in the sphere of radius `radius` (A) about
/// `centre`.
inline mesh::Surface octahedron(double radius,
                                const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  Eigen::MatrixX3d p(6, 3);
  p << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  p *= radius;
  p.rowwise() += centre.transpose();
  Eigen::MatrixX3i f(8, 3);
  f << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return mesh::Surface::from_arrays(p, f, "octahedron");
}

/// Both surfaces in one mesh (two or more connected components): `first`'s vertices, then
/// `second`'s.
inline mesh::Surface merged(const mesh::Surface& first, const mesh::Surface& second) {
  const Eigen::Index n = static_cast<Eigen::Index>(first.n_vertices());
  Eigen::MatrixX3d p(n + static_cast<Eigen::Index>(second.n_vertices()), 3);
  p << first.positions(), second.positions();
  Eigen::MatrixX3i f(static_cast<Eigen::Index>(first.n_faces() + second.n_faces()), 3);
  f << first.faces(), (second.faces().array() + static_cast<int>(n)).matrix();
  return mesh::Surface::from_arrays(p, f, first.source() + " + " + second.source());
}

/// The same surface with every face's orientation reversed (an inside-out surface).
inline mesh::Surface with_flipped_faces(const mesh::Surface& surface) {
  Eigen::MatrixX3i faces = surface.faces();
  faces.col(1).swap(faces.col(2));
  return mesh::Surface::from_arrays(surface.positions(), faces, surface.source() + " (flipped)");
}

/// The surface with its vertex positions replaced (same faces), e.g. after adding noise.
inline mesh::Surface with_positions(const mesh::Surface& surface,
                                    const Eigen::Ref<const Eigen::MatrixX3d>& positions) {
  return mesh::Surface::from_arrays(positions, surface.faces(), surface.source());
}

}  // namespace surfcomp::test
