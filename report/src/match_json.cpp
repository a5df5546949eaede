#include "match_document.hpp"

#include "surfcomp/report/match_json.hpp"

namespace surfcomp::report {
namespace detail {

nlohmann::json match_document(const matching::InputMatch& compared,
                              const matching::MatchOptions& asked_options) {
  matching::MatchOptions applied = asked_options;
  applied.shape_only = compared.shape_only;
  const matching::MatchOptions options = matching::shape_only_options(applied);
  const matching::MatchResult& result = compared.result;
  const matching::PreparedInput& ref = compared.reference;
  nlohmann::json alignments = nlohmann::json::array();
  for (const auto& a : result.alignments) {
    nlohmann::json transform = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) {
      transform.push_back(
          {a.transform(r, 0), a.transform(r, 1), a.transform(r, 2), a.transform(r, 3)});
    }
    nlohmann::json pairs = nlohmann::json::array();
    for (const auto& [x, y] : a.cp_pairs) pairs.push_back({x, y});
    const char* source = matching::alignment_source_names[static_cast<std::size_t>(a.source)];
    alignments.push_back(
        {{"rank", a.rank},
         {"source", source},
         {"transform", transform},
         {"rmsd", a.rmsd},
         {"n_points", a.n_points},
         {"r_chem", a.r_chem},
         {"consensus", a.consensus},
         {"refined", a.refined},
         {"overlay",
          {{"score", a.overlay.score},
           {"shape", a.overlay.shape},
           {"chem", a.overlay.chem},
           {"atoms", a.overlay.atoms}}},
         {"atom_fit", a.atom_fit},
         {"cp_pairs", pairs},
         {"parent", a.parent > 0 ? nlohmann::json(a.parent) : nlohmann::json(nullptr)},
         {"children", a.children}});
  }
  nlohmann::json trace = nlohmann::json::array();
  for (const auto& stage : result.trace) {
    trace.push_back({{"stage", stage.stage}, {"nodes", stage.nodes}, {"edges", stage.edges}});
  }
  nlohmann::json timing = nlohmann::json::object();
  for (const auto& [stage, ms] : result.timing_ms) timing[stage] = ms;
  const auto& g = options.graph;
  nlohmann::json site = nullptr;  // two sites on structures: their similarity
  if (compared.lining) {
    site = {{"lining", *compared.lining},
            {"lining_weight", options.site.lining_weight},
            {"score",
             compared.site_score ? nlohmann::json(*compared.site_score) : nlohmann::json(nullptr)}};
  }
  return {{"reference", ref.name},
          {"probe", compared.probe.name},
          {"alignments", alignments},
          {"trace", trace},
          {"timing_ms", timing},
          {"cliques",
           {{"count", result.cliques},
            {"complete", result.cliques_complete},
            {"work", result.clique_work}}},
          {"warnings", compared.warnings},
          {"notes", compared.notes},
          {"shape_only", compared.shape_only},
          {"site", site},
          {"scale", {{"unit", compared.unit}, {"from", compared.unit_from}}},
          {"parameters",
           {{"fuzzy_threshold", g.fuzzy_threshold},
            {"image_threshold", g.image_threshold},
            {"distance_tolerance", g.distance_tolerance},
            {"min_distance", g.min_distance},
            {"overlap_tolerance_degrees", g.overlap_tolerance_degrees},
            {"rmsd_cut", options.clustering.rmsd_cut},
            {"merge_cut", options.clustering.merge_cut},
            {"min_clique_size", options.min_clique_size},
            {"max_graph_nodes", g.max_nodes},
            {"max_clique_work", options.max_clique_work},
            {"max_cliques", options.max_cliques},
            {"refine_top", options.refine_top},
            {"overlay_sigma", options.overlay.sigma},
            {"overlay_spacing", options.overlay.spacing},
            {"overlay_chem_weight", options.overlay.chem_weight},
            {"overlay_atom_weight", options.overlay.atom_weight},
            {"polish_top", options.polish_top},
            {"atom_polish_sigma", options.atom_polish.sigma},
            {"atom_polish_weight", options.atom_polish.weight},
            {"overlay_tolerance", options.overlay.tolerance},
            {"principal_axes_starts", options.principal_axes_starts},
            {"site_overlay_radius", options.site.overlay_radius},
            {"site_chem_weight", options.site.chem_weight},
            {"site_lining_weight", options.site.lining_weight},
            {"site_principal_axes_starts", options.site.principal_axes_starts},
            {"critical_point_radius", ref.descriptors.options.critical_points.radius},
            {"patch_radius", ref.descriptors.options.patch.radius},
            {"image_rings", ref.descriptors.options.image.rings},
            {"image_sectors", ref.descriptors.options.image.sectors}}}};
}

std::string json_text(const nlohmann::json& document, int indent) {
  return document.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace detail

std::string match_json(const matching::InputMatch& compared,
                       const matching::MatchOptions& options) {
  return detail::json_text(detail::match_document(compared, options), 2) + "\n";
}

}  // namespace surfcomp::report
