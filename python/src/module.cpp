// The C++ side of `import surfcomp` (the Python package in python/surfcomp/ wraps it): the
// module's classes, exceptions and functions. Keyword options are set through the library's
// option tables (the same definitions the command line's --help and parsing come from), inputs
// become matching::MatchInput, the library runs with the GIL released, and results come back as
// NumPy arrays and plain Python values (convert.hpp, functions.hpp).
#include "convert.hpp"
#include "functions.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/mesh/topology.hpp"
#include "surfcomp/molsurf/pockets.hpp"
#include "surfcomp/report/patch_files.hpp"
#include "surfcomp/screening/hit_files.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/library_build.hpp"
#include "surfcomp/screening/receptor_screen.hpp"
#include "surfcomp/screening/screen.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <string>
#include <vector>

namespace py = pybind11;

namespace surfcomp::python {
namespace {

struct ErrorClasses {
  PyObject* error = nullptr;
  PyObject* input = nullptr;
  PyObject* option = nullptr;
  PyObject* file = nullptr;
};

ErrorClasses& error_classes() {
  static ErrorClasses classes;
  return classes;
}

void add_error_classes(py::module_& m) {
  ErrorClasses& c = error_classes();
  c.error = PyErr_NewExceptionWithDoc("surfcomp.Error", "Base of every error surfcomp raises.",
                                      PyExc_Exception, nullptr);
  const py::tuple input_bases = py::make_tuple(py::handle(c.error), py::handle(PyExc_ValueError));
  c.input = PyErr_NewExceptionWithDoc(
      "surfcomp.InputError", "Bad input: a file's contents, a molecule, a mesh or an option.",
      input_bases.ptr(), nullptr);
  c.option = PyErr_NewExceptionWithDoc("surfcomp.OptionError",
                                       "An option outside its range or not one of its choices.",
                                       c.input, nullptr);
  const py::tuple file_bases = py::make_tuple(py::handle(c.error), py::handle(PyExc_OSError));
  c.file = PyErr_NewExceptionWithDoc("surfcomp.FileError",
                                     "A file that cannot be opened, read or written.",
                                     file_bases.ptr(), nullptr);
  m.attr("Error") = py::handle(c.error);
  m.attr("InputError") = py::handle(c.input);
  m.attr("OptionError") = py::handle(c.option);
  m.attr("FileError") = py::handle(c.file);
}

/// The options of every table the module reads that are switches (Python passes them True).
const std::vector<std::string>& flag_fields() {
  static const std::vector<std::string> fields = [] {
    std::vector<std::string> out;
    const auto add = [&out](const auto& table) {
      for (const auto& option : table) {
        if (option.spec.kind == options::Kind::flag)
          out.push_back(options::python_name(option.spec.name));
      }
    };
    add(matching::pair_match_option_table());
    add(matching::describe_option_table());
    add(screening::screen_option_table());
    add(screening::receptor_screen_option_table());
    add(molsurf::pocket_search_option_table());
    add(screening::library_build_option_table());
    return out;
  }();
  return fields;
}

/// Python's spelling of an option a library message names: the keyword argument, and a switch
/// with the value that turns it on ("repair=True").
std::string python_spelling(const std::string& field) {
  const std::vector<std::string>& flags = flag_fields();
  return std::find(flags.begin(), flags.end(), field) != flags.end() ? field + "=True" : field;
}

// pybind11 calls translators as void(std::exception_ptr).
void translate(std::exception_ptr error) {  // NOLINT(performance-unnecessary-value-param)
  const ErrorClasses& c = error_classes();
  try {
    if (error) std::rethrow_exception(error);
  } catch (const FileError& e) {
    PyErr_SetString(c.file, e.what());
  } catch (const OptionError& e) {
    PyErr_SetString(c.option, e.what());
  } catch (const InputError& e) {
    PyErr_SetString(c.input, e.what());
  } catch (const Error& e) {
    PyErr_SetString(c.error, e.what());
  }
}

}  // namespace
}  // namespace surfcomp::python

PYBIND11_MODULE(_surfcomp, m) {
  namespace sp = surfcomp::python;
  m.doc() = "The C++ core of the surfcomp package; use `import surfcomp`.";
  sp::add_error_classes(m);
  sp::flag_fields();  // the tables are built with the fields' own names, before Python's spelling
  surfcomp::options::set_spelling(&sp::python_spelling);
  py::register_exception_translator(&sp::translate);

  py::class_<sp::MoleculeBlock>(m, "MoleculeBlock", "An RDKit molecule as an MDL block.")
      .def(py::init<std::string, std::string, std::optional<std::vector<double>>>(),
           py::arg("text"), py::arg("name"), py::arg("charges") = py::none())
      .def_readonly("name", &sp::MoleculeBlock::name);

  py::class_<sp::PySurface>(m, "Surface")
      .def_property_readonly(
          "vertices", [](const sp::PySurface& s) { return sp::owned_array(s.surface.positions()); })
      .def_property_readonly("normals",
                             [](sp::PySurface& s) {
                               if (!s.surface.has_normals()) s.surface.compute_normals();
                               return sp::owned_array(s.surface.normals());
                             })
      .def_property_readonly(
          "faces", [](const sp::PySurface& s) { return sp::owned_array(s.surface.faces()); })
      .def_property_readonly("properties",
                             [](const sp::PySurface& s) { return sp::properties_dict(s.surface); })
      .def_property_readonly("source", [](const sp::PySurface& s) { return s.surface.source(); })
      .def_property_readonly("n_vertices",
                             [](const sp::PySurface& s) { return s.surface.n_vertices(); })
      .def_property_readonly("n_faces", [](const sp::PySurface& s) { return s.surface.n_faces(); })
      .def_property_readonly("has_molecule",
                             [](const sp::PySurface& s) { return s.molecule.has_value(); })
      .def_property_readonly("length_unit", [](const sp::PySurface& s) { return s.length_unit; })
      .def("_measures",
           [](const sp::PySurface& s) {
             const surfcomp::mesh::SurfaceMeasures measures =
                 surfcomp::mesh::measure_surface(s.surface);
             return py::dict(py::arg("area") = measures.area, py::arg("volume") = measures.volume,
                             py::arg("euler_characteristic") = measures.euler_characteristic,
                             py::arg("boundary_edges") = measures.boundary_edges);
           })
      .def(
          "save",
          [](const sp::PySurface& s, const std::filesystem::path& path, bool ascii) {
            py::gil_scoped_release release;
            sp::save_surface(s.surface, path, ascii);
          },
          py::arg("path"), py::arg("ascii") = false);

  py::class_<sp::PyDescriptors>(m, "Descriptors")
      .def_property_readonly(
          "surface",
          [](const sp::PyDescriptors& d) {
            return sp::PySurface{d.descriptors.surface, std::nullopt, d.descriptors.length_unit};
          })
      .def_property_readonly("length_unit",
                             [](const sp::PyDescriptors& d) { return d.descriptors.length_unit; })
      .def("_critical_points",
           [](const sp::PyDescriptors& d) { return sp::critical_points_dict(d.descriptors); })
      .def_property_readonly(
          "images", [](const sp::PyDescriptors& d) { return sp::images_array(d.descriptors); })
      .def(
          "_patch",
          [](const sp::PyDescriptors& d, std::size_t index) {
            return sp::patch_dict(d.descriptors, index);
          },
          py::arg("index"))
      .def("_parameters",
           [](const sp::PyDescriptors& d) {
             return sp::descriptor_options_dict(d.descriptors.options);
           })
      .def(
          "write_critical_points",
          [](const sp::PyDescriptors& d, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            sp::write_critical_points(d.descriptors, path);
          },
          py::arg("path"),
          "Writes the critical points as cp-detect does, in the format the extension names: "
          ".json, .pdb or .ply.")
      .def_property_readonly("atoms",
                             [](const sp::PyDescriptors& d) {
                               py::list elements;
                               Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> positions(
                                   static_cast<Eigen::Index>(d.descriptors.atoms.size()), 3);
                               for (std::size_t i = 0; i < d.descriptors.atoms.size(); ++i) {
                                 elements.append(d.descriptors.atoms[i].element);
                                 positions.row(static_cast<Eigen::Index>(i)) =
                                     d.descriptors.atoms[i].position.transpose();
                               }
                               return py::make_tuple(elements,
                                                     sp::owned_array(std::move(positions)));
                             })
      .def(
          "save",
          [](const sp::PyDescriptors& d, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            surfcomp::harmonic::io::write_hsi(d.descriptors, path);
          },
          py::arg("path"));

  m.def(
      "load_descriptors",
      [](const std::string& path) {
        py::gil_scoped_release release;
        return sp::PyDescriptors{surfcomp::harmonic::io::read_hsi(path)};
      },
      py::arg("path"));
  m.def("build_surface", &sp::build_surface, py::arg("input"), py::arg("options"));
  m.def("describe", &sp::describe, py::arg("input"), py::arg("options"));
  m.def("match", &sp::match, py::arg("reference"), py::arg("probe"), py::arg("options"),
        py::arg("report") = std::string());
  m.def("screen", &sp::screen, py::arg("query"), py::arg("library"), py::arg("options"),
        py::arg("molecules"));
  m.def("screen_receptor", &sp::screen_receptor, py::arg("receptor"), py::arg("library"),
        py::arg("options"));
  m.def("screen_shapes", &sp::screen_shapes, py::arg("query"), py::arg("library"),
        py::arg("options"), py::arg("mesh_options"));
  m.def("pockets", &sp::pockets, py::arg("structure"), py::arg("options"));
  m.def("matrix", &sp::matrix, py::arg("set"), py::arg("against"), py::arg("options"),
        py::arg("transforms"), py::arg("output"));
  m.def("dock", &sp::dock, py::arg("ligand"), py::arg("receptor"), py::arg("options"),
        py::arg("output") = std::string(), py::arg("report") = std::string());
  m.def("option_table", &sp::option_table, py::arg("function"));
  m.def("curvatures", &sp::curvatures, py::arg("mesh"), py::arg("options"));
  m.def("critical_points", &sp::critical_points, py::arg("mesh"), py::arg("options"));
  m.def("geodesic_distances", &sp::geodesic_distances, py::arg("mesh"), py::arg("source_vertex"),
        py::arg("max_distance"), py::arg("method"));
  m.def("patch", &sp::patch, py::arg("mesh"), py::arg("center_vertex"), py::arg("radius"),
        py::arg("options"));
  m.def("disk_map", &sp::disk_map, py::arg("positions"), py::arg("faces"),
        py::arg("outer_boundary"), py::arg("method"), py::arg("options"));
  m.def("shape_image", &sp::shape_image, py::arg("mesh"), py::arg("center_vertex"),
        py::arg("radius"), py::arg("options"));
  m.def(
      "library_info",
      [](const std::string& path) {
        const surfcomp::screening::Library library(path);
        const surfcomp::screening::LibrarySummary summary =
            surfcomp::screening::summarize_library(library);
        py::list entries;
        for (std::size_t i = 0; i < library.size(); ++i) {
          const surfcomp::screening::LibraryEntryInfo info = library.info(i);
          entries.append(py::dict(py::arg("entry") = i + 1, py::arg("name") = info.name,
                                  py::arg("source") = info.source, py::arg("record") = info.record,
                                  py::arg("conformer") = info.conformer,
                                  py::arg("heavy_atoms") = info.heavy_atoms,
                                  py::arg("site_spheres") = info.site_spheres));
        }
        return py::dict(
            py::arg("version") = library.version(), py::arg("settings") = library.settings(),
            py::arg("bytes") = summary.file_bytes, py::arg("molecules") = summary.molecules,
            py::arg("largest_entry_bytes") = summary.largest_entry_bytes,
            py::arg("entries") = entries);
      },
      py::arg("path"));
}
