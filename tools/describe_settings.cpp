#include "describe_settings.hpp"

#include "console.hpp"
#include "options.hpp"

namespace surfcomp::tools {

harmonic::SpringWeights parse_weights(const std::string& name) {
  const std::vector<std::string> names(harmonic::spring_weights_names.begin(),
                                       harmonic::spring_weights_names.end());
  require_one_of("weights", name, names);
  return *harmonic::spring_weights_from_name(name);
}

void add_describe_options(boost::program_options::options_description& options,
                          DescribeSettings& settings) {
  namespace po = boost::program_options;
  harmonic::DescriptorOptions& d = settings.descriptors;
  // clang-format off
  options.add_options()
      ("critical-point-radius", defaulted(&d.critical_points.radius),
       "critical point radius r_cp (on-surface), A")
      ("patch-radius", defaulted(&d.patch.radius),
       "patch radius (on-surface), A; about 5 for ligands, larger for protein sites")
      ("image-rings", defaulted(&d.image.rings),
       "image grid: rings of the polar grid")
      ("image-sectors", defaulted(&d.image.sectors),
       "image grid: sectors (samples per ring; 180 = 2-degree rotation steps)")
      ("weights", po::value(&settings.weights)->default_value(harmonic::to_string(d.disk_map.weights)),
       "harmonic map spring weights: inverse-length (seed) | uniform | cotangent | mean-value")
      ("threads", po::value(&settings.threads)->default_value(0), "worker threads (0 = all cores)")
      ("max-image-bytes", defaulted(&d.max_image_bytes),
       "limit: memory of the shape images, bytes");
  // clang-format on
  add_surface_options(options, settings.input);
}

void finish_describe_options(DescribeSettings& settings) {
  finish_surface_options(settings.input);
  harmonic::DescriptorOptions& d = settings.descriptors;
  require_in_range("critical-point-radius", d.critical_points.radius, 1e-3, 100.0);
  require_in_range("patch-radius", d.patch.radius, 0.1, 100.0);
  require_in_range("image-rings", d.image.rings, 1, 1024);
  require_in_range("image-sectors", d.image.sectors, 1, 4096);
  require_in_range("threads", settings.threads, 0, 1024);
  d.disk_map.weights = parse_weights(settings.weights);
  d.progress = describe_progress();
}

std::function<void(std::int64_t, std::int64_t)> describe_progress() {
  if (!console::progress_shown()) return {};
  auto line = std::make_shared<console::ProgressLine>("describing", "critical points");
  return [line](std::int64_t done, std::int64_t total) { (*line)(done, total); };
}

std::unique_ptr<tbb::global_control> limit_threads(int threads) {
  require_in_range("threads", threads, 0, 1024);
  if (threads == 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<std::size_t>(threads));
}

}  // namespace surfcomp::tools
