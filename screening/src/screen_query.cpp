// A screen's query: its match options, its chemistry and shape weight, and the warning given
// before any screening work.
#include "surfcomp/screening/screen.hpp"

#include "screen_stages.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/protein_lipophilicity.hpp"

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::screening {

matching::MatchOptions query_match_options(const ScreenQuery& query, const ScreenOptions& options) {
  matching::MatchOptions match = options.match;
  match.mode =
      query.site.empty() ? matching::MatchMode::whole_surfaces : matching::MatchMode::binding_sites;
  // A hit is scored by its overlay: the coverage would add a third to each pair's match time.
  match.coverage_distance = 0.0;
  return match;
}

std::string macromolecule_query_warning(const Molecule& query, const std::string& source) {
  std::size_t heavy = 0;
  std::map<std::string, std::set<std::pair<int, std::string>>> chain_residues;
  for (const Atom& atom : query.atoms) {
    if (atom.element != "H") ++heavy;
    if (protein_atom_lipophilicity(atom.residue_name, "CA"))
      chain_residues[atom.chain].emplace(atom.residue_number, atom.residue_name);
  }
  std::size_t longest = 0;
  for (const auto& [chain, residues] : chain_residues) longest = std::max(longest, residues.size());
  if (heavy <= macromolecule_heavy_atoms && longest < macromolecule_chain_residues) return {};
  return source + ": the query is a macromolecule (" + std::to_string(heavy) + " heavy atoms" +
         (longest >= macromolecule_chain_residues
              ? ", a chain of " + std::to_string(longest) + " amino-acid residues"
              : std::string()) +
         "): its whole surface is compared with the library's molecules";
}

double query_shape_weight(QueryChemistry chemistry, bool whole_molecule, const Molecule* molecule) {
  if (!whole_molecule || chemistry == QueryChemistry::on) return 0.0;
  if (chemistry == QueryChemistry::off) return 1.0;
  return molecule != nullptr && !carries_ionic_group(*molecule) ? neutral_query_shape_weight : 0.0;
}

ScreenQuery make_screen_query(harmonic::SurfaceDescriptors descriptors,
                              const ScreenOptions& options, std::vector<molsurf::SiteSphere> site,
                              const Molecule* molecule) {
  matching::require_match_properties(descriptors.surface);  // the entries are compared by ESP/LP
  ScreenQuery query;
  query.site = std::move(site);
  const matching::OverlayOptions overlay =
      matching::mode_overlay_options(query_match_options(query, options));
  if (query.site.empty()) {
    query.sample = matching::sample_surface(descriptors.surface, overlay.spacing);
    query.atoms = matching::sample_atoms(descriptors.atoms);
  } else {
    query.site_points = matching::critical_points_in_site(descriptors, query.site);
    const std::vector<bool> lining =
        matching::pocket_lining(descriptors, &query.site_points, options.match.site.overlay_radius);
    query.sample = matching::sample_surface(descriptors.surface, overlay.spacing, &lining);
    // A site that no amino acid lines is scored by its overlay alone.
    if (molecule != nullptr) query.lining = matching::lining_composition(*molecule, query.site);
  }
  if (query.sample.size() == 0) {
    throw InputError(descriptors.surface.source() + (query.site.empty()
                                                         ? ": the query's surface has no vertex"
                                                         : ": the query site's pocket lining has "
                                                           "no vertex"));
  }
  query.atom_sample = molecule != nullptr && query.site.empty()
                          ? matching::sample_molecule(*molecule, overlay.spacing, options.surface)
                          : query.sample;
  if (query.atom_sample.size() == 0) query.atom_sample = query.sample;
  query.packed = std::make_shared<const matching::PackedQuery>(matching::PackedSample(
      query.sample, query.atoms, overlay.sigma, matching::SampleKind::surface));
  query.atom_packed = std::make_shared<const matching::PackedQuery>(matching::PackedSample(
      query.atom_sample, query.atoms, overlay.sigma, matching::SampleKind::atoms));
  query.descriptors = std::move(descriptors);
  query.shape_weight = query_shape_weight(options.chemistry, query.site.empty(), molecule);
  return query;
}

void agree_on_chemistry(std::vector<ScreenQuery>& queries) {
  const bool mixed =
      std::adjacent_find(queries.begin(), queries.end(), [](const auto& a, const auto& b) {
        return a.shape_weight != b.shape_weight;
      }) != queries.end();
  if (mixed) {
    for (ScreenQuery& query : queries) query.shape_weight = 0.0;
  }
}

}  // namespace surfcomp::screening
