// Internal to the report module: the parts of an HTML report page that a match's report
// (html_report.cpp) and a dock's (dock_report.cpp) share.
#pragma once

#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/report/html_report.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace surfcomp::report::detail {

/// One side of the page: its surface (decimated for display to report.max_display_vertices),
/// its ESP, LP, shape index and curvedness, its molecule as PDB text, its critical points and,
/// for a site, the vertices lining it (within lining_radius of the site's critical points, in
/// the side's coordinates). Throws OptionError for max_display_vertices < 4.
nlohmann::json side_json(const matching::PreparedInput& side, double lining_radius,
                         const HtmlReportOptions& report);

/// The last part of a path, for titles.
std::string file_name(const std::string& path);

/// The page: report/assets/report_template.html with `document` (and generated_by) as its data
/// and the 3Dmol.js viewer inlined. Throws FileError when the viewer script cannot be read,
/// FormatError when it cannot stand inside a <script> element, OptionError for
/// max_display_vertices < 4.
std::string report_page(nlohmann::json document, const HtmlReportOptions& report);

}  // namespace surfcomp::report::detail
