#include "functions.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/docking/dock.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/molsurf/pockets.hpp"
#include "surfcomp/report/dock_files.hpp"
#include "surfcomp/report/html_report.hpp"
#include "surfcomp/screening/hit_files.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/matrix.hpp"
#include "surfcomp/screening/receptor_screen.hpp"
#include "surfcomp/screening/screen.hpp"
#include "surfcomp/screening/shape_screen.hpp"

#include <pybind11/stl.h>

#include <cstdint>
#include <filesystem>
#include <limits>

namespace surfcomp::python {
namespace {

/// A row of a screen's table: its rank and its molecule's entry, as Hit and FusedHit begin.
py::dict entry_row(const screening::Library& library, std::size_t rank, std::size_t entry) {
  const screening::LibraryEntryInfo info = library.info(entry);
  py::dict d;
  d["rank"] = rank;
  d["entry"] = entry + 1;
  d["name"] = info.name;
  d["source"] = info.source;
  d["record"] = info.record;
  d["conformer"] = info.conformer;
  return d;
}

/// One screen's rows as dicts (Hit's fields), with each hit's molecule moved onto the query
/// ("aligned": its text and format) when `molecules`.
py::list hit_list(const screening::Library& library, const std::vector<screening::Hit>& hits,
                  const screening::QueryScreenOptions& settings, bool molecules) {
  py::list rows;
  for (std::size_t k = 0; k < hits.size(); ++k) {
    const screening::Hit& hit = hits[k];
    Eigen::Matrix<double, 4, 4, Eigen::RowMajor> transform = hit.score.transform;
    py::dict d = entry_row(library, k + 1, hit.entry);
    d["score"] = hit.score.score;
    d["stage"] = hit.stage;
    d["shape"] = hit.score.shape;
    d["chem"] = hit.score.chem;
    d["atoms"] = hit.score.atoms;
    d["fast_score"] = hit.fast_score;
    d["transform"] = owned_array(std::move(transform));
    if (molecules) {
      const bool site = screening::is_site_query(settings);
      d["aligned"] = py::make_tuple(
          site ? screening::aligned_site_model(library, hit, k + 1, settings.screen.read)
               : screening::aligned_hit_record(library, hit, k + 1),
          site ? "pdb" : "sdf");
    }
    rows.append(d);
  }
  return rows;
}

}  // namespace

PySurface build_surface(const py::object& input, const py::dict& keywords) {
  const auto settings = settings_from(molsurf::surface_input_option_table(), keywords);
  matching::MatchInput in = input_of(input, settings);
  py::gil_scoped_release release;
  PySurface out;
  if (in.molecule) {
    out.surface = molsurf::build_molecular_surface(*in.molecule, settings.surface);
    out.molecule = std::move(in.molecule);
  } else {
    molsurf::LoadedSurface loaded =
        in.surface ? molsurf::load_mesh_surface(std::move(*in.surface), settings)
                   : molsurf::load_surface(in.path, settings);
    out.surface = std::move(loaded.surface);
    out.molecule = std::move(loaded.molecule);
    out.length_unit = loaded.unit.value;
  }
  return out;
}

PyDescriptors describe(const py::object& input, const py::dict& keywords) {
  auto settings = settings_from(matching::describe_option_table(), keywords);
  // A Surface built in a unit of its own is described in it unless another is asked for.
  if (py::isinstance<PySurface>(input) && settings.input.unit == 0.0 &&
      input.cast<const PySurface&>().length_unit != 1.0) {
    settings.input.unit = input.cast<const PySurface&>().length_unit;
  }
  const matching::MatchInput in = input_of(input, settings.input);
  py::gil_scoped_release release;
  const ThreadLimit limit(settings.threads);
  PyDescriptors out;
  out.descriptors = matching::prepare_input(in, settings).descriptors;
  return out;
}

py::dict match(const py::object& reference, const py::object& probe, const py::dict& keywords,
               const std::string& report_path) {
  const auto settings = settings_from(matching::pair_match_option_table(), keywords);
  const matching::MatchInput ref =
      matching::with_site(input_of(reference, settings.inputs.input), settings.sites, true);
  const matching::MatchInput prb =
      matching::with_site(input_of(probe, settings.inputs.input), settings.sites, false);
  matching::check_match_input(ref, settings.inputs, "REF",
                              matching::site_ligand_option(settings.sites, true));
  matching::check_match_input(prb, settings.inputs, "PROBE",
                              matching::site_ligand_option(settings.sites, false));
  report::HtmlReportOptions report_options;
  if (!report_path.empty()) {  // as the CLI checks --report: before the work
    io::check_command_files(
        {{{"REF", ref.path}, {"PROBE", prb.path}}, {{"report", report_path, {".html"}, ""}}});
    report_options.viewer_script = report::find_viewer_script();
  }
  std::optional<matching::InputMatch> compared;
  {
    py::gil_scoped_release release;
    const ThreadLimit limit(settings.inputs.threads);
    compared = matching::match_inputs(ref, prb, settings.inputs);
    if (!report_path.empty())
      report::write_html_report(report_path, *compared, settings.inputs.match, report_options);
  }
  return match_dict(*compared, settings.inputs.match.site.lining_weight);
}

/// Every query of `queries` screened against the library in one pass: {"hits": one list of
/// rows per query, "fused": the fused ranking's rows (several queries only)}.
py::dict screen(const py::list& queries, const std::string& library_path, const py::dict& keywords,
                bool molecules) {
  const auto settings = settings_from(screening::screen_option_table(), keywords);
  const matching::MatchInputOptions query_options = screening::screen_query_options(settings);
  std::vector<matching::MatchInput> inputs;
  for (const py::handle query : queries) {
    inputs.push_back(screening::screen_query_input(input_of(query, query_options.input), settings));
    matching::check_match_input(inputs.back(), query_options, "QUERY");
  }
  std::optional<screening::Library> library;
  screening::MultiScreenResult result;
  {
    py::gil_scoped_release release;
    const ThreadLimit limit(settings.query.threads);
    library.emplace(library_path);
    screening::check_library_kind(*library, screening::is_site_query(settings));
    std::vector<screening::ScreenQuery> prepared_queries;
    for (const matching::MatchInput& in : inputs) {
      matching::PreparedInput prepared = matching::prepare_input(in, query_options);
      prepared_queries.push_back(screening::make_screen_query(
          std::move(prepared.descriptors), settings.screen, prepared.site,
          prepared.molecule ? &*prepared.molecule : nullptr));
    }
    screening::agree_on_chemistry(prepared_queries);
    std::vector<const screening::ScreenQuery*> pointers(prepared_queries.size());
    for (std::size_t q = 0; q < pointers.size(); ++q) pointers[q] = &prepared_queries[q];
    result = screening::screen_queries(pointers, *library, settings.screen);
  }
  py::list per_query;
  for (const std::vector<screening::Hit>& hits : result.hits)
    per_query.append(hit_list(*library, hits, settings, molecules));
  py::list fused;
  for (std::size_t k = 0; k < result.fused.size(); ++k) {
    const screening::FusedHit& hit = result.fused[k];
    py::dict d = entry_row(*library, k + 1, hit.entry);
    d["score"] = hit.score;
    d["query"] = hit.query + 1;
    d["scores"] = py::tuple(py::cast(hit.scores));
    fused.append(d);
  }
  py::dict out;
  out["hits"] = per_query;
  out["fused"] = fused;
  return out;
}

py::list screen_receptor(const py::object& receptor, const std::string& library_path,
                         const py::dict& keywords) {
  const auto settings = settings_from(screening::receptor_screen_option_table(), keywords);
  screening::validate(settings);
  const matching::MatchInput input = input_of(receptor, settings.dock.inputs.input);
  std::optional<screening::Library> library;
  screening::ReceptorScreenResult result;
  {
    py::gil_scoped_release release;
    const ThreadLimit limit(settings.dock.inputs.threads);
    library.emplace(library_path);
    result = screening::receptor_screen(input, *library, settings);
  }
  py::list rows;
  for (std::size_t k = 0; k < result.hits.size(); ++k) {
    const screening::ReceptorHit& hit = result.hits[k];
    py::dict d = entry_row(*library, k + 1, hit.entry);
    d["score"] = hit.score.score;
    d["stage"] = hit.stage;
    d["contact"] = hit.score.contact;
    d["clash"] = hit.score.clash;
    d["esp"] = hit.score.esp;
    d["lp"] = hit.score.lp;
    d["deepest"] = hit.score.deepest;
    d["area"] = hit.area;
    d["fast_score"] = hit.fast_score;
    Eigen::Matrix<double, 4, 4, Eigen::RowMajor> transform = hit.transform;
    d["transform"] = owned_array(std::move(transform));
    rows.append(d);
  }
  return rows;
}

/// A mesh query screened by shape against a library of meshes (screening::screen_shapes): one
/// dict per hit (ShapeHit's fields), best first.
py::list screen_shapes(const py::handle& query, const std::string& library_path,
                       const py::dict& keywords, const py::dict& mesh_keywords) {
  auto settings = settings_from(screening::screen_option_table(), keywords);
  settings.query.input = settings_from(molsurf::surface_input_option_table(), mesh_keywords);
  const matching::MatchInput input = input_of(query, settings.query.input);
  std::optional<screening::Library> library;
  std::vector<screening::ShapeHit> hits;
  {
    py::gil_scoped_release release;
    const ThreadLimit limit(settings.query.threads);
    mesh::Surface surface;
    if (input.surface && !input.molecule) {
      surface = *input.surface;
    } else if (!input.path.empty() && mesh::io::is_mesh_file(input.path)) {
      molsurf::check_surface_input(input.path, settings.query.input);
      surface = molsurf::read_mesh_input(input.path, settings.query.input).surface;
    } else {
      throw InputError(input.name() +
                       ": a shape screen's query is a mesh (a mesh file, (V, F) or a Surface "
                       "built from one)");
    }
    library.emplace(library_path);
    screening::ShapeScreenOptions options;
    options.inputs = settings.query;
    options.top = static_cast<std::size_t>(settings.screen.top);
    hits = screening::screen_shapes(surface, *library, options);
  }
  py::list rows;
  for (std::size_t k = 0; k < hits.size(); ++k) {
    const screening::ShapeHit& hit = hits[k];
    py::dict d = entry_row(*library, k + 1, hit.entry);
    d.attr("pop")("record");
    d.attr("pop")("conformer");
    d["score"] = hit.score;
    d["entry_coverage"] = hit.entry_coverage;
    d["overlay"] = hit.overlay;
    d["unit"] = hit.unit;
    d["transform"] = owned_array(Eigen::Matrix4d(hit.transform));
    d["note"] = hit.note;
    rows.append(d);
  }
  return rows;
}

py::list pockets(const std::string& structure, const py::dict& keywords) {
  const auto settings = settings_from(molsurf::pocket_search_option_table(), keywords);
  molsurf::StructurePockets found;
  {
    py::gil_scoped_release release;
    found = molsurf::find_pockets(structure, settings);
  }
  py::list out;
  for (const molsurf::Pocket& pocket : found.pockets) {
    py::list spheres;
    for (const molsurf::SiteSphere& s : pocket.spheres) {
      spheres.append(py::make_tuple(s.center.x(), s.center.y(), s.center.z(), s.radius));
    }
    out.append(py::dict(
        py::arg("rank") = pocket.rank, py::arg("score") = pocket.score,
        py::arg("volume") = pocket.volume, py::arg("buriedness") = pocket.buriedness,
        py::arg("cavity") = pocket.cavity,
        py::arg("center") = py::make_tuple(pocket.center.x(), pocket.center.y(), pocket.center.z()),
        py::arg("lining_residues") = pocket.lining_residues, py::arg("spheres") = spheres));
  }
  return out;
}

py::dict dock(const py::object& ligand, const py::object& receptor, const py::dict& keywords,
              const std::string& output_path, const std::string& report_path) {
  const auto settings = settings_from(docking::dock_option_table(), keywords);
  const matching::MatchInput lig = input_of(ligand, settings.inputs.input);
  const matching::MatchInput rec = input_of(receptor, settings.inputs.input);
  docking::check_dock_inputs(lig, rec, settings);
  if (!output_path.empty() && lig.path.empty())
    throw OptionError("output: the poses are records of a LIGAND file");
  if (!output_path.empty() || !report_path.empty()) {  // as the CLI checks -o and --report
    io::check_command_files(
        {{{"LIGAND", lig.path}, {"RECEPTOR", rec.path}},
         {{"output", output_path, {".sdf"}, ""}, {"report", report_path, {".html"}, ""}}});
  }
  report::HtmlReportOptions report_options;
  if (!report_path.empty()) report_options.viewer_script = report::find_viewer_script();
  docking::DockResult docked;
  {
    py::gil_scoped_release release;
    const ThreadLimit limit(settings.inputs.threads);
    docked = docking::dock(lig, rec, settings);
    // Outputs last, each atomic; a failure of the report removes the poses (as the CLI does).
    if (!output_path.empty()) {
      const std::string poses =
          report::dock_poses_sdf(docked, lig.path, settings.inputs.input.read.record);
      io::write_file_atomically(output_path, [&](std::ostream& out) { out << poses; });
    }
    try {
      if (!report_path.empty())
        report::write_dock_html_report(report_path, docked, settings, report_options);
    } catch (...) {
      if (!output_path.empty()) std::filesystem::remove(output_path);
      throw;
    }
  }
  py::list poses;
  for (const docking::DockPose& p : docked.poses) {
    Eigen::Matrix<double, 4, 4, Eigen::RowMajor> transform = p.transform;
    poses.append(py::dict(
        py::arg("rank") = p.rank, py::arg("score") = p.score.score,
        py::arg("contact") = p.score.contact, py::arg("clash") = p.score.clash,
        py::arg("esp") = p.score.esp, py::arg("lp") = p.score.lp,
        py::arg("deepest") = p.score.deepest, py::arg("intersects") = p.intersects,
        py::arg("transform") = owned_array(std::move(transform)), py::arg("start") = p.start,
        py::arg("conformer") = p.conformer, py::arg("cp_pairs") = pair_array(p.cp_pairs)));
  }
  py::dict timing;
  for (const auto& [step, ms] : docked.timing_ms) timing[py::str(step)] = ms;
  return py::dict(py::arg("poses") = poses, py::arg("conformers") = docked.conformers,
                  py::arg("starts") = docked.starts, py::arg("site_volume") = docked.site_volume,
                  py::arg("ligand_volume") = docked.ligand_volume, py::arg("notes") = docked.notes,
                  py::arg("timing_ms") = timing);
}

py::dict matrix(const std::vector<std::string>& set, const std::vector<std::string>& against,
                const py::dict& keywords, bool transforms, const std::string& output_path) {
  auto settings = settings_from(screening::matrix_option_table(), keywords);
  settings.transforms = transforms;
  if (!output_path.empty()) {  // as the CLI checks -o
    std::vector<io::InputFile> inputs;
    inputs.reserve(set.size() + against.size());
    for (const std::string& file : set) inputs.push_back({"set", file});
    for (const std::string& file : against) inputs.push_back({"against", file});
    io::check_command_files({inputs, {{"output", output_path, {".csv"}, ""}}});
  }
  screening::SimilarityMatrix computed;
  {
    py::gil_scoped_release release;
    const ThreadLimit limit(settings.inputs.threads);
    computed = screening::similarity_matrix({set.begin(), set.end()},
                                            {against.begin(), against.end()}, settings);
    if (!output_path.empty()) {
      io::write_file_atomically(output_path, [&](std::ostream& out) {
        if (settings.neighbours > 0) {
          screening::write_neighbours_csv(out, computed);
        } else {
          screening::write_matrix_csv(out, computed);
        }
      });
    }
  }
  const auto members = [](const std::vector<screening::MatrixMember>& list) {
    py::list out;
    for (const screening::MatrixMember& m : list) {
      out.append(py::dict(py::arg("name") = m.name, py::arg("source") = m.source.string(),
                          py::arg("record") = m.record));
    }
    return out;
  };
  const auto rows = static_cast<py::ssize_t>(computed.rows.size());
  const bool sparse = settings.neighbours > 0;
  // The transforms: per cell, or per row and neighbour.
  // A row's neighbours: at most K, and no more than its other molecules.
  const std::size_t others = computed.columns.size() - (computed.symmetric ? 1 : 0);
  const auto columns = static_cast<py::ssize_t>(sparse ? std::min(settings.neighbours, others)
                                                       : computed.columns.size());
  py::object moves = py::none(), neighbours = py::none(), neighbour_scores = py::none(),
             neighbour_stages = py::none();
  if (transforms) {
    py::array_t<double> all({rows, columns, py::ssize_t{4}, py::ssize_t{4}});
    auto view = all.mutable_unchecked<4>();
    for (py::ssize_t i = 0; i < rows; ++i) {
      for (py::ssize_t j = 0; j < columns; ++j) {
        const auto r = static_cast<std::size_t>(i), c = static_cast<std::size_t>(j);
        Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
        if (!sparse) {
          t = computed.transforms[r * static_cast<std::size_t>(columns) + c];
        } else if (c < computed.neighbours[r].size()) {
          t = computed.neighbours[r][c].transform;
        }
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b) view(i, j, a, b) = t(a, b);
      }
    }
    moves = std::move(all);
  }
  if (sparse) {
    Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> index =
        Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>::Constant(
            rows, columns, -1);
    Eigen::MatrixXd score =
        Eigen::MatrixXd::Constant(rows, columns, std::numeric_limits<double>::quiet_NaN());
    Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic> stage =
        Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic>::Zero(rows, columns);
    for (std::size_t i = 0; i < computed.neighbours.size(); ++i) {
      for (std::size_t k = 0; k < computed.neighbours[i].size(); ++k) {
        const screening::Neighbour& next = computed.neighbours[i][k];
        const auto r = static_cast<Eigen::Index>(i), c = static_cast<Eigen::Index>(k);
        index(r, c) = static_cast<std::int64_t>(next.column);
        score(r, c) = next.score;
        stage(r, c) = next.stage;
      }
    }
    neighbours = owned_array(std::move(index));
    neighbour_scores = owned_array(std::move(score));
    neighbour_stages = owned_array(std::move(stage));
  }
  return py::dict(
      py::arg("scores") = sparse ? py::object(py::none()) : owned_array(std::move(computed.score)),
      py::arg("stage") = sparse ? py::object(py::none()) : owned_array(std::move(computed.stage)),
      py::arg("neighbours") = neighbours, py::arg("neighbour_scores") = neighbour_scores,
      py::arg("neighbour_stages") = neighbour_stages, py::arg("transforms") = moves,
      py::arg("rows") = members(computed.rows), py::arg("columns") = members(computed.columns),
      py::arg("symmetric") = computed.symmetric, py::arg("left_out") = computed.left_out,
      py::arg("warnings") = computed.warnings, py::arg("describe_ms") = computed.describe_ms,
      py::arg("match_ms") = computed.match_ms);
}

py::list option_table(const std::string& function) {
  if (function == "build_surface") return table_list(molsurf::surface_input_option_table());
  if (function == "describe") return table_list(matching::describe_option_table());
  if (function == "match") return table_list(matching::pair_match_option_table());
  if (function == "screen") return table_list(screening::screen_option_table());
  if (function == "pockets") return table_list(molsurf::pocket_search_option_table());
  if (function == "dock") return table_list(docking::dock_option_table());
  if (function == "matrix") return table_list(screening::matrix_option_table());
  if (function == "screen_receptor") return table_list(screening::receptor_screen_option_table());
  for (const char* name : {"curvatures", "critical_points", "patch", "disk_map", "shape_image"}) {
    if (function == name) return table_list(array_option_table(function));
  }
  throw py::value_error("no function '" + function +
                        "' with options (build_surface, describe, match, screen, pockets, dock, "
                        "screen_receptor, matrix, "
                        "curvatures, critical_points, patch, disk_map, shape_image)");
}

/// The module's exception classes: Error, the base of all; InputError (also a ValueError) and

}  // namespace surfcomp::python
