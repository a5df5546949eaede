#include "surfcomp/mesh/io/read_mesh.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/mesh/io/formats.hpp"

#include <Eigen/Geometry>

#include <algorithm>

namespace surfcomp::mesh::io {
namespace {

/// `s` without the vertices that no face uses (normals, properties and storage types kept for
/// the others, in their order); `dropped` receives how many went.
Surface without_unused_vertices(Surface s, std::size_t& dropped) {
  const Eigen::MatrixX3i faces = s.faces();
  const auto n = static_cast<Eigen::Index>(s.n_vertices());
  std::vector<int> renamed(static_cast<std::size_t>(n), -1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (Eigen::Index c = 0; c < 3; ++c) renamed[static_cast<std::size_t>(faces(f, c))] = 0;
  }
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (renamed[static_cast<std::size_t>(i)] < 0) continue;
    renamed[static_cast<std::size_t>(i)] = static_cast<int>(kept.size());
    kept.push_back(i);
  }
  dropped = static_cast<std::size_t>(n) - kept.size();
  if (dropped == 0) return s;
  const auto m = static_cast<Eigen::Index>(kept.size());
  const auto subset = [&](const auto& values) {
    std::decay_t<decltype(values)> out(m, values.cols());
    for (Eigen::Index i = 0; i < m; ++i) out.row(i) = values.row(kept[static_cast<std::size_t>(i)]);
    return out;
  };
  Eigen::MatrixX3i kept_faces(faces.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (Eigen::Index c = 0; c < 3; ++c)
      kept_faces(f, c) = renamed[static_cast<std::size_t>(faces(f, c))];
  }
  Surface out = Surface::from_arrays(subset(s.positions()), kept_faces, s.source());
  out.set_position_type(s.position_type());
  if (s.has_normals()) {
    out.set_normals(subset(s.normals()));
    out.set_normal_type(s.normal_type());
  }
  for (const std::string& name : s.property_names()) {
    out.set_property(name, subset(s.property(name)), s.property_type(name));
  }
  return out;
}

/// The faces of `s` whose area is at most 1e-12 times the squared bounding-box diagonal.
std::vector<Eigen::Index> zero_area_faces(const Surface& s) {
  const Eigen::MatrixX3d p = s.positions();
  const Eigen::MatrixX3i f = s.faces();
  std::vector<Eigen::Index> found;
  if (p.rows() == 0) return found;
  const double diagonal_squared = (p.colwise().maxCoeff() - p.colwise().minCoeff()).squaredNorm();
  const double min_area = 1e-12 * diagonal_squared;
  for (Eigen::Index t = 0; t < f.rows(); ++t) {
    const Eigen::Vector3d a = p.row(f(t, 0));
    const Eigen::Vector3d b = p.row(f(t, 1));
    const Eigen::Vector3d c = p.row(f(t, 2));
    if (0.5 * (b - a).cross(c - a).norm() <= min_area) found.push_back(t);
  }
  return found;
}

std::string zero_area_note(const std::string& source, const std::vector<Eigen::Index>& faces) {
  constexpr std::size_t shown = 5;
  std::string list;
  for (std::size_t k = 0; k < faces.size() && k < shown; ++k) {
    if (k > 0) list += ", ";
    list += std::to_string(faces[k]);
  }
  if (faces.size() > shown) list += ", ...";
  const bool one = faces.size() == 1;
  return source + ": " + std::to_string(faces.size()) +
         (one ? " zero-area triangle (face " : " zero-area triangles (faces ") + list +
         ", counted from 0); " + options::named("repair") + " removes " + (one ? "it" : "them");
}

[[noreturn]] void unknown_extension(const std::filesystem::path& path, MeshUse use) {
  const std::string expected =
      use == MeshUse::read ? "a mesh extension (" : "an extension surfcomp writes (";
  throw FormatError(path.string(), "expected " + expected + mesh_extensions(use) + "), found '" +
                                       path.extension().string() + "'");
}

}  // namespace

bool is_mesh_file(const std::filesystem::path& path) {
  const MeshFormat* format = find_mesh_format(path);
  return format != nullptr && format->read != nullptr;
}

Surface read_mesh(const std::filesystem::path& path, std::vector<std::string>* notes) {
  const MeshFormat* format = find_mesh_format(path);
  if (format == nullptr || format->read == nullptr) unknown_extension(path, MeshUse::read);
  std::size_t dropped = 0;
  Surface surface = without_unused_vertices(format->read(path), dropped);
  if (notes == nullptr) return surface;
  const std::string& source = surface.source();
  if (dropped > 0) {
    notes->push_back(source + ": dropped " + std::to_string(dropped) +
                     (dropped == 1 ? " unused vertex" : " unused vertices"));
  }
  const std::vector<Eigen::Index> degenerate = zero_area_faces(surface);
  if (!degenerate.empty()) notes->push_back(zero_area_note(source, degenerate));
  return surface;
}

Surface read_mesh(const std::filesystem::path& path) { return read_mesh(path, nullptr); }

void write_mesh(const Surface& s, const std::filesystem::path& path) {
  const MeshFormat* format = find_mesh_format(path);
  if (format == nullptr || format->write == nullptr) unknown_extension(path, MeshUse::write);
  format->write(s, path);
}

}  // namespace surfcomp::mesh::io
