// What the Python module's files share (python/src/ only): the Python-side types, and the
// conversions between Python objects and the library's: keyword options through the option
// tables, inputs (paths, RDKit molecules as MDL blocks, surfaces, (V, F) arrays), and results as
// NumPy arrays and plain Python values.
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/load_surface.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace surfcomp::python {

namespace py = pybind11;

/// An RDKit molecule handed over by the Python package: its MDL block (hydrogens as the molecule
/// has them, the conformer's coordinates), its name, and its partial charges when it carries some.
struct MoleculeBlock {
  std::string text;
  std::string name;
  std::optional<std::vector<double>> charges;
};

/// A surface with the molecule it was built from, if any (its heavy atoms go with a description).
struct PySurface {
  mesh::Surface surface;
  std::optional<Molecule> molecule;
  /// The length unit its curvature was fitted in (molsurf::LoadedSurface::unit): 1 in A.
  double length_unit = 1.0;
};

struct PyDescriptors {
  harmonic::SurfaceDescriptors descriptors;
};

// --- arrays -------------------------------------------------------------------------------------

/// A C-ordered NumPy array that owns the values of `matrix` (moved in when `matrix` is row-major
/// or a vector; else copied once into row-major order, which C and NumPy code expect).
template <class Matrix>
py::array owned_array(Matrix&& matrix) {
  using Plain = std::decay_t<Matrix>;
  using Scalar = typename Plain::Scalar;
  if constexpr (Plain::ColsAtCompileTime == 1) {
    auto* owned = new Plain(std::forward<Matrix>(matrix));
    py::capsule free(owned, [](void* p) { delete static_cast<Plain*>(p); });
    return py::array_t<Scalar>({static_cast<py::ssize_t>(owned->rows())}, owned->data(), free);
  } else {
    using RowMajor =
        Eigen::Matrix<Scalar, Plain::RowsAtCompileTime, Plain::ColsAtCompileTime,
                      Plain::ColsAtCompileTime == 1 ? Eigen::ColMajor : Eigen::RowMajor>;
    auto* owned = new RowMajor(std::forward<Matrix>(matrix));
    py::capsule free(owned, [](void* p) { delete static_cast<RowMajor*>(p); });
    return py::array_t<Scalar>(
        {static_cast<py::ssize_t>(owned->rows()), static_cast<py::ssize_t>(owned->cols())},
        owned->data(), free);
  }
}

// --- options ------------------------------------------------------------------------------------

/// The option value of the Python object for `spec`: a number (not a bool) for a real, an
/// integer for an integer, a str (or path) for text and choices, a bool for a flag, and for
/// spheres one (x, y, z, r) or a list of them. TypeError naming `shown` otherwise; the value is
/// then checked as the command line checks it (ValueError).
options::Value python_value(const options::Spec& spec, const py::handle& object,
                            const std::string& shown);

/// `settings` with the keyword options of `keywords` set through `table` (Python names; None
/// leaves an option at its default). TypeError for a name the table does not hold.
template <class Settings>
Settings settings_from(const options::Table<Settings>& table, const py::dict& keywords) {
  Settings settings;
  for (const auto& [key, object] : keywords) {
    const std::string name = py::str(key).cast<std::string>();
    const options::Option<Settings>* option = nullptr;
    for (const options::Option<Settings>& candidate : table) {
      if (options::python_name(candidate.spec.name) == name) option = &candidate;
    }
    if (option == nullptr) throw py::type_error("unexpected keyword argument '" + name + "'");
    if (object.is_none()) continue;
    option->set(settings, python_value(option->spec, object, name));
  }
  return settings;
}

/// An option's default as a Python value: None for an optional option.
py::object python_default(const options::Spec& spec, const options::Value& value);

/// The options of `table` as Python sees them, in order: name (Python's), option (the command
/// line's), kind, default, help (with unit and range), unit, range, choices.
template <class Settings>
py::list table_list(const options::Table<Settings>& table) {
  const Settings defaults;
  py::list out;
  for (const options::Option<Settings>& option : table) {
    const options::Spec& spec = option.spec;
    out.append(py::dict(
        py::arg("name") = options::python_name(spec.name), py::arg("option") = "--" + spec.name,
        py::arg("kind") = options::kind_names[static_cast<std::size_t>(spec.kind)],
        py::arg("default") = python_default(spec, option.get(defaults)),
        py::arg("help") = options::help_line(spec), py::arg("unit") = spec.unit,
        py::arg("range") = options::range_text(spec), py::arg("choices") = spec.choices));
  }
  return out;
}

// --- inputs -------------------------------------------------------------------------------------

/// A molecule handed over as an MDL block, read as the library reads a record, with the block's
/// partial charges when `read` takes charges from the file.
Molecule molecule_of(const MoleculeBlock& block, const io::MoleculeReadOptions& read);

/// A mesh given as a (V, F) pair of arrays: #V by 3 positions and #F by 3 0-based triangles;
/// repaired first (mesh::repair_triangles) when `repair`.
mesh::Surface surface_of_arrays(const py::tuple& pair, bool repair);

/// A Python input (a path, a MoleculeBlock, a Surface, a Descriptors, a (V, F) pair) as the
/// library's.
matching::MatchInput input_of(const py::handle& object,
                              const molsurf::SurfaceInputOptions& options);

// --- results ------------------------------------------------------------------------------------

/// (k, 2) int array of index pairs, a row each.
py::array pair_array(const std::vector<std::pair<int, int>>& pairs);

py::dict alignment_dict(const matching::Alignment& a);

py::dict match_dict(const matching::InputMatch& compared, double lining_weight);

py::dict descriptor_options_dict(const harmonic::DescriptorOptions& o);

/// Critical points as arrays, one row per point: position, normal, vertex, type, cc1, cc2,
/// shape_index, curvedness, esp, lp.
py::dict points_dict(const std::vector<mesh::CriticalPoint>& points);

/// The critical points of a description as arrays, one row per point: points_dict and status.
py::dict critical_points_dict(const harmonic::SurfaceDescriptors& d);

/// Critical point `index`'s patch and harmonic map: positions (p, 3), faces (f, 3),
/// surface_vertex, distance, uv (p, 2), outer_boundary, center, status. IndexError when out of
/// range; empty arrays when the point has no patch.
py::dict patch_dict(const harmonic::SurfaceDescriptors& d, std::size_t index);

/// Writes `image` into the (rings, sectors) grid at `out`, row-major; NaN where a grid point is
/// not valid, or everywhere when the image is not of that grid (a point without an image).
void fill_image(const harmonic::ShapeImage& image, int rings, int sectors, double* out);

/// The images as one array (n_cp, rings, sectors); NaN where a grid point is not valid or a
/// point has no image.
py::array images_array(const harmonic::SurfaceDescriptors& d);

py::dict properties_dict(const mesh::Surface& surface);

void write_critical_points(const harmonic::SurfaceDescriptors& d,
                           const std::filesystem::path& path);

void save_surface(const mesh::Surface& surface, const std::filesystem::path& p, bool ascii);

}  // namespace surfcomp::python
