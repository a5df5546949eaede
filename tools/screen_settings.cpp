#include "screen_settings.hpp"

#include "console.hpp"
#include "describe_settings.hpp"
#include "options.hpp"

namespace surfcomp::tools {

void add_screen_options(boost::program_options::options_description& described) {
  add_table_options(described, screening::screen_option_table());
}

screening::QueryScreenOptions screen_options_from(const boost::program_options::variables_map& vm) {
  screening::QueryScreenOptions options;
  apply_table_options(screening::screen_option_table(), vm, options);
  options.query.descriptors.progress = describe_progress();
  if (console::level() == console::Level::verbose) options.query.log = &console::step;
  return options;
}

}  // namespace surfcomp::tools
