// surfcomp report: the HTML report of a match, one self-contained file to open in a browser.
#include "command.hpp"
#include "console.hpp"
#include "describe_settings.hpp"
#include "match_settings.hpp"
#include "options.hpp"

#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/report/html_report.hpp"

#include <cstdint>
#include <cstdio>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp report REF PROBE -o report.html [match options]\n\n"
    "Matches PROBE onto REF as `surfcomp match` does (the same options) and writes one HTML\n"
    "file that works offline: the two surfaces superposed by the chosen alignment, coloured\n"
    "by ESP, LP, shape index or curvedness (a control switches), the critical points, the\n"
    "alignment's critical-point pairs as lines, the molecules as sticks, a table of the\n"
    "alignments (click a row to show it), the association graph's trace and the timings. For\n"
    "binding sites the pocket linings stand out. Surfaces above --max-display-vertices are\n"
    "simplified for display, and the page says so. The 3Dmol.js viewer is inlined from where\n"
    "scripts/install-deps.sh installed it (or $SURFCOMP_VIEWER_SCRIPT).";

}  // namespace

int report(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output;
  report::HtmlReportOptions options;
  // Read as signed integers, so that a negative value is refused rather than wrapped.
  auto top = static_cast<std::int64_t>(options.top);
  auto max_vertices = static_cast<std::int64_t>(options.max_display_vertices);
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "the report (.html)")
      ("top", defaulted(&top), "alignments listed in the report's table (0: all)")
      ("max-display-vertices", defaulted(&max_vertices),
       "simplify a surface with more vertices than this for display");
  // clang-format on
  add_match_options(described);
  po::variables_map vm;
  if (!parse_command_line(args, described, 2, kUsage, vm)) return 0;
  const auto inputs =
      vm.count("input") ? vm["input"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (inputs.size() != 2) throw OptionError("expected REF and PROBE (see --help)");
  require_in_range("top", static_cast<double>(top), 0, 1e6);
  require_in_range("max-display-vertices", static_cast<double>(max_vertices), 4, 1e7);
  options.top = static_cast<std::size_t>(top);
  options.max_display_vertices = static_cast<std::size_t>(max_vertices);
  const matching::PairMatchOptions settings = match_options_from(vm);
  const PairInputs pair = pair_inputs(inputs[0], inputs[1], settings);
  io::check_command_files({{{"REF", inputs[0]},
                            {"PROBE", inputs[1]},
                            {"--molecule", settings.inputs.input.molecule_file}},
                           {{"--output", output, {".html"}, ""}}});
  options.viewer_script = report::find_viewer_script();  // before the work, not after it

  const ThreadLimit limit(settings.inputs.threads);
  const matching::InputMatch compared =
      matching::match_inputs(pair.reference, pair.probe, settings.inputs);
  for (const std::string& note : compared.notes) console::note(note);
  for (const std::string& warning : compared.warnings)
    std::fprintf(stderr, "surfcomp report: warning: %s\n", warning.c_str());
  report::write_html_report(output, compared, settings.inputs.match, options);
  const auto& alignments = compared.result.alignments;
  if (alignments.empty()) {
    console::summary("%s vs %s: no alignment; %.0f ms -> %s\n", inputs[0].c_str(),
                     inputs[1].c_str(), compared.prepare_ms + compared.match_ms, output.c_str());
  } else {
    console::summary("%s vs %s: %zu alignments, top overlay score %.3f; %.0f ms -> %s\n",
                     inputs[0].c_str(), inputs[1].c_str(), alignments.size(),
                     alignments.front().overlay.score, compared.prepare_ms + compared.match_ms,
                     output.c_str());
  }
  return 0;
}

}  // namespace surfcomp::tools
