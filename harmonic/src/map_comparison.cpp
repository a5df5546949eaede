// compare_with_cgal (cgal_reference.hpp): CGAL's headers stay in cgal_reference.cpp.
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/cgal_reference.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <vector>

namespace surfcomp::harmonic {
namespace {

/// The median time of `run`, ms, over as many runs as fit in about 20 ms (at least 3).
double median_ms(const std::function<void()>& run) {
  std::vector<double> times;
  const Stopwatch total;
  while (times.size() < 3 || (total.elapsed_ms() < 20.0 && times.size() < 1000)) {
    const Stopwatch one;
    run();
    times.push_back(one.elapsed_ms());
  }
  std::nth_element(times.begin(), times.begin() + static_cast<std::ptrdiff_t>(times.size() / 2),
                   times.end());
  return times[times.size() / 2];
}

}  // namespace

DiskMapComparison compare_with_cgal(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                    const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                                    const std::vector<int>& outer_boundary,
                                    const DiskMapOptions& options) {
  DiskMapComparison out;
  out.ours_ms =
      median_ms([&] { out.ours = harmonic_disk_map(positions, faces, outer_boundary, options); });
  out.cgal_ms =
      median_ms([&] { out.cgal = cgal_disk_map(positions, faces, outer_boundary, options); });
  const Eigen::VectorXd distance = (out.ours.uv - out.cgal.uv).rowwise().norm();
  out.max_distance = distance.size() > 0 ? distance.maxCoeff() : 0.0;
  out.mean_distance = distance.size() > 0 ? distance.mean() : 0.0;
  out.ours_distortion = map_distortion(positions, faces, out.ours.uv);
  out.cgal_distortion = map_distortion(positions, faces, out.cgal.uv);
  return out;
}

std::vector<ParameterizationResult> compare_parameterizations(
    const Eigen::Ref<const Eigen::MatrixX3d>& positions,
    const Eigen::Ref<const Eigen::MatrixX3i>& faces, const std::vector<int>& outer_boundary,
    const std::vector<Parameterization>& methods, const DiskMapOptions& options) {
  std::vector<ParameterizationResult> out;
  for (const Parameterization method : methods) {
    ParameterizationResult result;
    result.method = method;
    try {
      result.ms = median_ms([&] {
        result.uv = parameterize_patch(positions, faces, outer_boundary, method, options);
      });
      result.distortion = map_distortion(positions, faces, result.uv);
    } catch (const NumericError& e) {
      result.failure = e.what();
    } catch (const TopologyError& e) {
      result.failure = e.what();
    }
    if (!result.failure.empty()) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      result.ms = nan;
      result.distortion = {nan, nan, nan, nan, -1};
      result.uv.resize(0, 2);
    }
    out.push_back(result);
  }
  return out;
}

}  // namespace surfcomp::harmonic
