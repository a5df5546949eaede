#include "surfcomp/matching/correspondences.hpp"

#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/harmonic/shape_image.hpp"

#include <cmath>
#include <string>

namespace surfcomp::matching {

namespace {

const harmonic::CriticalPointDescriptor& imaged_point(const harmonic::SurfaceDescriptors& d,
                                                      int index, const char* side) {
  if (index < 0 || static_cast<std::size_t>(index) >= d.critical_points.size()) {
    throw InputError(std::string("correspondences: critical point ") + std::to_string(index) +
                     " of surface " + side + " (" + d.surface.source() + ") is outside its " +
                     std::to_string(d.critical_points.size()) + " critical points");
  }
  const auto& point = d.critical_points[static_cast<std::size_t>(index)];
  if (point.status != harmonic::PatchStatus::ok) {
    throw InputError(std::string("correspondences: critical point ") + std::to_string(index) +
                     " of surface " + side + " (" + d.surface.source() +
                     ") has no shape image; expected a point with status ok");
  }
  return point;
}

Eigen::VectorXd surface_property(const harmonic::SurfaceDescriptors& d, const std::string& name,
                                 const char* side) {
  if (name.empty()) return Eigen::VectorXd::Zero(static_cast<Eigen::Index>(d.surface.n_vertices()));
  if (!d.surface.has_property(name)) {
    throw InputError(std::string("correspondences: surface ") + side + " (" + d.surface.source() +
                     ") has no vertex property '" + name + "'");
  }
  return d.surface.property(name);
}

/// The property at grid point `grid` of the point's image: barycentric over the face corners'
/// surface vertices.
double property_at(const harmonic::CriticalPointDescriptor& point, int grid,
                   const Eigen::VectorXd& property) {
  const int face = point.image.face(grid);
  double value = 0.0;
  for (int c = 0; c < 3; ++c) {
    const int local = point.patch.faces(face, c);
    const int vertex = point.patch.surface_vertex[static_cast<std::size_t>(local)];
    value += point.image.barycentric(grid, c) * property(vertex);
  }
  return value;
}

}  // namespace

Correspondences pair_correspondences(const harmonic::SurfaceDescriptors& a,
                                     const harmonic::SurfaceDescriptors& b, const MatchedPair& pair,
                                     const CorrespondenceOptions& options) {
  detail::check_correspondence_options(options, {"pair_correspondences", ""});
  const auto& pa = imaged_point(a, pair.a, "A");
  const auto& pb = imaged_point(b, pair.b, "B");
  const harmonic::ShapeImage& ia = pa.image;
  const harmonic::ShapeImage& ib = pb.image;
  if (ia.rings != ib.rings || ia.sectors != ib.sectors) {
    throw InputError("correspondences: image grids of " + std::to_string(ia.rings) + " rings x " +
                     std::to_string(ia.sectors) + " sectors (A, point " + std::to_string(pair.a) +
                     ") and " + std::to_string(ib.rings) + " rings x " +
                     std::to_string(ib.sectors) + " sectors (B, point " + std::to_string(pair.b) +
                     "); expected equal grids");
  }
  const Eigen::VectorXd property_a = surface_property(a, options.property, "A");
  const Eigen::VectorXd property_b = surface_property(b, options.property, "B");
  const int sectors = ia.sectors;
  const int shift = ((pair.image_shift % sectors) + sectors) % sectors;

  std::vector<std::pair<int, int>> grid_pairs;
  for (int ring = 0; ring < ia.rings; ring += options.ring_step) {
    for (int sector = 0; sector < sectors; sector += options.sector_step) {
      const int i = ring * sectors + sector;
      const int j = ring * sectors + (sector + shift) % sectors;
      if (ia.valid[static_cast<std::size_t>(i)] && ib.valid[static_cast<std::size_t>(j)]) {
        grid_pairs.emplace_back(i, j);
      }
    }
  }
  Correspondences out;
  const auto n = static_cast<Eigen::Index>(grid_pairs.size());
  out.a_points.resize(3, n);
  out.b_points.resize(3, n);
  out.a_property.resize(n);
  out.b_property.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto [i, j] = grid_pairs[static_cast<std::size_t>(k)];
    out.a_points.col(k) =
        harmonic::image_point_to_surface(ia, i, pa.patch.positions, pa.patch.faces);
    out.b_points.col(k) =
        harmonic::image_point_to_surface(ib, j, pb.patch.positions, pb.patch.faces);
    out.a_property(k) = property_at(pa, i, property_a);
    out.b_property(k) = property_at(pb, j, property_b);
  }
  return out;
}

Correspondences concatenate(const std::vector<const Correspondences*>& parts) {
  Eigen::Index n = 0;
  for (const Correspondences* part : parts) n += part->a_points.cols();
  Correspondences out;
  out.a_points.resize(3, n);
  out.b_points.resize(3, n);
  out.a_property.resize(n);
  out.b_property.resize(n);
  Eigen::Index at = 0;
  for (const Correspondences* part : parts) {
    const Eigen::Index m = part->a_points.cols();
    if (part->b_points.cols() != m || part->a_property.size() != m ||
        part->b_property.size() != m) {
      throw InputError("correspondences: a part has " + std::to_string(m) + " A points, " +
                       std::to_string(part->b_points.cols()) + " B points and " +
                       std::to_string(part->a_property.size()) + " / " +
                       std::to_string(part->b_property.size()) +
                       " property values; expected equal counts");
    }
    out.a_points.middleCols(at, m) = part->a_points;
    out.b_points.middleCols(at, m) = part->b_points;
    out.a_property.segment(at, m) = part->a_property;
    out.b_property.segment(at, m) = part->b_property;
    at += m;
  }
  return out;
}

double property_correlation(const Correspondences& correspondences) {
  const Eigen::VectorXd& x = correspondences.a_property;
  const Eigen::VectorXd& y = correspondences.b_property;
  if (x.size() != y.size()) {
    throw InputError("R_chem: " + std::to_string(x.size()) + " and " + std::to_string(y.size()) +
                     " property values; expected equal counts");
  }
  if (!x.allFinite() || !y.allFinite()) {
    throw InputError("R_chem: a property value is not finite");
  }
  if (x.size() < 2) return 0.0;
  const Eigen::VectorXd dx = x.array() - x.mean();
  const Eigen::VectorXd dy = y.array() - y.mean();
  const double sx = dx.norm(), sy = dy.norm();
  if (sx == 0.0 || sy == 0.0 || sx <= 1e-12 * x.norm() || sy <= 1e-12 * y.norm()) return 0.0;
  return dx.dot(dy) / (sx * sy);
}

}  // namespace surfcomp::matching
