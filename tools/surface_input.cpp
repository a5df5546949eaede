#include "surface_input.hpp"

#include "console.hpp"
#include "options.hpp"

#include <cstdint>
#include <memory>

namespace surfcomp::tools {
namespace {

/// A progress line for an ESP or LP sum (console::ProgressLine), or none.
mesh::PotentialProgress potential_progress(const char* what) {
  if (!console::progress_shown()) return {};
  auto line = std::make_shared<console::ProgressLine>(what, "points");
  return [line](std::int64_t done, std::int64_t total) { (*line)(done, total); };
}

}  // namespace

void add_surface_options(boost::program_options::options_description& described) {
  add_table_options(described, mesh::surface_input_option_table());
}

mesh::SurfaceInputOptions surface_options_from(const boost::program_options::variables_map& vm) {
  mesh::SurfaceInputOptions input;
  apply_table_options(mesh::surface_input_option_table(), vm, input);
  show_potential_progress(input.surface);
  return input;
}

void show_potential_progress(mesh::MolecularSurfaceOptions& surface) {
  surface.esp.progress = potential_progress("ESP");
  surface.lp.progress = potential_progress("LP");
}

mesh::LoadedSurface load_noted(const std::filesystem::path& path,
                               const mesh::SurfaceInputOptions& options) {
  mesh::LoadedSurface loaded = mesh::load_surface(path, options);
  for (const std::string& note : loaded.notes) console::note(note);
  return loaded;
}

}  // namespace surfcomp::tools
