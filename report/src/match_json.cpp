#include "match_document.hpp"

#include "surfcomp/report/match_json.hpp"

namespace surfcomp::report {
namespace detail {

namespace {

/// Each critical point of a description, as the alignments' cp_pairs index them: its vertex,
/// type, position (the input's coordinates) and patch status.
nlohmann::json critical_point_list(const harmonic::SurfaceDescriptors& descriptors) {
  nlohmann::json list = nlohmann::json::array();
  for (const harmonic::CriticalPointDescriptor& d : descriptors.critical_points) {
    const mesh::CriticalPoint& p = d.point;
    list.push_back({{"vertex", p.vertex},
                    {"type", mesh::type_name(p.type)},
                    {"position", {p.position.x(), p.position.y(), p.position.z()}},
                    {"patch", harmonic::to_string(d.status)}});
  }
  return list;
}

}  // namespace

nlohmann::json match_document(const matching::InputMatch& compared,
                              const matching::MatchOptions& asked_options, std::size_t top) {
  matching::MatchOptions applied = asked_options;
  applied.shape_only = compared.shape_only;
  const matching::MatchOptions options = matching::shape_only_options(applied);
  const matching::MatchResult& result = compared.result;
  const matching::PreparedInput& ref = compared.reference;
  nlohmann::json alignments = nlohmann::json::array();
  std::size_t distinct = 0;
  for (const auto& a : result.alignments) distinct += a.repeat_of == 0 ? 1 : 0;
  for (const auto& a : result.alignments) {
    if (top > 0 && (a.repeat_of != 0 || alignments.size() >= top)) continue;
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
         {"coverage",
          {{"score", a.coverage.score},
           {"reference", a.coverage.reference},
           {"probe", a.coverage.probe}}},
         {"icp", a.icp},
         {"repeat_of", a.repeat_of > 0 ? nlohmann::json(a.repeat_of) : nlohmann::json(nullptr)},
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
    site = {
        {"lining", *compared.lining},
        {"lining_weight", options.site.lining_weight},
        {"score",
         compared.site_score ? nlohmann::json(*compared.site_score) : nlohmann::json(nullptr)},
        {"z_score", compared.site_z ? nlohmann::json(*compared.site_z) : nlohmann::json(nullptr)},
        {"interactions",
         compared.interactions ? nlohmann::json(*compared.interactions) : nlohmann::json(nullptr)},
        {"fields", compared.fields ? nlohmann::json({{"similarity", compared.fields->similarity},
                                                     {"coverage", compared.fields->coverage}})
                                   : nlohmann::json(nullptr)}};
  }
  return {{"reference", ref.name},
          {"probe", compared.probe.name},
          {"alignments", alignments},
          {"alignments_found", {{"all", result.alignments.size()}, {"distinct", distinct}}},
          {"critical_points",
           {{"reference", critical_point_list(ref.descriptors)},
            {"probe", critical_point_list(compared.probe.descriptors)}}},
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
            {"coverage_distance", options.coverage_distance},
            {"icp_top", options.icp_top},
            {"icp_max_distance", options.icp.max_distance},
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

std::string match_json(const matching::InputMatch& compared, const matching::MatchOptions& options,
                       std::size_t top) {
  return detail::json_text(detail::match_document(compared, options, top), 2) + "\n";
}

}  // namespace surfcomp::report
