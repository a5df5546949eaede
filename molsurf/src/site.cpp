#include "surfcomp/molsurf/site.hpp"

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

namespace surfcomp::molsurf {
namespace {

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

namespace {

/// The region build_site_surface meshes, beyond the spheres' radii, A; 0 when it meshes the
/// whole surface of the atoms within the margin (a margin of 0 or of at most
/// surface_region_within_margin).
double meshed_region(const BindingSite& site) {
  const double region = site.surface_margin - surface_region_within_margin;
  return region > 0.0 ? region : 0.0;
}

/// site_atom_reach for the structure's balls and the grid's voxel.
double atom_reach(const BindingSite& site, const Eigen::VectorXd& radii, double probe,
                  double voxel) {
  const double region = meshed_region(site);
  if (region == 0.0) return site.surface_margin;
  // The SES within the region depends on the atoms within two probe radii and an atom radius
  // of it; the grid reads the field a voxel or two beyond it.
  return region + 2.0 * probe + radii.maxCoeff() + 2.0 * voxel;
}

}  // namespace

double site_atom_reach(const BindingSite& site, const SesOptions& ses) {
  validate_molecule(site.structure);
  const auto [centers, radii] = molsurf::atom_balls(site.structure);
  return atom_reach(site, radii, ses.probe_radius, molsurf::ses_voxel_size(centers, radii, ses));
}

mesh::Surface build_site_surface(const BindingSite& site,
                                 const molsurf::MolecularSurfaceOptions& options) {
  const Molecule& structure = site.structure;
  validate_molecule(structure);
  const auto [centers, radii] = molsurf::atom_balls(structure);
  const auto n = static_cast<Eigen::Index>(structure.atoms.size());
  molsurf::SesOptions ses = options.ses;
  ses.voxel_size = molsurf::ses_voxel_size(centers, radii, ses);
  const double region = meshed_region(site);
  const bool whole = region == 0.0;
  const double reach = atom_reach(site, radii, ses.probe_radius, ses.voxel_size);
  std::vector<Eigen::Index> near;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d position = centers.row(i).transpose();
    const bool kept =
        site.surface_margin == 0.0 ||
        std::any_of(site.spheres.begin(), site.spheres.end(), [&](const SiteSphere& s) {
          return (position - s.center).norm() <= s.radius + reach;
        });
    if (kept) near.push_back(i);
  }
  if (near.empty()) {
    std::ostringstream message;
    message << structure.source << ": no atom lies within " << reach << " A of the site's spheres";
    if (whole) {
      message << " (its surface margin)";
    } else {
      message << " (its surface margin " << site.surface_margin << " A less "
              << surface_region_within_margin
              << " A, plus the reach of the atoms that shape the surface there)";
    }
    throw InputError(message.str());
  }
  mesh::Surface surface;
  if (whole) {
    surface = molsurf::build_ses(centers(near, Eigen::all), radii(near), ses, structure.source);
  } else {
    SesRegion balls;
    balls.centers.resize(static_cast<Eigen::Index>(site.spheres.size()), 3);
    balls.radii.resize(static_cast<Eigen::Index>(site.spheres.size()));
    for (std::size_t k = 0; k < site.spheres.size(); ++k) {
      balls.centers.row(static_cast<Eigen::Index>(k)) = site.spheres[k].center.transpose();
      balls.radii(static_cast<Eigen::Index>(k)) = site.spheres[k].radius + region;
    }
    surface =
        molsurf::build_ses(centers(near, Eigen::all), radii(near), balls, ses, structure.source);
  }
  surface = mesh::spatially_ordered(surface);
  surface.set_source(structure.source);
  mesh::require_closed_manifold(surface);
  molsurf::assign_surface_properties(surface, &structure, options);
  return surface;
}

Molecule site_neighbourhood(const Molecule& structure, const std::vector<SiteSphere>& spheres,
                            double reach) {
  if (!std::isfinite(reach) || reach < 0.0)
    throw InputError("site neighbourhood: the reach must be a finite number >= 0 A");
  Molecule kept = structure;
  kept.atoms.clear();
  kept.ionisable_atoms.clear();
  // The smallest atom sets the SES grid (molsurf::ses_voxel_size): it stays, wherever it is.
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
          "a binding site: the site of one copy of this ligand residue, RES[:CHAIN[:NUMBER]] "
          "(match: on both inputs)",
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
           "a site's surface is the structure's SES meshed within a site sphere's "
           "radius plus this margin less 3 A, the margin at least the patch radius + 8 "
           "(0: the whole structure's); "
           "ESP and LP come from every atom",
           "A", 0.0, 1000.0},
          [](auto& b) -> auto& { return b.surface_margin; }),
  };
  return table;
}

bool in_site(const Eigen::Vector3d& position, const std::vector<SiteSphere>& spheres) {
  return std::any_of(spheres.begin(), spheres.end(),
                     [&](const SiteSphere& s) { return (position - s.center).norm() <= s.radius; });
}

}  // namespace surfcomp::molsurf
