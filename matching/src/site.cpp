#include "surfcomp/matching/site.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/protein_charges.hpp"
#include "surfcomp/matching/rigid_fit.hpp"
#include "surfcomp/mesh/spatial_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

namespace surfcomp::matching {
std::vector<bool> pocket_lining(const harmonic::SurfaceDescriptors& descriptors,
                                const std::vector<bool>* allowed, double radius) {
  const auto& cps = descriptors.critical_points;
  const Eigen::MatrixX3d positions = descriptors.surface.positions();
  std::vector<bool> inside(static_cast<std::size_t>(positions.rows()), false);
  for (std::size_t c = 0; c < cps.size(); ++c) {
    if ((allowed != nullptr && !(*allowed)[c]) || cps[c].status == harmonic::PatchStatus::skipped)
      continue;
    const Eigen::Vector3d centre = cps[c].point.position;
    for (Eigen::Index v = 0; v < positions.rows(); ++v) {
      if ((Eigen::Vector3d(positions.row(v)) - centre).squaredNorm() <= radius * radius)
        inside[static_cast<std::size_t>(v)] = true;
    }
  }
  return inside;
}

std::vector<bool> critical_points_in_site(const harmonic::SurfaceDescriptors& descriptors,
                                          const std::vector<molsurf::SiteSphere>& spheres) {
  std::vector<bool> flags(descriptors.critical_points.size(), false);
  for (std::size_t i = 0; i < flags.size(); ++i)
    flags[i] = molsurf::in_site(descriptors.critical_points[i].point.position, spheres);
  return flags;
}

harmonic::SurfaceDescriptors describe_site(mesh::Surface surface,
                                           const std::vector<molsurf::SiteSphere>& spheres,
                                           const harmonic::DescriptorOptions& options) {
  return harmonic::describe_surface(std::move(surface), options,
                                    [&spheres](const mesh::CriticalPoint& point) {
                                      return molsurf::in_site(point.position, spheres);
                                    });
}

harmonic::SurfaceDescriptors describe_site(mesh::Surface surface, const Molecule& molecule,
                                           const std::vector<molsurf::SiteSphere>& spheres,
                                           const harmonic::DescriptorOptions& options) {
  return harmonic::describe_surface(std::move(surface), molecule, options,
                                    [&spheres](const mesh::CriticalPoint& point) {
                                      return molsurf::in_site(point.position, spheres);
                                    });
}

namespace {

/// The lining class of a standard amino acid (the order of LiningComposition), or none.
std::optional<std::size_t> lining_class(const std::string& residue) {
  static const std::map<std::string, std::size_t> classes = {
      {"ALA", 0}, {"VAL", 0}, {"LEU", 0}, {"ILE", 0}, {"MET", 0}, {"PHE", 1}, {"TRP", 1},
      {"TYR", 1}, {"HIS", 2}, {"LYS", 3}, {"ARG", 3}, {"ASP", 4}, {"GLU", 4}, {"SER", 5},
      {"THR", 5}, {"ASN", 5}, {"GLN", 5}, {"GLY", 6}, {"PRO", 7}, {"CYS", 8}};
  const auto found = classes.find(residue_key(residue));
  if (found == classes.end()) return std::nullopt;
  return found->second;
}

}  // namespace

std::optional<LiningComposition> lining_composition(const Molecule& structure,
                                                    const std::vector<molsurf::SiteSphere>& spheres,
                                                    double reach) {
  std::map<std::tuple<std::string, int, std::string>, std::size_t> lining;
  for (const Atom& atom : structure.atoms) {
    if (atom.element == "H") continue;
    const std::optional<std::size_t> kind = lining_class(atom.residue_name);
    if (!kind) continue;
    const bool near =
        std::any_of(spheres.begin(), spheres.end(), [&](const molsurf::SiteSphere& sphere) {
          return (atom.position - sphere.center).norm() < sphere.radius + reach;
        });
    if (near)
      lining.emplace(std::make_tuple(atom.chain, atom.residue_number, atom.residue_name), *kind);
  }
  if (lining.empty()) return std::nullopt;
  LiningComposition composition{};
  for (const auto& [residue, kind] : lining) composition[kind] += 1.0;
  for (double& fraction : composition) fraction /= static_cast<double>(lining.size());
  return composition;
}

namespace {

/// The histogram intersection of two compositions: the sum over the classes of the smaller
/// fraction.
template <std::size_t N>
double shared_fraction(const std::array<double, N>& a, const std::array<double, N>& b) {
  double shared = 0.0;
  for (std::size_t k = 0; k < N; ++k) shared += std::min(a[k], b[k]);
  return shared;
}

}  // namespace

double lining_similarity(const LiningComposition& a, const LiningComposition& b) {
  return shared_fraction(a, b);
}

double site_score(double overlay_score, double lining, double weight) {
  return (overlay_score + weight * lining) / (1.0 + weight);
}

double site_z_score(double score, std::size_t points_a, std::size_t points_b,
                    const SiteScoreNull& null) {
  if (points_a == 0 || points_b == 0) throw InputError("site z-score: a site has no surface point");
  const auto spread_at = [&](double n) {
    return null.spread_intercept + null.spread_slope * std::log10(n);
  };
  if (!(null.min_points >= 1.0 && null.min_points <= null.max_points) ||
      !(spread_at(null.min_points) > 0.0 && spread_at(null.max_points) > 0.0)) {
    throw InputError(
        "site z-score: the null needs 1 <= min_points <= max_points and a positive "
        "spread over that range");
  }
  const double n = std::clamp(static_cast<double>(std::min(points_a, points_b)), null.min_points,
                              null.max_points);
  return (score - null.mean_intercept - null.mean_slope * std::log10(n)) / spread_at(n);
}

namespace {

/// A contact's interaction: one class, or half donor and half acceptor.
enum class Contact { donor, acceptor, aromatic, positive, negative, hydrophobic, polar };

static_assert(static_cast<std::size_t>(Contact::hydrophobic) ==
                  static_cast<std::size_t>(Interaction::hydrophobic),
              "Contact's first six classes are Interaction's, in its order");

/// The amino-acid atoms whose interaction their name decides (residue and atom name).
const std::map<std::pair<std::string, std::string>, Contact>& named_contacts() {
  static const std::map<std::pair<std::string, std::string>, Contact> table = {
      {{"PRO", "N"}, Contact::hydrophobic}, {{"ASP", "OD1"}, Contact::negative},
      {{"ASP", "OD2"}, Contact::negative},  {{"GLU", "OE1"}, Contact::negative},
      {{"GLU", "OE2"}, Contact::negative},  {{"LYS", "NZ"}, Contact::positive},
      {{"ARG", "NE"}, Contact::positive},   {{"ARG", "NH1"}, Contact::positive},
      {{"ARG", "NH2"}, Contact::positive},  {{"HIS", "ND1"}, Contact::polar},
      {{"HIS", "NE2"}, Contact::polar},     {{"SER", "OG"}, Contact::polar},
      {{"THR", "OG1"}, Contact::polar},     {{"TYR", "OH"}, Contact::polar},
      {{"ASN", "ND2"}, Contact::donor},     {{"GLN", "NE2"}, Contact::donor},
      {{"TRP", "NE1"}, Contact::donor},     {{"ASN", "OD1"}, Contact::acceptor},
      {{"GLN", "OE1"}, Contact::acceptor}};
  return table;
}

/// The interaction of an atom by its element alone.
Contact element_contact(const std::string& element) {
  if (element == "N") return Contact::polar;
  if (element == "O") return Contact::acceptor;
  if (element == "P") return Contact::negative;  // a phosphate
  static const std::set<std::string> apolar = {"C", "S", "Se", "F", "Cl", "Br", "I"};
  return apolar.count(element) != 0 ? Contact::hydrophobic : Contact::positive;  // metal ions
}

Contact contact_of(const Atom& atom) {
  if (is_water_residue(atom.residue_name)) return Contact::polar;
  const std::string residue = residue_key(atom.residue_name);
  if (!lining_class(residue)) return element_contact(atom.element);
  const auto& table = named_contacts();
  if (const auto found = table.find({residue, atom.name}); found != table.end()) {
    return found->second;
  }
  if (atom.name == "N") return Contact::donor;       // the backbone's
  if (atom.name == "O") return Contact::acceptor;    // the backbone's
  if (atom.name == "OXT") return Contact::negative;  // the C terminus
  const bool ring = residue == "PHE" || residue == "TYR" || residue == "TRP" || residue == "HIS";
  if (ring && atom.element == "C" && atom.name != "CA" && atom.name != "C" && atom.name != "CB") {
    return Contact::aromatic;
  }
  return element_contact(atom.element);
}

}  // namespace

InteractionComposition interaction_of(const Atom& atom) {
  InteractionComposition weights{};
  if (atom.element == "H") return weights;
  const Contact contact = contact_of(atom);
  if (contact == Contact::polar) {
    weights[static_cast<std::size_t>(Interaction::donor)] = 0.5;
    weights[static_cast<std::size_t>(Interaction::acceptor)] = 0.5;
  } else {
    weights[static_cast<std::size_t>(contact)] = 1.0;  // Contact's first six are Interaction's
  }
  return weights;
}

std::vector<InteractionPoint> interaction_points(const mesh::Surface& surface,
                                                 const Molecule& structure,
                                                 const std::vector<molsurf::SiteSphere>& spheres) {
  // A site vertex lies within a sphere; its nearest atom lies within the sphere's radius plus a
  // contact reach of its centre (a vertex is at most a probe diameter from an atom surface).
  constexpr double contact_reach = 6.0;  // A
  std::vector<const Atom*> near;
  for (const Atom& atom : structure.atoms) {
    if (atom.element == "H") continue;
    const bool close =
        std::any_of(spheres.begin(), spheres.end(), [&](const molsurf::SiteSphere& s) {
          return (atom.position - s.center).norm() <= s.radius + contact_reach;
        });
    if (close) near.push_back(&atom);
  }
  std::vector<InteractionPoint> points;
  if (near.empty()) return points;
  const Eigen::MatrixX3d positions = surface.positions();
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const Eigen::Vector3d x = positions.row(v).transpose();
    if (!molsurf::in_site(x, spheres)) continue;
    const Atom* nearest = nullptr;
    double best = std::numeric_limits<double>::infinity();
    for (const Atom* atom : near) {
      const double d = (atom->position - x).squaredNorm();
      if (d < best) {
        best = d;
        nearest = atom;
      }
    }
    points.push_back({x, interaction_of(*nearest)});
  }
  return points;
}

std::optional<InteractionComposition> interaction_composition(
    const std::vector<InteractionPoint>& points) {
  if (points.empty()) return std::nullopt;
  InteractionComposition composition{};
  for (const InteractionPoint& point : points) {
    for (std::size_t k = 0; k < interaction_classes; ++k) composition[k] += point.weights[k];
  }
  for (double& fraction : composition) fraction /= static_cast<double>(points.size());
  return composition;
}

double interaction_similarity(const InteractionComposition& a, const InteractionComposition& b) {
  return shared_fraction(a, b);
}

namespace {

/// The summed agreement of `from`'s points (moved by `move`) with their nearest point of `to`
/// within `contact` (to_grid: a SpatialGrid of to's positions).
double agreement(const std::vector<InteractionPoint>& from, const Eigen::Matrix4d& move,
                 const std::vector<InteractionPoint>& to, const mesh::SpatialGrid& to_grid,
                 double contact) {
  double total = 0.0;
  const double contact_squared = contact * contact;
  for (const InteractionPoint& point : from) {
    const Eigen::Vector3d x =
        move.topLeftCorner<3, 3>() * point.position + move.topRightCorner<3, 1>();
    std::ptrdiff_t nearest = -1;
    double best = contact_squared;
    to_grid.for_each_near(x, contact, [&](int i) {
      const double d = (to[static_cast<std::size_t>(i)].position - x).squaredNorm();
      if (d <= best) {
        best = d;
        nearest = i;
      }
    });
    if (nearest < 0) continue;
    const InteractionComposition& other = to[static_cast<std::size_t>(nearest)].weights;
    for (std::size_t k = 0; k < interaction_classes; ++k) {
      total += std::min(point.weights[k], other[k]);
    }
  }
  return total;
}

mesh::SpatialGrid grid_of(const std::vector<InteractionPoint>& points, double contact) {
  Eigen::Matrix3Xd positions(3, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    positions.col(static_cast<Eigen::Index>(i)) = points[i].position;
  }
  return mesh::SpatialGrid(positions, contact);
}

}  // namespace

AlignedInteractions aligned_interactions(const std::vector<InteractionPoint>& a,
                                         const std::vector<InteractionPoint>& b,
                                         const Eigen::Matrix4d& b_to_a, double contact) {
  if (!(contact > 0.0) || !std::isfinite(contact)) {
    throw OptionError("aligned_interactions: contact = " + std::to_string(contact) +
                      " A, expected a finite number > 0");
  }
  AlignedInteractions result;
  if (a.empty() || b.empty()) return result;
  const Eigen::Matrix4d a_to_b = RigidTransform::from_matrix(b_to_a).inverse().matrix();
  const double of_a = agreement(a, a_to_b, b, grid_of(b, contact), contact);
  const double of_b = agreement(b, b_to_a, a, grid_of(a, contact), contact);
  result.similarity = (of_a + of_b) / static_cast<double>(a.size() + b.size());
  result.coverage = a.size() <= b.size() ? of_a / static_cast<double>(a.size())
                                         : of_b / static_cast<double>(b.size());
  return result;
}

}  // namespace surfcomp::matching
