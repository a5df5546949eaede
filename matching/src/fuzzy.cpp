#include "surfcomp/matching/fuzzy.hpp"

#include "surfcomp/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace surfcomp::matching {

FuzzyMemberships fuzzy_memberships(double z) {
  if (std::isnan(z)) throw InputError("fuzzy filter: the value is NaN, expected a number");
  FuzzyMemberships m{};
  if (z <= -2.0) {
    m[0] = 1.0;
    return m;
  }
  if (z >= 2.0) {
    m[4] = 1.0;
    return m;
  }
  // Between two neighbouring centres k - 2 and k - 1 the two triangles cross linearly.
  const double shifted = z + 2.0;  // in (0, 4)
  const int lower = std::min(3, static_cast<int>(std::floor(shifted)));
  const double upper_weight = shifted - lower;
  m[static_cast<std::size_t>(lower)] = 1.0 - upper_weight;
  m[static_cast<std::size_t>(lower) + 1] = upper_weight;
  return m;
}

double fuzzy_similarity(const FuzzyMemberships& m, const FuzzyMemberships& n) {
  double minima = 0.0, maxima = 0.0;
  for (std::size_t k = 0; k < m.size(); ++k) {
    minima += std::min(m[k], n[k]);
    maxima += std::max(m[k], n[k]);
  }
  if (!(maxima > 0.0)) {
    throw InputError(
        "fuzzy_similarity: both membership vectors are zero, expected memberships "
        "with a positive sum");
  }
  return minima / maxima;
}

double fuzzy_similarity(double z_a, double z_b) {
  if (std::isnan(z_a) || std::isnan(z_b)) return std::numeric_limits<double>::quiet_NaN();
  return fuzzy_similarity(fuzzy_memberships(z_a), fuzzy_memberships(z_b));
}

std::vector<double> autoscaled_point_values(const harmonic::SurfaceDescriptors& descriptors,
                                            const std::string& property) {
  const bool esp = property == mesh::property::esp;
  if (!esp && property != mesh::property::lp) {
    throw InputError("fuzzy filter: property '" + property +
                     "' is not a fuzzy-filter property, expected 'esp' or 'lp'");
  }
  const std::size_t n = descriptors.critical_points.size();
  const mesh::Surface& surface = descriptors.surface;
  if (!surface.has_property(property) || surface.n_vertices() == 0) {
    return std::vector<double>(n, std::numeric_limits<double>::quiet_NaN());
  }
  const Eigen::VectorXd values = surface.property(property);
  const double mean = values.mean();
  const double deviation =
      std::sqrt((values.array() - mean).square().sum() / static_cast<double>(values.size()));
  std::vector<double> z(n, 0.0);
  // A deviation at round-off level of the values means a constant property.
  if (!(deviation > 1e-12 * std::max(1.0, std::abs(mean)))) return z;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& point = descriptors.critical_points[i].point;
    z[i] = ((esp ? point.esp : point.lp) - mean) / deviation;
  }
  return z;
}

}  // namespace surfcomp::matching
