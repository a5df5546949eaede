// surfcomp dock: LIGAND placed into RECEPTOR's pocket by its surface (docs/method.md §15), as a
// table on stdout, the poses as SDF in the receptor's frame and a JSON result file.
#include "command.hpp"
#include "console.hpp"
#include "describe_settings.hpp"
#include "options.hpp"
#include "surface_input.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/docking/dock.hpp"
#include "surfcomp/report/dock_files.hpp"

#include <cstdio>
#include <filesystem>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp dock LIGAND RECEPTOR [-o poses.sdf] [--json result.json]\n"
    "                     [--report dock.html] [options]\n\n"
    "Places LIGAND into RECEPTOR's pocket where its surface fits: the pocket's critical points\n"
    "are paired with the complement of the ligand's (its peaks with the pocket's valleys, its\n"
    "images against the mirror of the pocket's, ESP of opposite and LP of like sign), cliques\n"
    "of pairs give rigid fits and a consensus order. The first --refine-top fits, and every\n"
    "local optimum of --search-chains Monte Carlo chains over the site, are optimised on the\n"
    "complementarity score (contact rewarded, interpenetration penalised, ESP product and LP\n"
    "agreement over the contact; docs/method.md section 15) and ranked by it. A pose that sinks a\n"
    "ligand surface point deeper than twice --clash-tolerance into the receptor's atoms is\n"
    "ranked after every pose that does not (marked ! after its 'deepest'). With --conformers N,\n"
    "N RDKit conformers of the ligand (ETKDG + MMFF, from its bonds) are docked instead of its\n"
    "own coordinates and the best poses over all kept ('conf' names the conformer, 0: its own).\n"
    "--local-only optimises the ligand's own pose on the score and --score-only scores it as\n"
    "it is (a crystal pose, or another program's): one pose, no match and no search.\n\n"
    "LIGAND    a molecule file (.sdf .mol .mol2 for the -o poses)\n"
    "RECEPTOR  a protein structure (.pdb .ent .cif .cif.gz .pqr)\n"
    "The pocket: --site-ligand RES (the crystal's: that HETATM residue is taken out and its\n"
    "neighbourhood is the site), --site-sphere x,y,z,r (repeatable), or --site-pocket N, pocket\n"
    "N as `surfcomp pockets` ranks them; none of these: pocket 1.";

}  // namespace

int dock(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, json, report_out;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output), "write the poses as SDF records in RECEPTOR's frame (.sdf)")
      ("json", po::value(&json), "write the result as JSON (poses, scores, trace, timing_ms)")
      ("report", po::value(&report_out),
       "write the HTML report (.html): the ligand's poses in the pocket, offline in a browser");
  // clang-format on
  add_table_options(described, docking::dock_option_table());
  po::variables_map vm;
  if (!parse_command_line(args, described, 2, kUsage, vm)) return 0;
  const auto inputs =
      vm.count("input") ? vm["input"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (inputs.size() != 2) throw OptionError("expected LIGAND and RECEPTOR (see --help)");
  docking::DockOptions options;
  apply_table_options(docking::dock_option_table(), vm, options);
  show_surface_progress(options.inputs.input.surface);
  options.inputs.descriptors.progress = describe_progress();
  if (console::level() == console::Level::verbose) options.inputs.log = &console::step;

  matching::MatchInput ligand, receptor;
  ligand.path = inputs[0];
  receptor.path = inputs[1];
  docking::check_dock_inputs(ligand, receptor, options);
  io::check_command_files({{{"LIGAND", ligand.path}, {"RECEPTOR", receptor.path}},
                           {{"--output", output, {".sdf"}, ""},
                            {"--json", json, {}, ""},
                            {"--report", report_out, {".html"}, ""}}});
  report::HtmlReportOptions report_options;
  if (!report_out.empty())  // before the work, not after it
    report_options.viewer_script = report::find_viewer_script();

  const ThreadLimit limit(options.inputs.threads);
  const docking::DockResult docked = docking::dock(ligand, receptor, options);
  for (const std::string& note : docked.notes) console::note(note);
  double total_ms = 0.0;
  for (const auto& [step, ms] : docked.timing_ms) total_ms += ms;
  if (options.local_only || options.score_only) {
    console::summary("%s into %s: its own pose, %s, %.0f ms\n", inputs[0].c_str(),
                     inputs[1].c_str(), options.local_only ? "optimised" : "as it is", total_ms);
  } else {
    console::summary("%s into %s: %zu poses from %zu clique alignments, %.0f ms\n",
                     inputs[0].c_str(), inputs[1].c_str(), docked.poses.size(), docked.starts,
                     total_ms);
  }
  if (!docked.poses.empty()) {
    console::summary("%5s %8s %8s %8s %8s %8s %8s %6s %5s  %s\n", "rank", "score", "contact",
                     "clash", "esp", "lp", "deepest", "start", "conf", "translation (A)");
  }
  for (const docking::DockPose& p : docked.poses) {
    console::summary("%5d %8.3f %8.3f %8.3f %8.3f %8.3f %7.2f%s %6d %5d  (%.2f, %.2f, %.2f)\n",
                     p.rank, p.score.score, p.score.contact, p.score.clash, p.score.esp, p.score.lp,
                     p.score.deepest, p.intersects ? "!" : " ", p.start, p.conformer,
                     p.transform(0, 3), p.transform(1, 3), p.transform(2, 3));
  }
  // Outputs last, each atomic; a failure of a later one removes the earlier ones.
  std::vector<std::filesystem::path> written;
  try {
    if (!output.empty()) {
      const std::string poses =
          report::dock_poses_sdf(docked, ligand.path, options.inputs.input.read.record);
      io::write_file_atomically(output, [&](std::ostream& out) { out << poses; });
      written.emplace_back(output);
    }
    if (!json.empty()) {
      const std::string document = report::dock_json(docked, options);
      io::write_file_atomically(json, [&](std::ostream& out) { out << document; });
      written.emplace_back(json);
    }
    if (!report_out.empty()) {
      report::write_dock_html_report(report_out, docked, options, report_options);
      written.emplace_back(report_out);
    }
  } catch (...) {
    for (const auto& path : written) std::filesystem::remove(path);
    throw;
  }
  return 0;
}

}  // namespace surfcomp::tools
