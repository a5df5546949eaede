#include "describe_settings.hpp"

#include "console.hpp"
#include "options.hpp"
#include "surface_input.hpp"

namespace surfcomp::tools {

void add_describe_options(boost::program_options::options_description& described) {
  add_table_options(described, matching::describe_option_table());
}

matching::MatchInputOptions describe_options_from(const boost::program_options::variables_map& vm) {
  matching::MatchInputOptions options;
  apply_table_options(matching::describe_option_table(), vm, options);
  show_surface_progress(options.input.surface);
  options.descriptors.progress = describe_progress();
  return options;
}

std::function<void(std::int64_t, std::int64_t)> describe_progress() {
  if (!console::progress_shown()) return {};
  auto line = std::make_shared<console::ProgressLine>("describing", "critical points");
  return [line](std::int64_t done, std::int64_t total) { (*line)(done, total); };
}

}  // namespace surfcomp::tools
