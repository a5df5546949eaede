#include "surfcomp/mesh/decimate.hpp"

#include "surface_mesh.hpp"
#include "surfcomp/core/error.hpp"

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <numeric>
#include <string>

namespace surfcomp::mesh {

DecimatedSurface decimate(const Surface& surface, std::size_t max_vertices) {
  if (max_vertices < 4) {
    throw OptionError(surface.source() + ": decimation to " + std::to_string(max_vertices) +
                      " vertices: expected at least 4");
  }
  DecimatedSurface out;
  out.surface = surface;
  out.original.resize(surface.n_vertices());
  std::iota(out.original.begin(), out.original.end(), 0);
  if (surface.n_vertices() <= max_vertices) return out;

  TriMesh& mesh = tri_mesh(out.surface);
  OpenMesh::VPropHandleT<int> original;
  mesh.add_property(original);
  for (const auto v : mesh.vertices()) mesh.property(original, v) = v.idx();
  mesh.update_face_normals();  // the quadric module reads the face planes
  {
    OpenMesh::Decimater::DecimaterT<TriMesh> decimater(mesh);
    OpenMesh::Decimater::ModQuadricT<TriMesh>::Handle quadric;
    decimater.add(quadric);
    decimater.module(quadric).unset_max_err();
    decimater.initialize();
    decimater.decimate_to(max_vertices);
  }
  mesh.garbage_collection();
  out.original.resize(mesh.n_vertices());
  for (const auto v : mesh.vertices()) {
    out.original[static_cast<std::size_t>(v.idx())] = mesh.property(original, v);
  }
  mesh.remove_property(original);
  return out;
}

}  // namespace surfcomp::mesh
