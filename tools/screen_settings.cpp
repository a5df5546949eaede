#include "screen_settings.hpp"

#include "console.hpp"
#include "describe_settings.hpp"
#include "match_settings.hpp"
#include "options.hpp"

namespace surfcomp::tools {

void add_screen_options(boost::program_options::options_description& options,
                        ScreenSettings& settings) {
  namespace po = boost::program_options;
  // clang-format off
  options.add_options()
      ("top", defaulted(&settings.top), "rows of the table (0: every molecule)")
      ("refine", defaulted(&settings.refine),
       "conformers of each molecule whose overlay is refined (stage 2), best fast score "
       "first (0: none)")
      ("refine-starts", defaulted(&settings.refine_starts),
       "principal-axes starts of each conformer refined in stage 2, best start score first "
       "(0: all)")
      ("candidates", defaulted(&settings.candidates),
       "molecules given the full match (stage 3), best score after stage 2 first")
      ("record", po::value(&settings.record),
       "QUERY holding several molecules: read molecule N (1-based)")
      ("site-ligand", po::value(&settings.site_ligand),
       "a site query: the binding site of this ligand residue on the QUERY structure")
      ("site-sphere", po::value(&settings.site_spheres)->composing(),
       "a site query: site sphere x,y,z,r on QUERY (A; repeatable)")
      ("site-radius", defaulted(&settings.site.sphere_radius),
       "radius of the spheres around the site ligand's atoms, A")
      ("site-margin", defaulted(&settings.site.surface_margin), kSiteMarginHelp)
      ("threads", po::value(&settings.threads)->default_value(0), "worker threads (0 = all cores)");
  // clang-format on
}

void finish_screen_options(ScreenSettings& settings) {
  require_in_range("top", settings.top, 0, 1e9);
  require_in_range("refine", settings.refine, 0, 1e6);
  require_in_range("candidates", settings.candidates, 0, 1e6);
  require_in_range("refine-starts", settings.refine_starts, 0, 24);
  require_in_range("threads", settings.threads, 0, 1024);
  require_in_range("site-radius", settings.site.sphere_radius, 0.1, 100);
  require_in_range("site-margin", settings.site.surface_margin, 0.0, 1000.0);
  settings.spheres.clear();
  for (const std::string& text : settings.site_spheres)
    settings.spheres.push_back(parse_sphere_option(text));
  settings.options.site = settings.site;
  settings.options.top = static_cast<std::size_t>(settings.top);
  settings.options.refine = static_cast<std::size_t>(settings.refine);
  settings.options.candidates = static_cast<std::size_t>(settings.candidates);
  settings.options.refine_starts = static_cast<std::size_t>(settings.refine_starts);
}

bool is_site_query(const ScreenSettings& settings) {
  return !settings.site_ligand.empty() || !settings.site_spheres.empty();
}

matching::MatchInput screen_query_input(matching::MatchInput query,
                                        const ScreenSettings& settings) {
  query.site_ligand = settings.site_ligand;
  query.site_spheres.insert(query.site_spheres.end(), settings.spheres.begin(),
                            settings.spheres.end());
  return query;
}

matching::MatchInputOptions screen_query_options(const ScreenSettings& settings) {
  matching::MatchInputOptions options;
  options.input.read.record = settings.record;
  options.site = settings.site;
  options.descriptors.progress = describe_progress();
  if (console::level() == console::Level::verbose) options.log = &console::step;
  return options;
}

}  // namespace surfcomp::tools
