#include "surfcomp/molsurf/pockets.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/mesh/spatial_grid.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <tuple>
#include <utility>

namespace surfcomp::molsurf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<std::size_t, Kernel>;
using DataStructure =
    CGAL::Triangulation_data_structure_3<VertexBase,
                                         CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, DataStructure>;

/// A ray from an alpha sphere's centre is blocked by an atom whose centre passes within this
/// distance of it (about a heavy atom's van der Waals radius plus a margin for the gaps between
/// atoms), A.
constexpr double ray_blocking_radius = 2.0;
/// The reach of a pocket atom into its alpha sphere (a carbon's van der Waals radius, rounded),
/// A: the pocket's volume is that of its spheres shrunk by it.
constexpr double atom_reach = 1.6;
constexpr double volume_spacing = 0.5;  // A
constexpr int direction_count = 30;

struct AlphaSphere {
  Eigen::Vector3d center;
  double radius = 0.0;
  std::array<std::size_t, 4> atoms{};  ///< indices into the structure, ascending
  double buriedness = 0.0;
};

void check_options(const PocketOptions& options) {
  if (!(std::isfinite(options.max_volume) && options.max_volume >= 0.0)) {
    throw OptionError(options::named("pocket_max_volume") +
                      " must be a finite volume >= 0 A^3 (0: no split)");
  }
  const auto positive = [](double value) { return std::isfinite(value) && value > 0.0; };
  if (!positive(options.min_sphere_radius) || !positive(options.max_sphere_radius) ||
      !(options.max_sphere_radius > options.min_sphere_radius)) {
    throw OptionError(options::named("pocket_max_radius") + " must be larger than " +
                      options::named("pocket_min_radius") + " (both > 0 A)");
  }
  if (!(options.min_buriedness >= 0.0 && options.min_buriedness <= 1.0)) {
    throw OptionError(options::named("pocket_buriedness") + " must lie in [0, 1]");
  }
  if (!positive(options.buried_distance) || !positive(options.cluster_distance)) {
    throw OptionError("pocket detection: the buried and cluster distances must be finite and > 0");
  }
  if (options.min_spheres < 1)
    throw OptionError(options::named("pocket_min_spheres") + " must be at least 1");
}

/// Unit vectors spread evenly over the sphere (a Fibonacci lattice).
std::array<Eigen::Vector3d, direction_count> ray_directions() {
  std::array<Eigen::Vector3d, direction_count> directions;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < direction_count; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / direction_count;
    const double r = std::sqrt(1.0 - z * z);
    directions[static_cast<std::size_t>(k)] =
        Eigen::Vector3d(r * std::cos(golden * k), r * std::sin(golden * k), z);
  }
  return directions;
}

/// The empty spheres of the Delaunay cells of `positions` with a radius in the options' bounds;
/// `atom_of` maps a position to its structure atom.
std::vector<AlphaSphere> alpha_spheres(const Eigen::Matrix3Xd& positions,
                                       const std::vector<std::size_t>& atom_of,
                                       const PocketOptions& options) {
  std::vector<std::pair<Kernel::Point_3, std::size_t>> points;
  points.reserve(atom_of.size());
  for (std::size_t i = 0; i < atom_of.size(); ++i) {
    points.emplace_back(Kernel::Point_3(positions(0, i), positions(1, i), positions(2, i)), i);
  }
  const Delaunay triangulation(points.begin(), points.end());
  std::vector<AlphaSphere> spheres;
  for (auto cell = triangulation.finite_cells_begin(); cell != triangulation.finite_cells_end();
       ++cell) {
    const Kernel::Point_3 c =
        CGAL::circumcenter(cell->vertex(0)->point(), cell->vertex(1)->point(),
                           cell->vertex(2)->point(), cell->vertex(3)->point());
    AlphaSphere sphere;
    sphere.center = Eigen::Vector3d(c.x(), c.y(), c.z());
    sphere.radius = std::sqrt(CGAL::squared_distance(c, cell->vertex(0)->point()));
    if (!(sphere.radius >= options.min_sphere_radius && sphere.radius <= options.max_sphere_radius))
      continue;
    for (int v = 0; v < 4; ++v) {
      sphere.atoms[static_cast<std::size_t>(v)] = atom_of[cell->vertex(v)->info()];
    }
    std::sort(sphere.atoms.begin(), sphere.atoms.end());
    spheres.push_back(sphere);
  }
  // The triangulation's cell order follows its construction; the atoms make the order unique.
  std::sort(spheres.begin(), spheres.end(),
            [](const AlphaSphere& a, const AlphaSphere& b) { return a.atoms < b.atoms; });
  return spheres;
}

/// The fraction of ray_directions from `center` that pass within ray_blocking_radius of an atom
/// no farther than `reach`.
double buriedness(const Eigen::Vector3d& center, const Eigen::Matrix3Xd& positions,
                  const mesh::SpatialGrid& grid, double reach,
                  const std::array<Eigen::Vector3d, direction_count>& directions) {
  std::array<bool, direction_count> blocked{};
  grid.for_each_near(center, reach, [&](std::size_t i) {
    const Eigen::Vector3d to_atom = positions.col(static_cast<Eigen::Index>(i)) - center;
    const double distance2 = to_atom.squaredNorm();
    if (distance2 > reach * reach) return;
    for (std::size_t k = 0; k < directions.size(); ++k) {
      if (blocked[k]) continue;
      const double along = to_atom.dot(directions[k]);
      if (along > 0.0 && distance2 - along * along < ray_blocking_radius * ray_blocking_radius) {
        blocked[k] = true;
      }
    }
  });
  return static_cast<double>(std::count(blocked.begin(), blocked.end(), true)) / direction_count;
}

/// The clusters of `spheres` by single linkage of centres within `distance`, each ascending.
std::vector<std::vector<std::size_t>> single_linkage(const std::vector<AlphaSphere>& spheres,
                                                     double distance) {
  std::vector<std::size_t> parent(spheres.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  const auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  Eigen::Matrix3Xd centers(3, static_cast<Eigen::Index>(spheres.size()));
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    centers.col(static_cast<Eigen::Index>(i)) = spheres[i].center;
  }
  const mesh::SpatialGrid grid(centers, distance);
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    grid.for_each_near(spheres[i].center, distance, [&](std::size_t j) {
      if (j <= i || (spheres[j].center - spheres[i].center).norm() > distance) return;
      const std::size_t a = root(i);
      const std::size_t b = root(j);
      parent[std::max(a, b)] = std::min(a, b);
    });
  }
  std::map<std::size_t, std::vector<std::size_t>> clusters;
  for (std::size_t i = 0; i < spheres.size(); ++i) clusters[root(i)].push_back(i);
  std::vector<std::vector<std::size_t>> out;
  out.reserve(clusters.size());
  for (auto& entry : clusters) out.push_back(std::move(entry.second));
  return out;
}

/// The volume of the union of `spheres` shrunk by atom_reach, counted on a grid, A^3.
double shrunk_union_volume(const std::vector<SiteSphere>& spheres) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY);
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-INFINITY);
  for (const SiteSphere& s : spheres) {
    lo = lo.cwiseMin(s.center - Eigen::Vector3d::Constant(s.radius));
    hi = hi.cwiseMax(s.center + Eigen::Vector3d::Constant(s.radius));
  }
  const Eigen::Vector3i cells = ((hi - lo) / volume_spacing).array().ceil().cast<int>();
  std::size_t inside = 0;
  for (int i = 0; i < cells.x(); ++i) {
    for (int j = 0; j < cells.y(); ++j) {
      for (int k = 0; k < cells.z(); ++k) {
        const Eigen::Vector3d p =
            lo + volume_spacing * (Eigen::Vector3d(i, j, k).array() + 0.5).matrix();
        const bool in = std::any_of(spheres.begin(), spheres.end(), [&](const SiteSphere& s) {
          const double r = s.radius - atom_reach;
          return r > 0.0 && (p - s.center).squaredNorm() < r * r;
        });
        if (in) ++inside;
      }
    }
  }
  return static_cast<double>(inside) * volume_spacing * volume_spacing * volume_spacing;
}

/// The spheres of `part` (indices into `spheres`) as site spheres.
std::vector<SiteSphere> site_spheres(const std::vector<AlphaSphere>& spheres,
                                     const std::vector<std::size_t>& part) {
  std::vector<SiteSphere> out;
  out.reserve(part.size());
  for (std::size_t s : part) out.push_back({spheres[s].center, spheres[s].radius});
  return out;
}

/// `part` in two by two-means on its sphere centres, seeded by the sphere farthest from the
/// centroid and the sphere farthest from that one (ties: the lower index); deterministic.
std::pair<std::vector<std::size_t>, std::vector<std::size_t>> two_means(
    const std::vector<AlphaSphere>& spheres, const std::vector<std::size_t>& part) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t s : part) centroid += spheres[s].center;
  centroid /= static_cast<double>(part.size());
  const auto farthest = [&](const Eigen::Vector3d& from) {
    std::size_t best = part.front();
    for (std::size_t s : part) {
      if ((spheres[s].center - from).squaredNorm() > (spheres[best].center - from).squaredNorm())
        best = s;
    }
    return spheres[best].center;
  };
  Eigen::Vector3d a = farthest(centroid);
  Eigen::Vector3d b = farthest(a);
  std::vector<std::size_t> first, second;
  constexpr int rounds = 50;
  for (int round = 0; round < rounds; ++round) {
    std::vector<std::size_t> near_a, near_b;
    for (std::size_t s : part) {
      const bool to_a =
          (spheres[s].center - a).squaredNorm() <= (spheres[s].center - b).squaredNorm();
      (to_a ? near_a : near_b).push_back(s);
    }
    if (near_a == first && near_b == second) break;
    first = std::move(near_a);
    second = std::move(near_b);
    if (first.empty() || second.empty()) break;
    a.setZero();
    b.setZero();
    for (std::size_t s : first) a += spheres[s].center;
    for (std::size_t s : second) b += spheres[s].center;
    a /= static_cast<double>(first.size());
    b /= static_cast<double>(second.size());
  }
  return {first, second};
}

/// Reorders pockets sorted by score so that each cavity's best part comes first, cavities by
/// number (their summed score), then each cavity's second part, and so on: a split keeps the
/// cavities' order at the top of the list, where the parts' own scores would put the parts of
/// one large cavity first.
void interleave_cavities(std::vector<Pocket>& pockets) {
  std::stable_sort(pockets.begin(), pockets.end(),
                   [](const Pocket& a, const Pocket& b) { return a.cavity < b.cavity; });
  std::vector<int> part(pockets.size(), 0);  // its place among its cavity's parts, by score
  for (std::size_t k = 1; k < pockets.size(); ++k) {
    if (pockets[k - 1].cavity == pockets[k].cavity) part[k] = part[k - 1] + 1;
  }
  std::vector<std::size_t> order(pockets.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return part[x] != part[y] ? part[x] < part[y] : pockets[x].cavity < pockets[y].cavity;
  });
  std::vector<Pocket> sorted;
  sorted.reserve(pockets.size());
  for (std::size_t k : order) sorted.push_back(std::move(pockets[k]));
  pockets = std::move(sorted);
}

/// The sub-pockets of a cavity (PocketOptions::max_volume): `cavity` itself when it holds at
/// most max_volume (or max_volume is 0), else the sub-pockets of each side of its two-means
/// split, unless a side would hold fewer than min_spheres spheres.
std::vector<std::vector<std::size_t>> sub_pockets(const std::vector<AlphaSphere>& spheres,
                                                  const std::vector<std::size_t>& cavity,
                                                  const PocketOptions& options) {
  if (options.max_volume <= 0.0 ||
      shrunk_union_volume(site_spheres(spheres, cavity)) <= options.max_volume) {
    return {cavity};
  }
  const auto [first, second] = two_means(spheres, cavity);
  const auto fewest = static_cast<std::size_t>(options.min_spheres);
  if (first.size() < fewest || second.size() < fewest) return {cavity};
  std::vector<std::vector<std::size_t>> parts = sub_pockets(spheres, first, options);
  for (auto& part : sub_pockets(spheres, second, options)) parts.push_back(std::move(part));
  return parts;
}

std::string residue_label(const Atom& atom) {
  std::string label = atom.residue_name + std::to_string(atom.residue_number);
  if (!atom.chain.empty() && atom.chain != " ") label += ":" + atom.chain;
  return label;
}

bool is_hydrogen(const Atom& atom) { return atom.element == "H" || atom.element == "D"; }

/// An atom pockets are found on: an ATOM record other than water.
bool is_pocket_atom(const Atom& atom) {
  return !atom.hetero && !is_water_residue(atom.residue_name);
}

[[noreturn]] void refuse_without_protein(const Molecule& structure) {
  throw InputError(structure.source +
                   ": no protein atom (ATOM record) to find pockets on; the structure holds "
                   "only HETATM records or water");
}

}  // namespace

const options::Table<PocketOptions>& pocket_option_table() {
  using options::Kind;
  using P = PocketOptions;
  static const options::Table<P> table = {
      options::field<P>(
          {"pocket-min-radius", Kind::real,
           "pockets: smallest alpha sphere kept (centre to its four atoms' centres)", "A", 0.0,
           20.0, true},
          [](auto& p) -> auto& { return p.min_sphere_radius; }),
      options::field<P>(
          {"pocket-max-radius", Kind::real,
           "pockets: largest alpha sphere kept (larger ones lie over open surface)", "A", 0.0, 50.0,
           true},
          [](auto& p) -> auto& { return p.max_sphere_radius; }),
      options::field<P>(
          {"pocket-buriedness", Kind::real,
           "pockets: fewest of 30 rays from an alpha sphere's centre that must meet "
           "an atom within 10 A, as a fraction",
           "", 0.0, 1.0},
          [](auto& p) -> auto& { return p.min_buriedness; }),
      options::field<P>(
          {"pocket-min-spheres", Kind::integer, "pockets: fewest alpha spheres a pocket holds", "",
           1, 1e6},
          [](auto& p) -> auto& { return p.min_spheres; }),
      options::field<P>(
          {"pocket-max-volume", Kind::real,
           "pockets: split a cavity larger than this into sub-pockets of at most this volume "
           "(0: no split)",
           "A^3", 0.0, 1e6},
          [](auto& p) -> auto& { return p.max_volume; }),
  };
  return table;
}

options::Spec site_pocket_spec() {
  return {"site-pocket",
          options::Kind::integer,
          "binding site: the structure's pocket N (as `surfcomp pockets` ranks them), found "
          "without a ligand",
          "",
          1,
          1e6,
          false,
          {},
          true};
}

Molecule pocket_structure(const Molecule& structure) {
  Molecule protein;
  protein.source = structure.source;
  protein.title = structure.title;
  protein.charge_source = structure.charge_source;
  protein.lipophilicity_assigned = structure.lipophilicity_assigned;
  for (const Atom& atom : structure.atoms) {
    if (is_pocket_atom(atom)) protein.atoms.push_back(atom);
  }
  if (protein.atoms.empty()) refuse_without_protein(structure);
  return protein;
}

std::vector<Pocket> detect_pockets(const Molecule& structure, const PocketOptions& options) {
  check_options(options);
  // Indices into `structure` of the protein's heavy atoms, in order.
  std::vector<std::size_t> atom_of;
  bool protein = false;
  for (std::size_t i = 0; i < structure.atoms.size(); ++i) {
    const Atom& atom = structure.atoms[i];
    if (!is_pocket_atom(atom)) continue;
    protein = true;
    if (!is_hydrogen(atom)) atom_of.push_back(i);
  }
  if (!protein) refuse_without_protein(structure);
  if (atom_of.size() < 4) return {};
  Eigen::Matrix3Xd positions(3, static_cast<Eigen::Index>(atom_of.size()));
  for (std::size_t i = 0; i < atom_of.size(); ++i) {
    positions.col(static_cast<Eigen::Index>(i)) = structure.atoms[atom_of[i]].position;
  }
  std::vector<AlphaSphere> spheres = alpha_spheres(positions, atom_of, options);

  const mesh::SpatialGrid grid(positions, 4.0);
  const auto directions = ray_directions();
  std::vector<AlphaSphere> buried;
  for (AlphaSphere& sphere : spheres) {
    sphere.buriedness =
        buriedness(sphere.center, positions, grid, options.buried_distance, directions);
    if (sphere.buriedness >= options.min_buriedness) buried.push_back(sphere);
  }

  std::vector<Pocket> pockets;
  std::vector<double> cavity_score;  // by cavity, in cluster order
  for (const std::vector<std::size_t>& cavity : single_linkage(buried, options.cluster_distance)) {
    if (cavity.size() < static_cast<std::size_t>(options.min_spheres)) continue;
    cavity_score.push_back(0.0);
    for (const std::vector<std::size_t>& cluster : sub_pockets(buried, cavity, options)) {
      Pocket pocket;
      pocket.cavity = static_cast<int>(cavity_score.size());
      std::set<std::size_t> lining;
      for (std::size_t s : cluster) {
        const AlphaSphere& sphere = buried[s];
        pocket.spheres.push_back({sphere.center, sphere.radius});
        pocket.score += sphere.buriedness;
        pocket.center += sphere.center;
        lining.insert(sphere.atoms.begin(), sphere.atoms.end());
      }
      pocket.center /= static_cast<double>(cluster.size());
      pocket.buriedness = pocket.score / static_cast<double>(cluster.size());
      pocket.volume = shrunk_union_volume(pocket.spheres);
      pocket.lining_atoms.assign(lining.begin(), lining.end());
      std::set<std::string> seen;
      for (std::size_t atom : pocket.lining_atoms) {
        std::string label = residue_label(structure.atoms[atom]);
        if (seen.insert(label).second) pocket.lining_residues.push_back(std::move(label));
      }
      cavity_score.back() += pocket.score;
      pockets.push_back(std::move(pocket));
    }
  }
  // Cavities numbered by decreasing summed score (ties: cluster order).
  std::vector<int> by_score(cavity_score.size());
  for (std::size_t k = 0; k < by_score.size(); ++k) by_score[k] = static_cast<int>(k);
  std::stable_sort(by_score.begin(), by_score.end(),
                   [&](int x, int y) { return cavity_score[x] > cavity_score[y]; });
  std::vector<int> number(cavity_score.size());
  for (std::size_t k = 0; k < by_score.size(); ++k) number[by_score[k]] = static_cast<int>(k + 1);
  for (Pocket& pocket : pockets) pocket.cavity = number[pocket.cavity - 1];
  std::sort(pockets.begin(), pockets.end(), [](const Pocket& a, const Pocket& b) {
    if (a.score != b.score) return a.score > b.score;
    return std::make_tuple(a.center.x(), a.center.y(), a.center.z()) <
           std::make_tuple(b.center.x(), b.center.y(), b.center.z());
  });
  if (options.max_volume > 0.0) interleave_cavities(pockets);
  for (std::size_t k = 0; k < pockets.size(); ++k) pockets[k].rank = static_cast<int>(k + 1);
  return pockets;
}

BindingSite pocket_site(const Molecule& structure, int rank, const PocketOptions& pocket_options,
                        const BindingSiteOptions& options) {
  std::vector<Pocket> pockets = detect_pockets(structure, pocket_options);
  if (rank < 1 || static_cast<std::size_t>(rank) > pockets.size()) {
    throw InputError(structure.source + ": has " + std::to_string(pockets.size()) +
                     (pockets.size() == 1 ? " pocket" : " pockets") + "; pocket " +
                     std::to_string(rank) + " was asked for");
  }
  return binding_site(pocket_structure(structure),
                      std::move(pockets[static_cast<std::size_t>(rank - 1)].spheres), options);
}

const options::Table<PocketSearchOptions>& pocket_search_option_table() {
  using P = PocketSearchOptions;
  static const options::Table<P> table = [] {
    options::Table<P> t;
    options::append(
        t, options::pick(molsurf::surface_input_option_table(), {"min-plddt", "max-atoms"}),
        [](auto& p) -> auto& { return p.input; });
    options::append(
        t, pocket_option_table(), [](auto& p) -> auto& { return p.pockets; });
    return t;
  }();
  return table;
}

StructurePockets find_pockets(const std::filesystem::path& structure,
                              const PocketSearchOptions& options) {
  if (!io::is_structure_file(structure)) {
    throw InputError(structure.string() + ": not a structure file (expected " +
                     io::molecule_extensions(io::MoleculeUse::structure) + ")");
  }
  StructurePockets found;
  io::MoleculeRecord record;  // the file read and converted once, its models counted
  record.source = structure;
  record.format = io::RecordFormat::structure;
  record.text = io::read_structure_text(structure, &found.models);
  const Molecule molecule = io::read_record_molecule(record, options.input.read);
  const auto max_atoms = static_cast<std::size_t>(options.input.surface.ses.max_atoms);
  if (molecule.atoms.size() > max_atoms) {
    throw InputError(structure.string() + ": " + std::to_string(molecule.atoms.size()) +
                     " atoms, more than the limit of " + std::to_string(max_atoms) + " (" +
                     options::named("max_atoms") + ")");
  }
  found.protein_atoms = pocket_structure(molecule).atoms.size();
  found.pockets = detect_pockets(molecule, options.pockets);
  return found;
}

}  // namespace surfcomp::molsurf
