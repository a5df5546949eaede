// A dock's HTML report: the page of a match's report in its dock mode, the receptor's site as
// the reference, each pose's ligand (or conformer) as the probe.
#include "surfcomp/report/dock_files.hpp"

#include "dock_pose_terms.hpp"
#include "report_page.hpp"
#include "surfcomp/core/io/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <map>

namespace surfcomp::report {
namespace {

nlohmann::json pose_json(const docking::DockPose& p, int probe) {
  nlohmann::json transform = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) {
    transform.push_back(
        {p.transform(r, 0), p.transform(r, 1), p.transform(r, 2), p.transform(r, 3)});
  }
  nlohmann::json pairs = nlohmann::json::array();
  for (const auto& [receptor, ligand] : p.cp_pairs) pairs.push_back({receptor, ligand});
  nlohmann::json terms = detail::dock_pose_terms<nlohmann::json>(p);
  terms["start"] = p.start;
  terms["conformer"] = p.conformer;
  return {{"rank", p.rank},
          {"transform", transform},
          {"cp_pairs", pairs},
          {"probe", probe},
          {"dock", terms}};
}

}  // namespace

std::string dock_html_report(const docking::DockResult& docked, const docking::DockOptions& options,
                             const HtmlReportOptions& report) {
  nlohmann::json document;
  document["title"] =
      detail::file_name(docked.ligand.name) + " in " + detail::file_name(docked.receptor.name);
  document["mode"] = "dock";
  const double lining = options.inputs.match.site.overlay_radius;  // A: molecules only
  document["reference"] = detail::side_json(docked.receptor, lining, report);
  document["probe"] = detail::side_json(docked.ligand, lining, report);
  // A probe side per conformer that a listed pose places, in the order the poses first name
  // them (a page of 1000 conformers' surfaces would be of little use).
  nlohmann::json poses = nlohmann::json::array();
  nlohmann::json probes = nlohmann::json::array();
  std::map<int, int> probe_of;  // conformer -> index into probes
  for (const docking::DockPose& p : docked.poses) {
    if (report.top > 0 && poses.size() >= report.top) break;
    int probe = 0;
    if (p.conformer > 0) {
      const auto [at, added] = probe_of.try_emplace(p.conformer, static_cast<int>(probes.size()));
      if (added) {
        probes.push_back(detail::side_json(
            docked.conformer_inputs.at(static_cast<std::size_t>(p.conformer - 1)), lining, report));
      }
      probe = at->second;
    }
    poses.push_back(pose_json(p, probe));
  }
  if (!probes.empty()) document["probes"] = probes;
  document["alignments"] = poses;
  nlohmann::json trace = nlohmann::json::array();
  for (const matching::TraceStage& stage : docked.trace)
    trace.push_back({{"stage", stage.stage}, {"nodes", stage.nodes}, {"edges", stage.edges}});
  document["trace"] = trace;
  nlohmann::json timing = nlohmann::json::object();
  for (const auto& [step, ms] : docked.timing_ms) timing[step] = ms;
  document["timing_ms"] = timing;
  document["warnings"] = docked.notes;
  nlohmann::json parameters = detail::dock_parameters<nlohmann::json>(options);
  parameters["site free volume (A^3)"] = docked.site_volume;
  parameters["ligand volume (A^3)"] = docked.ligand_volume;
  parameters["clique alignments"] = docked.starts;
  parameters["conformers docked"] = docked.conformers.size();
  document["parameters"] = parameters;
  return detail::report_page(std::move(document), report);
}

void write_dock_html_report(const std::filesystem::path& path, const docking::DockResult& docked,
                            const docking::DockOptions& options, const HtmlReportOptions& report) {
  const std::string page = dock_html_report(docked, options, report);
  io::write_file_atomically(path, [&](std::ostream& out) { out << page; });
}

}  // namespace surfcomp::report
