// Pockets found without a ligand, and the structures they are found in: a buried cavity carved
// into a block of atoms is found, and moves with the block; a sheet of atoms has none; 1THL's
// inhibitor site is among its top three pockets; a pocket's site is built on the ATOM records.
// mmCIF (and gzipped mmCIF), written from the PDB files by gemmi here, reads as its PDB file:
// the same atoms, charges, lipophilicities and surface; --min-plddt drops exactly the residues
// whose mean B-factor is below it; broken or empty mmCIF files are refused naming the file.
#include "surfcomp/molsurf/pockets.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include "test_data.hpp"

#define USE_STD_SNPRINTF
#define GEMMI_WRITE_IMPLEMENTATION
#include <gemmi/pdb.hpp>
#include <gemmi/to_cif.hpp>
#include <gemmi/to_mmcif.hpp>
#undef GEMMI_WRITE_IMPLEMENTATION

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

Atom protein_atom(const Eigen::Vector3d& position, int number) {
  Atom a;
  a.element = "C";
  a.name = "CA";
  a.position = position;
  a.radius = 1.7;
  a.residue_name = "ALA";
  a.residue_number = number;
  a.chain = "A";
  return a;
}

/// A cube of side 2 * half (A) of atoms on a 3 A lattice, each moved by a fixed pseudo-random
/// offset of up to 0.3 A (so that no five atoms are cospherical), without the atoms `carved`
/// takes: a closed cavity.
template <typename Carved>
Molecule carved_block(double half, const Carved& carved) {
  Molecule m;
  m.source = "block.pdb";
  const int n = static_cast<int>(std::floor(2 * half / 3.0));
  unsigned state = 12345;
  const auto jitter = [&state] {
    state = state * 1103515245u + 12345u;
    return 0.3 * (static_cast<double>((state >> 8) % 2001) / 1000.0 - 1.0);
  };
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      for (int k = 0; k <= n; ++k) {
        Eigen::Vector3d p = Eigen::Vector3d(i, j, k) * 3.0 - Eigen::Vector3d::Constant(half);
        p += Eigen::Vector3d(jitter(), jitter(), jitter());
        if (carved(p)) continue;
        m.atoms.push_back(protein_atom(p, static_cast<int>(m.atoms.size()) / 4 + 1));
      }
    }
  }
  return m;
}

/// carved_block without the atoms within `cavity` A of the centre.
Molecule block_with_cavity(double half, double cavity) {
  return carved_block(half, [cavity](const Eigen::Vector3d& p) { return p.norm() < cavity; });
}

TEST(DetectPockets, FindsAClosedCavityAndMovesWithTheStructure) {
  const Molecule block = block_with_cavity(12.0, 6.0);
  const std::vector<molsurf::Pocket> pockets = molsurf::detect_pockets(block);
  ASSERT_FALSE(pockets.empty());
  const molsurf::Pocket& cavity = pockets.front();
  EXPECT_EQ(cavity.rank, 1);
  EXPECT_LT(cavity.center.norm(), 1.0);
  // Rays from inside meet the wall but for the few that run along the lattice's channels.
  EXPECT_GT(cavity.buriedness, 0.9);
  for (const molsurf::SiteSphere& s : cavity.spheres) {
    EXPECT_LT(s.center.norm(), 6.0);  // inside the carved ball
  }
  // Its lining is the cavity's wall: atoms within a lattice step of the carved ball.
  for (std::size_t atom : cavity.lining_atoms) {
    const double r = block.atoms[atom].position.norm();
    EXPECT_GE(r, 6.0);
    EXPECT_LT(r, 6.0 + 3.0 * std::sqrt(3.0));
  }
  EXPECT_GT(cavity.volume, 0.0);
  EXPECT_LT(cavity.volume, 4.0 / 3.0 * M_PI * 6.0 * 6.0 * 6.0);

  // A rigid motion moves the cavity's pocket by the same motion and changes nothing else of it.
  const Eigen::Isometry3d motion =
      Eigen::Translation3d(20.0, -7.0, 3.0) *
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(1.0, 2.0, -0.5).normalized());
  Molecule moved = block;
  for (Atom& atom : moved.atoms) atom.position = motion * atom.position;
  const std::vector<molsurf::Pocket> moved_pockets = molsurf::detect_pockets(moved);
  ASSERT_FALSE(moved_pockets.empty());
  const molsurf::Pocket& moved_cavity = moved_pockets.front();
  EXPECT_LT((moved_cavity.center - motion * cavity.center).norm(), 1e-6);
  EXPECT_EQ(moved_cavity.spheres.size(), cavity.spheres.size());
  EXPECT_EQ(moved_cavity.lining_atoms, cavity.lining_atoms);
  EXPECT_NEAR(moved_cavity.volume, cavity.volume, 0.05 * cavity.volume);  // an axis-aligned grid

  // The same input gives the same pockets.
  const std::vector<molsurf::Pocket> again = molsurf::detect_pockets(block);
  ASSERT_EQ(again.size(), pockets.size());
  for (std::size_t k = 0; k < pockets.size(); ++k) {
    EXPECT_EQ(again[k].center, pockets[k].center);
    EXPECT_EQ(again[k].score, pockets[k].score);
  }
}

// Two lobes (balls of 5.5 A around (+-6, 0, 0)) joined by a channel (4.5 A around the x axis):
// one cavity. Unsplit, it is one pocket; with a volume cap below the whole's, it splits into
// sub-pockets of at most the cap, the two lobes, which share the cavity and its spheres.
TEST(DetectPockets, ATwoLobeCavitySplitsIntoItsLobes) {
  const Molecule block = carved_block(18.0, [](const Eigen::Vector3d& p) {
    const double lobe =
        std::min((p - Eigen::Vector3d(-6, 0, 0)).norm(), (p - Eigen::Vector3d(6, 0, 0)).norm());
    return lobe < 5.5 || (std::abs(p.x()) < 6.0 && std::hypot(p.y(), p.z()) < 4.5);
  });
  const std::vector<molsurf::Pocket> whole = molsurf::detect_pockets(block);
  ASSERT_FALSE(whole.empty());
  const molsurf::Pocket& cavity = whole.front();
  EXPECT_EQ(cavity.cavity, 1);
  const auto spans_both = [](const molsurf::Pocket& p) {
    bool left = false, right = false;
    for (const molsurf::SiteSphere& s : p.spheres) {
      left = left || s.center.x() < -4.0;
      right = right || s.center.x() > 4.0;
    }
    return left && right;
  };
  ASSERT_TRUE(spans_both(cavity));

  molsurf::PocketOptions split;
  split.max_volume = 0.6 * cavity.volume;
  const std::vector<molsurf::Pocket> parts = molsurf::detect_pockets(block, split);
  std::vector<const molsurf::Pocket*> of_cavity;
  std::size_t spheres = 0;
  for (const molsurf::Pocket& p : parts) {
    if (p.cavity != 1) continue;
    of_cavity.push_back(&p);
    spheres += p.spheres.size();
    EXPECT_LE(p.volume, split.max_volume);
    EXPECT_FALSE(spans_both(p));
  }
  ASSERT_GE(of_cavity.size(), 2u);
  EXPECT_EQ(spheres, cavity.spheres.size());  // the parts partition the cavity's spheres
  // The cavity's parts lie in the lobes, some in each; its best part is pocket 1.
  EXPECT_EQ(of_cavity[0]->rank, 1);
  const auto in_lobe = [&](double side) {
    return std::any_of(of_cavity.begin(), of_cavity.end(),
                       [side](const molsurf::Pocket* p) { return side * p->center.x() > 4.0; });
  };
  EXPECT_TRUE(in_lobe(-1.0));
  EXPECT_TRUE(in_lobe(1.0));
  // Deterministic.
  const std::vector<molsurf::Pocket> again = molsurf::detect_pockets(block, split);
  ASSERT_EQ(again.size(), parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k) EXPECT_EQ(again[k].center, parts[k].center);
  molsurf::PocketOptions negative;
  negative.max_volume = -1.0;
  EXPECT_THROW(molsurf::detect_pockets(block, negative), OptionError);
}

TEST(DetectPockets, ASheetOfAtomsHasNoPocket) {
  Molecule sheet;
  sheet.source = "sheet.pdb";
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j < 12; ++j) {
      sheet.atoms.push_back(protein_atom(
          Eigen::Vector3d(3.0 * i + 0.1 * ((i * j) % 3), 3.0 * j, 0.2 * ((i + 2 * j) % 3)), i + 1));
    }
  }
  EXPECT_TRUE(molsurf::detect_pockets(sheet).empty());
}

TEST(DetectPockets, RefusesStructuresWithoutProteinAtomsAndBadOptions) {
  Molecule ligand = block_with_cavity(6.0, 0.0);
  for (Atom& atom : ligand.atoms) atom.hetero = true;
  try {
    molsurf::detect_pockets(ligand);
    FAIL() << "a structure of HETATM records only was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("block.pdb: no protein atom"), std::string::npos)
        << e.what();
  }
  molsurf::PocketOptions crossed;
  crossed.min_sphere_radius = 5.0;
  crossed.max_sphere_radius = 4.0;
  EXPECT_THROW(molsurf::detect_pockets(block_with_cavity(9.0, 4.0), crossed), OptionError);
  EXPECT_THROW(molsurf::pocket_site(block_with_cavity(12.0, 6.0), 50), InputError);
}

TEST(DetectPockets, ThermolysinInhibitorSiteIsInTheTopThreeOf1THL) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/1THL.pdb");
  const Molecule structure = io::read_molecule(pdb);
  std::vector<Eigen::Vector3d> ligand;
  for (std::size_t i : select_ligand(structure, LigandSelector{"0DB", {}, {}})) {
    if (structure.atoms[i].element != "H") ligand.push_back(structure.atoms[i].position);
  }
  const std::vector<molsurf::Pocket> pockets = molsurf::detect_pockets(structure);
  ASSERT_GE(pockets.size(), 3u);
  // The site is found by the first of the top three pockets whose alpha spheres hold at least
  // half the inhibitor's heavy atoms.
  int found = 0;
  for (std::size_t k = 0; k < 3 && found == 0; ++k) {
    std::size_t inside = 0;
    for (const Eigen::Vector3d& atom : ligand) {
      for (const molsurf::SiteSphere& s : pockets[k].spheres) {
        if ((atom - s.center).norm() <= s.radius) {
          ++inside;
          break;
        }
      }
    }
    if (2 * inside >= ligand.size()) found = pockets[k].rank;
  }
  ASSERT_GE(found, 1);
  // A pocket's site lies on the protein alone: no HETATM record (inhibitor, zinc, calcium).
  const molsurf::BindingSite site = molsurf::pocket_site(structure, found);
  for (const Atom& atom : site.structure.atoms) EXPECT_FALSE(atom.hetero) << atom.residue_name;
  EXPECT_EQ(site.spheres.size(), pockets[static_cast<std::size_t>(found - 1)].spheres.size());
}

/// `pdb` written as mmCIF by gemmi at `cif` (gzipped by gzip when the name ends in .gz).
void write_mmcif(const fs::path& pdb, const fs::path& cif) {
  const gemmi::Structure structure = gemmi::read_pdb_file(pdb.string());
  const bool gzipped = cif.extension() == ".gz";
  const fs::path text = gzipped ? fs::path(cif).replace_extension() : cif;
  {
    std::ofstream file(text);
    gemmi::cif::write_cif_to_stream(file, gemmi::make_mmcif_document(structure));
  }
  if (gzipped) {
    ASSERT_EQ(std::system(("gzip -f '" + text.string() + "'").c_str()), 0);
  }
}

void expect_same_atoms(const Molecule& a, const Molecule& b) {
  ASSERT_EQ(a.atoms.size(), b.atoms.size());
  for (std::size_t i = 0; i < a.atoms.size(); ++i) {
    const Atom& x = a.atoms[i];
    const Atom& y = b.atoms[i];
    EXPECT_EQ(x.element, y.element) << i;
    EXPECT_EQ(x.name, y.name) << i;
    EXPECT_EQ(x.residue_name, y.residue_name) << i;
    EXPECT_EQ(x.residue_number, y.residue_number) << i;
    EXPECT_EQ(x.chain, y.chain) << i;
    EXPECT_EQ(x.hetero, y.hetero) << i;
    EXPECT_EQ(x.position, y.position) << i;
    EXPECT_EQ(x.charge, y.charge) << i;
    EXPECT_EQ(x.radius, y.radius) << i;
    EXPECT_EQ(x.lipophilicity, y.lipophilicity) << i;
  }
}

class Mmcif : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("surfcomp_mmcif_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(Mmcif, ReadsAsItsPdbFileWithTheSameSurface) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/1THL.pdb");
  write_mmcif(pdb, dir_ / "1THL.cif");
  write_mmcif(pdb, dir_ / "1thl.cif.gz");
  EXPECT_TRUE(io::is_molecule_file(dir_ / "1thl.cif.gz"));
  EXPECT_EQ(io::structure_stem(dir_ / "1thl.cif.gz"), "1thl");
  const Molecule from_pdb = io::read_molecule(pdb);
  const Molecule from_cif = io::read_molecule(dir_ / "1THL.cif");
  expect_same_atoms(from_pdb, from_cif);
  expect_same_atoms(from_pdb, io::read_molecule(dir_ / "1thl.cif.gz"));
  // A ligand selected from mmCIF is the PDB file's, Crippen contributions included.
  io::MoleculeReadOptions ligand;
  ligand.ligand = "0DB";
  expect_same_atoms(io::read_molecule(pdb, ligand), io::read_molecule(dir_ / "1THL.cif", ligand));

  // The same atoms give the same surface, vertex for vertex, and the same pockets.
  const mesh::Surface a = molsurf::build_molecular_surface(from_pdb);
  const mesh::Surface b = molsurf::build_molecular_surface(from_cif);
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  EXPECT_EQ(a.positions(), b.positions());
  EXPECT_EQ(a.property(mesh::property::esp), b.property(mesh::property::esp));
  const auto pockets_pdb = molsurf::detect_pockets(from_pdb);
  const auto pockets_cif = molsurf::detect_pockets(from_cif);
  ASSERT_EQ(pockets_pdb.size(), pockets_cif.size());
  for (std::size_t k = 0; k < pockets_pdb.size(); ++k)
    EXPECT_EQ(pockets_pdb[k].center, pockets_cif[k].center);
}

TEST_F(Mmcif, MinPlddtDropsTheResiduesWhoseMeanBFactorIsBelowIt) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/1THL.pdb");
  // The residues' mean B-factors, from the file's columns.
  std::map<std::string, std::pair<double, int>> mean;
  std::ifstream in(pdb);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("ENDMDL", 0) == 0) break;
    if (line.rfind("ATOM  ", 0) != 0 && line.rfind("HETATM", 0) != 0) continue;
    auto& [sum, count] = mean[line.substr(17, 10)];
    sum += std::stod(line.substr(60, 6));
    ++count;
  }
  const double threshold = 20.0;
  std::set<std::string> kept_residues;
  for (const auto& [key, value] : mean) {
    const std::string name = key.substr(0, 3);
    if (value.first / value.second >= threshold && name != "HOH")
      kept_residues.insert(key.substr(4, 1) + ":" + std::to_string(std::stoi(key.substr(5, 4))) +
                           ":" + name);
  }
  io::MoleculeReadOptions options;
  options.min_plddt = threshold;
  write_mmcif(pdb, dir_ / "1THL.cif");
  for (const fs::path& file : {pdb, dir_ / "1THL.cif"}) {
    const Molecule read = io::read_molecule(file, options);
    std::set<std::string> residues;
    for (const Atom& atom : read.atoms) {
      residues.insert(atom.chain + ":" + std::to_string(atom.residue_number) + ":" +
                      atom.residue_name);
    }
    EXPECT_EQ(residues, kept_residues) << file;
    EXPECT_LT(residues.size(), mean.size());
  }
  options.min_plddt = 99.0;
  try {
    io::read_molecule(dir_ / "1THL.cif", options);
    FAIL() << "a --min-plddt that removes every residue was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("1THL.cif: no residue has a pLDDT"), std::string::npos)
        << e.what();
  }
}

TEST_F(Mmcif, BrokenAndEmptyFilesAreRefusedNamingTheFile) {
  std::ofstream(dir_ / "empty.cif") << "data_EMPTY\n_entry.id EMPTY\n";
  std::ofstream(dir_ / "cut.cif") << "data_CUT\nloop_\n_atom_site.group_PDB\n_atom_site.id\n"
                                     "_atom_site.type_symbol\n_atom_site.Cartn_x\n"
                                     "ATOM 1 C 1.0\n'unterminated\n";
  std::ofstream(dir_ / "zero.cif").flush();
  std::ofstream(dir_ / "no_block.cif") << "# a comment, and no data_ block\n";
  const auto refused = [&](const std::string& name, const std::string& reason) {
    try {
      io::read_molecule(dir_ / name);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(name), std::string::npos) << message;
      EXPECT_NE(message.find(reason), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      // The C++ library's own words never reach the user.
      EXPECT_EQ(message.find("_M_range_check"), std::string::npos) << message;
    }
  };
  refused("empty.cif", "");
  refused("cut.cif", "");
  refused("zero.cif", "the file is empty");
  refused("no_block.cif", "no data_ block");
}

TEST_F(Mmcif, ACompressedFileCutShortIsSaidToBeCutShort) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/1THL.pdb");
  write_mmcif(pdb, dir_ / "whole.cif.gz");
  std::ifstream in(dir_ / "whole.cif.gz", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 100u);
  // Cut at 10 % (inside the deflate stream), and without only the 8-byte trailer (CRC, size).
  for (const std::size_t kept : {bytes.size() / 10, bytes.size() - 8, bytes.size() - 1}) {
    const std::string name = "cut" + std::to_string(kept) + ".cif.gz";
    std::ofstream(dir_ / name, std::ios::binary) << bytes.substr(0, kept);
    try {
      io::read_molecule(dir_ / name);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(name + ": the compressed file is cut short"),
                std::string::npos)
          << e.what();
    }
  }
  std::ofstream(dir_ / "empty.cif.gz").flush();
  try {
    io::read_molecule(dir_ / "empty.cif.gz");
    ADD_FAILURE() << "empty.cif.gz was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("empty.cif.gz: the file is empty"), std::string::npos)
        << e.what();
  }
  EXPECT_GT(io::read_molecule(dir_ / "whole.cif.gz").atoms.size(), 2000u);
}

}  // namespace
}  // namespace surfcomp
