#include "surfcomp/harmonic/surface_descriptors.hpp"

#include "surfcomp/core/error.hpp"

#include <tbb/parallel_for.h>

namespace surfcomp::harmonic {
namespace {

/// The patch, map and image of one critical point. Failures that belong to the patch's shape
/// (no triangle left, a handle, an unsolvable map) become a status; anything else propagates.
void describe_point(const mesh::Surface& surface, const Eigen::VectorXd& image_values,
                    const DescriptorOptions& options, CriticalPointDescriptor& out) {
  try {
    out.patch = mesh::extract_patch(surface, out.point.vertex, options.patch);
  } catch (const TopologyError&) {
    out.status = PatchStatus::empty;
    return;
  }
  if (out.patch.genus > 0) {
    out.status = PatchStatus::not_a_disk;
    return;
  }
  try {
    out.map = harmonic_disk_map(out.patch.positions, out.patch.faces, out.patch.outer_boundary,
                                options.disk_map);
  } catch (const NumericError&) {
    out.status = PatchStatus::map_failed;
    return;
  } catch (const TopologyError&) {
    out.status = PatchStatus::map_failed;
    return;
  }
  Eigen::VectorXd values(static_cast<Eigen::Index>(out.patch.surface_vertex.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    values(i) = image_values(out.patch.surface_vertex[static_cast<std::size_t>(i)]);
  }
  out.image = harmonic_shape_image(out.map.uv, out.patch.faces, values, options.image);
  out.status = PatchStatus::ok;
}

}  // namespace

CriticalPointDescriptor describe_point(const mesh::Surface& surface,
                                       const mesh::CriticalPoint& point,
                                       const DescriptorOptions& options) {
  CriticalPointDescriptor out;
  out.point = point;
  describe_point(surface, surface.property(options.image_property), options, out);
  return out;
}

SurfaceDescriptors describe_surface(
    mesh::Surface surface, const DescriptorOptions& options,
    const std::function<bool(const mesh::CriticalPoint&)>& describe_if) {
  SurfaceDescriptors result;
  result.options = options;
  const std::vector<mesh::CriticalPoint> points =
      mesh::detect_critical_points(surface, options.critical_points);
  const Eigen::VectorXd image_values = surface.property(options.image_property);
  result.critical_points.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) result.critical_points[i].point = points[i];
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) {
    if (describe_if && !describe_if(points[i])) {
      result.critical_points[i].status = PatchStatus::skipped;
      return;
    }
    describe_point(surface, image_values, options, result.critical_points[i]);
  });
  result.surface = std::move(surface);
  return result;
}

std::vector<SurfaceAtom> surface_atoms(const Molecule& molecule) {
  std::vector<SurfaceAtom> atoms;
  for (const Atom& atom : molecule.atoms) {
    if (atom.element != "H") atoms.push_back(SurfaceAtom{atom.element, atom.position});
  }
  return atoms;
}

SurfaceDescriptors describe_surface(
    mesh::Surface surface, const Molecule& molecule, const DescriptorOptions& options,
    const std::function<bool(const mesh::CriticalPoint&)>& describe_if) {
  SurfaceDescriptors result = describe_surface(std::move(surface), options, describe_if);
  result.atoms = surface_atoms(molecule);
  return result;
}

DescriptorCounts count_descriptors(const SurfaceDescriptors& descriptors) {
  DescriptorCounts counts;
  for (const auto& cp : descriptors.critical_points) {
    if (cp.point.type == mesh::CriticalPointType::peak) {
      ++counts.peaks;
    } else {
      ++counts.valleys;
    }
    if (cp.status == PatchStatus::ok) ++counts.imaged;
  }
  return counts;
}

}  // namespace surfcomp::harmonic
