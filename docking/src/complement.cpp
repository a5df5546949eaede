#include "surfcomp/docking/complement.hpp"

#include "surfcomp/mesh/critical_points.hpp"

#include <utility>

namespace surfcomp::docking {

harmonic::ShapeImage mirrored_image(const harmonic::ShapeImage& image) {
  harmonic::ShapeImage out = image;
  const int sectors = image.sectors;
  for (int ring = 0; ring < image.rings; ++ring) {
    for (int sector = 0; sector < sectors; ++sector) {
      const int from = ring * sectors + sector;
      const int to = ring * sectors + (sectors - sector) % sectors;
      out.values(to) = -image.values(from);
      out.valid[static_cast<std::size_t>(to)] = image.valid[static_cast<std::size_t>(from)];
      out.face(to) = image.face(from);
      out.barycentric.row(to) = image.barycentric.row(from);
    }
  }
  // A grid point that is not valid keeps 0, not -0, as the image builder leaves it.
  for (Eigen::Index i = 0; i < out.values.size(); ++i) {
    if (out.values(i) == 0.0) out.values(i) = 0.0;
  }
  return out;
}

harmonic::SurfaceDescriptors complement(harmonic::SurfaceDescriptors descriptors) {
  for (harmonic::CriticalPointDescriptor& d : descriptors.critical_points) {
    mesh::CriticalPoint& p = d.point;
    p.type = p.type == mesh::CriticalPointType::peak ? mesh::CriticalPointType::valley
                                                     : mesh::CriticalPointType::peak;
    const double cc1 = p.cc1;
    p.cc1 = -p.cc2;
    p.cc2 = -cc1;
    p.shape_index = -p.shape_index;
    p.normal = -p.normal;
    p.esp = -p.esp;
    if (d.map.uv.rows() > 0) d.map.uv.col(1) = -d.map.uv.col(1);
    if (d.image.values.size() > 0) d.image = mirrored_image(d.image);
  }
  mesh::Surface& surface = descriptors.surface;
  if (surface.has_property(mesh::property::esp)) {
    Eigen::VectorXd esp = surface.property(mesh::property::esp);
    surface.set_property(mesh::property::esp, -esp);
  }
  return descriptors;
}

}  // namespace surfcomp::docking
