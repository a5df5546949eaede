#include "surface_input.hpp"

#include "console.hpp"
#include "options.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace surfcomp::tools {
namespace {

/// A progress line for a step counting `unit`s (console::ProgressLine) on a terminal; with
/// --verbose elsewhere (a log, a batch job), a step line as the work starts and as it ends;
/// otherwise none.
std::function<void(std::int64_t, std::int64_t)> progress_line(const char* what, const char* unit) {
  if (!console::progress_shown()) {
    if (console::level() != console::Level::verbose) return {};
    auto started = std::make_shared<std::atomic<bool>>(false);
    return [what = std::string(what), unit = std::string(unit), started](std::int64_t done,
                                                                         std::int64_t total) {
      if (!started->exchange(true)) {
        console::step(what + ": " + std::to_string(total) + " " + unit);
      }
      if (done == total) console::step(what + " done");
    };
  }
  auto line = std::make_shared<console::ProgressLine>(what, unit);
  return [line](std::int64_t done, std::int64_t total) { (*line)(done, total); };
}

}  // namespace

void add_surface_options(boost::program_options::options_description& described) {
  add_table_options(described, molsurf::surface_input_option_table());
}

molsurf::SurfaceInputOptions surface_options_from(const boost::program_options::variables_map& vm) {
  molsurf::SurfaceInputOptions input;
  apply_table_options(molsurf::surface_input_option_table(), vm, input);
  show_surface_progress(input.surface);
  return input;
}

void show_surface_progress(molsurf::MolecularSurfaceOptions& surface) {
  surface.ses.progress = progress_line("SES", "stages");
  surface.esp.progress = progress_line("ESP", "points");
  surface.lp.progress = progress_line("LP", "points");
  surface.curvature.progress = progress_line("curvature", "vertices");
}

molsurf::LoadedSurface load_noted(const std::filesystem::path& path,
                                  const molsurf::SurfaceInputOptions& options) {
  molsurf::LoadedSurface loaded = molsurf::load_surface(path, options);
  for (const std::string& note : loaded.notes) console::note(note);
  return loaded;
}

}  // namespace surfcomp::tools
