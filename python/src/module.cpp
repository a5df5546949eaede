// The C++ side of `import surfcomp` (the Python package in python/surfcomp/ wraps it). Keyword
// options are set through the library's option tables (the same definitions the command line's
// --help and parsing come from), inputs (paths, RDKit molecules as MDL blocks, surfaces,
// descriptions) become matching::MatchInput, the library runs with the GIL released, and results
// come back as NumPy arrays and plain Python values.
#include "command.hpp"
#include "command_files.hpp"
#include "describe_settings.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/harmonic/cgal_reference.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/mesh/geodesic.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/mesh/patch.hpp"
#include "surfcomp/mesh/topology.hpp"
#include "surfcomp/molsurf/load_surface.hpp"
#include "surfcomp/molsurf/pockets.hpp"
#include "surfcomp/report/critical_point_files.hpp"
#include "surfcomp/report/html_report.hpp"
#include "surfcomp/report/patch_files.hpp"
#include "surfcomp/screening/hit_files.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/library_build.hpp"
#include "surfcomp/screening/screen.hpp"
#include "surfcomp/screening/shape_screen.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace surfcomp::python {
namespace {

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
                            const std::string& shown) {
  const bool is_bool = PyBool_Check(object.ptr()) != 0;
  const auto fail = [&shown](const char* expected) {
    return py::type_error(shown + ": expected " + expected);
  };
  options::Value value;
  switch (spec.kind) {
    case options::Kind::real: {
      if (is_bool || !py::hasattr(object, "__float__")) throw fail("a number");
      const double x = PyFloat_AsDouble(object.ptr());
      if (x == -1.0 && PyErr_Occurred() != nullptr) {  // an int beyond a double's range
        PyErr_Clear();
        value = std::numeric_limits<double>::infinity();
      } else {
        value = x;
      }
      break;
    }
    case options::Kind::integer: {
      if (is_bool || PyIndex_Check(object.ptr()) == 0) throw fail("an integer");
      const py::int_ whole(py::reinterpret_borrow<py::object>(object));
      int overflow = 0;
      const long long n = PyLong_AsLongLongAndOverflow(whole.ptr(), &overflow);
      if (overflow != 0) {
        throw OptionError(shown + ": value " + py::repr(whole).cast<std::string>() +
                          " is outside " + options::range_text(spec));
      }
      value = static_cast<std::int64_t>(n);
      break;
    }
    case options::Kind::flag:
      if (!is_bool) throw fail("True or False");
      value = object.cast<bool>();
      break;
    case options::Kind::text:
    case options::Kind::choice:
      if (py::hasattr(object, "__fspath__")) {
        value = py::module_::import("os").attr("fsdecode")(object).cast<std::string>();
      } else if (py::isinstance<py::str>(object)) {
        value = object.cast<std::string>();
      } else {
        throw fail("a str");
      }
      break;
    case options::Kind::spheres: {
      const auto sphere_of = [&](const py::handle& item) {
        if (py::isinstance<py::str>(item)) {
          const options::Value parsed = options::parse(spec, item.cast<std::string>(), shown);
          return std::get<std::vector<options::Sphere>>(parsed).front();
        }
        if (!py::hasattr(item, "__len__") || py::len(item) != 4) {
          throw fail("(x, y, z, r), \"x,y,z,r\" or a list of them");
        }
        options::Sphere sphere{};
        std::size_t k = 0;
        for (const py::handle number : item) {
          if (PyBool_Check(number.ptr()) != 0 || !py::hasattr(number, "__float__"))
            throw fail("(x, y, z, r), \"x,y,z,r\" or a list of them");
          sphere[k++] = py::float_(py::reinterpret_borrow<py::object>(number)).cast<double>();
        }
        return sphere;
      };
      std::vector<options::Sphere> spheres;
      // One sphere: four numbers (no item of it has a length, as a NumPy row would).
      bool one = py::hasattr(object, "__len__") && !py::isinstance<py::str>(object) &&
                 py::len(object) == 4;
      if (one) {
        for (const py::handle item : object)
          one = one && !py::hasattr(item, "__len__") && py::hasattr(item, "__float__");
      }
      if (one || py::isinstance<py::str>(object)) {
        spheres.push_back(sphere_of(object));
      } else if (py::hasattr(object, "__iter__")) {
        for (const py::handle item : object) spheres.push_back(sphere_of(item));
      } else {
        throw fail("(x, y, z, r), \"x,y,z,r\" or a list of them");
      }
      value = std::move(spheres);
      break;
    }
  }
  options::check(spec, value, shown);
  return value;
}

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
py::object python_default(const options::Spec& spec, const options::Value& value) {
  if (spec.optional) return py::none();
  return std::visit(
      [](const auto& v) -> py::object {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, std::vector<options::Sphere>>) {
          py::list spheres;
          for (const options::Sphere& s : v) spheres.append(py::make_tuple(s[0], s[1], s[2], s[3]));
          return std::move(spheres);
        } else {
          return py::cast(v);
        }
      },
      value);
}

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

Molecule molecule_of(const MoleculeBlock& block, const io::MoleculeReadOptions& read) {
  io::MoleculeRecord record;
  record.source = block.name;
  record.name = block.name;
  record.format = io::RecordFormat::mdl;
  record.text = block.text;
  Molecule molecule = io::read_record_molecule(record, read);
  if (block.charges && read.charges == io::ChargeModel::file) {
    const std::vector<double>& charges = *block.charges;
    if (charges.size() != molecule.atoms.size()) {
      throw InputError(block.name + ": " + std::to_string(charges.size()) +
                       " partial charges for " + std::to_string(molecule.atoms.size()) + " atoms");
    }
    for (std::size_t i = 0; i < charges.size(); ++i) {
      if (!std::isfinite(charges[i])) {
        throw InputError(block.name + ": the partial charge of atom " + std::to_string(i + 1) +
                         " is not finite");
      }
      molecule.atoms[i].charge = charges[i];
    }
    molecule.charge_source = ChargeSource::file;
  }
  return molecule;
}

/// A mesh given as a (V, F) pair of arrays: #V by 3 positions and #F by 3 0-based triangles;
/// repaired first (mesh::repair_triangles) when `repair`.
mesh::Surface surface_of_arrays(const py::tuple& pair, bool repair) {
  const auto positions =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(pair[0]);
  const auto faces = py::array_t<int, py::array::c_style | py::array::forcecast>::ensure(pair[1]);
  if (!positions || positions.ndim() != 2 || positions.shape(1) != 3 || !faces ||
      faces.ndim() != 2 || faces.shape(1) != 3) {
    const auto shape = [](const py::handle& array) {
      return py::hasattr(array, "shape") ? py::str(array.attr("shape")).cast<std::string>()
                                         : "(not an array of numbers)";
    };
    throw InputError("a mesh as (V, F) needs V of shape (n, 3) and F of shape (m, 3), got V " +
                     shape(positions ? py::handle(positions) : pair[0]) + " and F " +
                     shape(faces ? py::handle(faces) : pair[1]));
  }
  using Rows3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using Rows3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
  const Eigen::MatrixX3d v = Eigen::Map<const Rows3d>(positions.data(), positions.shape(0), 3);
  const Eigen::MatrixX3i f = Eigen::Map<const Rows3i>(faces.data(), faces.shape(0), 3);
  const char* source = "<(V, F) arrays>";
  if (repair) return mesh::repair_triangles(v, f, source).surface;
  try {
    return mesh::Surface::from_arrays(v, f, source);
  } catch (const TopologyError& e) {  // the caller's arrays: bad input
    throw InputError(e.what());
  }
}

/// A Python input (a path, a MoleculeBlock, a Surface, a Descriptors, a (V, F) pair) as the
/// library's.
matching::MatchInput input_of(const py::handle& object,
                              const molsurf::SurfaceInputOptions& options) {
  const io::MoleculeReadOptions& read = options.read;
  matching::MatchInput input;
  if (py::isinstance<py::tuple>(object) && py::len(object) == 2) {
    input.surface = surface_of_arrays(object.cast<py::tuple>(), options.repair);
  } else if (py::isinstance<py::str>(object)) {
    input.path = object.cast<std::string>();
  } else if (py::isinstance<MoleculeBlock>(object)) {
    input.molecule = molecule_of(object.cast<const MoleculeBlock&>(), read);
  } else if (py::isinstance<PySurface>(object)) {
    const auto& surface = object.cast<const PySurface&>();
    input.surface = surface.surface;
    input.molecule = surface.molecule;
  } else if (py::isinstance<PyDescriptors>(object)) {
    input.descriptors = object.cast<const PyDescriptors&>().descriptors;
  } else {
    throw py::type_error(
        "expected a path, an RDKit molecule, a Surface, a Descriptors or (V, F) arrays, got " +
        py::str(py::type::of(object)).cast<std::string>());
  }
  return input;
}

// --- results ------------------------------------------------------------------------------------

py::dict alignment_dict(const matching::Alignment& a) {
  Eigen::Matrix<double, 4, 4, Eigen::RowMajor> transform = a.transform;
  Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor> pairs(
      static_cast<Eigen::Index>(a.cp_pairs.size()), 2);
  for (std::size_t k = 0; k < a.cp_pairs.size(); ++k) {
    pairs(static_cast<Eigen::Index>(k), 0) = a.cp_pairs[k].first;
    pairs(static_cast<Eigen::Index>(k), 1) = a.cp_pairs[k].second;
  }
  py::dict d;
  d["rank"] = a.rank;
  d["source"] = matching::alignment_source_names[static_cast<std::size_t>(a.source)];
  d["transform"] = owned_array(std::move(transform));
  d["rmsd"] = a.rmsd;
  d["n_points"] = a.n_points;
  d["r_chem"] = a.r_chem;
  d["consensus"] = a.consensus;
  d["refined"] = a.refined;
  d["overlay"] = py::dict(py::arg("score") = a.overlay.score, py::arg("shape") = a.overlay.shape,
                          py::arg("chem") = a.overlay.chem, py::arg("atoms") = a.overlay.atoms);
  d["atom_fit"] = a.atom_fit;
  d["coverage"] =
      py::dict(py::arg("score") = a.coverage.score, py::arg("reference") = a.coverage.reference,
               py::arg("probe") = a.coverage.probe);
  d["icp"] = a.icp;
  d["repeat_of"] = a.repeat_of > 0 ? py::object(py::int_(a.repeat_of)) : py::object(py::none());
  d["cp_pairs"] = owned_array(std::move(pairs));
  d["parent"] = a.parent > 0 ? py::object(py::int_(a.parent)) : py::object(py::none());
  d["children"] = a.children;
  return d;
}

py::dict critical_points_dict(const harmonic::SurfaceDescriptors& d);

py::dict match_dict(const matching::InputMatch& compared, double lining_weight) {
  py::list alignments;
  for (const auto& a : compared.result.alignments) alignments.append(alignment_dict(a));
  py::list trace;
  for (const auto& stage : compared.result.trace) {
    trace.append(py::dict(py::arg("stage") = stage.stage, py::arg("nodes") = stage.nodes,
                          py::arg("edges") = stage.edges, py::arg("ms") = stage.milliseconds));
  }
  py::dict timing;
  for (const auto& [stage, ms] : compared.result.timing_ms) timing[py::str(stage)] = ms;
  py::dict d;
  d["alignments"] = alignments;
  d["trace"] = trace;
  d["timing_ms"] = timing;
  d["warnings"] = compared.warnings;
  d["notes"] = compared.notes;
  d["shape_only"] = compared.shape_only;
  d["site"] =
      compared.lining
          ? py::object(py::dict(
                py::arg("lining") = *compared.lining, py::arg("lining_weight") = lining_weight,
                py::arg("score") = compared.site_score
                                       ? py::object(py::float_(*compared.site_score))
                                       : py::object(py::none()),
                py::arg("z_score") = compared.site_z ? py::object(py::float_(*compared.site_z))
                                                     : py::object(py::none()),
                py::arg("interactions") = compared.interactions
                                              ? py::object(py::float_(*compared.interactions))
                                              : py::object(py::none()),
                py::arg("fields") =
                    compared.fields
                        ? py::object(py::dict(py::arg("similarity") = compared.fields->similarity,
                                              py::arg("coverage") = compared.fields->coverage))
                        : py::object(py::none())))
          : py::object(py::none());
  d["unit"] = compared.unit;
  d["cliques"] = compared.result.cliques;
  d["cliques_complete"] = compared.result.cliques_complete;
  d["reference_critical_points"] = critical_points_dict(compared.reference.descriptors);
  d["probe_critical_points"] = critical_points_dict(compared.probe.descriptors);
  d["prepare_ms"] = compared.prepare_ms;
  d["match_ms"] = compared.match_ms;
  return d;
}

py::dict descriptor_options_dict(const harmonic::DescriptorOptions& o) {
  py::dict d;
  d["critical_point_radius"] = o.critical_points.radius;
  d["disc_radius"] = o.critical_points.property_disc_radius;
  d["patch_radius"] = o.patch.radius;
  d["image_rings"] = o.image.rings;
  d["image_sectors"] = o.image.sectors;
  d["weights"] = harmonic::to_string(o.disk_map.weights);
  d["image_property"] = o.image_property;
  return d;
}

/// Critical points as arrays, one row per point: position, normal, vertex, type, cc1, cc2,
/// shape_index, curvedness, esp, lp.
py::dict points_dict(const std::vector<mesh::CriticalPoint>& points) {
  const auto n = static_cast<Eigen::Index>(points.size());
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> positions(n, 3), normals(n, 3);
  Eigen::VectorXd cc1(n), cc2(n), shape_index(n), curvedness(n), esp(n), lp(n);
  Eigen::VectorXi vertex(n);
  py::list types;
  for (Eigen::Index i = 0; i < n; ++i) {
    const mesh::CriticalPoint& point = points[static_cast<std::size_t>(i)];
    positions.row(i) = point.position.transpose();
    normals.row(i) = point.normal.transpose();
    cc1(i) = point.cc1;
    cc2(i) = point.cc2;
    shape_index(i) = point.shape_index;
    curvedness(i) = point.curvedness;
    esp(i) = point.esp;
    lp(i) = point.lp;
    vertex(i) = point.vertex;
    types.append(mesh::type_name(point.type));
  }
  py::dict out;
  out["position"] = owned_array(std::move(positions));
  out["normal"] = owned_array(std::move(normals));
  out["vertex"] = owned_array(std::move(vertex));
  // An empty list would make a float array; the types are text.
  out["type"] = types.empty() ? py::array(py::dtype("<U6"), {0}, {}) : py::array(types);
  out["cc1"] = owned_array(std::move(cc1));
  out["cc2"] = owned_array(std::move(cc2));
  out["shape_index"] = owned_array(std::move(shape_index));
  out["curvedness"] = owned_array(std::move(curvedness));
  out["esp"] = owned_array(std::move(esp));
  out["lp"] = owned_array(std::move(lp));
  return out;
}

/// The critical points of a description as arrays, one row per point: points_dict and status.
py::dict critical_points_dict(const harmonic::SurfaceDescriptors& d) {
  std::vector<mesh::CriticalPoint> points;
  py::list status;
  for (const harmonic::CriticalPointDescriptor& cp : d.critical_points) {
    points.push_back(cp.point);
    status.append(harmonic::to_string(cp.status));
  }
  py::dict out = points_dict(points);
  out["status"] = status.empty() ? py::array(py::dtype("<U10"), {0}, {}) : py::array(status);
  return out;
}

/// Critical point `index`'s patch and harmonic map: positions (p, 3), faces (f, 3),
/// surface_vertex, distance, uv (p, 2), outer_boundary, center, status. IndexError when out of
/// range; empty arrays when the point has no patch.
py::dict patch_dict(const harmonic::SurfaceDescriptors& d, std::size_t index) {
  if (index >= d.critical_points.size()) {
    throw py::index_error("critical point " + std::to_string(index) + " of " +
                          std::to_string(d.critical_points.size()));
  }
  const harmonic::CriticalPointDescriptor& cp = d.critical_points[index];
  py::dict out;
  out["status"] = harmonic::to_string(cp.status);
  out["center"] = cp.patch.center;
  out["positions"] = owned_array(Eigen::MatrixX3d(cp.patch.positions));
  out["faces"] = owned_array(Eigen::MatrixX3i(cp.patch.faces));
  out["surface_vertex"] = cp.patch.surface_vertex;
  out["distance"] = owned_array(Eigen::VectorXd(cp.patch.distance));
  out["uv"] = owned_array(Eigen::MatrixX2d(cp.map.uv));
  out["outer_boundary"] = cp.patch.outer_boundary;
  return out;
}

/// Writes `image` into the (rings, sectors) grid at `out`, row-major; NaN where a grid point is
/// not valid, or everywhere when the image is not of that grid (a point without an image).
void fill_image(const harmonic::ShapeImage& image, int rings, int sectors, double* out) {
  const std::size_t size = static_cast<std::size_t>(rings) * static_cast<std::size_t>(sectors);
  const bool has = image.values.size() == static_cast<Eigen::Index>(size);
  for (std::size_t g = 0; g < size; ++g)
    out[g] = has && image.valid[g] != 0 ? image.values(static_cast<Eigen::Index>(g)) : std::nan("");
}

/// The images as one array (n_cp, rings, sectors); NaN where a grid point is not valid or a
/// point has no image.
py::array images_array(const harmonic::SurfaceDescriptors& d) {
  const int rings = d.options.image.rings, sectors = d.options.image.sectors;
  const auto n = static_cast<py::ssize_t>(d.critical_points.size());
  py::array_t<double> out({n, static_cast<py::ssize_t>(rings), static_cast<py::ssize_t>(sectors)});
  for (py::ssize_t i = 0; i < n; ++i) {
    fill_image(d.critical_points[static_cast<std::size_t>(i)].image, rings, sectors,
               out.mutable_data(i, 0, 0));
  }
  return out;
}

py::dict properties_dict(const mesh::Surface& surface) {
  py::dict out;
  for (const std::string& name : surface.property_names())
    out[py::str(name)] = owned_array(surface.property(name));
  return out;
}

void write_critical_points(const harmonic::SurfaceDescriptors& d,
                           const std::filesystem::path& path) {
  report::CriticalPointSet set{d.surface.source(),
                               d.options.critical_points,
                               static_cast<std::size_t>(d.surface.n_vertices()),
                               {},
                               d.length_unit};
  for (const harmonic::CriticalPointDescriptor& cp : d.critical_points)
    set.points.push_back(cp.point);
  report::write_critical_points(path, set);
}

void save_surface(const mesh::Surface& surface, const std::filesystem::path& p, bool ascii) {
  std::string extension = p.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".ply") {
    mesh::io::write_ply(
        surface, p, ascii ? mesh::io::PlyFormat::ascii : mesh::io::PlyFormat::binary_little_endian);
  } else {
    mesh::io::write_mesh(surface, p);
  }
}

// --- the functions
// --------------------------------------------------------------------------------

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
  const auto limit = tools::limit_threads(settings.threads);
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
    tools::check_command_files(
        {{{"REF", ref.path}, {"PROBE", prb.path}}, {{"report", report_path, {".html"}, ""}}});
    report_options.viewer_script = report::find_viewer_script();
  }
  std::optional<matching::InputMatch> compared;
  {
    py::gil_scoped_release release;
    const auto limit = tools::limit_threads(settings.inputs.threads);
    compared = matching::match_inputs(ref, prb, settings.inputs);
    if (!report_path.empty())
      report::write_html_report(report_path, *compared, settings.inputs.match, report_options);
  }
  return match_dict(*compared, settings.inputs.match.site.lining_weight);
}

// --- (V, F) functions ---------------------------------------------------------------------------

/// The keyword options of the (V, F) functions, from the library's tables: the length unit
/// (scale, unit: molsurf::surface_input_option_table) and, per function, the critical point options
/// (critical_points), the spring weights (disk_map) or the image grid and weights (shape_image).
/// Held in a matching::MatchInputOptions: `input` and `descriptors` are the parts they set.
const options::Table<matching::MatchInputOptions>& array_option_table(const std::string& function) {
  using I = matching::MatchInputOptions;
  const auto unit_options = [](options::Table<I>& t) {
    options::append(
        t, options::pick(molsurf::surface_input_option_table(), {"scale", "unit"}),
        [](auto& i) -> auto& { return i.input; });
  };
  const auto description_options = [](options::Table<I>& t, const std::vector<std::string>& names) {
    options::append(
        t, options::pick(harmonic::descriptor_option_table(), names),
        [](auto& i) -> auto& { return i.descriptors; });
  };
  static const options::Table<I> unit_only = [&] {
    options::Table<I> t;
    unit_options(t);
    return t;
  }();
  static const options::Table<I> critical_points = [&] {
    options::Table<I> t;
    unit_options(t);
    options::append(
        t, mesh::critical_point_option_table(),
        [](auto& i) -> auto& { return i.descriptors.critical_points; });
    return t;
  }();
  static const options::Table<I> weights = [&] {
    options::Table<I> t;
    description_options(t, {"weights"});
    return t;
  }();
  static const options::Table<I> image = [&] {
    options::Table<I> t;
    unit_options(t);
    description_options(t, {"image-rings", "image-sectors", "weights"});
    return t;
  }();
  if (function == "critical_points") return critical_points;
  if (function == "disk_map") return weights;
  if (function == "shape_image") return image;
  return unit_only;  // curvatures, patch
}

/// What the (V, F) functions need of their mesh argument.
enum class Needs {
  geometry,   ///< the surface alone
  unit,       ///< and its length unit
  curvature,  ///< and cc1, cc2, shape_index, curvedness fitted at that unit
};

/// A mesh argument as the Python caller gave it, taken while the GIL is held: (V, F) arrays as a
/// surface (vertex i is row i of V), or a Surface with the unit its curvature was fitted at.
struct MeshArgument {
  mesh::Surface surface;
  bool from_arrays = false;
  double length_unit = 1.0;  ///< a Surface's (PySurface::length_unit)
};

MeshArgument mesh_argument(const py::handle& object) {
  MeshArgument out;
  if (py::isinstance<py::tuple>(object) && py::len(object) == 2) {
    out.surface = surface_of_arrays(object.cast<py::tuple>(), false);
    out.from_arrays = true;
  } else if (py::isinstance<PySurface>(object)) {
    const auto& surface = object.cast<const PySurface&>();
    out.surface = surface.surface;
    out.length_unit = surface.length_unit;
  } else {
    throw py::type_error("expected (V, F) arrays or a Surface, got " +
                         py::str(py::type::of(object)).cast<std::string>());
  }
  if (out.surface.n_faces() == 0)
    throw InputError(out.surface.source() + ": the mesh has no triangle (F is empty)");
  return out;
}

/// The length unit of `mesh` under `options`, its curvature fitted at it when `needs` says so.
/// (V, F) arrays are a general mesh, as build_surface takes them (molsurf::load_mesh_surface). A
/// Surface keeps its unit and curvature unless scale="none" or unit= asks for another; unit= on a
/// Surface in A (with ESP and LP) is refused. Runs without the GIL.
double settle_unit(MeshArgument& mesh, const molsurf::SurfaceInputOptions& options, Needs needs) {
  if (needs == Needs::geometry) return 1.0;
  const std::string& name = mesh.surface.source();
  if (!mesh.from_arrays) {
    if (options.unit > 0.0 && mesh::is_molecular_mesh(mesh.surface, "")) {
      throw OptionError("unit: applies to general meshes; " + name +
                        " is in A (it carries ESP and LP)");
    }
    const double asked = options.unit > 0.0                         ? options.unit
                         : options.scale == mesh::LengthScale::none ? 1.0
                                                                    : mesh.length_unit;
    if (asked == mesh.length_unit || needs == Needs::unit) return asked;
  }
  if (needs == Needs::unit)
    return mesh::general_mesh_unit({&mesh.surface}, options.scale, options.unit, name).value;
  molsurf::LoadedSurface loaded = molsurf::load_mesh_surface(std::move(mesh.surface), options);
  mesh.surface = std::move(loaded.surface);
  return loaded.unit.value;
}

/// `vertex` checked as the vertex argument `argument` of a function on `surface`.
int vertex_argument(long long vertex, const mesh::Surface& surface, const char* argument) {
  const auto n = static_cast<long long>(surface.n_vertices());
  if (vertex < 0 || vertex >= n) {
    throw InputError(std::string(argument) + " " + std::to_string(vertex) + " is outside 0.." +
                     std::to_string(n - 1) + " (the mesh has " + std::to_string(n) + " vertices)");
  }
  return static_cast<int>(vertex);
}

/// A number as Python prints it, for messages.
std::string python_number(double x) { return py::repr(py::float_(x)).cast<std::string>(); }

/// Checks a patch radius argument: None, or finite and > 0 (the mesh's coordinates).
void check_radius(const std::optional<double>& radius) {
  if (radius && (!std::isfinite(*radius) || *radius <= 0.0)) {
    throw OptionError("radius: " + python_number(*radius) +
                      ", expected a finite number > 0 (in the mesh's coordinates) or None");
  }
}

/// The patch radius in units: `radius` (the mesh's coordinates, check_radius) over `unit`, or
/// `fallback` (units) without one.
double radius_in_units(const std::optional<double>& radius, double unit, double fallback) {
  return radius ? *radius / unit : fallback;
}

/// The value named `name` among `names` (the library's names of an enum), as an enum; OptionError
/// naming `argument` and the names otherwise.
template <class Enum, std::size_t N>
Enum named(const std::string& name, const std::array<const char*, N>& names, const char* argument) {
  std::string known;
  for (std::size_t i = 0; i < N; ++i) {
    if (name == names[i]) return static_cast<Enum>(i);
    known += std::string(i == 0 ? "" : ", ") + names[i];
  }
  throw OptionError(std::string(argument) + ": '" + name + "' is not one of " + known);
}

/// A library TopologyError raised on the caller's arrays (a patch that is not a disk, a radius
/// shorter than the edges) as the bad input it is.
template <class Work>
auto on_arrays(Work&& work) {
  try {
    return work();
  } catch (const TopologyError& e) {
    throw InputError(e.what());
  }
}

py::dict curvatures(const py::object& input, const py::dict& keywords) {
  const auto settings = settings_from(array_option_table("curvatures"), keywords);
  MeshArgument mesh = mesh_argument(input);
  double unit = 1.0;
  {
    py::gil_scoped_release release;
    unit = on_arrays([&] { return settle_unit(mesh, settings.input, Needs::curvature); });
  }
  py::dict out;
  for (const char* name : {mesh::property::cc1, mesh::property::cc2, mesh::property::shape_index,
                           mesh::property::curvedness}) {
    out[name] = owned_array(mesh.surface.property(name));
  }
  out["length_unit"] = unit;
  return out;
}

py::dict critical_points(const py::object& input, const py::dict& keywords) {
  const auto settings = settings_from(array_option_table("critical_points"), keywords);
  MeshArgument mesh = mesh_argument(input);
  double unit = 1.0;
  std::vector<mesh::CriticalPoint> points;
  {
    py::gil_scoped_release release;
    on_arrays([&] {
      unit = settle_unit(mesh, settings.input, Needs::curvature);
      points = mesh::detect_critical_points_in_unit(mesh.surface, unit,
                                                    settings.descriptors.critical_points);
      return 0;
    });
  }
  py::dict out = points_dict(points);
  out["length_unit"] = unit;
  return out;
}

py::array geodesic_distances(const py::object& input, long long source,
                             const std::optional<double>& max_distance, const std::string& method) {
  MeshArgument mesh = mesh_argument(input);
  mesh::GeodesicOptions geodesic;
  geodesic.method = named<mesh::GeodesicMethod>(method, mesh::geodesic_method_names, "method");
  if (max_distance) {
    if (std::isnan(*max_distance) || *max_distance < 0.0) {
      throw OptionError("max_distance: " + python_number(*max_distance) +
                        ", expected a number >= 0 (in the mesh's coordinates) or None");
    }
    geodesic.max_distance = *max_distance;
  }
  const int vertex = vertex_argument(source, mesh.surface, "source_vertex");
  Eigen::VectorXd distances;
  {
    py::gil_scoped_release release;
    distances = on_arrays([&] { return mesh::geodesic_distances(mesh.surface, vertex, geodesic); });
  }
  return owned_array(std::move(distances));
}

py::dict patch(const py::object& input, long long center, const std::optional<double>& radius,
               const py::dict& keywords) {
  const auto settings = settings_from(array_option_table("patch"), keywords);
  MeshArgument mesh = mesh_argument(input);
  const int vertex = vertex_argument(center, mesh.surface, "center_vertex");
  check_radius(radius);
  mesh::Patch cut;
  double unit = 1.0;
  mesh::PatchOptions patch_options = settings.descriptors.patch;  // as describe cuts them
  {
    py::gil_scoped_release release;
    on_arrays([&] {
      unit = settle_unit(mesh, settings.input, Needs::unit);
      patch_options.radius = radius_in_units(radius, unit, patch_options.radius);
      try {
        cut = mesh::extract_patch_in_unit(mesh.surface, vertex, unit, patch_options);
      } catch (const TopologyError&) {  // the one a manifold mesh can raise, in Python's words
        std::ostringstream message;
        message << mesh.surface.source() << ": center_vertex " << vertex
                << ": no triangle of its patch is left within radius "
                << patch_options.radius * unit
                << " (the mesh's coordinates); expected a radius longer than its edges";
        throw InputError(message.str());
      }
      return 0;
    });
  }
  const auto indices = [](const std::vector<int>& list) {
    return owned_array(Eigen::VectorXi(
        Eigen::Map<const Eigen::VectorXi>(list.data(), static_cast<Eigen::Index>(list.size()))));
  };
  py::list holes;
  for (const std::vector<int>& hole : cut.holes) holes.append(indices(hole));
  py::dict out;
  out["center"] = cut.center;
  out["surface_vertex"] = indices(cut.surface_vertex);
  out["positions"] = owned_array(std::move(cut.positions));
  out["faces"] = owned_array(std::move(cut.faces));
  out["distance"] = owned_array(std::move(cut.distance));
  out["outer_boundary"] = indices(cut.outer_boundary);
  out["holes"] = holes;
  out["genus"] = cut.genus;
  out["radius"] = patch_options.radius * unit;
  return out;
}

py::array disk_map(const py::object& positions_in, const py::object& faces_in,
                   const std::optional<std::vector<int>>& outer_boundary, const std::string& method,
                   const py::dict& keywords) {
  const auto settings = settings_from(array_option_table("disk_map"), keywords);
  const auto parameterization =
      named<harmonic::Parameterization>(method, harmonic::parameterization_names, "method");
  const mesh::Surface surface = surface_of_arrays(py::make_tuple(positions_in, faces_in), false);
  Eigen::MatrixX2d uv;
  {
    py::gil_scoped_release release;
    uv = on_arrays([&] {
      const Eigen::MatrixX3i faces = surface.faces();
      std::vector<int> border;
      if (outer_boundary) {
        border = *outer_boundary;
      } else {
        std::vector<int> all(static_cast<std::size_t>(faces.rows()));
        for (std::size_t f = 0; f < all.size(); ++f) all[f] = static_cast<int>(f);
        border = mesh::boundary_loops(surface, all).outer;
        if (border.empty()) {
          throw InputError(surface.source() +
                           ": the mesh has no border; a disk map needs a disk (a patch)");
        }
      }
      const Eigen::MatrixX2d map = harmonic::parameterize_patch(
          surface.positions(), faces, border, parameterization, settings.descriptors.disk_map);
      // A free border's map, whose position and scale are arbitrary, as patch-map writes it.
      return harmonic::has_free_border(parameterization) ? report::fit_to_disk_square(map) : map;
    });
  }
  return owned_array(std::move(uv));
}

/// Why describe gives a critical point at a vertex no image, in a user's words.
std::string no_image_reason(harmonic::PatchStatus status) {
  switch (status) {
    case harmonic::PatchStatus::empty:
      return "no triangle of its patch is left (a radius shorter than its edges?)";
    case harmonic::PatchStatus::not_a_disk:
      return "its patch has a handle, and a harmonic map needs a disk (a smaller radius?)";
    case harmonic::PatchStatus::map_failed:
      return "the harmonic map of its patch cannot be solved (degenerate triangles)";
    case harmonic::PatchStatus::at_border:
      return "its patch reaches the mesh's border, and describe images no truncated patch";
    default:
      return harmonic::to_string(status);
  }
}

py::array shape_image(const py::object& input, long long center,
                      const std::optional<double>& radius, const py::dict& keywords) {
  auto settings = settings_from(array_option_table("shape_image"), keywords);
  MeshArgument mesh = mesh_argument(input);
  const int vertex = vertex_argument(center, mesh.surface, "center_vertex");
  check_radius(radius);
  harmonic::CriticalPointDescriptor described;
  {
    py::gil_scoped_release release;
    on_arrays([&] {
      const double unit = settle_unit(mesh, settings.input, Needs::curvature);
      harmonic::DescriptorOptions& d = settings.descriptors;
      d.patch.radius = radius_in_units(radius, unit, d.patch.radius);
      mesh::CriticalPoint point;  // describe_points_in_unit uses its vertex alone
      point.vertex = vertex;
      point.position = point.normal = Eigen::Vector3d::Zero();
      described = std::move(harmonic::describe_points_in_unit(mesh.surface, {point}, unit, d)[0]);
      return 0;
    });
  }
  if (described.status != harmonic::PatchStatus::ok) {
    throw InputError(mesh.surface.source() + ": center_vertex " + std::to_string(vertex) + ": " +
                     no_image_reason(described.status));
  }
  const harmonic::ImageOptions& grid = settings.descriptors.image;
  py::array_t<double> out(
      {static_cast<py::ssize_t>(grid.rings), static_cast<py::ssize_t>(grid.sectors)});
  fill_image(described.image, grid.rings, grid.sectors, out.mutable_data(0, 0));
  return out;
}

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
    const auto limit = tools::limit_threads(settings.query.threads);
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
    const auto limit = tools::limit_threads(settings.query.threads);
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

py::list option_table(const std::string& function) {
  if (function == "build_surface") return table_list(molsurf::surface_input_option_table());
  if (function == "describe") return table_list(matching::describe_option_table());
  if (function == "match") return table_list(matching::pair_match_option_table());
  if (function == "screen") return table_list(screening::screen_option_table());
  if (function == "pockets") return table_list(molsurf::pocket_search_option_table());
  for (const char* name : {"curvatures", "critical_points", "patch", "disk_map", "shape_image"}) {
    if (function == name) return table_list(array_option_table(function));
  }
  throw py::value_error("no function '" + function +
                        "' with options (build_surface, describe, match, screen, pockets, "
                        "curvatures, critical_points, patch, disk_map, shape_image)");
}

/// The module's exception classes: Error, the base of all; InputError (also a ValueError) and
/// OptionError under it; FileError (also an OSError).
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
  m.def("screen_shapes", &sp::screen_shapes, py::arg("query"), py::arg("library"),
        py::arg("options"), py::arg("mesh_options"));
  m.def("pockets", &sp::pockets, py::arg("structure"), py::arg("options"));
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
      "run_command_line",
      [](const std::vector<std::string>& args) {
        py::gil_scoped_release release;
        return surfcomp::tools::run_command_line(args);
      },
      py::arg("args"));
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
