#include "surfcomp/report/html_report.hpp"

#include "match_document.hpp"
#include "report_page.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/mesh/decimate.hpp"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>
#include <system_error>
#include <vector>

namespace surfcomp::report {
namespace detail {
extern const char* const report_template;  // report/assets/report_template.html (CMake)
}  // namespace detail

namespace {

constexpr const char* kViewerMark = "/*SURFCOMP_VIEWER_JS*/";
constexpr const char* kDataMark = "/*SURFCOMP_REPORT_DATA*/";
constexpr const char* kViewerName = "3Dmol-min.js";

/// Row-major values of `values` as single-precision numbers (what a display needs; a third of
/// the text of doubles).
nlohmann::json flat_floats(const Eigen::MatrixXd& values) {
  nlohmann::json out = nlohmann::json::array();
  out.get_ref<nlohmann::json::array_t&>().reserve(static_cast<std::size_t>(values.size()));
  for (Eigen::Index r = 0; r < values.rows(); ++r)
    for (Eigen::Index c = 0; c < values.cols(); ++c)
      out.push_back(static_cast<float>(values(r, c)));
  return out;
}

/// The side's molecule for sticks, as PDB text (the viewer bonds atoms by distance): the
/// molecule read or built, else the heavy atoms a description keeps; null when there is none.
nlohmann::json molecule_json(const matching::PreparedInput& side) {
  Molecule molecule;
  if (side.molecule) {
    molecule = *side.molecule;
  } else {
    for (const harmonic::SurfaceAtom& a : side.descriptors.atoms) {
      Atom atom;
      atom.element = a.element;
      atom.position = a.position;
      atom.hetero = true;
      molecule.atoms.push_back(atom);
    }
  }
  if (molecule.atoms.empty()) return nullptr;
  std::ostringstream pdb;
  io::write_pdb(molecule, pdb);
  return {{"format", "pdb"}, {"text", pdb.str()}};
}

/// `document` as text that may stand inside a <script> element: every '<' (only ever inside a
/// JSON string) as the JSON escape \u003c, so that no "</script" or "<!--" can end or disturb
/// the element.
std::string script_safe_json(const nlohmann::json& document) {
  const std::string text = detail::json_text(document, -1);
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

bool contains_ignoring_case(const std::string& text, const std::string& needle) {
  const auto found =
      std::search(text.begin(), text.end(), needle.begin(), needle.end(), [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) ==
               std::tolower(static_cast<unsigned char>(b));
      });
  return found != text.end();
}

void require_display_vertices(const HtmlReportOptions& report) {
  if (report.max_display_vertices < 4) {
    throw OptionError(options::named("max_display_vertices") + " must be at least 4, got " +
                      std::to_string(report.max_display_vertices));
  }
}

std::filesystem::path running_program() {
  std::error_code error;
  return std::filesystem::read_symlink("/proc/self/exe", error);
}

}  // namespace

std::filesystem::path find_viewer_script() {
  std::vector<std::filesystem::path> tried;
  if (const char* set = std::getenv("SURFCOMP_VIEWER_SCRIPT"); set != nullptr && *set != '\0') {
    tried.emplace_back(set);
  } else {
    const std::filesystem::path program = running_program();
    if (!program.empty())
      tried.push_back(program.parent_path().parent_path() / "share" / "surfcomp" / kViewerName);
    tried.emplace_back(SURFCOMP_BUILD_VIEWER_SCRIPT);
  }
  std::string list;
  for (const std::filesystem::path& path : tried) {
    std::error_code error;
    if (!path.empty() && std::filesystem::is_regular_file(path, error)) return path;
    if (!path.empty()) list += (list.empty() ? "" : ", ") + path.string();
  }
  throw FileError(kViewerName,
                  "the 3Dmol.js viewer the report inlines was not found (tried " + list +
                      "); run scripts/install-deps.sh, or set SURFCOMP_VIEWER_SCRIPT to the file");
}

namespace detail {

nlohmann::json side_json(const matching::PreparedInput& side, double lining_radius,
                         const HtmlReportOptions& report) {
  require_display_vertices(report);
  const mesh::Surface& surface = side.descriptors.surface;
  const mesh::DecimatedSurface shown = mesh::decimate(surface, report.max_display_vertices);
  mesh::Surface display = shown.surface;
  if (!display.has_normals()) display.compute_normals();
  nlohmann::json properties = nlohmann::json::object();
  for (const char* name : {mesh::property::esp, mesh::property::lp, mesh::property::shape_index,
                           mesh::property::curvedness}) {
    if (display.has_property(name)) properties[name] = flat_floats(display.property(name));
  }
  const Eigen::MatrixX3i faces = display.faces();
  nlohmann::json face_indices = nlohmann::json::array();
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) face_indices.push_back(faces(f, k));

  nlohmann::json points = nlohmann::json::array();
  for (std::size_t i = 0; i < side.descriptors.critical_points.size(); ++i) {
    const mesh::CriticalPoint& p = side.descriptors.critical_points[i].point;
    const bool in_site = side.site_points.empty() || side.site_points[i];
    points.push_back({{"position", {p.position.x(), p.position.y(), p.position.z()}},
                      {"type", mesh::type_name(p.type)},
                      {"in_site", in_site}});
  }
  nlohmann::json lining = nullptr;
  if (!side.site.empty()) {
    const std::vector<bool> lined =
        matching::pocket_lining(side.descriptors, &side.site_points, lining_radius);
    lining = nlohmann::json::array();
    for (std::size_t v = 0; v < shown.original.size(); ++v) {
      if (lined[static_cast<std::size_t>(shown.original[v])]) lining.push_back(v);
    }
  }
  const bool decimated = display.n_vertices() < surface.n_vertices();
  return {{"path", side.name},
          {"surface",
           {{"vertices", flat_floats(display.positions())},
            {"normals", flat_floats(display.normals())},
            {"faces", face_indices},
            {"properties", properties},
            {"vertices_before_decimation",
             decimated ? nlohmann::json(surface.n_vertices()) : nlohmann::json(nullptr)}}},
          {"molecule", molecule_json(side)},
          {"critical_points", points},
          {"site_lining", lining}};
}

std::string file_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

std::string report_page(nlohmann::json document, const HtmlReportOptions& report) {
  require_display_vertices(report);
  const std::filesystem::path viewer_path =
      report.viewer_script.empty() ? find_viewer_script() : report.viewer_script;
  const std::string viewer = io::read_input_file(viewer_path);
  if (contains_ignoring_case(viewer, "</script")) {
    throw FormatError(viewer_path.string(), "holds '</script', so it cannot be inlined in a page");
  }
  document["generated_by"] = std::string("surfcomp ") + SURFCOMP_VERSION;
  std::string page = report_template;
  const std::size_t viewer_at = page.find(kViewerMark);
  const std::size_t data_at = page.find(kDataMark);
  if (viewer_at == std::string::npos || data_at == std::string::npos || viewer_at > data_at)
    throw InputError("the report template lacks its placeholders");
  const std::string data = script_safe_json(document);
  page.replace(data_at, std::string(kDataMark).size(), data);
  page.replace(viewer_at, std::string(kViewerMark).size(), viewer);
  return page;
}

}  // namespace detail

std::string html_report(const matching::InputMatch& compared, const matching::MatchOptions& options,
                        const HtmlReportOptions& report) {
  nlohmann::json document = detail::match_document(compared, options);
  nlohmann::json& alignments = document["alignments"];
  if (report.top > 0 && alignments.size() > report.top) {
    alignments.erase(alignments.begin() + static_cast<std::ptrdiff_t>(report.top),
                     alignments.end());
  }
  const bool sites = !compared.reference.site.empty() || !compared.probe.site.empty();
  document["title"] =
      detail::file_name(compared.reference.name) + " vs " + detail::file_name(compared.probe.name);
  document["mode"] = sites ? "binding_sites" : "molecules";
  document["total_ms"] = {{"surfaces and descriptors", compared.prepare_ms},
                          {"match", compared.match_ms}};
  // The lining's radius is in the inputs' coordinates.
  const double lining = options.site.overlay_radius * compared.unit;
  document["reference"] = detail::side_json(compared.reference, lining, report);
  document["probe"] = detail::side_json(compared.probe, lining, report);
  for (const std::string& note : compared.notes) document["warnings"].push_back(note);
  return detail::report_page(std::move(document), report);
}

void write_html_report(const std::filesystem::path& path, const matching::InputMatch& compared,
                       const matching::MatchOptions& options, const HtmlReportOptions& report) {
  const std::string page = html_report(compared, options, report);
  io::write_file_atomically(path, [&](std::ostream& out) { out << page; });
}

}  // namespace surfcomp::report
