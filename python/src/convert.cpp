#include "convert.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/mesh/topology.hpp"
#include "surfcomp/report/critical_point_files.hpp"

#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace surfcomp::python {

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

py::array pair_array(const std::vector<std::pair<int, int>>& pairs) {
  Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor> out(
      static_cast<Eigen::Index>(pairs.size()), 2);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    out(static_cast<Eigen::Index>(k), 0) = pairs[k].first;
    out(static_cast<Eigen::Index>(k), 1) = pairs[k].second;
  }
  return owned_array(std::move(out));
}

py::dict alignment_dict(const matching::Alignment& a) {
  Eigen::Matrix<double, 4, 4, Eigen::RowMajor> transform = a.transform;
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
  d["cp_pairs"] = pair_array(a.cp_pairs);
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

}  // namespace surfcomp::python
