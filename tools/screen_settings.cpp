#include "screen_settings.hpp"

#include "console.hpp"
#include "describe_settings.hpp"
#include "options.hpp"

#include "surfcomp/molsurf/load_surface.hpp"

namespace surfcomp::tools {

namespace {

/// The options of a mesh query (a shape screen) beside those of molecule and site screens.
const options::Table<molsurf::SurfaceInputOptions>& mesh_query_option_table() {
  static const options::Table<molsurf::SurfaceInputOptions> table =
      options::pick(molsurf::surface_input_option_table(), {"repair", "scale", "unit"});
  return table;
}

}  // namespace

void add_screen_options(boost::program_options::options_description& described) {
  add_table_options(described, screening::screen_option_table());
  add_table_options(described, mesh_query_option_table());
}

screening::QueryScreenOptions screen_options_from(const boost::program_options::variables_map& vm) {
  screening::QueryScreenOptions options;
  apply_table_options(screening::screen_option_table(), vm, options);
  apply_table_options(mesh_query_option_table(), vm, options.query.input);
  options.query.descriptors.progress = describe_progress();
  if (console::level() == console::Level::verbose) options.query.log = &console::step;
  return options;
}

}  // namespace surfcomp::tools
