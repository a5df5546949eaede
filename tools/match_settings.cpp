#include "match_settings.hpp"

#include "console.hpp"
#include "describe_settings.hpp"
#include "options.hpp"

#include <algorithm>
#include <optional>
#include <utility>

namespace surfcomp::tools {
namespace {

/// A notifier refusing a value <= 0 as a command-line error (like a value that is no integer).
auto positive(const char* name) {
  return [name](std::int64_t value) {
    if (value <= 0) {
      namespace po = boost::program_options;
      po::validation_error error(po::validation_error::invalid_option_value, name,
                                 std::to_string(value), po::command_line_style::allow_long);
      error.set_substitute("value", std::to_string(value));
      throw error;
    }
  };
}

}  // namespace

matching::SiteSphere parse_sphere_option(const std::string& text) {
  const std::optional<matching::SiteSphere> sphere = matching::parse_site_sphere(text);
  if (!sphere) throw OptionError("--site-sphere '" + text + "': expected x,y,z,r with r > 0 (A)");
  return *sphere;
}

void add_match_options(boost::program_options::options_description& options,
                       MatchSettings& settings) {
  namespace po = boost::program_options;
  auto& g = settings.match.graph;
  auto& m = settings.match;
  // clang-format off
  options.add_options()
      ("site-ligand", po::value(&settings.site_ligand),
       "binding site of both proteins: this ligand residue name")
      ("ref-site-ligand", po::value(&settings.ref_site_ligand), "binding site of REF only")
      ("probe-site-ligand", po::value(&settings.probe_site_ligand), "binding site of PROBE only")
      ("site-radius", defaulted(&settings.site.sphere_radius),
       "radius of the spheres around the site ligand's atoms, A")
      ("site-sphere", po::value(&settings.site_spheres)->composing(),
       "site sphere x,y,z,r on both sides (A)")
      ("site-margin", defaulted(&settings.site.surface_margin), kSiteMarginHelp)
      ("ref-site-sphere", po::value(&settings.ref_site_spheres)->composing(),
       "site sphere on REF only")
      ("probe-site-sphere", po::value(&settings.probe_site_spheres)->composing(),
       "site sphere on PROBE only")
      ("fuzzy-threshold", defaulted(&g.fuzzy_threshold),
       "fuzzy ESP/LP similarity threshold F")
      ("image-threshold", defaulted(&g.image_threshold),
       "harmonic shape image correlation threshold R")
      ("distance-tolerance", defaulted(&g.distance_tolerance),
       "distance filter tolerance t, A")
      ("min-distance", defaulted(&g.min_distance),
       "distance filter minimum d_min, A")
      ("overlap-tolerance", defaulted(&g.overlap_tolerance_degrees),
       "overlap filter tolerance j_tol, degrees")
      ("max-graph-nodes", defaulted(&settings.max_graph_nodes)
                              ->notifier(positive("max-graph-nodes")),
       "refuse a match whose association graph keeps more critical-point pairs than this after "
       "the image filter (a positive integer); its cost grows with the square of the count")
      ("max-clique-work", defaulted(&settings.max_clique_work)
                              ->notifier(positive("max-clique-work")),
       "stop the clique search after this much work (a positive integer; a unit is one 64-node "
       "word of a set operation, a few ns) and go on with the cliques found, saying so")
      ("max-cliques", defaulted(&settings.max_cliques)
                          ->notifier(positive("max-cliques")),
       "stop the clique search rather than report more cliques than this (a positive integer); "
       "each is fitted and merged, in time quadratic in their number")
      ("rmsd-cut", defaulted(&m.clustering.rmsd_cut),
       "drop cliques whose fit RMSD exceeds this, A")
      ("ranking", po::value(&settings.ranking)->default_value("rank"),
       "consensus: rank (rank-by-rank) | number (rank-by-number) | vote (rank-by-vote)")
      ("refine-top", defaulted(&m.refine_top),
       "refine this many alignments on the whole surfaces and rank them by their overlay score "
       "(0: the seed's consensus ranking alone)")
      ("overlay-sigma", defaulted(&m.overlay.sigma),
       "Gaussian width of the whole-surface overlay, A")
      ("overlay-chem-weight", defaulted(&m.overlay.chem_weight),
       "weight of the ESP/LP Tanimoto against the shape Tanimoto in the overlay score")
      ("overlay-atom-weight", defaulted(&m.overlay.atom_weight),
       "weight of the same-element heteroatom Tanimoto in the overlay score, where both inputs "
       "are molecules (or .hsi files built from molecules); not for site matches")
      ("polish-top", defaulted(&m.polish_top),
       "with the atom term, refine the first N alignments again on the whole score, heteroatoms "
       "pulled too, and order them again (0: no polish)")
      ("overlay-tolerance", defaulted(&m.overlay.tolerance),
       "a refinement stops when a step moves no sampled probe point farther than this, A")
      ("principal-axes-starts", defaulted(&m.principal_axes_starts),
       "also refine this many principal-axes superpositions of the whole surfaces: 0, 4 or 24 "
       "(with --refine-top > 0; so do the --site-* overlay options)")
      ("site-overlay-radius", defaulted(&m.site.overlay_radius),
       "site matches: overlay the vertices within this distance of the site's critical points, A")
      ("site-chem-weight", defaulted(&m.site.chem_weight),
       "site matches: --overlay-chem-weight for the pocket overlay")
      ("site-principal-axes-starts", defaulted(&m.site.principal_axes_starts),
       "site matches: --principal-axes-starts for the pocket overlay (0, 4 or 24)")
      ("patch-radius", defaulted(&settings.descriptors.patch.radius),
       "patch radius for molecule/mesh inputs, A (about 5 for ligands, larger for sites)")
      ("max-image-bytes", defaulted(&settings.descriptors.max_image_bytes),
       "limit: memory of the shape images of a molecule/mesh input, bytes");
  // clang-format on
  add_surface_options(options, settings.input);
}

void finish_match_options(MatchSettings& settings,
                          const boost::program_options::variables_map& vm) {
  finish_surface_options(settings.input);
  auto& m = settings.match;
  auto& g = m.graph;
  m.max_clique_work = settings.max_clique_work;
  m.max_cliques = static_cast<std::size_t>(settings.max_cliques);
  g.max_nodes = static_cast<std::size_t>(settings.max_graph_nodes);
  require_in_range("site-radius", settings.site.sphere_radius, 0.1, 100.0);
  require_in_range("site-margin", settings.site.surface_margin, 0.0, 1000.0);
  require_in_range("fuzzy-threshold", g.fuzzy_threshold, 0.0, 1.0);
  require_in_range("image-threshold", g.image_threshold, -1.0, 1.0);
  require_in_range("distance-tolerance", g.distance_tolerance, 0.0, 100.0);
  require_in_range("min-distance", g.min_distance, 0.0, 100.0);
  require_in_range("overlap-tolerance", g.overlap_tolerance_degrees, 0.0, 180.0);
  require_positive("rmsd-cut", m.clustering.rmsd_cut, 100.0);
  require_in_range("patch-radius", settings.descriptors.patch.radius, 0.1, 100.0);
  require_in_range("refine-top", m.refine_top, 0, 1e6);
  require_in_range("overlay-sigma", m.overlay.sigma, 0.1, 10.0);
  require_in_range("overlay-chem-weight", m.overlay.chem_weight, 0.0, 100.0);
  require_in_range("overlay-atom-weight", m.overlay.atom_weight, 0.0, 1000.0);
  require_in_range("overlay-tolerance", m.overlay.tolerance, 0.0, 10.0);
  require_in_range("polish-top", m.polish_top, 0, 1e6);
  require_in_range("site-overlay-radius", m.site.overlay_radius, 0.1, 100.0);
  require_in_range("site-chem-weight", m.site.chem_weight, 0.0, 100.0);
  for (const auto& [name, value] :
       {std::pair<const char*, int>{"principal-axes-starts", m.principal_axes_starts},
        std::pair<const char*, int>{"site-principal-axes-starts", m.site.principal_axes_starts}}) {
    if (!matching::is_axes_start_count(value)) {
      throw OptionError(std::string("--") + name + " must be 0, 4 or 24, got " +
                        std::to_string(value));
    }
  }
  require_one_of("ranking", settings.ranking, {"rank", "number", "vote"});
  m.ranking.scheme = settings.ranking == "number" ? matching::ConsensusScheme::rank_by_number
                     : settings.ranking == "vote" ? matching::ConsensusScheme::rank_by_vote
                                                  : matching::ConsensusScheme::rank_by_rank;
  settings.ref_spheres.clear();
  settings.probe_spheres.clear();
  for (const auto& text : settings.site_spheres) {
    settings.ref_spheres.push_back(parse_sphere_option(text));
    settings.probe_spheres.push_back(parse_sphere_option(text));
  }
  for (const auto& text : settings.ref_site_spheres)
    settings.ref_spheres.push_back(parse_sphere_option(text));
  for (const auto& text : settings.probe_site_spheres)
    settings.probe_spheres.push_back(parse_sphere_option(text));
  settings.ref_site_option =
      settings.ref_site_ligand.empty() ? "--site-ligand" : "--ref-site-ligand";
  settings.probe_site_option =
      settings.probe_site_ligand.empty() ? "--site-ligand" : "--probe-site-ligand";
  if (settings.ref_site_ligand.empty()) settings.ref_site_ligand = settings.site_ligand;
  if (settings.probe_site_ligand.empty()) settings.probe_site_ligand = settings.site_ligand;
  matching::MatchOptions checked = m;
  if (!settings.ref_site_ligand.empty() || !settings.probe_site_ligand.empty() ||
      !settings.ref_spheres.empty() || !settings.probe_spheres.empty()) {
    checked.mode = matching::MatchMode::binding_sites;
  }
  matching::validate(checked);
}

matching::MatchInputOptions match_input_options(const MatchSettings& settings) {
  matching::MatchInputOptions options;
  options.input = settings.input;
  options.descriptors = settings.descriptors;
  options.descriptors.progress = describe_progress();
  options.site = settings.site;
  options.match = settings.match;
  if (console::level() == console::Level::verbose) options.log = &console::step;
  return options;
}

matching::MatchInput with_site(matching::MatchInput input, const MatchSettings& settings,
                               bool reference) {
  input.site_ligand = reference ? settings.ref_site_ligand : settings.probe_site_ligand;
  const auto& spheres = reference ? settings.ref_spheres : settings.probe_spheres;
  input.site_spheres.insert(input.site_spheres.end(), spheres.begin(), spheres.end());
  return input;
}

PairInputs pair_inputs(const std::filesystem::path& reference, const std::filesystem::path& probe,
                       const MatchSettings& settings) {
  PairInputs inputs;
  inputs.reference.path = reference;
  inputs.probe.path = probe;
  inputs.reference = with_site(std::move(inputs.reference), settings, true);
  inputs.probe = with_site(std::move(inputs.probe), settings, false);
  const matching::MatchInputOptions options = match_input_options(settings);
  matching::check_match_input(inputs.reference, options, "REF", settings.ref_site_option);
  matching::check_match_input(inputs.probe, options, "PROBE", settings.probe_site_option);
  return inputs;
}

}  // namespace surfcomp::tools
