// The functions the module binds (python/src/ only), one per function of the package: each
// takes Python objects and the keyword options as a dict, sets the options through the library's
// tables (convert.hpp), runs the library with the GIL released and returns Python values.
// pipeline_functions.cpp: the method's steps (surfaces, descriptions, matches, screens, pockets,
// docks);
// array_functions.cpp: its stages on (V, F) arrays.
#pragma once

#include "convert.hpp"

#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

namespace surfcomp::python {

// --- the method's steps (pipeline_functions.cpp) -------------------------------------------------

/// surfcomp.build_surface: a molecule's surface with ESP and LP, or a mesh loaded.
PySurface build_surface(const py::object& input, const py::dict& keywords);

/// surfcomp.describe: critical points, patches, harmonic maps and images.
PyDescriptors describe(const py::object& input, const py::dict& keywords);

/// surfcomp.match: PROBE aligned onto REF (match_dict), with an HTML report when `report_path`
/// is given.
py::dict match(const py::object& reference, const py::object& probe, const py::dict& keywords,
               const std::string& report_path);

/// Every query of `queries` screened against the library in one pass: {"hits": one list of
/// rows per query, "fused": the fused ranking's rows (several queries only)}.
py::dict screen(const py::list& queries, const std::string& library_path, const py::dict& keywords,
                bool molecules);

/// A library ranked by its fit into `receptor`'s site (screening::receptor_screen): one dict
/// per molecule (ReceptorHit's fields), best first.
py::list screen_receptor(const py::object& receptor, const std::string& library_path,
                         const py::dict& keywords);

/// A mesh query screened by shape against a library of meshes (screening::screen_shapes): one
/// dict per hit (ShapeHit's fields), best first.
py::list screen_shapes(const py::handle& query, const std::string& library_path,
                       const py::dict& keywords, const py::dict& mesh_keywords);

/// surfcomp.pockets: a structure's detected pockets, best first.
py::list pockets(const std::string& structure, const py::dict& keywords);

/// surfcomp.dock: a ligand's poses in a receptor's site, best first; with `output_path`, also
/// written there as SDF records, and with `report_path` its HTML report.
py::dict dock(const py::object& ligand, const py::object& receptor, const py::dict& keywords,
              const std::string& output_path, const std::string& report_path);

/// surfcomp.matrix: the molecules of the `set` files matched all against all, or against those
/// of the `against` files: "scores" (rows x columns), with `transforms` "transforms" (rows x
/// columns x 4 x 4), "rows" and "columns" (each molecule's name, file and record), "left_out",
/// "describe_ms" and "match_ms"; with `output_path`, also written there as CSV.
py::dict matrix(const std::vector<std::string>& set, const std::vector<std::string>& against,
                const py::dict& keywords, bool transforms, const std::string& output_path);

/// The keyword options of the package's function `function`, as table_list gives them.
py::list option_table(const std::string& function);

// --- stages on (V, F) arrays (array_functions.cpp) -----------------------------------------------

/// The keyword options of the (V, F) functions, from the library's tables: the length unit
/// (scale, unit: molsurf::surface_input_option_table) and, per function, the critical point options
/// (critical_points), the spring weights (disk_map) or the image grid and weights (shape_image).
/// Held in a matching::MatchInputOptions: `input` and `descriptors` are the parts they set.
const options::Table<matching::MatchInputOptions>& array_option_table(const std::string& function);

/// surfcomp.curvatures: per-vertex principal curvatures, shape index and curvedness.
py::dict curvatures(const py::object& input, const py::dict& keywords);

/// surfcomp.critical_points: the shape critical points (points_dict).
py::dict critical_points(const py::object& input, const py::dict& keywords);

/// surfcomp.geodesic_distances: on-surface distances from `source`, up to `max_distance`.
py::array geodesic_distances(const py::object& input, long long source,
                             const std::optional<double>& max_distance, const std::string& method);

/// surfcomp.patch: the geodesic patch around `center` and its harmonic map onto the disk.
py::dict patch(const py::object& input, long long center, const std::optional<double>& radius,
               const py::dict& keywords);

/// surfcomp.disk_map: the harmonic map of a disk-like mesh onto the unit disk.
py::array disk_map(const py::object& positions_in, const py::object& faces_in,
                   const std::optional<std::vector<int>>& outer_boundary, const std::string& method,
                   const py::dict& keywords);

/// surfcomp.shape_image: the harmonic shape image of the patch around `center`.
py::array shape_image(const py::object& input, long long center,
                      const std::optional<double>& radius, const py::dict& keywords);

}  // namespace surfcomp::python
