// The HTML report of a match (`surfcomp report`, `match --report`): one self-contained file that
// works offline, showing the two surfaces superposed by the chosen alignment and coloured by
// ESP, LP, shape index or curvedness, the critical points, the chosen alignment's critical-point
// pairs, the molecules as sticks, a table of alignments (a click shows one), the graph trace and
// the timings. The viewer is 3Dmol.js (https://3dmol.org), inlined at report time from where the
// setup command installed it; the page's Content-Security-Policy forbids every request.
#pragma once

#include "surfcomp/matching/match_inputs.hpp"

#include <cstddef>
#include <filesystem>
#include <string>

namespace surfcomp::report {

struct HtmlReportOptions {
  /// Default 60,000 (what 3Dmol draws as one piece). A surface with more vertices is decimated
  /// for display (mesh::decimate), and the page says so. >= 4.
  std::size_t max_display_vertices = 60000;
  /// Default 20. Alignments listed in the table, best first; 0: all.
  std::size_t top = 20;
  /// Default empty: find_viewer_script(). The 3Dmol.js file to inline (3Dmol-min.js).
  std::filesystem::path viewer_script;
};

/// Where 3Dmol-min.js is: $SURFCOMP_VIEWER_SCRIPT if set; else share/surfcomp/3Dmol-min.js
/// beside the running program's bin/ folder (an installed surfcomp); else the copy the build
/// found (report/node_modules/3dmol, installed by scripts/install-deps.sh). Throws FileError
/// naming what was tried when none exists.
std::filesystem::path find_viewer_script();

/// The report of `compared` (matched with `options`) as one HTML document. Throws FileError
/// when the viewer script cannot be read, OptionError for max_display_vertices < 4.
std::string html_report(const matching::InputMatch& compared, const matching::MatchOptions& options,
                        const HtmlReportOptions& report = {});

/// html_report written to `path` atomically (io::write_file_atomically).
void write_html_report(const std::filesystem::path& path, const matching::InputMatch& compared,
                       const matching::MatchOptions& options, const HtmlReportOptions& report = {});

}  // namespace surfcomp::report
