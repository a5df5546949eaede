#include "surfcomp/harmonic/surface_descriptors.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/mesh/topology.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp::harmonic {
namespace {

/// The patch, map and image of one critical point. Failures that belong to the patch's shape
/// (no triangle left, a handle, the surface's own border reached, an unsolvable map) become a
/// status; anything else propagates. `border` flags the surface's border vertices.
void describe_point(const mesh::Surface& surface, const Eigen::VectorXd& image_values,
                    const std::vector<bool>& border, const DescriptorOptions& options,
                    CriticalPointDescriptor& out) {
  try {
    out.patch = mesh::extract_patch(surface, out.point.vertex, options.patch);
  } catch (const TopologyError&) {
    out.status = PatchStatus::empty;
    return;
  }
  for (const int v : out.patch.surface_vertex) {
    if (border[static_cast<std::size_t>(v)]) {
      out.status = PatchStatus::at_border;
      return;
    }
  }
  const auto on = [&out](const std::vector<int>& loop) {
    return std::find(loop.begin(), loop.end(), out.patch.center) != loop.end();
  };
  if (on(out.patch.outer_boundary) ||
      std::any_of(out.patch.holes.begin(), out.patch.holes.end(), on)) {
    out.status = PatchStatus::at_border;
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

std::vector<CriticalPointDescriptor> describe_points(const mesh::Surface& surface,
                                                     const std::vector<mesh::CriticalPoint>& points,
                                                     const DescriptorOptions& options) {
  const Eigen::VectorXd image_values = surface.property(options.image_property);
  const std::vector<bool> border = mesh::border_vertices(surface);
  std::vector<CriticalPointDescriptor> out(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) {
    out[i].point = points[i];
    describe_point(surface, image_values, border, options, out[i]);
  });
  return out;
}

std::vector<CriticalPointDescriptor> describe_points_in_unit(
    const mesh::Surface& surface, const std::vector<mesh::CriticalPoint>& points, double unit,
    const DescriptorOptions& options) {
  if (unit == 1.0) return describe_points(surface, points, options);
  mesh::Surface in_units = surface;
  mesh::scale_surface(in_units, 1.0 / unit);  // checks the unit
  std::vector<mesh::CriticalPoint> scaled = points;
  for (mesh::CriticalPoint& point : scaled) mesh::scale_critical_point(point, 1.0 / unit);
  std::vector<CriticalPointDescriptor> out = describe_points(in_units, scaled, options);
  for (CriticalPointDescriptor& d : out) scale_point_descriptor(d, unit, options.image_property);
  return out;
}

CriticalPointDescriptor describe_point(const mesh::Surface& surface,
                                       const mesh::CriticalPoint& point,
                                       const DescriptorOptions& options) {
  CriticalPointDescriptor out;
  out.point = point;
  describe_point(surface, surface.property(options.image_property), mesh::border_vertices(surface),
                 options, out);
  return out;
}

SurfaceDescriptors describe_surface(
    mesh::Surface surface, const DescriptorOptions& options,
    const std::function<bool(const mesh::CriticalPoint&)>& describe_if) {
  surfcomp::options::check_all(descriptor_option_table(), options);
  SurfaceDescriptors result;
  result.options = options;
  result.options.progress = {};  // a description keeps its parameters, not the caller's callback
  const std::vector<mesh::CriticalPoint> points =
      mesh::detect_critical_points(surface, options.critical_points);
  const Eigen::VectorXd image_values = surface.property(options.image_property);
  const std::vector<bool> border = mesh::border_vertices(surface);
  std::vector<bool> wanted(points.size(), true);
  std::int64_t count = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (describe_if) wanted[i] = describe_if(points[i]);
    count += wanted[i] ? 1 : 0;
  }
  const double bytes = image_bytes(options.image, count);
  if (bytes > static_cast<double>(options.max_image_bytes)) {
    std::ostringstream message;
    message << surface.source() << ": " << count << " shape images of " << options.image.rings
            << " rings x " << options.image.sectors << " sectors would take about " << bytes
            << " bytes; the limit is " << options.max_image_bytes
            << " (raise it with " + options::named("max_image_bytes") +
                   ", or use a "
                   "smaller grid)";
    throw InputError(message.str());
  }
  result.critical_points.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) result.critical_points[i].point = points[i];
  std::atomic<std::int64_t> done{0};
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) {
    if (!wanted[i]) {
      result.critical_points[i].status = PatchStatus::skipped;
      return;
    }
    describe_point(surface, image_values, border, options, result.critical_points[i]);
    if (options.progress) options.progress(++done, count);
  });
  if (options.progress) options.progress(count, count);
  result.surface = std::move(surface);
  return result;
}

double image_bytes(const ImageOptions& image, std::int64_t count) {
  constexpr double per_point =
      sizeof(double) + sizeof(std::uint8_t) + sizeof(int) + 3 * sizeof(double);
  return static_cast<double>(count) * image.rings * image.sectors * per_point;
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

void scale_descriptors(SurfaceDescriptors& descriptors, double factor) {
  mesh::scale_surface(descriptors.surface, factor);  // checks the factor
  for (CriticalPointDescriptor& cp : descriptors.critical_points)
    scale_point_descriptor(cp, factor, descriptors.options.image_property);
  for (SurfaceAtom& atom : descriptors.atoms) atom.position *= factor;
  descriptors.length_unit *= factor;
}

void scale_point_descriptor(CriticalPointDescriptor& descriptor, double factor,
                            const std::string& image_property) {
  mesh::scale_critical_point(descriptor.point, factor);
  mesh::scale_patch(descriptor.patch, factor);
  const bool image_is_curvature = image_property == mesh::property::cc1 ||
                                  image_property == mesh::property::cc2 ||
                                  image_property == mesh::property::curvedness;
  if (image_is_curvature) descriptor.image.values /= factor;
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

const char* to_string(PatchStatus status) {
  switch (status) {
    case PatchStatus::ok:
      return "ok";
    case PatchStatus::empty:
      return "empty";
    case PatchStatus::not_a_disk:
      return "not_a_disk";
    case PatchStatus::map_failed:
      return "map_failed";
    case PatchStatus::skipped:
      return "skipped";
    case PatchStatus::at_border:
      return "at_border";
  }
  return "unknown";
}

}  // namespace surfcomp::harmonic
