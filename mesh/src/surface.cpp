#include "surfcomp/mesh/surface.hpp"

#include "surface_mesh.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"

#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

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

Surface::Impl::Impl() {
  quiet_openmesh();
  mesh.request_vertex_normals();
  mesh.request_face_normals();
}

Surface::Surface() = default;

Surface::Surface(const Surface& other)
    : impl_(other.impl_ ? std::make_unique<Impl>(*other.impl_) : nullptr) {}

Surface::Surface(Surface&& other) noexcept = default;

Surface& Surface::operator=(const Surface& other) {
  if (this != &other) impl_ = other.impl_ ? std::make_unique<Impl>(*other.impl_) : nullptr;
  return *this;
}

Surface& Surface::operator=(Surface&& other) noexcept = default;

Surface::~Surface() = default;

const Surface::Impl& Surface::impl() const {
  if (impl_) return *impl_;
  static const Impl empty;
  return empty;
}

Surface::Impl& Surface::impl() {
  if (!impl_) impl_ = std::make_unique<Impl>();
  return *impl_;
}

Surface Surface::from_arrays(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                             const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                             const std::string& source) {
  Surface surface;
  surface.impl().source = source;
  TriMesh& mesh = surface.impl().mesh;
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
      throw TopologyError(source + ": face " + std::to_string(f) + " repeats a vertex (" +
                          options::named("repair") + " removes degenerate faces)");
    }
    if (!mesh.add_face(tri[0], tri[1], tri[2]).is_valid()) {
      throw TopologyError(source + ": face " + std::to_string(f) +
                          " makes the mesh non-manifold (complex edge or vertex; " +
                          options::named("repair") +
                          " "
                          "splits such vertices and removes duplicate faces)");
    }
  }
  return surface;
}

std::size_t Surface::n_vertices() const { return impl().mesh.n_vertices(); }

std::size_t Surface::n_faces() const { return impl().mesh.n_faces(); }

Eigen::MatrixX3d Surface::positions() const {
  const TriMesh& mesh = impl().mesh;
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    out.row(v.idx()) << p[0], p[1], p[2];
  }
  return out;
}

Eigen::MatrixX3i Surface::faces() const {
  const TriMesh& mesh = impl().mesh;
  Eigen::MatrixX3i out(static_cast<Eigen::Index>(mesh.n_faces()), 3);
  for (auto f : mesh.faces()) {
    int k = 0;
    for (auto v : mesh.fv_range(f)) out(f.idx(), k++) = v.idx();
  }
  return out;
}

Eigen::MatrixX3d Surface::normals() const {
  const TriMesh& mesh = impl().mesh;
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (auto v : mesh.vertices()) {
    const auto& n = mesh.normal(v);
    out.row(v.idx()) << n[0], n[1], n[2];
  }
  return out;
}

void Surface::set_normals(const Eigen::Ref<const Eigen::MatrixX3d>& normals) {
  Impl& d = impl();
  TriMesh& mesh = d.mesh;
  if (static_cast<std::size_t>(normals.rows()) != mesh.n_vertices()) {
    throw InputError(d.source + ": " + std::to_string(normals.rows()) + " normals for " +
                     std::to_string(mesh.n_vertices()) + " vertices");
  }
  for (auto v : mesh.vertices()) {
    mesh.set_normal(v,
                    TriMesh::Normal(normals(v.idx(), 0), normals(v.idx(), 1), normals(v.idx(), 2)));
  }
  d.has_normals = true;
}

bool Surface::has_normals() const { return impl().has_normals; }

void Surface::compute_normals() {
  Impl& d = impl();
  TriMesh& mesh = d.mesh;
  std::vector<OpenMesh::Vec3d> sums(mesh.n_vertices(), OpenMesh::Vec3d(0, 0, 0));
  for (auto f : mesh.faces()) {
    auto h = mesh.halfedge_handle(f);
    const auto& a = mesh.point(mesh.from_vertex_handle(h));
    const auto& b = mesh.point(mesh.to_vertex_handle(h));
    const auto& c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    const OpenMesh::Vec3d area_normal = OpenMesh::cross(b - a, c - a);  // 2 * area * n
    mesh.set_normal(f, area_normal.norm() > 0 ? area_normal.normalized() : area_normal);
    for (auto v : mesh.fv_range(f)) sums[static_cast<std::size_t>(v.idx())] += area_normal;
  }
  for (auto v : mesh.vertices()) {
    const auto& s = sums[static_cast<std::size_t>(v.idx())];
    mesh.set_normal(v, s.norm() > 0 ? s.normalized() : s);
  }
  d.has_normals = true;
}

const std::vector<std::string>& Surface::property_names() const { return impl().property_names; }

bool Surface::has_property(const std::string& name) const {
  const std::vector<std::string>& names = impl().property_names;
  return std::find(names.begin(), names.end(), name) != names.end();
}

OpenMesh::VPropHandleT<double> Surface::Impl::handle(const std::string& name) const {
  OpenMesh::VPropHandleT<double> h;
  if (std::find(property_names.begin(), property_names.end(), name) == property_names.end() ||
      !mesh.get_property_handle(h, name)) {
    throw InputError(source + ": the surface has no vertex property '" + name + "'");
  }
  return h;
}

Eigen::VectorXd Surface::property(const std::string& name) const {
  const Impl& d = impl();
  const std::vector<double>& data = d.mesh.property(d.handle(name)).data_vector();
  return Eigen::Map<const Eigen::VectorXd>(data.data(), static_cast<Eigen::Index>(data.size()));
}

double Surface::property(const std::string& name, std::size_t vertex) const {
  const Impl& d = impl();
  return d.mesh.property(d.handle(name), TriMesh::VertexHandle(static_cast<int>(vertex)));
}

void Surface::set_property(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values,
                           ValueType stored_as) {
  Impl& d = impl();
  if (static_cast<std::size_t>(values.size()) != d.mesh.n_vertices()) {
    throw InputError(d.source + ": property '" + name + "' has " + std::to_string(values.size()) +
                     " values for " + std::to_string(d.mesh.n_vertices()) + " vertices");
  }
  OpenMesh::VPropHandleT<double> h;
  if (!has_property(name)) {
    d.mesh.add_property(h, name);
    d.property_names.push_back(name);
    d.property_types.push_back(stored_as);
  } else {
    h = d.handle(name);
    const auto it = std::find(d.property_names.begin(), d.property_names.end(), name);
    d.property_types[static_cast<std::size_t>(it - d.property_names.begin())] = stored_as;
  }
  std::vector<double>& data = d.mesh.property(h).data_vector();
  data.assign(values.data(), values.data() + values.size());
}

void Surface::remove_property(const std::string& name) {
  if (!has_property(name)) return;
  Impl& d = impl();
  const auto it = std::find(d.property_names.begin(), d.property_names.end(), name);
  auto h = d.handle(name);
  d.mesh.remove_property(h);
  d.property_types.erase(d.property_types.begin() + (it - d.property_names.begin()));
  d.property_names.erase(it);
}

ValueType Surface::property_type(const std::string& name) const {
  const Impl& d = impl();
  const auto it = std::find(d.property_names.begin(), d.property_names.end(), name);
  if (it == d.property_names.end()) {
    throw InputError(d.source + ": the surface has no vertex property '" + name + "'");
  }
  return d.property_types[static_cast<std::size_t>(it - d.property_names.begin())];
}

ValueType Surface::position_type() const { return impl().position_type; }

ValueType Surface::normal_type() const { return impl().normal_type; }

void Surface::set_position_type(ValueType type) { impl().position_type = type; }

void Surface::set_normal_type(ValueType type) { impl().normal_type = type; }

const std::string& Surface::source() const { return impl().source; }

void Surface::set_source(std::string source) { impl().source = std::move(source); }

Surface spatially_ordered(const Surface& surface) {
  const Eigen::MatrixX3d positions = surface.positions();
  const Eigen::MatrixX3i faces = surface.faces();
  const auto n = static_cast<std::size_t>(positions.rows());
  std::vector<int> order(n);  // order[new index] = old index
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<int>(i);
  const auto key = [&](int v) {
    return std::array<double, 3>{positions(v, 0), positions(v, 1), positions(v, 2)};
  };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  std::vector<int> renamed(n);  // renamed[old index] = new index
  for (std::size_t i = 0; i < n; ++i)
    renamed[static_cast<std::size_t>(order[i])] = static_cast<int>(i);

  Eigen::MatrixX3d sorted_positions(positions.rows(), 3);
  for (std::size_t i = 0; i < n; ++i)
    sorted_positions.row(static_cast<Eigen::Index>(i)) = positions.row(order[i]);
  std::vector<std::array<int, 3>> triangles(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    std::array<int, 3> t{renamed[static_cast<std::size_t>(faces(f, 0))],
                         renamed[static_cast<std::size_t>(faces(f, 1))],
                         renamed[static_cast<std::size_t>(faces(f, 2))]};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    triangles[static_cast<std::size_t>(f)] = t;
  }
  std::sort(triangles.begin(), triangles.end());
  Eigen::MatrixX3i sorted_faces(faces.rows(), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int k = 0; k < 3; ++k)
      sorted_faces(static_cast<Eigen::Index>(f), k) = triangles[f][static_cast<std::size_t>(k)];

  const auto permuted = [&](const auto& values) {
    std::decay_t<decltype(values)> out(values.rows(), values.cols());
    for (std::size_t i = 0; i < n; ++i)
      out.row(static_cast<Eigen::Index>(i)) = values.row(order[i]);
    return out;
  };
  Surface out = Surface::from_arrays(sorted_positions, sorted_faces, surface.source());
  out.set_position_type(surface.position_type());
  if (surface.has_normals()) {
    out.set_normals(permuted(surface.normals()));
    out.set_normal_type(surface.normal_type());
  }
  for (const std::string& name : surface.property_names())
    out.set_property(name, permuted(surface.property(name)), surface.property_type(name));
  return out;
}

void transform_surface(Surface& surface, const Eigen::Matrix3d& rotation,
                       const Eigen::Vector3d& translation) {
  TriMesh& mesh = tri_mesh(surface);
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

void scale_surface(Surface& surface, double factor) {
  if (!(factor > 0.0) || !std::isfinite(factor)) {
    throw InputError(surface.source() + ": a length scale of " + std::to_string(factor) +
                     ", expected a finite value > 0");
  }
  TriMesh& mesh = tri_mesh(surface);
  for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * factor);
  for (const char* name : {property::cc1, property::cc2, property::curvedness}) {
    if (surface.has_property(name)) surface.set_property(name, surface.property(name) / factor);
  }
}

/// Barycentric vertex areas: a third of the area of every incident triangle, A^2.
Eigen::VectorXd vertex_areas(const Surface& surface) {
  const TriMesh& mesh = tri_mesh(surface);
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
  const TriMesh& mesh = tri_mesh(surface);
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
  const TriMesh& mesh = tri_mesh(surface);
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
