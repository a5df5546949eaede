// The surface stage end to end on real molecules: the SAS against FreeSASA, topology and
// Gauss-Bonnet on ligand SES, curvature of a one-atom SES, invariance under rigid motion.
#include "surfcomp/core/elements.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/mesh/curvature.hpp"
#include "surfcomp/mesh/topology.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "surfcomp/molsurf/ses.hpp"

#include "surface_components.hpp"
#include "test_data.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <regex>
#include <sstream>

namespace surfcomp {
namespace {

/// Writes `molecule` as PDB ATOM records with the radius in the occupancy column.
void write_pdb_with_radii(const Molecule& molecule, const std::filesystem::path& path) {
  std::ofstream out(path);
  int serial = 1;
  for (const Atom& atom : molecule.atoms) {
    char line[100];
    std::snprintf(line, sizeof line,
                  "ATOM  %5d %-4s MOL A   1    %8.3f%8.3f%8.3f%6.2f  0.00          %2s\n",
                  serial++ % 100000, atom.element.c_str(), atom.position.x(), atom.position.y(),
                  atom.position.z(), atom.radius, atom.element.c_str());
    out << line;
  }
  out << "END\n";
}

/// FreeSASA's Lee-Richards SASA (probe 1.4 A, 100 slices) of `molecule` with its own radii;
/// nullopt when the freesasa program is not installed.
std::optional<double> freesasa_area(const Molecule& molecule, const std::string& tag) {
  if (std::system("command -v freesasa >/dev/null 2>&1") != 0) return std::nullopt;
  const test::TempDir dir;
  const auto pdb = dir / (tag + ".pdb");
  write_pdb_with_radii(molecule, pdb);
  const std::string command =
      "freesasa --lee-richards --resolution=100 --probe-radius=1.4 "
      "--radius-from-occupancy --hetatm --hydrogen " +
      pdb.string();
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return std::nullopt;
  std::ostringstream text;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) text << buffer;
  pclose(pipe);
  std::smatch match;
  const std::string output = text.str();
  if (!std::regex_search(output, match, std::regex(R"(Total\s*:\s*([0-9.]+))"))) {
    ADD_FAILURE() << "cannot read freesasa output:\n" << output;
    return std::nullopt;
  }
  return std::stod(match[1]);
}

void atoms_as_arrays(const Molecule& molecule, Eigen::MatrixX3d& centers, Eigen::VectorXd& radii) {
  const auto n = static_cast<Eigen::Index>(molecule.atoms.size());
  centers.resize(n, 3);
  radii.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    centers.row(i) = molecule.atoms[static_cast<std::size_t>(i)].position.transpose();
    radii(i) = molecule.atoms[static_cast<std::size_t>(i)].radius;
  }
}

void expect_sas_matches_freesasa(const std::filesystem::path& file, const std::string& tag,
                                 const molsurf::SesOptions& options = {}) {
  const Molecule molecule = io::read_molecule(file);
  const auto reference = freesasa_area(molecule, tag);
  if (!reference) GTEST_SKIP() << "freesasa is not installed (scripts/install-deps.sh installs it)";
  Eigen::MatrixX3d centers;
  Eigen::VectorXd radii;
  atoms_as_arrays(molecule, centers, radii);
  const mesh::Surface sas = molsurf::build_sas(centers, radii, options);
  const double area = mesh::measure_surface(sas).area;
  std::printf(
      "[ SAS      ] %s: %zu atoms, voxel %s, ours %.2f A^2, FreeSASA Lee-Richards %.2f A^2 "
      "(%+.2f%%)\n",
      tag.c_str(), molecule.atoms.size(),
      options.voxel_size > 0 ? std::to_string(options.voxel_size).c_str() : "auto", area,
      *reference, 100.0 * (area - *reference) / *reference);
  EXPECT_NEAR(area, *reference, 0.01 * *reference);
}

TEST(SurfaceBuild, SasOf1thlLigandMatchesFreeSasa) {
  SURFCOMP_SHARED_OR_SKIP(file, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  expect_sas_matches_freesasa(file, "1THL_ligand");
}

// A protein's SAS has hundreds of tiny exposed sphere pieces (about 0.4 A^2 each) that the
// default grid (voxel = edge length, 0.68 A) does not resolve: -1.6 % there. A 0.34 A grid
// resolves enough of them for 1 %.
TEST(SurfaceBuild, SasOf4we2MatchesFreeSasa) {
  SURFCOMP_FETCHED_OR_SKIP(file, "edtsurf/4we2.pdb");
  molsurf::SesOptions fine;
  fine.voxel_size = 0.34;
  expect_sas_matches_freesasa(file, "4we2", fine);
}

TEST(SurfaceBuild, LigandSurfacesAreClosedSpheresTopologically) {
  for (const char* id : {"1THL", "4TMN", "1TLP", "1TMN", "3TMN"}) {
    SURFCOMP_SHARED_OR_SKIP(file,
                            std::string("thermolysin/ligands-common-frame/") + id + "_ligand.sdf");
    const mesh::Surface surface = molsurf::build_molecular_surface(io::read_molecule(file));
    const mesh::SurfaceMeasures m = mesh::measure_surface(surface);
    EXPECT_EQ(m.euler_characteristic, 2) << id;
    EXPECT_EQ(m.boundary_edges, 0u) << id;
    EXPECT_GT(m.volume, 0.0) << id;
    EXPECT_NEAR(mesh::angle_defects(surface).sum(), 4.0 * M_PI, 1e-8) << id;
    for (const char* name : {mesh::property::esp, mesh::property::lp, mesh::property::cc1,
                             mesh::property::cc2, mesh::property::shape_index}) {
      EXPECT_TRUE(surface.property(name).allFinite()) << id << " " << name;
    }
  }
}

// Kahraman site 1NAZ (HEM 200 A): the surface of the pocket, the atoms within 5 A of the heme
// (heme and water excluded). Where LEU 89 CD1 and ALA 71 CB nearly touch, 3 A from the heme,
// the SES joins them by a neck of ~0.1 A radius, thinner than the grid. The grid mesh cuts
// that neck (an ambiguous face that is the only one of both its cells separates its inside
// corners), leaving a tiny fragment on which the curvature fit would stop the build; the
// default component filter drops it, and nothing else.
TEST(SurfaceBuild, KahramanSite1nazPocketHasNoFragment) {
  SURFCOMP_SHARED_OR_SKIP(file, "kahraman-dev/pdb/1NAZ.pdb");
  const Molecule structure = io::read_molecule(file);
  const auto is_heme = [](const Atom& atom) {
    return atom.residue_name == "HEM" && atom.residue_number == 200 && atom.chain == "A";
  };
  Molecule pocket = structure;
  pocket.atoms.clear();
  for (const Atom& atom : structure.atoms) {
    if (is_heme(atom)) continue;
    const auto within_5a = [&](const Atom& h) {
      return is_heme(h) && (h.position - atom.position).norm() <= 5.0;
    };
    const bool near = std::any_of(structure.atoms.begin(), structure.atoms.end(), within_5a);
    if (near) pocket.atoms.push_back(atom);
  }
  ASSERT_GT(pocket.atoms.size(), 100u);
  double smallest_atom = std::numeric_limits<double>::infinity();
  for (const Atom& atom : pocket.atoms) smallest_atom = std::min(smallest_atom, atom.radius);
  const double ball = 4.0 / 3.0 * M_PI * std::pow(smallest_atom, 3);

  Eigen::MatrixX3d centers;
  Eigen::VectorXd radii;
  atoms_as_arrays(pocket, centers, radii);
  molsurf::SesOptions keep_all;
  keep_all.min_component_volume_fraction = 0.0;
  // With every component kept, the grid mesh may cut a neck thinner than a voxel off as a
  // fragment (the mesher's face rule); the default component filter drops exactly those.
  const auto all = test::surface_components(molsurf::build_ses(centers, radii, keep_all));
  const auto is_fragment = [&](const test::SurfaceComponent& c) { return c.volume < 0.5 * ball; };
  const auto fragments = std::count_if(all.begin(), all.end(), is_fragment);

  const mesh::Surface surface = molsurf::build_molecular_surface(pocket);
  const auto components = test::surface_components(surface);
  std::printf("[ 1NAZ     ] %zu pocket atoms: %zu vertices in %zu components\n",
              pocket.atoms.size(), surface.n_vertices(), components.size());
  EXPECT_EQ(static_cast<std::ptrdiff_t>(components.size()),
            static_cast<std::ptrdiff_t>(all.size()) - fragments);
  for (const auto& c : components) EXPECT_FALSE(is_fragment(c)) << c.vertices << " vertices";
  for (const char* name : {mesh::property::esp, mesh::property::lp, mesh::property::cc1,
                           mesh::property::cc2, mesh::property::shape_index}) {
    EXPECT_TRUE(surface.property(name).allFinite()) << name;
  }
}

TEST(SurfaceBuild, OneAtomSurfaceHasSphereCurvatureAndCapShapeIndex) {
  Molecule molecule;
  molecule.source = "one-atom";
  Atom atom;
  atom.element = "C";
  atom.radius = 1.7;
  atom.charge = 1.0;
  atom.lipophilicity = 1.0;
  molecule.atoms.push_back(atom);
  const mesh::Surface surface = molsurf::build_molecular_surface(molecule);
  const Eigen::VectorXd cc1 = surface.property(mesh::property::cc1);
  const Eigen::VectorXd cc2 = surface.property(mesh::property::cc2);
  const Eigen::VectorXd si = surface.property(mesh::property::shape_index);
  const Eigen::VectorXd esp = surface.property(mesh::property::esp);
  const Eigen::MatrixX3d positions = surface.positions();
  const double k = -1.0 / atom.radius;
  std::size_t good_curvature = 0, good_index = 0;
  for (Eigen::Index v = 0; v < cc1.size(); ++v) {
    if (std::abs(cc1(v) - k) <= 0.05 * std::abs(k) && std::abs(cc2(v) - k) <= 0.05 * std::abs(k)) {
      ++good_curvature;
    }
    if (std::abs(si(v) - 1.0) <= 0.02) ++good_index;
    // The vertices lie on the sphere to within the level set's accuracy, so ESP = 332.06/|x|.
    const double r = positions.row(v).norm();
    EXPECT_NEAR(esp(v), 332.06 / r, 1e-9 * 332.06 / r);
  }
  const double n = static_cast<double>(cc1.size());
  std::printf(
      "[ sphere   ] %zu vertices: %.1f%% with cc1, cc2 within 5%% of -1/r, %.1f%% with S = 1 +- "
      "0.02\n",
      surface.n_vertices(), 100.0 * good_curvature / n, 100.0 * good_index / n);
  EXPECT_GE(good_curvature / n, 0.95);
  EXPECT_GE(good_index / n, 0.95);
}

/// Closest point to `p` on triangle (a, b, c) as barycentric weights (Ericson, Real-Time
/// Collision Detection, 5.1.5).
Eigen::Vector3d closest_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

/// A property of `surface` (positions and faces as the surface gives them) interpolated at the
/// point of the triangles around `near_vertex` closest to `p`; also returns that point's
/// distance to `p`.
std::pair<double, double> interpolate_near(const mesh::Surface& surface,
                                           const Eigen::MatrixX3d& positions,
                                           const Eigen::MatrixX3i& faces,
                                           const Eigen::VectorXd& values, int near_vertex,
                                           const Eigen::Vector3d& p) {
  double best_distance = std::numeric_limits<double>::infinity(), best_value = 0.0;
  for (const int f : mesh::one_ring_faces(surface, near_vertex)) {
    std::array<int, 3> v{};
    std::array<Eigen::Vector3d, 3> x;
    for (int k = 0; k < 3; ++k) {
      v[k] = faces(f, k);
      x[k] = positions.row(v[k]).transpose();
    }
    const Eigen::Vector3d w = closest_barycentric(p, x[0], x[1], x[2]);
    const double distance = (w[0] * x[0] + w[1] * x[1] + w[2] * x[2] - p).norm();
    if (distance < best_distance) {
      best_distance = distance;
      best_value = w[0] * values(v[0]) + w[1] * values(v[1]) + w[2] * values(v[2]);
    }
  }
  return {best_value, best_distance};
}

/// A rigid motion of the molecule moves the surface with it: area and volume stay, and each
/// property at a vertex of the moved surface equals the property of the original surface
/// interpolated at the same place (after undoing the motion), up to the discretisation.
/// ESP and LP are smooth, so they agree closely; the shape index jumps where a convex atom cap
/// meets a re-entrant patch of the SES, so a few vertices near those seams differ more.
TEST(SurfaceBuild, RigidMotionLeavesMeasuresAndPropertiesUnchanged) {
  SURFCOMP_SHARED_OR_SKIP(file, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  const Molecule molecule = io::read_molecule(file);
  std::mt19937 rng(20261122u);
  std::printf("[ motion   ] seed 20261122\n");
  std::normal_distribution<double> gauss;
  const Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  const Eigen::Matrix3d rotation = q.normalized().toRotationMatrix();
  const Eigen::Vector3d translation(gauss(rng) * 10, gauss(rng) * 10, gauss(rng) * 10);
  Molecule moved = molecule;
  transform_molecule(moved, rotation, translation);

  const mesh::Surface a = molsurf::build_molecular_surface(molecule);
  const mesh::Surface b = molsurf::build_molecular_surface(moved);
  const auto ma = mesh::measure_surface(a);
  const auto mb = mesh::measure_surface(b);
  std::printf("[ motion   ] area %.2f -> %.2f A^2, volume %.2f -> %.2f A^3\n", ma.area, mb.area,
              ma.volume, mb.volume);
  EXPECT_NEAR(mb.area, ma.area, 0.005 * ma.area);
  EXPECT_NEAR(mb.volume, ma.volume, 0.005 * ma.volume);

  struct Tolerance {
    const char* name;
    double median, p95;  // of |difference| / (max - min) over the original surface
  };
  const Eigen::MatrixX3d pa = a.positions();
  const Eigen::MatrixX3d pb = b.positions();
  const Eigen::MatrixX3i fa = a.faces();
  for (const Tolerance& tol :
       {Tolerance{mesh::property::esp, 0.01, 0.03}, Tolerance{mesh::property::lp, 0.01, 0.03},
        Tolerance{mesh::property::shape_index, 0.05, 0.25}}) {
    const Eigen::VectorXd va = a.property(tol.name);
    const Eigen::VectorXd vb = b.property(tol.name);
    const double range = va.maxCoeff() - va.minCoeff();
    std::vector<double> errors;
    double max_distance = 0.0;
    for (Eigen::Index i = 0; i < pb.rows(); ++i) {
      const Eigen::Vector3d back = rotation.transpose() * (pb.row(i).transpose() - translation);
      Eigen::Index nearest = 0;
      (pa.rowwise() - back.transpose()).rowwise().squaredNorm().minCoeff(&nearest);
      const auto [value, distance] =
          interpolate_near(a, pa, fa, va, static_cast<int>(nearest), back);
      max_distance = std::max(max_distance, distance);
      errors.push_back(std::abs(vb(i) - value) / range);
    }
    std::sort(errors.begin(), errors.end());
    const double median = test::median(errors);
    const double p95 = errors[errors.size() * 95 / 100];
    std::printf(
        "[ motion   ] %s: moved vertices within %.3f A of the original surface; "
        "|difference| / range: median %.4f, 95th percentile %.4f\n",
        tol.name, max_distance, median, p95);
    // Two triangulations of one surface: they differ by the chords' sag (edges ~0.68 A).
    EXPECT_LT(max_distance, 0.2) << tol.name;
    EXPECT_LT(median, tol.median) << tol.name;
    EXPECT_LT(p95, tol.p95) << tol.name;
  }
}

}  // namespace
}  // namespace surfcomp
