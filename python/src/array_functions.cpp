#include "functions.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/harmonic/cgal_reference.hpp"
#include "surfcomp/mesh/critical_points.hpp"
#include "surfcomp/mesh/geodesic.hpp"
#include "surfcomp/mesh/patch.hpp"
#include "surfcomp/mesh/topology.hpp"
#include "surfcomp/report/patch_files.hpp"

#include <pybind11/stl.h>

#include <array>
#include <cmath>

namespace surfcomp::python {
namespace {

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

}  // namespace

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

}  // namespace surfcomp::python
