// Binding sites on a structure (docs/method.md §7): a site is a set of spheres, built around a
// ligand copy or given, and the structure without water and without that copy; its surface is
// the structure's SES near the spheres with ESP and LP from every atom. matching/site.hpp
// describes and scores sites on these.
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace surfcomp::molsurf {

/// A sphere of a binding site, A.
struct SiteSphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// True when `position` lies in at least one of `spheres` (distance to the centre <= radius).
bool in_site(const Eigen::Vector3d& position, const std::vector<SiteSphere>& spheres);

/// The sphere written "x,y,z,r" (A; what `--site-sphere` and a site list take), or none when
/// `text` is not four comma-separated numbers with a finite centre and a finite radius > 0.
std::optional<SiteSphere> parse_site_sphere(const std::string& text);

/// Site spheres as an option's value, and back.
std::vector<options::Sphere> sphere_values(const std::vector<SiteSphere>& spheres);
std::vector<SiteSphere> site_spheres(const std::vector<options::Sphere>& values);

/// What the user sees of --site-ligand and --site-sphere, wherever a site is asked for.
options::Spec site_ligand_spec();
options::Spec site_sphere_spec();

/// The repeatable option of a list of site spheres at `access(settings)` (a generic lambda as
/// for options::field).
template <class Settings, class Access>
options::Option<Settings> sphere_option(options::Spec spec, Access access) {
  spec.kind = options::Kind::spheres;
  spec.optional = true;
  return {std::move(spec),
          [access](const Settings& s) { return options::Value(sphere_values(access(s))); },
          [access](Settings& s, const options::Value& v) {
            access(s) = site_spheres(std::get<std::vector<options::Sphere>>(v));
          }};
}

/// A site's surface (build_site_surface) is the whole structure's wherever the site's patches
/// reach when its margin is at least the patch radius plus this, A: it is meshed to 5 A beyond
/// the patches (surface_region_within_margin), which covers a vertex's curvature fit (about
/// 2 A) and the reach of the remeshing (docs/decisions.md#site-surfaces).
inline constexpr double surface_margin_beyond_patch = 8.0;

/// A site's surface (build_site_surface) is meshed within the spheres' radius plus the margin
/// less this, A, and closed there by those spheres: with the margin at least the patch radius
/// plus surface_margin_beyond_patch, 5 A beyond the patches, the reach of a vertex's curvature
/// fit and of the remeshing, within which the surface is the whole structure's at the default
/// vertex density (coarser meshes remesh farther: at 1 vertex per A^2 a few vertices at the
/// patches' edge move by hundredths of an A; docs/decisions.md#site-surfaces).
inline constexpr double surface_region_within_margin = 3.0;

/// The surface margin a site described with patches of `patch_radius` (A) is built with:
/// `margin` raised to at least patch_radius + surface_margin_beyond_patch, or 0 (every atom)
/// when `margin` is 0.
double site_surface_margin(double margin, double patch_radius);

struct BindingSiteOptions {
  /// Default 4 A. Radius of the sphere around each atom of the ligand copy. Finite, > 0.
  double sphere_radius = 4.0;
  /// Default 0 A: the site's structure keeps every chain. When > 0, it keeps only the chains
  /// with an atom within this distance of a sphere's centre (for a ligand, the ligand's own
  /// chain among them), so that the surface, whose ESP and LP cost #vertices x #atoms, leaves
  /// out chains far from the site. Finite, >= 0.
  double chain_contact_radius = 0.0;
  /// Default 16 A (patches of up to 8 A; see surface_margin_beyond_patch). build_site_surface
  /// meshes the structure's SES within a sphere's radius plus this margin less
  /// surface_region_within_margin of its centre, not the whole structure's. 0: every atom.
  /// Finite, >= 0. Where a site is described (match_inputs, prepare_input, a pocket screen), it
  /// is raised to site_surface_margin of the patch radius.
  double surface_margin = 16.0;
};

/// The user's options of BindingSiteOptions: --site-radius and --site-margin.
const options::Table<BindingSiteOptions>& binding_site_option_table();

/// A binding site and the structure whose surface it lies on.
struct BindingSite {
  std::vector<SiteSphere> spheres;  ///< the site, A
  /// The atoms of the ligand copy the site was built around, in the structure's order (source
  /// and title the structure's); no atoms when the site was built from spheres.
  Molecule ligand;
  /// The structure without water, without the ligand copy (only that copy: other copies of the
  /// ligand, ions and cofactors stay) and, with chain_contact_radius > 0, without the chains
  /// out of contact; the atoms keep their order and properties.
  Molecule structure;
  double surface_margin = 0.0;  ///< BindingSiteOptions::surface_margin, A
};

/// The site of the ligand copy select_ligand(structure, ligand) takes: a sphere of
/// options.sphere_radius around each of its atoms. Throws InputError when that copy is absent
/// (select_ligand's message: the file and the residues present) or when no atom is left in the
/// site's structure; OptionError for options outside their domain.
BindingSite binding_site(const Molecule& structure, const LigandSelector& ligand,
                         const BindingSiteOptions& options = {});

/// The site made of `spheres` on `structure` (options.sphere_radius is not used). Throws
/// InputError when there is no sphere, a sphere has a non-finite centre or a radius that is not
/// a finite number > 0, or no atom is left in the site's structure; OptionError for options
/// outside their domain.
BindingSite binding_site(const Molecule& structure, std::vector<SiteSphere> spheres,
                         const BindingSiteOptions& options = {});

/// The site's surface: the structure's SES (options.ses) within a sphere's radius plus
/// site.surface_margin - surface_region_within_margin of its centre, closed by those spheres
/// where they cut the structure (build_ses with a SesRegion), built from the atoms that reach
/// that region (within two probe radii and the largest atom radius of it); every atom's SES
/// when the margin is 0 (or not above surface_region_within_margin: then the SES of the atoms
/// within the margin). It is sampled on the grid of the whole structure
/// (molsurf::ses_voxel_size), with ESP and LP from every atom of the structure and curvature
/// (options.esp, lp, curvature); its source is the structure's. Throws InputError when no atom
/// lies within reach of the spheres, and as build_molecular_surface.
mesh::Surface build_site_surface(const BindingSite& site,
                                 const molsurf::MolecularSurfaceOptions& options = {});

/// How far beyond a sphere's radius (A) build_site_surface takes the structure's atoms, built
/// with `ses`: the margin when it meshes every atom's surface; otherwise the meshed region
/// (the margin less surface_region_within_margin) plus two probe radii, the largest atom radius
/// and two voxels of the grid, the atoms that shape the sampled surface there. Throws as
/// build_ses for the structure's atoms.
double site_atom_reach(const BindingSite& site, const SesOptions& ses);

/// Default 4 A beyond the surface margin: the reach of the atoms a site keeps
/// (site_neighbourhood). LP sums the atoms within molsurf::default_fauchere_cutoff (12 A) of a
/// vertex, so it is the whole structure's at every vertex within the margin - 8 A of a sphere:
/// at least the patch radius (site_surface_margin). A pocket library keeps the larger of this
/// and site_atom_reach, which it exceeds for a water probe and atoms up to 2.8 A.
inline constexpr double neighbourhood_beyond_margin = 4.0;

/// What a site's surface and scores need of `structure`, in its order: every atom within a
/// sphere's radius + `reach` (A) of its centre, every charged atom (the ESP sums them all), each
/// chain's first standard residue (whose N terminus a reader charges) and the smallest atom
/// (which sets the SES grid); ionisable_atoms follow their atoms. A pocket library stores this
/// rather than the structure. Throws InputError when `reach` is not finite and >= 0.
Molecule site_neighbourhood(const Molecule& structure, const std::vector<SiteSphere>& spheres,
                            double reach);

}  // namespace surfcomp::molsurf
