// Internal to the mesh module: the OpenMesh half-edge mesh under a mesh::Surface. Only the
// module's own sources include this header; the public surface.hpp names no OpenMesh type.
#pragma once

#include "surfcomp/mesh/surface.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <string>
#include <vector>

namespace surfcomp::mesh {

struct SurfaceTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<SurfaceTraits>;

/// The state of a Surface. Named properties are OpenMesh vertex properties of `mesh` (type
/// double) under their names; `property_names` and `property_types` list them in the order they
/// were added.
struct Surface::Impl {
  /// An empty mesh with vertex and face normals; keeps OpenMesh's log and error streams quiet
  /// (the module turns every face OpenMesh rejects into an exception).
  Impl();

  /// The handle of named property `name`. Throws InputError (naming `source`) if absent.
  OpenMesh::VPropHandleT<double> handle(const std::string& name) const;

  TriMesh mesh;
  std::vector<std::string> property_names;
  std::vector<ValueType> property_types;
  ValueType position_type = ValueType::float64;
  ValueType normal_type = ValueType::float64;
  bool has_normals = false;
  std::string source = "<arrays>";
};

namespace detail {

/// The module's only way into a Surface's mesh (a friend of Surface).
struct SurfaceAccess {
  static TriMesh& mesh(Surface& surface) { return surface.impl().mesh; }
  static const TriMesh& mesh(const Surface& surface) { return surface.impl().mesh; }
};

}  // namespace detail

/// The half-edge mesh under `surface`. Code that adds or removes vertices keeps the invariants
/// surface.hpp states (every face a triangle; named properties follow the vertices, which
/// OpenMesh's property vectors do).
inline TriMesh& tri_mesh(Surface& surface) { return detail::SurfaceAccess::mesh(surface); }
inline const TriMesh& tri_mesh(const Surface& surface) {
  return detail::SurfaceAccess::mesh(surface);
}

}  // namespace surfcomp::mesh
