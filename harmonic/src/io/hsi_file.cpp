#include "surfcomp/harmonic/io/hsi_file.hpp"

#include "surfcomp/core/elements.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/binary_stream.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/io/input_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <sstream>
#include <utility>

namespace surfcomp::harmonic::io {
namespace {

using surfcomp::io::BinaryReader;
using surfcomp::io::BinaryWriter;

constexpr std::array<char, 8> kMagic{'S', 'U', 'R', 'F', 'H', 'S', 'I', '\n'};
constexpr std::uint32_t kByteOrderMark = 0x01020304u;
constexpr std::size_t kHeaderSize = 8 + 4 + 4 + 8 + 8;
/// Bytes of a critical point that has no patch: type, vertex, position, normal, six values,
/// status. Bounds the count a file may claim.
constexpr std::size_t kMinPointBytes = 1 + 4 + 24 + 24 + 48 + 1;

/// A capitalised element symbol ("C", "Cl"), as SurfaceAtom holds it.
bool is_element_symbol(const std::string& symbol) {
  return bondi_radius(symbol).has_value() && symbol == normalize_element(symbol);
}

// ---- encoding -------------------------------------------------------------------------------

void put_options(BinaryWriter& w, const DescriptorOptions& o) {
  w.f64(o.critical_points.radius);
  w.f64(o.critical_points.property_disc_radius);
  w.u8(static_cast<std::uint8_t>(o.critical_points.distance));
  w.f64(o.patch.radius);
  w.f64(o.patch.margin);
  w.u8(static_cast<std::uint8_t>(o.patch.distance));
  w.u8(static_cast<std::uint8_t>(o.disk_map.weights));
  w.i32(o.image.rings);
  w.i32(o.image.sectors);
  w.string(o.image_property);
}

void put_surface(BinaryWriter& w, const mesh::Surface& s) {
  w.string(s.source());
  w.double_matrix(s.positions());
  w.u8(s.has_normals() ? 1 : 0);
  if (s.has_normals()) w.double_matrix(s.normals());
  w.int_matrix(s.faces());
  w.u8(static_cast<std::uint8_t>(s.position_type()));
  w.u8(static_cast<std::uint8_t>(s.normal_type()));
  w.u64(s.property_names().size());
  for (const std::string& name : s.property_names()) {
    w.string(name);
    w.u8(static_cast<std::uint8_t>(s.property_type(name)));
    w.doubles(s.property(name));
  }
}

void put_vector3(BinaryWriter& w, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) w.f64(v(k));
}

void put_point(BinaryWriter& w, const mesh::CriticalPoint& p) {
  w.u8(static_cast<std::uint8_t>(p.type));
  w.i32(p.vertex);
  put_vector3(w, p.position);
  put_vector3(w, p.normal);
  for (double value : {p.cc1, p.cc2, p.shape_index, p.curvedness, p.esp, p.lp}) w.f64(value);
}

void put_patch(BinaryWriter& w, const mesh::Patch& p) {
  w.i32(p.center);
  w.ints(p.surface_vertex);
  w.double_matrix(p.positions);
  w.int_matrix(p.faces);
  w.doubles(p.distance);
  w.ints(p.outer_boundary);
  w.u64(p.holes.size());
  for (const auto& hole : p.holes) w.ints(hole);
  w.i32(p.genus);
}

void put_image(BinaryWriter& w, const ShapeImage& image) {
  w.i32(image.rings);
  w.i32(image.sectors);
  w.doubles(image.values);
  w.u64(image.valid.size());
  for (std::uint8_t v : image.valid) w.u8(v);
  w.ints(std::vector<int>(image.face.data(), image.face.data() + image.face.size()));
  w.double_matrix(image.barycentric);
}

// ---- decoding -------------------------------------------------------------------------------

/// A stored length parameter (A): finite and in [lo, hi].
double get_length(BinaryReader& r, double lo, double hi, const char* what) {
  const double value = r.f64();
  if (!(std::isfinite(value) && value >= lo && value <= hi)) {
    std::ostringstream text;
    text << what << " " << value << " is not in [" << lo << ", " << hi << "]";
    r.fail(text.str());
  }
  return value;
}

/// A stored vector: every component finite.
void check_finite(BinaryReader& r, const Eigen::Ref<const Eigen::MatrixXd>& values,
                  const std::string& what) {
  if (!values.allFinite()) r.fail(what + " holds a non-finite value");
}

template <typename Enum>
Enum get_enum(BinaryReader& r, std::uint8_t last, const char* what) {
  const std::uint8_t value = r.u8();
  if (value > last) r.fail(std::string("unknown ") + what + " " + std::to_string(value));
  return static_cast<Enum>(value);
}

DescriptorOptions get_options(BinaryReader& r) {
  DescriptorOptions o;
  o.critical_points.radius =
      get_length(r, max_stored_length * 1e-6, max_stored_length, "critical point radius r_cp");
  o.critical_points.property_disc_radius =
      get_length(r, 0.0, max_stored_length, "property disc radius");
  o.critical_points.distance = get_enum<mesh::GeodesicMethod>(r, 1, "distance method");
  o.patch.radius = get_length(r, max_stored_length * 1e-6, max_stored_length, "patch radius");
  o.patch.margin = get_length(r, 0.0, 1.0, "patch margin");
  o.patch.distance = get_enum<mesh::GeodesicMethod>(r, 1, "distance method");
  o.disk_map.weights = get_enum<SpringWeights>(r, 3, "spring weight kind");
  o.image.rings = r.i32();
  o.image.sectors = r.i32();
  if (o.image.rings < 1 || o.image.rings > max_stored_rings || o.image.sectors < 1 ||
      o.image.sectors > max_stored_sectors) {
    r.fail("image grid of " + std::to_string(o.image.rings) + " rings x " +
           std::to_string(o.image.sectors) + " sectors is outside 1.." +
           std::to_string(max_stored_rings) + " x 1.." + std::to_string(max_stored_sectors));
  }
  o.image_property = r.string();
  if (o.image_property.empty()) r.fail("the image property has no name");
  return o;
}

mesh::Surface get_surface(BinaryReader& r) {
  const std::string source = r.string();
  const Eigen::MatrixXd positions = r.double_matrix();
  if (positions.cols() != 3) r.fail("vertex positions are not 3 columns");
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    surfcomp::io::check_read_position(positions.row(i).transpose(), r.source(),
                                      "stored vertex " + std::to_string(i));
  }
  const bool has_normals = r.u8() != 0;
  Eigen::MatrixXd normals;
  if (has_normals) {
    normals = r.double_matrix();
    if (normals.cols() != 3 || normals.rows() != positions.rows()) r.fail("bad normals");
    check_finite(r, normals, "the vertex normals");
  }
  const Eigen::MatrixXi faces = r.int_matrix();
  if (faces.cols() != 3 && faces.rows() != 0) r.fail("faces are not triangles");
  if (faces.rows() == 0) r.fail("the stored surface has no faces");
  mesh::Surface s;
  try {
    s = mesh::Surface::from_arrays(
        positions, faces.rows() ? Eigen::MatrixX3i(faces) : Eigen::MatrixX3i(0, 3), r.source());
  } catch (const Error& e) {
    r.fail(std::string("the stored surface is invalid: ") + e.what());
  }
  s.set_source(source);
  if (has_normals) s.set_normals(normals);
  s.set_position_type(get_enum<mesh::ValueType>(r, 7, "value type"));
  s.set_normal_type(get_enum<mesh::ValueType>(r, 7, "value type"));
  const std::uint64_t n_properties = r.u64();
  if (n_properties > r.remaining()) r.fail("implausible property count");
  for (std::uint64_t k = 0; k < n_properties; ++k) {
    const std::string name = r.string();
    const auto type = get_enum<mesh::ValueType>(r, 7, "value type");
    const Eigen::VectorXd values = r.doubles();
    if (static_cast<std::size_t>(values.size()) != s.n_vertices()) {
      r.fail("property '" + name + "' has the wrong number of values");
    }
    for (Eigen::Index i = 0; i < values.size(); ++i) {
      surfcomp::io::check_read_value(values(i), r.source(), "stored vertex " + std::to_string(i),
                                     "property '" + name + "'");
    }
    s.set_property(name, values, type);
  }
  return s;
}

Eigen::Vector3d get_vector3(BinaryReader& r) {
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) v(k) = r.f64();
  return v;
}

/// A critical point; its esp and lp are NaN where the surface has no such property (as
/// detect_critical_points gives them), finite otherwise.
mesh::CriticalPoint get_point(BinaryReader& r, const mesh::Surface& surface) {
  const std::size_t n_vertices = surface.n_vertices();
  mesh::CriticalPoint p;
  p.type = get_enum<mesh::CriticalPointType>(r, 1, "critical point type");
  p.vertex = r.i32();
  if (p.vertex < 0 || static_cast<std::size_t>(p.vertex) >= n_vertices) {
    r.fail("critical point vertex " + std::to_string(p.vertex) + " outside the surface");
  }
  p.position = get_vector3(r);
  surfcomp::io::check_read_position(p.position, r.source(),
                                    "critical point at vertex " + std::to_string(p.vertex));
  p.normal = get_vector3(r);
  check_finite(r, p.normal, "a critical point normal");
  for (double* value : {&p.cc1, &p.cc2, &p.shape_index, &p.curvedness, &p.esp, &p.lp}) {
    *value = r.f64();
  }
  check_finite(r, Eigen::Vector4d(p.cc1, p.cc2, p.shape_index, p.curvedness),
               "a critical point's curvatures");
  for (const auto& [value, name] : {std::pair<double, const char*>{p.esp, mesh::property::esp},
                                    std::pair<double, const char*>{p.lp, mesh::property::lp}}) {
    const bool absent = !surface.has_property(name) && std::isnan(value);
    if (!absent && !std::isfinite(value)) {
      r.fail(std::string("a critical point's ") + name + " is not finite");
    }
  }
  return p;
}

void check_indices(BinaryReader& r, const std::vector<int>& indices, std::size_t bound,
                   const char* what) {
  for (int i : indices) {
    if (i < 0 || static_cast<std::size_t>(i) >= bound) {
      r.fail(std::string(what) + " index " + std::to_string(i) + " outside 0.." +
             std::to_string(bound));
    }
  }
}

mesh::Patch get_patch(BinaryReader& r, std::size_t surface_vertices) {
  mesh::Patch p;
  p.center = r.i32();
  p.surface_vertex = r.ints();
  const std::size_t n = p.surface_vertex.size();
  check_indices(r, p.surface_vertex, surface_vertices, "patch back-reference");
  if (p.center < 0 || static_cast<std::size_t>(p.center) >= std::max<std::size_t>(n, 1)) {
    r.fail("patch centre outside the patch");
  }
  const Eigen::MatrixXd positions = r.double_matrix();
  if (static_cast<std::size_t>(positions.rows()) != n || positions.cols() != 3) {
    r.fail("patch positions do not match its vertices");
  }
  check_finite(r, positions, "patch positions");
  p.positions = positions;
  const Eigen::MatrixXi faces = r.int_matrix();
  if (faces.cols() != 3) r.fail("patch faces are not triangles");
  if (faces.size() > 0 &&
      (faces.minCoeff() < 0 || static_cast<std::size_t>(faces.maxCoeff()) >= n)) {
    r.fail("patch face index outside the patch");
  }
  p.faces = faces;
  p.distance = r.doubles();
  if (static_cast<std::size_t>(p.distance.size()) != n) r.fail("patch distances do not match");
  check_finite(r, p.distance, "patch distances");
  p.outer_boundary = r.ints();
  check_indices(r, p.outer_boundary, n, "patch border");
  const std::uint64_t n_holes = r.u64();
  if (n_holes > r.remaining() / 8) r.fail("implausible hole count");
  for (std::uint64_t k = 0; k < n_holes; ++k) {
    std::vector<int>& hole = p.holes.emplace_back(r.ints());
    check_indices(r, hole, n, "patch hole");
  }
  p.genus = r.i32();
  return p;
}

ShapeImage get_image(BinaryReader& r, std::size_t n_faces, const ImageOptions& grid) {
  ShapeImage image;
  image.rings = r.i32();
  image.sectors = r.i32();
  if (image.rings != grid.rings || image.sectors != grid.sectors) {
    r.fail("an image grid differs from the file's parameters");
  }
  const std::size_t n =
      static_cast<std::size_t>(grid.rings) * static_cast<std::size_t>(grid.sectors);
  image.values = r.doubles();
  check_finite(r, image.values, "image values");
  const std::uint64_t n_valid = r.u64();
  if (static_cast<std::size_t>(image.values.size()) != n || n_valid != n ||
      n_valid > r.remaining()) {
    r.fail("image sizes do not match its grid");
  }
  image.valid.resize(n);
  for (auto& v : image.valid) {
    v = r.u8();
    if (v > 1) r.fail("image validity flag " + std::to_string(v) + " is not 0 or 1");
  }
  const std::vector<int> faces = r.ints();
  if (faces.size() != n) r.fail("image face list does not match its grid");
  for (int f : faces) {
    if (f < -1 || (f >= 0 && static_cast<std::size_t>(f) >= n_faces))
      r.fail("image face outside the patch");
  }
  image.face = Eigen::Map<const Eigen::VectorXi>(faces.data(), static_cast<Eigen::Index>(n));
  const Eigen::MatrixXd barycentric = r.double_matrix();
  if (static_cast<std::size_t>(barycentric.rows()) != n || barycentric.cols() != 3) {
    r.fail("image barycentric coordinates do not match its grid");
  }
  check_finite(r, barycentric, "image barycentric coordinates");
  image.barycentric = barycentric;
  return image;
}

}  // namespace

std::vector<std::uint8_t> encode_hsi(const SurfaceDescriptors& d) {
  BinaryWriter payload;
  put_options(payload, d.options);
  put_surface(payload, d.surface);
  payload.u64(d.critical_points.size());
  for (const auto& cp : d.critical_points) {
    put_point(payload, cp.point);
    payload.u8(static_cast<std::uint8_t>(cp.status));
    if (cp.status != PatchStatus::ok) continue;
    put_patch(payload, cp.patch);
    payload.double_matrix(cp.map.uv);
    put_image(payload, cp.image);
  }
  payload.u64(d.atoms.size());
  for (std::size_t i = 0; i < d.atoms.size(); ++i) {
    const SurfaceAtom& atom = d.atoms[i];
    if (!is_element_symbol(atom.element) ||
        !atom.position.allFinite()) {  // what decode_hsi would refuse
      throw InputError(d.surface.source() + ": atom " + std::to_string(i + 1) + " ('" +
                       atom.element +
                       "') is not an element symbol with a finite position; no .hsi written");
    }
    payload.string(atom.element);
    put_vector3(payload, atom.position);
  }
  // A description in A is written as version 2, which older readers take; one of a general
  // mesh in a unit of its own adds the unit (version 3).
  const bool in_angstrom = d.length_unit == 1.0;
  if (!in_angstrom) {
    if (!(std::isfinite(d.length_unit) && d.length_unit > 0.0 &&
          d.length_unit <= max_stored_unit)) {
      throw InputError(d.surface.source() + ": length unit " + std::to_string(d.length_unit) +
                       " is not in (0, 1e12]; no .hsi written");
    }
    payload.f64(d.length_unit);
  }
  BinaryWriter file;
  for (char c : kMagic) file.u8(static_cast<std::uint8_t>(c));
  file.u32(in_angstrom ? 2 : hsi_format_version);
  file.u32(kByteOrderMark);
  file.u64(payload.bytes().size());
  file.u64(surfcomp::io::fnv1a64(payload.bytes().data(), payload.bytes().size()));
  std::vector<std::uint8_t> bytes = file.bytes();
  bytes.insert(bytes.end(), payload.bytes().begin(), payload.bytes().end());
  return bytes;
}

SurfaceDescriptors decode_hsi(const std::vector<std::uint8_t>& bytes, const std::string& source) {
  return decode_hsi(bytes.data(), bytes.size(), source);
}

SurfaceDescriptors decode_hsi(const std::uint8_t* data, std::size_t n_bytes,
                              const std::string& source) {
  if (n_bytes < kHeaderSize || std::memcmp(data, kMagic.data(), kMagic.size()) != 0) {
    throw FormatError(source, "not a .hsi file (no SURFHSI header)");
  }
  BinaryReader header(data + kMagic.size(), kHeaderSize - kMagic.size(), source);
  const std::uint32_t version = header.u32();
  const std::uint32_t mark = header.u32();
  if (mark != kByteOrderMark) {
    throw FormatError(source, "byte order mark " + std::to_string(mark) +
                                  " is not that of a .hsi file written by surfcomp");
  }
  if (version < 1 || version > hsi_format_version) {
    throw FormatError(source, "format version " + std::to_string(version) +
                                  ", this surfcomp reads versions 1 to " +
                                  std::to_string(hsi_format_version) +
                                  "; rebuild it with surfcomp hsi-build");
  }
  const std::uint64_t size = header.u64();
  const std::uint64_t checksum = header.u64();
  if (size != n_bytes - kHeaderSize) {
    throw FormatError(source, "the payload has " + std::to_string(n_bytes - kHeaderSize) +
                                  " bytes, the header says " + std::to_string(size) +
                                  " (truncated?)");
  }
  const std::uint8_t* payload = data + kHeaderSize;
  if (surfcomp::io::fnv1a64(payload, size) != checksum) {
    throw FormatError(source, "checksum mismatch: the file is corrupt");
  }
  BinaryReader r(payload, size, source);
  SurfaceDescriptors d;
  d.options = get_options(r);
  d.surface = get_surface(r);
  if (!d.surface.has_property(d.options.image_property)) {
    r.fail("its images are of property '" + d.options.image_property +
           "', which its surface does not carry");
  }
  const std::uint64_t n_points = r.u64();
  if (n_points > r.remaining() / kMinPointBytes) {
    r.fail("a count of " + std::to_string(n_points) + " critical points cannot fit in the " +
           std::to_string(r.remaining()) + " bytes left");
  }
  // Grown as points are read, not sized by the count: memory follows the bytes actually present.
  for (std::uint64_t k = 0; k < n_points; ++k) {
    CriticalPointDescriptor& cp = d.critical_points.emplace_back();
    cp.point = get_point(r, d.surface);
    cp.status = get_enum<PatchStatus>(r, 5, "patch status");
    if (cp.status != PatchStatus::ok) continue;
    cp.patch = get_patch(r, d.surface.n_vertices());
    const Eigen::MatrixXd uv = r.double_matrix();
    if (static_cast<std::size_t>(uv.rows()) != cp.patch.surface_vertex.size() || uv.cols() != 2) {
      r.fail("harmonic map does not match its patch");
    }
    check_finite(r, uv, "a harmonic map");
    cp.map.uv = uv;
    cp.image = get_image(r, static_cast<std::size_t>(cp.patch.faces.rows()), d.options.image);
  }
  if (version >= 2) {
    const std::uint64_t n_atoms = r.u64();
    if (n_atoms > r.remaining() / 29) {  // 4 + 1 + 24 bytes at least
      r.fail("a count of " + std::to_string(n_atoms) + " atoms cannot fit in the " +
             std::to_string(r.remaining()) + " bytes left");
    }
    d.atoms.resize(n_atoms);
    for (SurfaceAtom& atom : d.atoms) {
      atom.element = r.string();
      if (!is_element_symbol(atom.element)) {
        r.fail("atom element '" + atom.element + "' is not an element symbol");
      }
      atom.position = get_vector3(r);
      if (!atom.position.allFinite()) r.fail("atom position is not finite");
    }
  }
  if (version >= 3) {
    d.length_unit = r.f64();
    if (!(std::isfinite(d.length_unit) && d.length_unit > 0.0 &&
          d.length_unit <= max_stored_unit)) {
      r.fail("length unit " + std::to_string(d.length_unit) + " is not in (0, 1e12]");
    }
  }
  if (r.remaining() != 0)
    r.fail("unexpected bytes after the " + std::string(version >= 3   ? "length unit"
                                                       : version >= 2 ? "atoms"
                                                                      : "last critical point"));
  return d;
}

void write_hsi(const SurfaceDescriptors& descriptors, const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = encode_hsi(descriptors);
  surfcomp::io::write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
  });
}

SurfaceDescriptors read_hsi(const std::filesystem::path& path) {
  const std::string bytes = surfcomp::io::read_input_file(path);
  return decode_hsi(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                    path.string());
}

bool is_hsi_file(const std::filesystem::path& path) {
  return surfcomp::io::lowercase_extension(path) == ".hsi";
}

}  // namespace surfcomp::harmonic::io
