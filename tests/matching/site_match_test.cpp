// Binding-site comparison with a known answer (issue 4, "Binding sites"): the thermolysin sites
// of 1THL and 4TMN. 4TMN's protein is in the common frame of ../shared/datasets/thermolysin; the
// rigid transform taking the 1THL ligand from its own entry's frame into the common frame takes
// the 1THL protein there too. The top alignment of the 1THL site onto the 4TMN site must agree
// with that transform on the site residues' C-alphas.
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/match.hpp"
#include "surfcomp/matching/rigid_fit.hpp"
#include "surfcomp/matching/site.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp {
namespace {

constexpr double kPatchRadius = 8.0;  // A, harmonic patches of the site's critical points

/// A protein's binding site around its ligand (spheres of the default 4 A) and its description.
struct Site {
  molsurf::BindingSite site;
  harmonic::SurfaceDescriptors descriptors;  ///< critical points outside the site skipped
  std::vector<bool> in_site;                 ///< one flag per critical point
};

Site build_site(const std::filesystem::path& pdb, const std::string& ligand_name,
                const harmonic::DescriptorOptions& options) {
  Site out;
  // The whole structure is read, so the ligand's charges are not typed (Gasteiger cannot type
  // 4TMN's phosphonamidate), and only its positions are needed.
  out.site = molsurf::binding_site(io::read_molecule(pdb), LigandSelector{ligand_name, {}, {}});
  mesh::Surface surface = molsurf::build_molecular_surface(out.site.structure);
  out.descriptors =
      matching::describe_site(std::move(surface), out.site.structure, out.site.spheres, options);
  out.in_site = matching::critical_points_in_site(out.descriptors, out.site.spheres);
  return out;
}

/// Positions of `molecule`'s atoms as a 3 by N array.
Eigen::Matrix3Xd positions(const Molecule& molecule) {
  Eigen::Matrix3Xd out(3, static_cast<Eigen::Index>(molecule.atoms.size()));
  for (std::size_t i = 0; i < molecule.atoms.size(); ++i)
    out.col(static_cast<Eigen::Index>(i)) = molecule.atoms[i].position;
  return out;
}

/// C-alpha positions of the protein residues with an atom within `radius` of a ligand atom,
/// keyed by residue number (thermolysin's numbering is shared between the entries; each has one
/// chain, A in 1THL and E in 4TMN).
std::map<int, Eigen::Vector3d> site_c_alphas(const Molecule& protein, const Molecule& ligand,
                                             double radius) {
  std::set<int> residues;
  for (const Atom& atom : protein.atoms) {
    if (atom.hetero) continue;
    for (const Atom& l : ligand.atoms) {
      if ((atom.position - l.position).norm() <= radius) {
        residues.insert(atom.residue_number);
        break;
      }
    }
  }
  std::map<int, Eigen::Vector3d> out;
  for (const Atom& atom : protein.atoms) {
    if (!atom.hetero && atom.name == "CA" && residues.count(atom.residue_number)) {
      out[atom.residue_number] = atom.position;
    }
  }
  return out;
}

Eigen::Vector3d apply(const Eigen::Matrix4d& m, const Eigen::Vector3d& x) {
  return m.topLeftCorner<3, 3>() * x + m.topRightCorner<3, 1>();
}

TEST(SiteMatch, ThermolysinSitesAlignWithinHalfAnAngstrom) {
  SURFCOMP_SHARED_OR_SKIP(ref_pdb, "thermolysin/4TMN.pdb");
  SURFCOMP_SHARED_OR_SKIP(probe_pdb, "thermolysin/1THL.pdb");
  SURFCOMP_SHARED_OR_SKIP(original, "thermolysin/ligands-original/ligand1THL.pdb");
  SURFCOMP_SHARED_OR_SKIP(common, "thermolysin/ligands-common-frame/1THL_ligand.pdb");

  // The truth: Kabsch fit of the 1THL ligand's own-frame atoms onto the common-frame copy (the
  // two files list the same atoms in the same order, checked by name).
  const Molecule from = io::read_molecule(original);
  const Molecule to = io::read_molecule(common);
  ASSERT_EQ(from.atoms.size(), to.atoms.size());
  for (std::size_t i = 0; i < from.atoms.size(); ++i)
    ASSERT_EQ(from.atoms[i].name, to.atoms[i].name) << i;
  const matching::RigidFit truth_fit = matching::fit_rigid(positions(from), positions(to));
  ASSERT_LT(truth_fit.rmsd, 0.01);
  const Eigen::Matrix4d truth = truth_fit.transform.matrix();

  harmonic::DescriptorOptions options;
  options.patch.radius = kPatchRadius;
  const Site ref = build_site(ref_pdb, "0PK", options);
  const Site probe = build_site(probe_pdb, "0DB", options);
  std::printf("[ sites    ] 4TMN: %zu atoms, %zu vertices, %zu site CPs\n",
              ref.site.structure.atoms.size(), ref.descriptors.surface.n_vertices(),
              harmonic::count_descriptors(ref.descriptors).imaged);
  std::printf("[ sites    ] 1THL: %zu atoms, %zu vertices, %zu site CPs\n",
              probe.site.structure.atoms.size(), probe.descriptors.surface.n_vertices(),
              harmonic::count_descriptors(probe.descriptors).imaged);

  matching::MatchOptions match_options;
  match_options.mode = matching::MatchMode::binding_sites;
  const auto result = matching::match_surfaces(ref.descriptors, probe.descriptors, match_options,
                                               &ref.in_site, &probe.in_site);
  ASSERT_FALSE(result.alignments.empty());

  const double site_radius = molsurf::BindingSiteOptions{}.sphere_radius;
  const auto probe_cas = site_c_alphas(probe.site.structure, probe.site.ligand, site_radius);
  const auto ref_cas =
      site_c_alphas(ref.site.structure, ref.site.ligand, 1e9);  // all residues, by number
  ASSERT_GE(probe_cas.size(), 10u);
  auto ca_rmsd = [&](const Eigen::Matrix4d& found) {
    double sum = 0;
    for (const auto& [key, ca] : probe_cas)
      sum += (apply(found, ca) - apply(truth, ca)).squaredNorm();
    return std::sqrt(sum / static_cast<double>(probe_cas.size()));
  };
  // The truth against 4TMN's own C-alphas (shared numbering): how well the two sites agree at all.
  double sum = 0;
  std::size_t n = 0;
  for (const auto& [key, ca] : probe_cas) {
    const auto found = ref_cas.find(key);
    if (found == ref_cas.end()) continue;
    sum += (apply(truth, ca) - found->second).squaredNorm();
    ++n;
  }
  std::printf(
      "[ sites    ] %zu site residues; true transform vs 4TMN C-alphas: RMSD %.2f A over %zu\n",
      probe_cas.size(), std::sqrt(sum / static_cast<double>(n)), n);
  for (std::size_t i = 0; i < std::min<std::size_t>(5, result.alignments.size()); ++i) {
    const auto& a = result.alignments[i];
    std::printf(
        "[ sites    ] rank %d: %zu pairs, %zu points, RMSD %.2f A, site C-alpha RMSD %.2f A\n",
        a.rank, a.cp_pairs.size(), a.n_points, a.rmsd, ca_rmsd(a.transform));
  }
  for (const auto& stage : result.trace) {
    std::printf("[ sites    ] %-10s %6zu nodes %8zu edges\n", stage.stage.c_str(), stage.nodes,
                stage.edges);
  }
  // Measured 0.26 A; the bound leaves a margin for round-off across platforms, not for a
  // different pose.
  EXPECT_LT(ca_rmsd(result.alignments[0].transform), 0.5);
}

}  // namespace
}  // namespace surfcomp
