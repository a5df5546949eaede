#include "surfcomp/matching/site.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/protein_charges.hpp"
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
namespace {

bool inside(const Eigen::Vector3d& position, const std::vector<SiteSphere>& spheres) {
  return std::any_of(spheres.begin(), spheres.end(),
                     [&](const SiteSphere& s) { return (position - s.center).norm() <= s.radius; });
}

void check_options(const BindingSiteOptions& options) {
  if (!(options.sphere_radius > 0.0) || !std::isfinite(options.sphere_radius)) {
    throw OptionError("binding site: sphere_radius = " + std::to_string(options.sphere_radius) +
                      " A, expected a finite number > 0");
  }
  if (!(options.chain_contact_radius >= 0.0) || !std::isfinite(options.chain_contact_radius)) {
    throw OptionError(
        "binding site: chain_contact_radius = " + std::to_string(options.chain_contact_radius) +
        " A, expected a finite number >= 0");
  }
  if (!(options.surface_margin >= 0.0) || !std::isfinite(options.surface_margin)) {
    throw OptionError("binding site: surface_margin = " + std::to_string(options.surface_margin) +
                      " A, expected a finite number >= 0");
  }
}

/// `structure` without water, without the atoms flagged in `removed` and, with
/// chain_contact_radius > 0, without the chains that have no atom (water left out) within it
/// of a sphere's centre.
Molecule site_structure(const Molecule& structure, const std::vector<bool>& removed,
                        const std::vector<SiteSphere>& spheres, const BindingSiteOptions& options) {
  const auto kept = [&](std::size_t i) {
    return !removed[i] && !is_water_residue(structure.atoms[i].residue_name);
  };
  std::set<std::string> chains;
  if (options.chain_contact_radius > 0.0) {
    for (std::size_t i = 0; i < structure.atoms.size(); ++i) {
      const Atom& atom = structure.atoms[i];
      if (is_water_residue(atom.residue_name) || chains.count(atom.chain)) continue;
      for (const SiteSphere& s : spheres) {
        if ((atom.position - s.center).norm() <= options.chain_contact_radius) {
          chains.insert(atom.chain);
          break;
        }
      }
    }
  }
  Molecule out = structure;
  out.atoms.clear();
  for (std::size_t i = 0; i < structure.atoms.size(); ++i) {
    if (kept(i) && (options.chain_contact_radius == 0.0 || chains.count(structure.atoms[i].chain)))
      out.atoms.push_back(structure.atoms[i]);
  }
  if (out.atoms.empty()) {
    throw InputError(structure.source +
                     ": the binding site's structure has no atoms besides water and the ligand");
  }
  return out;
}

}  // namespace

BindingSite binding_site(const Molecule& structure, const LigandSelector& ligand,
                         const BindingSiteOptions& options) {
  check_options(options);
  BindingSite site;
  site.ligand = structure;
  site.ligand.atoms.clear();
  std::vector<bool> removed(structure.atoms.size(), false);
  for (std::size_t i : select_ligand(structure, ligand)) {
    const Atom& atom = structure.atoms[i];
    site.ligand.atoms.push_back(atom);
    site.spheres.push_back({atom.position, options.sphere_radius});
    removed[i] = true;
  }
  site.structure = site_structure(structure, removed, site.spheres, options);
  site.surface_margin = options.surface_margin;
  return site;
}

BindingSite binding_site(const Molecule& structure, std::vector<SiteSphere> spheres,
                         const BindingSiteOptions& options) {
  check_options(options);
  if (spheres.empty()) throw InputError(structure.source + ": a binding site needs a sphere");
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    const SiteSphere& s = spheres[k];
    if (!s.center.allFinite() || !(s.radius > 0.0) || !std::isfinite(s.radius)) {
      throw InputError(structure.source + ": site sphere " + std::to_string(k + 1) +
                       " has radius " + std::to_string(s.radius) +
                       " A; expected a finite centre and a finite radius > 0");
    }
  }
  BindingSite site;
  site.ligand.source = structure.source;
  site.ligand.title = structure.title;
  site.spheres = std::move(spheres);
  site.structure = site_structure(structure, std::vector<bool>(structure.atoms.size(), false),
                                  site.spheres, options);
  site.surface_margin = options.surface_margin;
  return site;
}

double site_surface_margin(double margin, double patch_radius) {
  return margin == 0.0 ? 0.0 : std::max(margin, patch_radius + surface_margin_beyond_patch);
}

mesh::Surface build_site_surface(const BindingSite& site,
                                 const mesh::MolecularSurfaceOptions& options) {
  const Molecule& structure = site.structure;
  validate_molecule(structure);
  const auto [centers, radii] = mesh::atom_balls(structure);
  const auto n = static_cast<Eigen::Index>(structure.atoms.size());
  mesh::SesOptions ses = options.ses;
  ses.voxel_size = mesh::ses_voxel_size(centers, radii, ses);
  std::vector<Eigen::Index> near;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d position = centers.row(i).transpose();
    const bool kept =
        site.surface_margin == 0.0 ||
        std::any_of(site.spheres.begin(), site.spheres.end(), [&](const SiteSphere& s) {
          return (position - s.center).norm() <= s.radius + site.surface_margin;
        });
    if (kept) near.push_back(i);
  }
  if (near.empty()) {
    std::ostringstream message;
    message << structure.source << ": no atom lies within " << site.surface_margin
            << " A (the site's surface margin) of the site's spheres";
    throw InputError(message.str());
  }
  mesh::Surface surface = mesh::spatially_ordered(
      mesh::build_ses(centers(near, Eigen::all), radii(near), ses, structure.source));
  surface.set_source(structure.source);
  mesh::require_closed_manifold(surface);
  mesh::assign_surface_properties(surface, &structure, options);
  return surface;
}

Molecule site_neighbourhood(const Molecule& structure, const std::vector<SiteSphere>& spheres,
                            double reach) {
  if (!std::isfinite(reach) || reach < 0.0)
    throw InputError("site neighbourhood: the reach must be a finite number >= 0 A");
  Molecule kept = structure;
  kept.atoms.clear();
  kept.ionisable_atoms.clear();
  // The smallest atom sets the SES grid (mesh::ses_voxel_size): it stays, wherever it is.
  const auto smallest =
      std::min_element(structure.atoms.begin(), structure.atoms.end(),
                       [](const Atom& x, const Atom& y) { return x.radius < y.radius; });
  // A chain's first residue as assign_protein_formal_charges finds it: its first atom of a
  // standard residue.
  std::set<std::string> chains;
  std::optional<std::tuple<std::string, int, std::string>> first_residue;
  std::vector<std::size_t> new_index(structure.atoms.size(), structure.atoms.size());
  for (std::size_t i = 0; i < structure.atoms.size(); ++i) {
    const Atom& atom = structure.atoms[i];
    const auto residue = std::make_tuple(atom.chain, atom.residue_number, atom.residue_name);
    if (protein_atom_formal_charge(atom.residue_name, atom.name) &&
        chains.insert(atom.chain).second)
      first_residue = residue;
    const bool near = std::any_of(spheres.begin(), spheres.end(), [&](const SiteSphere& s) {
      return (atom.position - s.center).norm() <= s.radius + reach;
    });
    const bool starts_chain = first_residue && residue == *first_residue;
    if (near || atom.charge != 0.0 || starts_chain || &atom == &*smallest) {
      new_index[i] = kept.atoms.size();
      kept.atoms.push_back(atom);
    }
  }
  for (const std::size_t i : structure.ionisable_atoms) {
    if (i < new_index.size() && new_index[i] < kept.atoms.size())
      kept.ionisable_atoms.push_back(new_index[i]);
  }
  return kept;
}

std::optional<SiteSphere> parse_site_sphere(const std::string& text) {
  const std::optional<options::Sphere> sphere = options::parse_sphere(text);
  if (!sphere) return std::nullopt;
  return site_spheres({*sphere}).front();
}

std::vector<options::Sphere> sphere_values(const std::vector<SiteSphere>& spheres) {
  std::vector<options::Sphere> values;
  values.reserve(spheres.size());
  for (const SiteSphere& s : spheres)
    values.push_back({s.center.x(), s.center.y(), s.center.z(), s.radius});
  return values;
}

std::vector<SiteSphere> site_spheres(const std::vector<options::Sphere>& values) {
  std::vector<SiteSphere> spheres;
  spheres.reserve(values.size());
  for (const options::Sphere& v : values)
    spheres.push_back({Eigen::Vector3d(v[0], v[1], v[2]), v[3]});
  return spheres;
}

options::Spec site_ligand_spec() {
  return {"site-ligand",
          options::Kind::text,
          "a binding site: the site of one copy of this ligand residue (match: on both inputs)",
          "",
          0,
          0,
          false,
          {},
          true};
}

options::Spec site_sphere_spec() {
  return {"site-sphere", options::Kind::spheres,
          "a binding site sphere x,y,z,r (repeatable; match: on both inputs)", "A"};
}

const options::Table<BindingSiteOptions>& binding_site_option_table() {
  using options::Kind;
  using B = BindingSiteOptions;
  static const options::Table<B> table = {
      options::field<B>(
          {"site-radius", Kind::real, "radius of the spheres around the site ligand's atoms", "A",
           0.1, 100.0},
          [](auto& b) -> auto& { return b.sphere_radius; }),
      options::field<B>(
          {"site-margin", Kind::real,
           "a site's surface is built from the atoms within a site sphere's radius "
           "plus this margin, at least the patch radius + 8 (0: from every atom); "
           "ESP and LP come from every atom",
           "A", 0.0, 1000.0},
          [](auto& b) -> auto& { return b.surface_margin; }),
  };
  return table;
}

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
                                          const std::vector<SiteSphere>& spheres) {
  std::vector<bool> flags(descriptors.critical_points.size(), false);
  for (std::size_t i = 0; i < flags.size(); ++i)
    flags[i] = inside(descriptors.critical_points[i].point.position, spheres);
  return flags;
}

harmonic::SurfaceDescriptors describe_site(mesh::Surface surface,
                                           const std::vector<SiteSphere>& spheres,
                                           const harmonic::DescriptorOptions& options) {
  return harmonic::describe_surface(
      std::move(surface), options,
      [&spheres](const mesh::CriticalPoint& point) { return inside(point.position, spheres); });
}

harmonic::SurfaceDescriptors describe_site(mesh::Surface surface, const Molecule& molecule,
                                           const std::vector<SiteSphere>& spheres,
                                           const harmonic::DescriptorOptions& options) {
  return harmonic::describe_surface(
      std::move(surface), molecule, options,
      [&spheres](const mesh::CriticalPoint& point) { return inside(point.position, spheres); });
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
                                                    const std::vector<SiteSphere>& spheres,
                                                    double reach) {
  std::map<std::tuple<std::string, int, std::string>, std::size_t> lining;
  for (const Atom& atom : structure.atoms) {
    if (atom.element == "H") continue;
    const std::optional<std::size_t> kind = lining_class(atom.residue_name);
    if (!kind) continue;
    const bool near = std::any_of(spheres.begin(), spheres.end(), [&](const SiteSphere& sphere) {
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
                                                 const std::vector<SiteSphere>& spheres) {
  // A site vertex lies within a sphere; its nearest atom lies within the sphere's radius plus a
  // contact reach of its centre (a vertex is at most a probe diameter from an atom surface).
  constexpr double contact_reach = 6.0;  // A
  std::vector<const Atom*> near;
  for (const Atom& atom : structure.atoms) {
    if (atom.element == "H") continue;
    const bool close = std::any_of(spheres.begin(), spheres.end(), [&](const SiteSphere& s) {
      return (atom.position - s.center).norm() <= s.radius + contact_reach;
    });
    if (close) near.push_back(&atom);
  }
  std::vector<InteractionPoint> points;
  if (near.empty()) return points;
  const Eigen::MatrixX3d positions = surface.positions();
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const Eigen::Vector3d x = positions.row(v).transpose();
    if (!inside(x, spheres)) continue;
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
  // The rigid inverse: R^T, -R^T t.
  Eigen::Matrix4d a_to_b = Eigen::Matrix4d::Identity();
  a_to_b.topLeftCorner<3, 3>() = b_to_a.topLeftCorner<3, 3>().transpose();
  a_to_b.topRightCorner<3, 1>() = -a_to_b.topLeftCorner<3, 3>() * b_to_a.topRightCorner<3, 1>();
  const double of_a = agreement(a, a_to_b, b, grid_of(b, contact), contact);
  const double of_b = agreement(b, b_to_a, a, grid_of(a, contact), contact);
  result.similarity = (of_a + of_b) / static_cast<double>(a.size() + b.size());
  result.coverage = a.size() <= b.size() ? of_a / static_cast<double>(a.size())
                                         : of_b / static_cast<double>(b.size());
  return result;
}

}  // namespace surfcomp::matching
