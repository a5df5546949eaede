#include "surfcomp/mesh/surface.hpp"

#include "surfcomp/core/error.hpp"

#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cmath>

namespace surfcomp::mesh {

std::size_t value_size(ValueType type) {
  switch (type) {
    case ValueType::int8:
    case ValueType::uint8:
      return 1;
    case ValueType::int16:
    case ValueType::uint16:
      return 2;
    case ValueType::int32:
    case ValueType::uint32:
    case ValueType::float32:
      return 4;
    case ValueType::float64:
      return 8;
  }
  return 8;
}

namespace {

/// OpenMesh reports rejected faces on its own error stream; the module turns them into
/// exceptions, so that stream (and its log) stay quiet. Runs once per program.
void quiet_openmesh() {
  static const bool quiet = [] {
    omerr().disable();
    omlog().disable();
    return true;
  }();
  (void)quiet;
}

}  // namespace

Surface::Surface() {
  quiet_openmesh();
  mesh_.request_vertex_normals();
  mesh_.request_face_normals();
}

Surface Surface::from_arrays(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                             const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                             const std::string& source) {
  Surface surface;
  surface.source_ = source;
  TriMesh& mesh = surface.mesh_;
  const Eigen::Index n = positions.rows();
  std::vector<TriMesh::VertexHandle> handles(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!positions.row(i).allFinite()) {
      throw InputError(source + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
    handles[static_cast<std::size_t>(i)] =
        mesh.add_vertex(TriMesh::Point(positions(i, 0), positions(i, 1), positions(i, 2)));
  }
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    std::array<TriMesh::VertexHandle, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const int v = faces(f, k);
      if (v < 0 || v >= n) {
        throw InputError(source + ": face " + std::to_string(f) + " refers to vertex " +
                         std::to_string(v) + ", outside 0.." + std::to_string(n - 1));
      }
      tri[static_cast<std::size_t>(k)] = handles[static_cast<std::size_t>(v)];
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      throw TopologyError(source + ": face " + std::to_string(f) + " repeats a vertex");
    }
    if (!mesh.add_face(tri[0], tri[1], tri[2]).is_valid()) {
      throw TopologyError(source + ": face " + std::to_string(f) +
                          " makes the mesh non-manifold (complex edge or vertex)");
    }
  }
  return surface;
}

Eigen::MatrixX3d Surface::positions() const {
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(mesh_.n_vertices()), 3);
  for (auto v : mesh_.vertices()) {
    const auto& p = mesh_.point(v);
    out.row(v.idx()) << p[0], p[1], p[2];
  }
  return out;
}

Eigen::MatrixX3i Surface::faces() const {
  Eigen::MatrixX3i out(static_cast<Eigen::Index>(mesh_.n_faces()), 3);
  for (auto f : mesh_.faces()) {
    int k = 0;
    for (auto v : mesh_.fv_range(f)) out(f.idx(), k++) = v.idx();
  }
  return out;
}

Eigen::MatrixX3d Surface::normals() const {
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(mesh_.n_vertices()), 3);
  for (auto v : mesh_.vertices()) {
    const auto& n = mesh_.normal(v);
    out.row(v.idx()) << n[0], n[1], n[2];
  }
  return out;
}

void Surface::set_normals(const Eigen::Ref<const Eigen::MatrixX3d>& normals) {
  if (static_cast<std::size_t>(normals.rows()) != mesh_.n_vertices()) {
    throw InputError(source_ + ": " + std::to_string(normals.rows()) + " normals for " +
                     std::to_string(mesh_.n_vertices()) + " vertices");
  }
  for (auto v : mesh_.vertices()) {
    mesh_.set_normal(
        v, TriMesh::Normal(normals(v.idx(), 0), normals(v.idx(), 1), normals(v.idx(), 2)));
  }
  has_normals_ = true;
}

void Surface::compute_normals() {
  std::vector<OpenMesh::Vec3d> sums(mesh_.n_vertices(), OpenMesh::Vec3d(0, 0, 0));
  for (auto f : mesh_.faces()) {
    auto h = mesh_.halfedge_handle(f);
    const auto& a = mesh_.point(mesh_.from_vertex_handle(h));
    const auto& b = mesh_.point(mesh_.to_vertex_handle(h));
    const auto& c = mesh_.point(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h)));
    const OpenMesh::Vec3d area_normal = OpenMesh::cross(b - a, c - a);  // 2 * area * n
    mesh_.set_normal(f, area_normal.norm() > 0 ? area_normal.normalized() : area_normal);
    for (auto v : mesh_.fv_range(f)) sums[static_cast<std::size_t>(v.idx())] += area_normal;
  }
  for (auto v : mesh_.vertices()) {
    const auto& s = sums[static_cast<std::size_t>(v.idx())];
    mesh_.set_normal(v, s.norm() > 0 ? s.normalized() : s);
  }
  has_normals_ = true;
}

bool Surface::has_property(const std::string& name) const {
  return std::find(property_names_.begin(), property_names_.end(), name) != property_names_.end();
}

OpenMesh::VPropHandleT<double> Surface::handle(const std::string& name) const {
  OpenMesh::VPropHandleT<double> h;
  if (!has_property(name) || !mesh_.get_property_handle(h, name)) {
    throw InputError(source_ + ": the surface has no vertex property '" + name + "'");
  }
  return h;
}

Eigen::VectorXd Surface::property(const std::string& name) const {
  const auto h = handle(name);
  const std::vector<double>& data = mesh_.property(h).data_vector();
  return Eigen::Map<const Eigen::VectorXd>(data.data(), static_cast<Eigen::Index>(data.size()));
}

double Surface::property(const std::string& name, std::size_t vertex) const {
  return mesh_.property(handle(name), TriMesh::VertexHandle(static_cast<int>(vertex)));
}

void Surface::set_property(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values,
                           ValueType stored_as) {
  if (static_cast<std::size_t>(values.size()) != mesh_.n_vertices()) {
    throw InputError(source_ + ": property '" + name + "' has " + std::to_string(values.size()) +
                     " values for " + std::to_string(mesh_.n_vertices()) + " vertices");
  }
  OpenMesh::VPropHandleT<double> h;
  if (!has_property(name)) {
    mesh_.add_property(h, name);
    property_names_.push_back(name);
    property_types_.push_back(stored_as);
  } else {
    h = handle(name);
    const auto it = std::find(property_names_.begin(), property_names_.end(), name);
    property_types_[static_cast<std::size_t>(it - property_names_.begin())] = stored_as;
  }
  std::vector<double>& data = mesh_.property(h).data_vector();
  data.assign(values.data(), values.data() + values.size());
}

void Surface::remove_property(const std::string& name) {
  const auto it = std::find(property_names_.begin(), property_names_.end(), name);
  if (it == property_names_.end()) return;
  auto h = handle(name);
  mesh_.remove_property(h);
  property_types_.erase(property_types_.begin() + (it - property_names_.begin()));
  property_names_.erase(it);
}

ValueType Surface::property_type(const std::string& name) const {
  const auto it = std::find(property_names_.begin(), property_names_.end(), name);
  if (it == property_names_.end()) {
    throw InputError(source_ + ": the surface has no vertex property '" + name + "'");
  }
  return property_types_[static_cast<std::size_t>(it - property_names_.begin())];
}

void transform_surface(Surface& surface, const Eigen::Matrix3d& rotation,
                       const Eigen::Vector3d& translation) {
  TriMesh& mesh = surface.mesh();
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    const Eigen::Vector3d moved = rotation * Eigen::Vector3d(p[0], p[1], p[2]) + translation;
    mesh.set_point(v, TriMesh::Point(moved.x(), moved.y(), moved.z()));
    const auto& n = mesh.normal(v);
    const Eigen::Vector3d turned = rotation * Eigen::Vector3d(n[0], n[1], n[2]);
    mesh.set_normal(v, TriMesh::Normal(turned.x(), turned.y(), turned.z()));
  }
  for (auto f : mesh.faces()) {
    const auto& n = mesh.normal(f);
    const Eigen::Vector3d turned = rotation * Eigen::Vector3d(n[0], n[1], n[2]);
    mesh.set_normal(f, TriMesh::Normal(turned.x(), turned.y(), turned.z()));
  }
}

/// Barycentric vertex areas: a third of the area of every incident triangle, A^2.
Eigen::VectorXd vertex_areas(const Surface& surface) {
  const TriMesh& mesh = surface.mesh();
  Eigen::VectorXd area = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.n_vertices()));
  for (const auto f : mesh.faces()) {
    const auto h = mesh.halfedge_handle(f);
    const auto a = mesh.from_vertex_handle(h);
    const auto b = mesh.to_vertex_handle(h);
    const auto c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
    const double third =
        OpenMesh::cross(mesh.point(b) - mesh.point(a), mesh.point(c) - mesh.point(a)).norm() / 6.0;
    area(a.idx()) += third;
    area(b.idx()) += third;
    area(c.idx()) += third;
  }
  return area;
}

SurfaceMeasures measure_surface(const Surface& surface) {
  const TriMesh& mesh = surface.mesh();
  SurfaceMeasures m;
  for (auto f : mesh.faces()) {
    auto h = mesh.halfedge_handle(f);
    const auto& a = mesh.point(mesh.from_vertex_handle(h));
    const auto& b = mesh.point(mesh.to_vertex_handle(h));
    const auto& c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    m.area += 0.5 * OpenMesh::cross(b - a, c - a).norm();
    m.volume += OpenMesh::dot(a, OpenMesh::cross(b, c)) / 6.0;
  }
  for (auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) ++m.boundary_edges;
  }
  m.euler_characteristic = static_cast<int>(mesh.n_vertices()) - static_cast<int>(mesh.n_edges()) +
                           static_cast<int>(mesh.n_faces());
  return m;
}

void require_closed_manifold(const Surface& surface, double min_area) {
  const TriMesh& mesh = surface.mesh();
  const std::string& src = surface.source();
  if (mesh.n_faces() == 0) throw TopologyError(src + ": the surface has no triangles");
  for (auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) {
      throw TopologyError(
          src + ": the surface is open (boundary edge between vertices " +
          std::to_string(mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)).idx()) + " and " +
          std::to_string(mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)).idx()) +
          "); a closed surface is required");
    }
  }
  for (auto v : mesh.vertices()) {
    if (!mesh.is_manifold(v)) {
      throw TopologyError(src + ": vertex " + std::to_string(v.idx()) + " is not manifold");
    }
    if (mesh.is_isolated(v)) {
      throw TopologyError(src + ": vertex " + std::to_string(v.idx()) + " belongs to no triangle");
    }
  }
  for (auto f : mesh.faces()) {
    auto h = mesh.halfedge_handle(f);
    const auto& a = mesh.point(mesh.from_vertex_handle(h));
    const auto& b = mesh.point(mesh.to_vertex_handle(h));
    const auto& c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    if (0.5 * OpenMesh::cross(b - a, c - a).norm() <= min_area) {
      throw TopologyError(src + ": triangle " + std::to_string(f.idx()) + " is degenerate");
    }
  }
}

}  // namespace surfcomp::mesh
