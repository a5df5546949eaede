// mesh::Surface — a triangle surface with per-vertex normals and named scalar vertex properties
// (esp, lp, cc1, cc2, shape_index, or whatever a file brought: MaSIF's charge, hphob, hbond,
// iface).
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace surfcomp::mesh {

namespace detail {
struct SurfaceAccess;  // the mesh module's own way in; defined in its sources only
}  // namespace detail

/// Names of the properties the project computes (method §0).
namespace property {
inline constexpr const char* esp = "esp";                  ///< kcal/(mol*e)
inline constexpr const char* lp = "lp";                    ///< lipophilic potential, logP units
inline constexpr const char* cc1 = "cc1";                  ///< 1/A, larger |k|; convex < 0
inline constexpr const char* cc2 = "cc2";                  ///< 1/A; convex < 0
inline constexpr const char* shape_index = "shape_index";  ///< [-1, 1]; cap +1, cup -1
inline constexpr const char* curvedness = "curvedness";    ///< 1/A
}  // namespace property

/// How a value is stored in a file; values live in memory as double, which holds every one of
/// these exactly, so writing with the stored type reproduces the file's bits.
enum class ValueType : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

/// Size in bytes of one value of `type`.
std::size_t value_size(ValueType type);

/// A triangle surface with named per-vertex scalar properties, in double precision.
/// Invariants: every face is a triangle of three distinct vertices; every edge borders one or
/// two faces, which traverse it in opposite directions; property vectors have one value per
/// vertex. A value type: copies are deep, moves are cheap and leave the source empty (as if
/// default-constructed).
class Surface {
 public:
  /// An empty surface: no vertices, no faces, no properties.
  Surface();
  Surface(const Surface& other);
  Surface(Surface&& other) noexcept;
  Surface& operator=(const Surface& other);
  Surface& operator=(Surface&& other) noexcept;
  ~Surface();

  /// Builds a surface from vertex positions (#V by 3, A) and triangles (#F by 3, 0-based,
  /// counter-clockwise seen from outside). Throws InputError for an index out of range or a
  /// non-finite coordinate and TopologyError when a face cannot be added to a manifold
  /// half-edge mesh (complex edge or vertex); `source` names the origin in messages.
  static Surface from_arrays(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                             const Eigen::Ref<const Eigen::MatrixX3i>& faces,
                             const std::string& source = "<arrays>");

  std::size_t n_vertices() const;
  std::size_t n_faces() const;

  /// Vertex positions, #V by 3, A.
  Eigen::MatrixX3d positions() const;
  /// Triangles, #F by 3, 0-based vertex indices.
  Eigen::MatrixX3i faces() const;
  /// Vertex normals, #V by 3 (unit, outward when has_normals()).
  Eigen::MatrixX3d normals() const;
  void set_normals(const Eigen::Ref<const Eigen::MatrixX3d>& normals);
  /// True when normals were read from a file or computed; false after from_arrays().
  bool has_normals() const;
  /// Area-weighted face normals averaged at the vertices, normalised.
  void compute_normals();

  /// Named scalar properties, in the order they were added (files are written in this order).
  const std::vector<std::string>& property_names() const;
  bool has_property(const std::string& name) const;
  /// A copy of property `name`, one value per vertex. Throws InputError if absent.
  Eigen::VectorXd property(const std::string& name) const;
  double property(const std::string& name, std::size_t vertex) const;
  /// Adds or replaces property `name`. Throws InputError if values.size() != n_vertices().
  void set_property(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& values,
                    ValueType stored_as = ValueType::float64);
  void remove_property(const std::string& name);
  /// The type a file stored the property as (float64 for computed ones).
  ValueType property_type(const std::string& name) const;

  /// Storage types of positions and normals in the file this came from (float64 otherwise).
  ValueType position_type() const;
  ValueType normal_type() const;
  void set_position_type(ValueType type);
  void set_normal_type(ValueType type);

  /// Where the surface came from (a file name, or "<arrays>"), for messages.
  const std::string& source() const;
  void set_source(std::string source);

 private:
  friend struct detail::SurfaceAccess;
  struct Impl;
  const Impl& impl() const;
  Impl& impl();

  std::unique_ptr<Impl> impl_;  ///< null for an empty surface (default-constructed or moved from)
};

/// Applies the rigid motion x -> rotation * x + translation to every vertex and turns the
/// normals with it; properties stay (they are invariant under a rigid motion).
void transform_surface(Surface& surface, const Eigen::Matrix3d& rotation,
                       const Eigen::Vector3d& translation);

/// Scales every vertex position by `factor` (> 0, finite), as a change of length unit:
/// the curvature properties (cc1, cc2, curvedness: 1/length) are divided by it, the others
/// (shape index, ESP, LP) stay. Throws InputError for another factor.
void scale_surface(Surface& surface, double factor);

/// The same surface (positions, normals, properties, value types, source) with its vertices in
/// lexicographic order of position (x, then y, then z) and its faces in lexicographic order of
/// their vertex indices, each face starting at its smallest index (orientation kept). What
/// follows vertex and face order (patch borders, the phase of a shape image) then depends only
/// on the geometry around it: where two surfaces share a piece of geometry, that piece gets
/// the same relative order in both, whatever else each surface holds.
Surface spatially_ordered(const Surface& surface);

/// Barycentric vertex areas: a third of the area of every incident triangle, A^2.
Eigen::VectorXd vertex_areas(const Surface& surface);

/// Global measures of a closed or open surface.
struct SurfaceMeasures {
  double area = 0.0;             ///< A^2
  double volume = 0.0;           ///< A^3, signed (divergence theorem); positive for outward faces
  int euler_characteristic = 0;  ///< V - E + F
  std::size_t boundary_edges = 0;
};
SurfaceMeasures measure_surface(const Surface& surface);

/// Throws TopologyError (naming surface.source()) unless the surface is non-empty, closed
/// (no boundary edge), 2-manifold and has no zero-area triangle (area <= min_area).
void require_closed_manifold(const Surface& surface, double min_area = 1e-12);

}  // namespace surfcomp::mesh
