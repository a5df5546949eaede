// surfcomp match: ranked rigid alignments of PROBE onto REF (method §5-7), as a table on
// stdout and a JSON file other tools read; optionally PROBE moved by the top alignment.
#include "command.hpp"
#include "console.hpp"
#include "describe_settings.hpp"
#include "match_settings.hpp"
#include "options.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/matching/match.hpp"
#include "surfcomp/matching/site.hpp"
#include "surfcomp/report/aligned_probe.hpp"
#include "surfcomp/report/html_report.hpp"
#include "surfcomp/report/match_json.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp match REF PROBE [-o result.json] [--aligned-out FILE.sdf|.pdb|.ply]\n"
    "                      [options]\n\n"
    "Finds where PROBE's surface looks and feels like REF's and returns ranked rigid\n"
    "alignments that move PROBE into REF's frame: critical-point pairs filtered by ESP/LP\n"
    "(fuzzy), harmonic shape images, distances and overlap; maximal cliques; least-squares fits\n"
    "on the images' corresponding points; single-linkage merging; consensus ranking\n"
    "(docs/method.md §5-6); then the first --refine-top alignments are refined on the whole "
    "surfaces\n"
    "(Gaussian overlay of shape, ESP and LP) and ranked by that overlay score (table column\n"
    "'overlay', * = refined), together with --principal-axes-starts superpositions refined the\n"
    "same way (column 'from': axes). Where both inputs are molecules (or .hsi files built from\n"
    "molecules), a refined pose's score also weighs the overlap of same-element heteroatoms\n"
    "(--overlay-atom-weight), and the first --polish-top poses are refined again on that whole\n"
    "score plus --atom-polish-weight x the like-element Gaussian overlap of all heavy atoms\n"
    "(--atom-polish-sigma; column 'atom_fit', a Tanimoto); the poses go by that sum.\n"
    "Poses that repeat a better one are left out (--all-alignments keeps them). The first\n"
    "--refine-top distinct poses get their coverage (column 'coverage'): the larger of the\n"
    "fractions of each surface within --coverage-distance of the other, near 1 for a true\n"
    "partial match (a scan of part of a mesh) where the overlay score stays low. --icp-top N\n"
    "polishes the first N distinct poses last by point-to-plane ICP on the whole surfaces.\n\n"
    "REF, PROBE  a molecule or a mesh (%s), or a .hsi file from\n"
    "            hsi-build (two .hsi files must have been built with the same parameters)\n"
    "Binding sites: --site-ligand RES (both sides) or --ref-site-ligand/--probe-site-ligand\n"
    "build the protein's surface without water and without one copy of that HETATM residue (the\n"
    "lowest chain, then residue number) and keep the critical points within --site-radius of\n"
    "its atoms; --site-sphere x,y,z,r (repeatable; also --ref-/--probe-site-sphere) adds\n"
    "spheres. --site-pocket N (also --ref-/--probe-site-pocket) takes the structure's pocket N\n"
    "as `surfcomp pockets` finds and ranks it, without a ligand: its alpha spheres on the\n"
    "ATOM records (ligands, ions and water set aside). A site's surface is the structure's\n"
    "SES meshed only within --site-margin - 3 A of its spheres (the whole structure's surface\n"
    "wherever patches of up to 8 A reach; ESP and LP from every atom). A site match overlays\n"
    "the pocket linings (within --site-overlay-radius of the\n"
    "site's critical points) on shape and, weighted by --site-chem-weight, ESP/LP colour from\n"
    "the cliques and 24 principal-axes starts; the top-1 overlay score is then the sites'\n"
    "similarity ((shape + w chem) / (1 + w) Tanimoto of the linings).";

}  // namespace

int match(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, aligned_out, report_out;
  int top = 10;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output),
       "write the result as JSON (alignments, trace, timing_ms, parameters)")
      ("aligned-out", po::value(&aligned_out),
       "write PROBE moved by the top alignment: .sdf (SDF/MOL/MOL2 PROBE), .pdb (molecule PROBE) "
       "or .ply; with no alignment, a warning and no file")
      ("report", po::value(&report_out),
       "also write the HTML report (.html) of the match, as `surfcomp report` does")
      ("top", defaulted(&top),
       "distinct alignments shown in the table and written to the result file (a pose that "
       "repeats a better one, no sampled point moved by more than 0.5 A, is left out)")
      ("all-alignments", po::bool_switch(),
       "write every alignment to the result file: the whole merge tree and the repeats")
      ("trace", po::bool_switch(), "print the association graph's nodes and edges after each stage");
  // clang-format on
  add_match_options(described);
  po::variables_map vm;
  if (!parse_command_line(args, described, 2, with_formats(kUsage).c_str(), vm)) return 0;
  const auto inputs =
      vm.count("input") ? vm["input"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (inputs.size() != 2) throw OptionError("expected REF and PROBE (see --help)");
  require_in_range("top", top, 1, 1e9);
  const matching::PairMatchOptions settings = match_options_from(vm);
  const std::filesystem::path ref_path = inputs[0], probe_path = inputs[1];
  const PairInputs pair = pair_inputs(ref_path, probe_path, settings);
  const std::vector<std::string> aligned = report::aligned_probe_formats(probe_path);
  io::check_command_files({{{"REF", ref_path},
                            {"PROBE", probe_path},
                            {"--molecule", settings.inputs.input.molecule_file}},
                           {{"--output", output, {}, ""},
                            {"--aligned-out", aligned_out, aligned,
                             aligned.size() == 1   ? "PROBE is not a molecule"
                             : aligned.size() == 2 ? "PROBE is not an SDF, MOL or MOL2 file"
                                                   : ""},
                            {"--report", report_out, {".html"}, ""}}});
  report::HtmlReportOptions report_options;
  if (!report_out.empty())  // before the work, not after it
    report_options.viewer_script = report::find_viewer_script();

  const ThreadLimit limit(settings.inputs.threads);
  const matching::InputMatch compared =
      matching::match_inputs(pair.reference, pair.probe, settings.inputs);
  const matching::MatchResult& result = compared.result;
  for (const std::string& note : compared.notes) console::note(note);
  for (const std::string& warning : compared.warnings)
    std::fprintf(stderr, "surfcomp match: warning: %s\n", warning.c_str());

  if (vm["trace"].as<bool>()) {
    console::summary("%-16s %8s %10s %10s\n", "stage", "nodes", "edges", "ms");
    for (const auto& stage : result.trace) {
      console::summary("%-16s %8zu %10zu %10.2f\n", stage.stage.c_str(), stage.nodes, stage.edges,
                       stage.milliseconds);
    }
    console::summary("%zu maximal cliques\n\n", result.cliques);
  }
  const auto distinct =
      std::count_if(result.alignments.begin(), result.alignments.end(),
                    [](const matching::Alignment& a) { return a.repeat_of == 0; });
  console::summary(
      "%s vs %s: %ld distinct poses of %zu alignments, surfaces and images %.0f ms, match %.0f "
      "ms\n",
      ref_path.string().c_str(), probe_path.string().c_str(), static_cast<long>(distinct),
      result.alignments.size(), compared.prepare_ms, compared.match_ms);
  if (compared.site_score) {
    const double w = settings.inputs.match.site.lining_weight;
    console::summary("site score %.3f: (overlay %.3f + %.2f x lining %.3f) / %.2f\n",
                     *compared.site_score, result.alignments.front().overlay.score, w,
                     *compared.lining, 1.0 + w);
    if (compared.site_z) {
      console::summary(
          "site z-score %.2f: spreads above unrelated sites of this size (0 unrelated, "
          "3 or more rare without a relation)\n",
          *compared.site_z);
    }
  }
  if (!result.alignments.empty()) {
    console::summary("%5s %-7s %8s %8s %8s %9s %8s %8s %8s %6s %7s  %s\n", "rank", "from", "rmsd",
                     "points", "r_chem", "consensus", "overlay", "coverage", "atom_fit", "pairs",
                     "parent", "rotation (deg) / translation (A)");
  }
  // The atom fit is scored between two molecules only: "-" elsewhere.
  const bool atom_fitted =
      std::any_of(result.alignments.begin(), result.alignments.end(),
                  [](const matching::Alignment& a) { return a.atom_fit > 0.0; });
  int shown = 0;
  for (const auto& a : result.alignments) {
    if (a.repeat_of != 0) continue;
    if (shown++ == top) break;
    const Eigen::Matrix3d r = a.transform.topLeftCorner<3, 3>();
    const double angle = std::acos(std::clamp((r.trace() - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / M_PI;
    char fit[16] = "-";
    if (atom_fitted) std::snprintf(fit, sizeof fit, "%.3f", a.atom_fit);
    char coverage[16] = "-";  // only the scored alignments are measured
    if (a.coverage.score > 0.0 || a.refined)
      std::snprintf(coverage, sizeof coverage, "%.3f", a.coverage.score);
    if (a.source == matching::AlignmentSource::cliques) {
      console::summary(
          "%5d %-7s %8.3f %8zu %8.3f %9.3f %7.3f%s %8s %8s %6zu %7s  %.1f / (%.2f, %.2f, %.2f)\n",
          a.rank, "cliques", a.rmsd, a.n_points, a.r_chem, a.consensus, a.overlay.score,
          a.refined ? "*" : " ", coverage, fit, a.cp_pairs.size(),
          a.parent > 0 ? std::to_string(a.parent).c_str() : "-", angle, a.transform(0, 3),
          a.transform(1, 3), a.transform(2, 3));
    } else {  // no CP correspondences behind it: no fit RMSD, points, R_chem, consensus or tree
      console::summary(
          "%5d %-7s %8s %8s %8s %9s %7.3f%s %8s %8s %6s %7s  %.1f / (%.2f, %.2f, %.2f)\n", a.rank,
          "axes", "-", "-", "-", "-", a.overlay.score, a.refined ? "*" : " ", coverage, fit, "-",
          "-", angle, a.transform(0, 3), a.transform(1, 3), a.transform(2, 3));
    }
  }
  // Outputs last, each atomic; a failure of a later one removes the earlier ones.
  std::vector<std::filesystem::path> written;
  try {
    if (!aligned_out.empty() && result.alignments.empty()) {
      std::fprintf(stderr, "surfcomp match: warning: no alignment found: %s not written\n",
                   aligned_out.c_str());
    } else if (!aligned_out.empty()) {
      report::write_aligned_probe(aligned_out, probe_path, settings.inputs.input.read.record,
                                  compared.probe, result.alignments.front().transform);
      written.emplace_back(aligned_out);
    }
    if (!output.empty()) {
      const std::string document =
          report::match_json(compared, settings.inputs.match,
                             vm["all-alignments"].as<bool>() ? 0 : static_cast<std::size_t>(top));
      surfcomp::io::write_file_atomically(output, [&](std::ostream& out) { out << document; });
      written.emplace_back(output);
    }
    if (!report_out.empty())
      report::write_html_report(report_out, compared, settings.inputs.match, report_options);
  } catch (...) {
    for (const auto& path : written) std::filesystem::remove(path);
    throw;
  }
  return 0;
}

}  // namespace surfcomp::tools
