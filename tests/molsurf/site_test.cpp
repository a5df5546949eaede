// Binding sites and the one ligand selection behind them: which copy of a ligand select_ligand
// takes (and read_molecule's `ligand` option with it), what a site built from that copy or from
// spheres holds, which chains the contact pruning keeps, which critical points a site flags
// and describes, and what its lining residues' composition and the site score are.
#include "surfcomp/matching/site.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include "test_data.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace surfcomp {
namespace {

Atom atom(const std::string& element, const Eigen::Vector3d& position, const std::string& residue,
          int number, const std::string& chain, bool hetero) {
  Atom a;
  a.element = element;
  a.name = element + "1";
  a.position = position;
  a.radius = 1.7;
  a.residue_name = residue;
  a.residue_number = number;
  a.chain = chain;
  a.hetero = hetero;
  return a;
}

/// A three-atom copy of ligand LIG at `origin`.
void add_ligand(Molecule& m, const Eigen::Vector3d& origin, int number, const std::string& chain) {
  for (int k = 0; k < 3; ++k)
    m.atoms.push_back(atom(k == 1 ? "O" : "C", origin + Eigen::Vector3d(1.4 * k, 0, 0), "LIG",
                           number, chain, true));
}

/// A structure with three copies of LIG, listed B 5, A 9, A 7 (the file order differs from the
/// selection order), a protein residue of chain A that carries the name LIG in an ATOM record
/// (not a HETATM residue: never selected), an ion and water.
Molecule structure_with_copies() {
  Molecule m;
  m.source = "copies.pdb";
  m.atoms.push_back(atom("N", {0, 0, 0}, "ALA", 1, "A", false));
  m.atoms.push_back(atom("C", {1.5, 0, 0}, "ALA", 1, "A", false));
  m.atoms.push_back(atom("C", {-3, 0, 0}, "LIG", 1, "A", false));
  add_ligand(m, {0, 30, 0}, 5, "B");
  m.atoms.push_back(atom("O", {0, 31, 3}, "HOH", 101, "B", true));
  add_ligand(m, {0, 0, 30}, 9, "A");
  add_ligand(m, {5, 0, 0}, 7, "A");
  m.atoms.push_back(atom("Zn", {5, 3, 0}, "ZN", 8, "A", true));
  m.atoms.push_back(atom("O", {5, -3, 0}, "HOH", 102, "A", true));
  return m;
}

/// The distinct (chain, residue number) of `indices` into `m`.
std::set<std::pair<std::string, int>> copies(const Molecule& m,
                                             const std::vector<std::size_t>& indices) {
  std::set<std::pair<std::string, int>> out;
  for (std::size_t i : indices) out.emplace(m.atoms[i].chain, m.atoms[i].residue_number);
  return out;
}

using Copies = std::set<std::pair<std::string, int>>;

TEST(SelectLigand, TakesTheLowestChainThenResidueNumberOfTheHetatmCopies) {
  const Molecule m = structure_with_copies();
  const auto selected = select_ligand(m, LigandSelector{"LIG", {}, {}});
  EXPECT_EQ(selected, (std::vector<std::size_t>{10, 11, 12}));  // A 7, in file order
  EXPECT_EQ(copies(m, selected), (Copies{{"A", 7}}));
  // The name is compared without blanks and case.
  EXPECT_EQ(select_ligand(m, LigandSelector{" lig", {}, {}}), selected);
}

TEST(SelectLigand, NarrowsByChainAndResidueNumber) {
  const Molecule m = structure_with_copies();
  EXPECT_EQ(copies(m, select_ligand(m, LigandSelector{"LIG", std::string("B"), {}})),
            (Copies{{"B", 5}}));
  EXPECT_EQ(copies(m, select_ligand(m, LigandSelector{"LIG", {}, 9})), (Copies{{"A", 9}}));
  EXPECT_EQ(copies(m, select_ligand(m, LigandSelector{"LIG", std::string("A"), 9})),
            (Copies{{"A", 9}}));
  try {
    select_ligand(m, LigandSelector{"LIG", std::string("B"), 9});
    ADD_FAILURE() << "no copy B 9, none thrown";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("copies.pdb"), std::string::npos) << message;
    EXPECT_NE(message.find("chain 'B' number 5"), std::string::npos) << message;
    EXPECT_NE(message.find("chain 'A' number 7"), std::string::npos) << message;
    EXPECT_NE(message.find("chain 'A' number 9"), std::string::npos) << message;
  }
}

TEST(SelectLigand, ParsesResidueChainAndNumberAsAUserWritesThem) {
  const Molecule m = structure_with_copies();
  const auto picked = [&](const char* text) {
    return copies(m, select_ligand(m, parse_ligand_selector(text)));
  };
  EXPECT_EQ(picked("LIG"), (Copies{{"A", 7}}));
  EXPECT_EQ(picked("LIG:B"), (Copies{{"B", 5}}));
  EXPECT_EQ(picked("lig:A:9"), (Copies{{"A", 9}}));
  EXPECT_EQ(picked("LIG::9"), (Copies{{"A", 9}}));
  EXPECT_EQ(picked("LIG:"), (Copies{{"A", 7}}));    // an empty chain is any
  EXPECT_EQ(picked("LIG:A:"), (Copies{{"A", 7}}));  // an empty number is any
  for (const char* bad : {"", ":A", "LIG:A:9x", "LIG:A:9:1", "LIG:A:99999999999"}) {
    try {
      parse_ligand_selector(bad);
      ADD_FAILURE() << "'" << bad << "' parsed";
    } catch (const OptionError& e) {
      EXPECT_NE(std::string(e.what()).find("RESIDUE[:CHAIN[:NUMBER]]"), std::string::npos)
          << e.what();
    }
  }
}

TEST(SelectLigand, AnAbsentLigandNamesTheFileAndTheResiduesPresent) {
  const Molecule m = structure_with_copies();
  try {
    select_ligand(m, LigandSelector{"ATP", {}, {}});
    ADD_FAILURE() << "no ATP, none thrown";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("copies.pdb"), std::string::npos) << message;
    EXPECT_NE(message.find("'ATP'"), std::string::npos) << message;
    EXPECT_NE(message.find("LIG, HOH, ZN"), std::string::npos) << message;
  }
}

/// A PDB line of `a` (HETATM or ATOM) with serial `serial`.
std::string pdb_line(const Atom& a, int serial) {
  char line[90];
  std::snprintf(line, sizeof line,
                "%-6s%5d %-4s %3s %1s%4d    %8.3f%8.3f%8.3f  1.00  0.00          %2s",
                a.hetero ? "HETATM" : "ATOM", serial, (" " + a.name).c_str(),
                a.residue_name.c_str(), a.chain.c_str(), a.residue_number, a.position.x(),
                a.position.y(), a.position.z(), a.element.c_str());
  return line;
}

// read_molecule's `ligand` option takes the copy select_ligand takes, not the first in the file.
TEST(SelectLigand, ReadMoleculeLigandOptionTakesTheSameCopy) {
  const test::TempDir dir;
  const auto path = dir / "two_copies.pdb";
  Molecule written;
  // An acetate-like copy in chain B first, one in chain A after it, far apart.
  for (const auto& [chain, number, origin] :
       {std::tuple<std::string, int, Eigen::Vector3d>{"B", 5, {0, 0, 0}},
        std::tuple<std::string, int, Eigen::Vector3d>{"A", 7, {20, 0, 0}}}) {
    const std::pair<const char*, Eigen::Vector3d> atoms[] = {
        {"C", {0, 0, 0}}, {"C", {1.52, 0, 0}}, {"O", {2.15, 1.08, 0}}, {"O", {2.15, -1.08, 0}}};
    int k = 0;
    for (const auto& [element, offset] : atoms) {
      written.atoms.push_back(atom(element, origin + offset, "ACT", number, chain, true));
      written.atoms.back().name = element + std::to_string(++k);
    }
  }
  {
    std::ofstream out(path);
    for (std::size_t i = 0; i < written.atoms.size(); ++i)
      out << pdb_line(written.atoms[i], static_cast<int>(i) + 1) << "\n";
    out << "END\n";
  }
  io::MoleculeReadOptions options;
  options.ligand = "act";
  const Molecule ligand = io::read_molecule(path, options);
  ASSERT_EQ(ligand.atoms.size(), 4u);
  for (const Atom& a : ligand.atoms) {
    EXPECT_EQ(a.chain, "A");
    EXPECT_EQ(a.residue_number, 7);
  }
  const Molecule whole = io::read_molecule(path);
  const auto selected = select_ligand(whole, LigandSelector{"ACT", {}, {}});
  ASSERT_EQ(selected.size(), ligand.atoms.size());
  for (std::size_t k = 0; k < selected.size(); ++k)
    EXPECT_EQ(ligand.atoms[k].position, whole.atoms[selected[k]].position) << k;
}

TEST(BindingSite, SpheresAreTheLigandCopysAtomsWithTheRadius) {
  const Molecule m = structure_with_copies();
  molsurf::BindingSiteOptions options;
  options.sphere_radius = 3.5;
  const auto site = molsurf::binding_site(m, LigandSelector{"LIG", {}, {}}, options);
  const std::vector<std::size_t> copy = {10, 11, 12};
  ASSERT_EQ(site.spheres.size(), copy.size());
  ASSERT_EQ(site.ligand.atoms.size(), copy.size());
  for (std::size_t k = 0; k < copy.size(); ++k) {
    EXPECT_EQ(site.spheres[k].center, m.atoms[copy[k]].position) << k;
    EXPECT_EQ(site.spheres[k].radius, 3.5) << k;
    EXPECT_EQ(site.ligand.atoms[k].position, m.atoms[copy[k]].position) << k;
  }
  EXPECT_EQ(site.ligand.source, m.source);
}

TEST(BindingSite, TheStructureLosesExactlyTheCopyAndTheWater) {
  const Molecule m = structure_with_copies();
  const auto site = molsurf::binding_site(m, LigandSelector{"LIG", {}, {}});
  // Kept: the protein (with its LIG-named ATOM record), the copies B 5 and A 9, the ion; in order.
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < m.atoms.size(); ++i) {
    const bool copy = i >= 10 && i <= 12;
    if (!copy && m.atoms[i].residue_name != "HOH") kept.push_back(i);
  }
  ASSERT_EQ(site.structure.atoms.size(), kept.size());
  EXPECT_EQ(site.structure.atoms.size(), m.atoms.size() - 3 - 2);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    EXPECT_EQ(site.structure.atoms[k].position, m.atoms[kept[k]].position) << k;
    EXPECT_EQ(site.structure.atoms[k].residue_number, m.atoms[kept[k]].residue_number) << k;
  }
  EXPECT_EQ(site.structure.source, m.source);
  // A copy chosen by chain and number leaves the others.
  const auto b5 = molsurf::binding_site(m, LigandSelector{"LIG", std::string("B"), 5});
  EXPECT_EQ(b5.structure.atoms.size(), m.atoms.size() - 3 - 2);
  for (const Atom& a : b5.structure.atoms)
    EXPECT_FALSE(a.residue_name == "LIG" && a.chain == "B") << a.residue_number;
}

TEST(BindingSite, ChainPruningKeepsOnlyTheChainsInContact) {
  Molecule m;
  m.source = "chains.pdb";
  add_ligand(m, {0, 0, 0}, 1, "L");  // atoms at x = 0, 1.4, 2.8; its chain has nothing else
  m.atoms.push_back(atom("C", {2.8, 4.9, 0}, "GLY", 1, "A", false));  // 4.9 A: in contact
  m.atoms.push_back(atom("C", {2.8, 20, 0}, "GLY", 2, "A", false));   // same chain, far
  m.atoms.push_back(atom("C", {0, -5.1, 0}, "GLY", 1, "B", false));   // 5.1 A: out
  m.atoms.push_back(atom("C", {0, 0, -5.0}, "GLY", 1, "C", false));   // 5.0 A: in contact
  m.atoms.push_back(atom("O", {0, 0, 4.0}, "HOH", 1, "D", true));     // water: never counts
  m.atoms.push_back(atom("C", {0, 0, 8.0}, "GLY", 1, "D", false));    // 8 A: out
  molsurf::BindingSiteOptions options;
  const auto whole = molsurf::binding_site(m, LigandSelector{"LIG", {}, {}}, options);
  EXPECT_EQ(whole.structure.atoms.size(), 5u);  // every chain, water and ligand out
  options.chain_contact_radius = 5.0;
  const auto pruned = molsurf::binding_site(m, LigandSelector{"LIG", {}, {}}, options);
  std::vector<std::string> chains;
  for (const Atom& a : pruned.structure.atoms) chains.push_back(a.chain);
  EXPECT_EQ(chains, (std::vector<std::string>{"A", "A", "C"}));
  // From spheres: the same rule about their centres.
  const auto spheres = molsurf::binding_site(m, pruned.spheres, options);
  EXPECT_EQ(spheres.structure.atoms.size(), 6u);  // the ligand is no copy here: it stays
  EXPECT_TRUE(spheres.ligand.atoms.empty());
  chains.clear();
  for (const Atom& a : spheres.structure.atoms) chains.push_back(a.chain);
  EXPECT_EQ(chains, (std::vector<std::string>{"L", "L", "L", "A", "A", "C"}));
}

TEST(BindingSite, BadSpheresAndOptionsAreRejected) {
  const Molecule m = structure_with_copies();
  EXPECT_THROW(molsurf::binding_site(m, std::vector<molsurf::SiteSphere>{}), InputError);
  EXPECT_THROW(molsurf::binding_site(m, {molsurf::SiteSphere{{0, 0, 0}, 0.0}}), InputError);
  EXPECT_THROW(molsurf::binding_site(m, {molsurf::SiteSphere{{0, std::nan(""), 0}, 1.0}}),
               InputError);
  molsurf::BindingSiteOptions options;
  options.sphere_radius = 0.0;
  EXPECT_THROW(molsurf::binding_site(m, LigandSelector{"LIG", {}, {}}, options), OptionError);
  options = {};
  options.chain_contact_radius = -1.0;
  EXPECT_THROW(molsurf::binding_site(m, LigandSelector{"LIG", {}, {}}, options), OptionError);
  options = {};
  for (double margin : {-1.0, std::nan(""), HUGE_VAL}) {
    options.surface_margin = margin;
    EXPECT_THROW(molsurf::binding_site(m, LigandSelector{"LIG", {}, {}}, options), OptionError);
  }
  EXPECT_THROW(molsurf::binding_site(m, LigandSelector{"ATP", {}, {}}), InputError);
}

TEST(BindingSite, TheMaskFlagsTheCriticalPointsInsideASphere) {
  harmonic::SurfaceDescriptors d;
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(2.01, 0, 0),
        Eigen::Vector3d(10.5, 0, 0), Eigen::Vector3d(0, 0, 5)}) {
    harmonic::CriticalPointDescriptor c;
    c.point.position = p;
    d.critical_points.push_back(c);
  }
  const std::vector<molsurf::SiteSphere> spheres = {{{0, 0, 0}, 2.0}, {{10, 0, 0}, 1.0}};
  EXPECT_EQ(matching::critical_points_in_site(d, spheres),
            (std::vector<bool>{true, true, false, true, false}));
  EXPECT_EQ(matching::critical_points_in_site(d, {}), std::vector<bool>(5, false));
}

// describe_site images the critical points its mask flags, exactly as describe_surface does,
// and only those; the others keep their place, skipped.
TEST(BindingSite, DescribeSiteImagesOnlyTheSiteCriticalPoints) {
  SURFCOMP_SHARED_OR_SKIP(file, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  const Molecule molecule = io::read_molecule(file);
  const mesh::Surface surface = molsurf::build_molecular_surface(molecule);
  const auto whole = harmonic::describe_surface(surface, molecule);
  ASSERT_GT(whole.critical_points.size(), 4u);
  const std::vector<molsurf::SiteSphere> spheres = {
      {whole.critical_points.front().point.position, 4.0}};
  const auto site = matching::describe_site(surface, molecule, spheres);
  const std::vector<bool> in_site = matching::critical_points_in_site(site, spheres);
  ASSERT_EQ(site.critical_points.size(), whole.critical_points.size());
  EXPECT_EQ(site.atoms.size(), whole.atoms.size());
  std::size_t inside = 0;
  for (std::size_t i = 0; i < site.critical_points.size(); ++i) {
    const auto& s = site.critical_points[i];
    const auto& w = whole.critical_points[i];
    EXPECT_EQ(s.point.vertex, w.point.vertex) << i;
    if (in_site[i]) {
      ++inside;
      EXPECT_EQ(s.status, w.status) << i;
      EXPECT_EQ(s.image.values, w.image.values) << i;
    } else {
      EXPECT_EQ(s.status, harmonic::PatchStatus::skipped) << i;
    }
  }
  EXPECT_GE(inside, 1u);
  EXPECT_LT(inside, site.critical_points.size());
  const auto without_atoms = matching::describe_site(surface, spheres);
  EXPECT_TRUE(without_atoms.atoms.empty());
}

// The site's surface, built from the atoms within the margin, is the whole structure's surface
// wherever the site's descriptors look (the site's spheres and 8 A patches around them): the
// same vertices, ESP and LP (from every atom), critical points and shape images.
TEST(SiteSurface, IsTheWholeSurfaceWhereTheSiteLooks) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/4TMN.pdb");
  const Molecule structure = io::read_molecule(pdb);
  molsurf::BindingSiteOptions whole_options;
  whole_options.surface_margin = 0.0;
  const molsurf::BindingSite whole_site =
      molsurf::binding_site(structure, LigandSelector{"0PK", {}, {}}, whole_options);
  const molsurf::BindingSite site = molsurf::binding_site(structure, LigandSelector{"0PK", {}, {}});
  ASSERT_EQ(site.surface_margin, 16.0);
  harmonic::DescriptorOptions options;
  options.patch.radius = 8.0;
  const auto whole = matching::describe_site(molsurf::build_site_surface(whole_site),
                                             whole_site.structure, whole_site.spheres, options);
  const auto local = matching::describe_site(molsurf::build_site_surface(site), site.structure,
                                             site.spheres, options);
  EXPECT_LT(local.surface.n_vertices(), 4 * whole.surface.n_vertices() / 5);
  EXPECT_EQ(local.surface.source(), pdb.string());

  const Eigen::MatrixX3d whole_positions = whole.surface.positions();
  const Eigen::MatrixX3d local_positions = local.surface.positions();
  const Eigen::VectorXd whole_esp = whole.surface.property(mesh::property::esp);
  const Eigen::VectorXd local_esp = local.surface.property(mesh::property::esp);
  const Eigen::VectorXd whole_lp = whole.surface.property(mesh::property::lp);
  const Eigen::VectorXd local_lp = local.surface.property(mesh::property::lp);
  std::size_t compared = 0;
  double worst_position = 0.0, worst_esp = 0.0, worst_lp = 0.0;
  for (Eigen::Index v = 0; v < whole_positions.rows(); ++v) {
    const Eigen::Vector3d x = whole_positions.row(v).transpose();
    const bool seen = std::any_of(site.spheres.begin(), site.spheres.end(), [&](const auto& s) {
      return (x - s.center).norm() <= s.radius + options.patch.radius;
    });
    if (!seen) continue;
    ++compared;
    Eigen::Index nearest = 0;
    worst_position =
        std::max(worst_position,
                 (local_positions.rowwise() - x.transpose()).rowwise().norm().minCoeff(&nearest));
    worst_esp = std::max(worst_esp, std::abs(whole_esp(v) - local_esp(nearest)));
    worst_lp = std::max(worst_lp, std::abs(whole_lp(v) - local_lp(nearest)));
  }
  EXPECT_GT(compared, 5000u);
  EXPECT_LT(worst_position, 1e-9);
  EXPECT_LT(worst_esp, 1e-6);
  EXPECT_LT(worst_lp, 1e-9);

  const std::vector<bool> whole_in = matching::critical_points_in_site(whole, site.spheres);
  const std::vector<bool> local_in = matching::critical_points_in_site(local, site.spheres);
  std::vector<std::size_t> whole_cps, local_cps;
  for (std::size_t i = 0; i < whole_in.size(); ++i)
    if (whole_in[i]) whole_cps.push_back(i);
  for (std::size_t i = 0; i < local_in.size(); ++i)
    if (local_in[i]) local_cps.push_back(i);
  ASSERT_EQ(local_cps.size(), whole_cps.size());
  ASSERT_GT(whole_cps.size(), 20u);
  for (std::size_t k = 0; k < whole_cps.size(); ++k) {
    const auto& w = whole.critical_points[whole_cps[k]];
    const auto& l = local.critical_points[local_cps[k]];
    EXPECT_LT((w.point.position - l.point.position).norm(), 1e-9) << k;
    EXPECT_EQ(w.status, l.status) << k;
    ASSERT_EQ(w.image.values.size(), l.image.values.size()) << k;
    if (w.image.values.size() > 0) {
      EXPECT_LT((w.image.values - l.image.values).cwiseAbs().maxCoeff(), 1e-9) << k;
    }
  }
}

// A pocket library stores the site's neighbourhood, not the structure: written as PDB and read
// back, it gives the site the same surface, with the same ESP (every charged atom is kept) and
// the same LP wherever the patches look (every atom within the LP cutoff of them is kept).
TEST(SiteNeighbourhood, GivesTheSiteTheStructuresSurfaceAndPotentials) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/4TMN.pdb");
  const Molecule structure = io::read_molecule(pdb);
  const molsurf::BindingSite site = molsurf::binding_site(structure, LigandSelector{"0PK", {}, {}});
  const Molecule kept = molsurf::site_neighbourhood(
      site.structure, site.spheres, site.surface_margin + molsurf::neighbourhood_beyond_margin);
  EXPECT_LT(kept.atoms.size(), site.structure.atoms.size());
  for (const Atom& a : site.structure.atoms) {
    const bool near = std::any_of(site.spheres.begin(), site.spheres.end(), [&](const auto& s) {
      return (a.position - s.center).norm() <= s.radius + site.surface_margin + 4.0;
    });
    if (!near && a.charge == 0.0) continue;
    EXPECT_TRUE(
        std::any_of(kept.atoms.begin(), kept.atoms.end(),
                    [&](const Atom& k) { return k.position == a.position && k.name == a.name; }))
        << a.name << " " << a.residue_number;
  }
  const std::string text = [&] {
    std::ostringstream out;
    io::write_pdb(kept, out);
    return out.str();
  }();
  io::MoleculeRecord record;
  record.source = pdb.string();
  record.format = io::RecordFormat::structure;
  record.text = text;
  molsurf::BindingSite stored = site;
  stored.structure = io::read_record_molecule(record);
  ASSERT_EQ(stored.structure.atoms.size(), kept.atoms.size());
  for (std::size_t i = 0; i < kept.atoms.size(); ++i)  // the same charges as the whole file gave
    ASSERT_EQ(stored.structure.atoms[i].charge, kept.atoms[i].charge) << i;

  const mesh::Surface whole = molsurf::build_site_surface(site);
  const mesh::Surface local = molsurf::build_site_surface(stored);
  ASSERT_EQ(local.n_vertices(), whole.n_vertices());
  EXPECT_EQ(local.positions(), whole.positions());
  const Eigen::VectorXd esp_gap =
      local.property(mesh::property::esp) - whole.property(mesh::property::esp);
  EXPECT_LT(esp_gap.cwiseAbs().maxCoeff(), 1e-9);
  const Eigen::MatrixX3d positions = whole.positions();
  const Eigen::VectorXd whole_lp = whole.property(mesh::property::lp);
  const Eigen::VectorXd local_lp = local.property(mesh::property::lp);
  std::size_t compared = 0;
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const Eigen::Vector3d x = positions.row(v).transpose();
    const bool seen = std::any_of(site.spheres.begin(), site.spheres.end(), [&](const auto& s) {
      return (x - s.center).norm() <= s.radius + site.surface_margin - 8.0;
    });
    if (!seen) continue;
    ++compared;
    EXPECT_NEAR(local_lp(v), whole_lp(v), 1e-9) << v;
  }
  EXPECT_GT(compared, 5000u);
}

// A site whose spheres reach no atom within the margin is refused, naming the file.
TEST(SiteSurface, ASiteFarFromEveryAtomIsRefused) {
  Molecule m = structure_with_copies();
  molsurf::BindingSiteOptions options;
  options.surface_margin = 2.0;
  const molsurf::BindingSite site =
      molsurf::binding_site(m, {{Eigen::Vector3d(500, 500, 500), 4.0}}, options);
  try {
    (void)molsurf::build_site_surface(site);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("copies.pdb: no atom lies within 2 A"), std::string::npos)
        << e.what();
  }
}

// The margin a site's surface is built with grows with the patch radius it is described with,
// also when a stored description on the other side fixes that radius.
TEST(SiteSurface, TheMarginGrowsWithThePatchRadiusTheOtherSideFixes) {
  EXPECT_EQ(molsurf::site_surface_margin(16.0, 5.0), 16.0);
  EXPECT_EQ(molsurf::site_surface_margin(16.0, 12.0), 20.0);
  EXPECT_EQ(molsurf::site_surface_margin(5.0, 5.0), 13.0);
  EXPECT_EQ(molsurf::site_surface_margin(0.0, 12.0), 0.0);
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/4TMN.pdb");
  matching::MatchInput site;
  site.molecule = io::read_molecule(pdb);
  site.site_ligand = "0PK";
  matching::MatchInputOptions wide;
  wide.descriptors.patch.radius = 12.0;
  const matching::PreparedInput stored = matching::prepare_input(site, wide);
  matching::MatchInput reference;
  reference.descriptors = stored.descriptors;
  reference.site_spheres = stored.site;
  matching::MatchInputOptions defaults;  // patch radius 5: the stored side's 12 prevails
  defaults.match.refine_top = 1;
  defaults.match.principal_axes_starts = 0;
  const matching::InputMatch compared = matching::match_inputs(reference, site, defaults);
  EXPECT_EQ(compared.probe.descriptors.options.patch.radius, 12.0);
  EXPECT_EQ(compared.probe.descriptors.surface.n_vertices(),
            stored.descriptors.surface.n_vertices());
  const molsurf::BindingSite narrow =
      molsurf::binding_site(*site.molecule, LigandSelector{"0PK", {}, {}});  // margin 16
  EXPECT_GT(stored.descriptors.surface.n_vertices(),
            molsurf::build_site_surface(narrow).n_vertices());
}

// Lining composition by hand: the residues with a heavy atom within a sphere's radius + 1 A,
// counted once each by chain, number and name, as class fractions; hydrogens, hetero residues
// and non-standard names are not lining residues.
TEST(LiningComposition, CountsEachLiningResidueOnceByClass) {
  Molecule structure;
  structure.atoms = {atom("N", {0, 0, 0}, "LYS", 1, "A", false),
                     atom("C", {0.5, 0, 0}, "LYS", 1, "A", false),  // the same residue
                     atom("C", {4.9, 0, 0}, "GLY", 2, "A", false),  // inside r + 1
                     atom("C", {0, 4.5, 0}, "GLY", 2, "B", false),  // another chain: another
                     atom("C", {5.1, 0, 0}, "ASP", 3, "A", false),  // just beyond r + 1
                     atom("H", {0, 0, 1}, "ALA", 4, "A", false),    // a hydrogen only
                     atom("C", {0, 0, -1}, "HEM", 5, "A", true),    // not an amino acid
                     atom("C", {0, -1, 0}, "MSE", 6, "A", false)};  // not a standard one
  const std::vector<molsurf::SiteSphere> spheres{{Eigen::Vector3d::Zero(), 4.0}};
  const matching::LiningComposition lining =
      matching::lining_composition(structure, spheres).value();
  matching::LiningComposition expected{};
  expected[3] = 1.0 / 3.0;  // basic: LYS
  expected[6] = 2.0 / 3.0;  // GLY, in chains A and B
  for (std::size_t k = 0; k < matching::lining_classes; ++k)
    EXPECT_DOUBLE_EQ(lining[k], expected[k]) << "class " << k;
  // A longer reach takes the ASP in: basic 1/4, acidic 1/4, GLY 1/2.
  const matching::LiningComposition wider =
      matching::lining_composition(structure, spheres, 1.2).value();
  EXPECT_DOUBLE_EQ(wider[4], 0.25);
  EXPECT_DOUBLE_EQ(wider[6], 0.5);
  // The histogram intersection: 1 with itself, the shared fractions otherwise, symmetric, and 0
  // against an empty composition.
  EXPECT_DOUBLE_EQ(matching::lining_similarity(lining, lining), 1.0);
  EXPECT_DOUBLE_EQ(matching::lining_similarity(lining, wider), 0.25 + 0.5);
  EXPECT_DOUBLE_EQ(matching::lining_similarity(wider, lining), 0.75);
  EXPECT_DOUBLE_EQ(matching::lining_similarity(lining, matching::LiningComposition{}), 0.0);
  // Spheres no residue reaches have no composition.
  EXPECT_FALSE(matching::lining_composition(structure, {{Eigen::Vector3d(50, 0, 0), 4.0}}));
  EXPECT_DOUBLE_EQ(matching::site_score(0.4, 0.75, 0.3), (0.4 + 0.3 * 0.75) / 1.3);
  EXPECT_DOUBLE_EQ(matching::site_score(0.4, 0.75, 0.0), 0.4);
}

// The z-score against the null: 0 at the null's mean, one per spread above it, sizes clamped to
// the fitted range, and the default null's spread positive over all of it.
TEST(SiteZScore, CountsSpreadsAboveTheNullOfTheSmallerSite) {
  const matching::SiteScoreNull null{0.1, 0.2, 0.3, -0.05, 100.0, 10000.0};
  const auto mean = [&](double n) { return 0.1 + 0.2 * std::log10(n); };
  const auto spread = [&](double n) { return 0.3 - 0.05 * std::log10(n); };
  EXPECT_NEAR(matching::site_z_score(mean(1000.0), 1000, 5000, null), 0.0, 1e-12);
  EXPECT_NEAR(matching::site_z_score(mean(1000.0) + 2.0 * spread(1000.0), 5000, 1000, null), 2.0,
              1e-12);
  EXPECT_NEAR(matching::site_z_score(mean(100.0) + spread(100.0), 10, 20, null), 1.0, 1e-12);
  EXPECT_NEAR(matching::site_z_score(mean(10000.0), 50000, 90000, null), 0.0, 1e-12);
  EXPECT_THROW(matching::site_z_score(0.5, 0, 100, null), InputError);
  EXPECT_THROW(matching::site_z_score(0.5, 10, 100, {0.1, 0.2, 0.3, -0.05, 500.0, 100.0}),
               InputError);  // an empty range
  EXPECT_THROW(matching::site_z_score(0.5, 10, 100, {0.1, 0.2, 0.1, -0.05, 100.0, 10000.0}),
               InputError);  // spread 0.1 - 0.05 * 4 < 0 at 10,000 points
  const matching::SiteScoreNull& fitted = matching::site_score_null;
  EXPECT_LT(fitted.min_points, fitted.max_points);
  for (const double n : {fitted.min_points, fitted.max_points})
    EXPECT_GT(fitted.spread_intercept + fitted.spread_slope * std::log10(n), 0.0) << n;
}

Atom named(const std::string& element, const std::string& name, const std::string& residue) {
  Atom a = atom(element, Eigen::Vector3d::Zero(), residue, 1, "A", false);
  a.name = name;
  return a;
}

// The interaction a contact meets, class by class, for the atoms the classes are defined by.
TEST(Interactions, EachAtomOffersItsClass) {
  using matching::Interaction;
  const auto weight = [](const Atom& a, Interaction kind) {
    return matching::interaction_of(a)[static_cast<std::size_t>(kind)];
  };
  EXPECT_EQ(weight(named("N", "NZ", "LYS"), Interaction::positive), 1.0);
  EXPECT_EQ(weight(named("N", "NH2", "ARG"), Interaction::positive), 1.0);
  EXPECT_EQ(weight(named("O", "OD2", "ASP"), Interaction::negative), 1.0);
  EXPECT_EQ(weight(named("O", "OE1", "GLU"), Interaction::negative), 1.0);
  EXPECT_EQ(weight(named("N", "N", "GLY"), Interaction::donor), 1.0);
  EXPECT_EQ(weight(named("N", "N", "PRO"), Interaction::hydrophobic), 1.0);
  EXPECT_EQ(weight(named("O", "O", "ALA"), Interaction::acceptor), 1.0);
  EXPECT_EQ(weight(named("O", "OG", "SER"), Interaction::donor), 0.5);
  EXPECT_EQ(weight(named("O", "OG", "SER"), Interaction::acceptor), 0.5);
  EXPECT_EQ(weight(named("C", "CZ", "PHE"), Interaction::aromatic), 1.0);
  EXPECT_EQ(weight(named("C", "CB", "PHE"), Interaction::hydrophobic), 1.0);
  EXPECT_EQ(weight(named("S", "SD", "MET"), Interaction::hydrophobic), 1.0);
  Atom zinc = named("Zn", "ZN", "ZN");
  zinc.hetero = true;
  EXPECT_EQ(weight(zinc, Interaction::positive), 1.0);
  EXPECT_EQ(weight(named("P", "PA", "ATP"), Interaction::negative), 1.0);
  const matching::InteractionComposition hydrogen =
      matching::interaction_of(named("H", "H", "ALA"));
  for (double w : hydrogen) EXPECT_EQ(w, 0.0);
}

/// The interaction points of a grid of vertices, 1 A apart, over x and y in [-4, 4], beside a
/// lysine NZ (x < 0) and an aspartate OD1 (x > 0); the site: a sphere of radius `r` around
/// `center`.
std::vector<matching::InteractionPoint> two_class_site(const Eigen::Vector3d& center, double r) {
  Molecule structure;
  Atom lysine = named("N", "NZ", "LYS");
  lysine.position = {-3, 0, -2};
  Atom aspartate = named("O", "OD1", "ASP");
  aspartate.position = {3, 0, -2};
  structure.atoms = {lysine, aspartate};
  std::vector<Eigen::Vector3d> vertices;
  for (int i = -4; i <= 4; ++i) {
    for (int j = -4; j <= 4; ++j) vertices.emplace_back(i + 0.5, j, 0);
  }
  Eigen::MatrixX3d positions(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    positions.row(static_cast<Eigen::Index>(v)) = vertices[v].transpose();
  }
  Eigen::MatrixX3i faces(1, 3);
  faces << 0, 1, 9;
  const mesh::Surface surface = mesh::Surface::from_arrays(positions, faces, "grid");
  return matching::interaction_points(surface, structure, {{center, r}});
}

// A site compared with itself, moved, and with a part of itself: the aligned agreement is 1
// where every point meets its like, the part is covered whole (partial matching), and a site
// whose classes are swapped agrees nowhere.
TEST(Interactions, AlignedPointsAgreeClassForClassAndAPartIsCovered) {
  const std::vector<matching::InteractionPoint> whole = two_class_site({0, 0, 0}, 10.0);
  ASSERT_EQ(whole.size(), 81u);
  const matching::InteractionComposition composition =
      matching::interaction_composition(whole).value();
  // x = -3.5 .. -0.5 nearer the lysine (36 points), 0.5 .. 4.5 nearer the aspartate (45).
  EXPECT_DOUBLE_EQ(composition[static_cast<std::size_t>(matching::Interaction::positive)],
                   36.0 / 81.0);
  EXPECT_DOUBLE_EQ(composition[static_cast<std::size_t>(matching::Interaction::negative)],
                   45.0 / 81.0);
  const matching::AlignedInteractions self =
      matching::aligned_interactions(whole, whole, Eigen::Matrix4d::Identity());
  EXPECT_DOUBLE_EQ(self.similarity, 1.0);
  EXPECT_DOUBLE_EQ(self.coverage, 1.0);

  // The same points moved by a rigid motion, and that motion's inverse as the alignment.
  Eigen::Matrix4d motion = Eigen::Matrix4d::Identity();
  motion.topLeftCorner<3, 3>() =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  motion.topRightCorner<3, 1>() = Eigen::Vector3d(5, -2, 9);
  std::vector<matching::InteractionPoint> moved = whole;
  for (auto& point : moved) {
    point.position = motion.topLeftCorner<3, 3>() * point.position + motion.topRightCorner<3, 1>();
  }
  const Eigen::Matrix4d back = motion.inverse();
  EXPECT_NEAR(matching::aligned_interactions(whole, moved, back).similarity, 1.0, 1e-12);
  EXPECT_NEAR(matching::aligned_interactions(moved, whole, motion).coverage, 1.0, 1e-12);
  EXPECT_EQ(matching::aligned_interactions(whole, moved, Eigen::Matrix4d::Identity()).similarity,
            0.0);

  // A cut: the points within 2.5 A of (2, 0, 0), all nearer the aspartate. The cut lies
  // whole inside the site (coverage 1); the similarity counts the site's unmatched points (with
  // contacts closer than the grid's 1 A, only a point's own copy is its contact).
  const std::vector<matching::InteractionPoint> cut = two_class_site({2, 0, 0}, 2.5);
  ASSERT_GT(cut.size(), 10u);
  const matching::AlignedInteractions part =
      matching::aligned_interactions(whole, cut, Eigen::Matrix4d::Identity(), 0.5);
  EXPECT_DOUBLE_EQ(part.coverage, 1.0);
  EXPECT_DOUBLE_EQ(part.similarity, 2.0 * static_cast<double>(cut.size()) /
                                        static_cast<double>(whole.size() + cut.size()));
  EXPECT_DOUBLE_EQ(matching::aligned_interactions(whole, cut, Eigen::Matrix4d::Identity()).coverage,
                   1.0);
  // Mirrored in x, the cut faces the lysine: it keeps its contacts but agrees with none.
  Eigen::Matrix4d mirror = Eigen::Matrix4d::Identity();
  mirror(0, 0) = -1.0;
  mirror(1, 1) = -1.0;  // a rotation by pi about z: x -> -x, y -> -y
  const matching::AlignedInteractions swapped = matching::aligned_interactions(whole, cut, mirror);
  EXPECT_EQ(swapped.coverage, 0.0);
  EXPECT_THROW(matching::aligned_interactions(whole, cut, mirror, 0.0), OptionError);
  EXPECT_FALSE(matching::interaction_composition({}));
}

}  // namespace
}  // namespace surfcomp
