// The options of `surfcomp hsi-build` that say how a surface is described (critical points,
// patches, harmonic maps, images), parsed into the library's options: shared by hsi-build,
// patch-map and the Python module's describe().
#pragma once

#include "surface_input.hpp"

#include "surfcomp/harmonic/surface_descriptors.hpp"

#include <boost/program_options.hpp>
#include <tbb/global_control.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace surfcomp::tools {

struct DescribeSettings {
  SurfaceInput input;
  harmonic::DescriptorOptions descriptors;
  std::string weights = harmonic::to_string(harmonic::DiskMapOptions{}.weights);
  int threads = 0;
};

/// Adds the surface options (add_surface_options) and --critical-point-radius,
/// --patch-radius, --image-rings, --image-sectors, --weights, --threads and --max-image-bytes,
/// bound to `settings`.
void add_describe_options(boost::program_options::options_description& options,
                          DescribeSettings& settings);

/// Checks the parsed values (OptionError naming the option) and completes `settings`.
void finish_describe_options(DescribeSettings& settings);

/// The spring weights named on the command line (inverse-length, uniform, cotangent,
/// mean-value); OptionError otherwise.
harmonic::SpringWeights parse_weights(const std::string& name);

/// A progress line for describing critical points (console::ProgressLine), or none.
std::function<void(std::int64_t, std::int64_t)> describe_progress();

/// Limits TBB to `threads` worker threads while the result lives; nothing for 0 (all cores).
std::unique_ptr<tbb::global_control> limit_threads(int threads);

}  // namespace surfcomp::tools
