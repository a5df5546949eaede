#include "match_settings.hpp"

#include "console.hpp"
#include "describe_settings.hpp"
#include "options.hpp"
#include "surface_input.hpp"

namespace surfcomp::tools {

void add_match_options(boost::program_options::options_description& described) {
  add_table_options(described, matching::pair_match_option_table());
}

matching::PairMatchOptions match_options_from(const boost::program_options::variables_map& vm) {
  matching::PairMatchOptions options;
  apply_table_options(matching::pair_match_option_table(), vm, options);
  show_surface_progress(options.inputs.input.surface);
  options.inputs.descriptors.progress = describe_progress();
  if (console::level() == console::Level::verbose) options.inputs.log = &console::step;
  return options;
}

PairInputs pair_inputs(const std::filesystem::path& reference, const std::filesystem::path& probe,
                       const matching::PairMatchOptions& options) {
  PairInputs inputs;
  inputs.reference.path = reference;
  inputs.probe.path = probe;
  inputs.reference = matching::with_site(std::move(inputs.reference), options.sites, true);
  inputs.probe = matching::with_site(std::move(inputs.probe), options.sites, false);
  matching::check_match_input(inputs.reference, options.inputs, "REF",
                              matching::site_ligand_option(options.sites, true));
  matching::check_match_input(inputs.probe, options.inputs, "PROBE",
                              matching::site_ligand_option(options.sites, false));
  return inputs;
}

}  // namespace surfcomp::tools
