// A dock as a user asks for it, on thermolysin and its inhibitor of 1TMN in the pocket carved
// around it: the score's optimum lies at the crystal pose; a moved ligand gets distinct, ordered
// poses inside the site; what a dock cannot do is refused in one line before the work.
#include "pocket_cut.hpp"
#include "test_data.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/docking/dock.hpp"
#include "surfcomp/report/dock_files.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace surfcomp::docking {
namespace {

Eigen::Matrix3Xd heavy_positions(const Molecule& m) {
  std::vector<Eigen::Vector3d> out;
  for (const Atom& a : m.atoms) {
    if (a.element != "H") out.push_back(a.position);
  }
  Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(out.size()));
  for (std::size_t i = 0; i < out.size(); ++i) points.col(static_cast<Eigen::Index>(i)) = out[i];
  return points;
}

double rmsd(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) {
  return std::sqrt((a - b).colwise().squaredNorm().mean());
}

class Thermolysin : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto structure = test::shared_dataset("thermolysin/1TMN.pdb");
    const auto ligand = test::shared_dataset("thermolysin/ligands-original/ligand1TMN.sdf");
    if (!structure || !ligand)
      SURFCOMP_DATA_ABSENT(test::shared_absent_message("thermolysin/1TMN.pdb"));
    structure_ = *structure;
    ligand_ = *ligand;
    // The pocket carved around the crystal ligand (0ZN), which the dock takes out again.
    test::write_pocket(structure_, "0ZN", 16.0, pocket_);
  }

  test::TempDir dir_;
  std::filesystem::path structure_, ligand_, pocket_ = dir_ / "pocket.pdb";
};

TEST_F(Thermolysin, TheCrystalPoseLiesInABasinOfTheScore) {
  // The score, refined from the crystal pose, stays within 2 A of it and does not push the
  // ligand into the receptor: the pose a dock should find is an optimum of what it maximises.
  DockOptions options;
  options.site_ligand = "0ZN";
  matching::MatchInput ligand, receptor;
  ligand.path = ligand_;
  receptor.path = pocket_;
  const matching::PreparedInput site =
      matching::prepare_input(with_dock_site(receptor, options), options.inputs);
  const matching::PreparedInput prepared = matching::prepare_input(ligand, options.inputs);
  const ReceptorField field(*site.molecule, site.site, options.complementarity);
  const LigandSample sample = sample_ligand(prepared.descriptors.surface, 1.0);
  const matching::RigidTransform refined = refine_pose(field, sample, {});
  const Eigen::Matrix3Xd crystal = heavy_positions(io::read_molecule(ligand_));
  EXPECT_LT(rmsd(refined.apply(crystal), crystal), 2.0);
  const ComplementarityScore score = field.score(sample, refined);
  EXPECT_LT(score.deepest, 2.0 * options.complementarity.clash_tolerance);
  EXPECT_GT(score.contact, 0.4);  // 0.58 measured: the inhibitor lies in a groove
  EXPECT_GT(score.esp, 0.0);      // opposite potentials meet across the contact
}

TEST_F(Thermolysin, AMovedLigandIsDockedBackToItsCrystalPose) {
  // Rotated by 130 degrees about a skew axis and moved 12 A away, the inhibitor comes back
  // within 2 A of its crystal pose (bench/redock_bench.py's 1TMN redock: docs/benchmarks.md),
  // and the other poses are distinct, ordered and in the site.
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(130.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, -1).normalized())
          .toRotationMatrix();
  const Eigen::Vector3d shift(12.0, -5.0, 7.0);
  const std::filesystem::path moved =
      dir_.write("moved.sdf", io::moved_mol_block(ligand_, turn, shift));
  DockOptions options;
  options.site_ligand = "0ZN";
  matching::MatchInput ligand, receptor;
  ligand.path = moved;
  receptor.path = pocket_;
  const DockResult docked = dock(ligand, receptor, options);
  ASSERT_FALSE(docked.poses.empty());
  EXPECT_LE(docked.poses.size(), 9u);
  const Eigen::Matrix3Xd start = heavy_positions(io::read_molecule(moved));
  const Eigen::Matrix3Xd crystal = heavy_positions(io::read_molecule(ligand_));
  const Eigen::Matrix4d& top = docked.poses.front().transform;
  EXPECT_LT(
      rmsd((top.topLeftCorner<3, 3>() * start).colwise() + top.topRightCorner<3, 1>(), crystal),
      2.0);
  EXPECT_FALSE(docked.poses.front().intersects);
  // The search reads a coarser sample of the ligand's surface; every pose's score is that of
  // the score's own sample, as a user would recompute it.
  const ReceptorField field(*docked.receptor.molecule, docked.receptor.site,
                            options.complementarity);
  const LigandSample fine =
      sample_ligand(docked.ligand.descriptors.surface, options.complementarity.sample_spacing);
  for (std::size_t k = 0; k < docked.poses.size(); ++k) {
    const DockPose& pose = docked.poses[k];
    EXPECT_EQ(pose.rank, static_cast<int>(k) + 1);
    EXPECT_NEAR(pose.score.score,
                field.score(fine, matching::RigidTransform::from_matrix(pose.transform)).score,
                1e-12);
    const auto place = [&](const DockPose& p) {
      return Eigen::Matrix3Xd((p.transform.topLeftCorner<3, 3>() * start).colwise() +
                              p.transform.topRightCorner<3, 1>());
    };
    const double determinant = pose.transform.topLeftCorner<3, 3>().determinant();
    EXPECT_NEAR(determinant, 1.0, 1e-9);
    EXPECT_LT(pose.score.outside, 1.0);  // its centre in the site
    if (k > 0) {
      const DockPose& better = docked.poses[k - 1];
      EXPECT_TRUE(better.intersects < pose.intersects ||
                  (better.intersects == pose.intersects && better.score.score >= pose.score.score));
      for (std::size_t j = 0; j < k; ++j)
        EXPECT_GE(rmsd(place(docked.poses[j]), place(pose)), options.distinct_rmsd);
    }
  }
}

TEST_F(Thermolysin, LocalAndScoreOnlyJudgeTheLigandsOwnPose) {
  // --score-only scores the crystal pose as it is; --local-only moves it to the score's nearest
  // optimum, within 2 A of the crystal and scoring at least as well. Each is the one pose, and
  // its score is the score's own sample's at its transform.
  DockOptions options;
  options.site_ligand = "0ZN";
  matching::MatchInput ligand, receptor;
  ligand.path = ligand_;
  receptor.path = pocket_;
  options.score_only = true;
  const DockResult scored = dock(ligand, receptor, options);
  options.score_only = false;
  options.local_only = true;
  const DockResult local = dock(ligand, receptor, options);
  ASSERT_EQ(scored.poses.size(), 1u);
  ASSERT_EQ(local.poses.size(), 1u);
  EXPECT_EQ(local.poses.front().rank, 1);
  EXPECT_TRUE(scored.poses.front().transform.isIdentity(0.0));
  const ReceptorField field(*local.receptor.molecule, local.receptor.site, options.complementarity);
  const LigandSample fine =
      sample_ligand(local.ligand.descriptors.surface, options.complementarity.sample_spacing);
  const auto score_of = [&](const DockPose& p) {
    return field.score(fine, matching::RigidTransform::from_matrix(p.transform)).score;
  };
  EXPECT_NEAR(scored.poses.front().score.score, score_of(scored.poses.front()), 1e-12);
  EXPECT_NEAR(local.poses.front().score.score, score_of(local.poses.front()), 1e-12);
  EXPECT_GE(local.poses.front().score.score, scored.poses.front().score.score);
  const Eigen::Matrix3Xd crystal = heavy_positions(io::read_molecule(ligand_));
  const Eigen::Matrix4d& moved = local.poses.front().transform;
  const Eigen::Matrix3Xd placed =
      (moved.topLeftCorner<3, 3>() * crystal).colwise() + moved.topRightCorner<3, 1>();
  EXPECT_LT(rmsd(placed, crystal), 2.0);
  EXPECT_EQ(local.starts, 0u);

  options.score_only = true;  // with local_only: one question at a time
  EXPECT_THROW(validate(options), OptionError);
  options.score_only = false;
  options.conformers = 2;
  EXPECT_THROW(validate(options), OptionError);
}

TEST_F(Thermolysin, ConformersAreDockedInsteadOfTheLigandsCoordinates) {
  // --conformers: RDKit's conformers of the inhibitor, made from its bonds, are docked and its
  // own coordinates are not; each pose names its conformer, whose atoms (hydrogens as the file
  // has them) are placed in the site. The search is shortened: this asserts the plumbing, and
  // bench/redock_bench.py measures the accuracy (docs/benchmarks.md).
  DockOptions options;
  options.site_ligand = "0ZN";
  options.conformers = 3;
  options.search.chains = 6;
  options.refine_top = 5;
  options.poses = 4;
  matching::MatchInput ligand, receptor;
  ligand.path = ligand_;
  receptor.path = pocket_;
  const DockResult docked = dock(ligand, receptor, options);
  ASSERT_FALSE(docked.conformers.empty());
  EXPECT_LE(docked.conformers.size(), 3u);
  ASSERT_FALSE(docked.poses.empty());
  const Molecule own = io::read_molecule(ligand_);
  for (const std::string& block : docked.conformers) {
    const auto positions = io::mdl_coordinates(block);
    ASSERT_TRUE(positions);
    EXPECT_EQ(positions->size(), own.atoms.size());
  }
  const std::string sdf = report::dock_poses_sdf(docked, ligand_);
  for (const DockPose& pose : docked.poses) {
    EXPECT_GE(pose.conformer, 1);
    EXPECT_LE(pose.conformer, static_cast<int>(docked.conformers.size()));
    EXPECT_LT(pose.score.outside, 1.0);  // its centre in the site
  }
  EXPECT_NE(sdf.find(">  <surfcomp_conformer>\n" + std::to_string(docked.poses[0].conformer)),
            std::string::npos);
  // The first record is the top pose's conformer, moved by its transform.
  const auto first = io::mdl_coordinates(sdf.substr(0, sdf.find("$$$$")));
  const auto unmoved = io::mdl_coordinates(
      docked.conformers[static_cast<std::size_t>(docked.poses[0].conformer - 1)]);
  ASSERT_TRUE(first && unmoved);
  ASSERT_EQ(first->size(), unmoved->size());
  const Eigen::Matrix4d& top = docked.poses[0].transform;
  for (std::size_t i = 0; i < first->size(); ++i) {
    const Eigen::Vector3d expected =
        top.topLeftCorner<3, 3>() * (*unmoved)[i] + top.topRightCorner<3, 1>();
    EXPECT_LT(((*first)[i] - expected).norm(), 1e-3);  // the block's four decimals
  }
}

TEST_F(Thermolysin, WhatADockCannotDoIsRefusedInOneLine) {
  DockOptions options;
  matching::MatchInput ligand, receptor;
  ligand.path = ligand_;
  // The ligand alone as a structure: HETATM records only, no protein atoms.
  Molecule hetero = io::read_molecule(ligand_);
  hetero.atoms.erase(std::remove_if(hetero.atoms.begin(), hetero.atoms.end(),
                                    [](const Atom& a) { return a.element == "H"; }),
                     hetero.atoms.end());
  for (Atom& atom : hetero.atoms) atom.hetero = true;
  std::ostringstream pdb;
  io::write_pdb(hetero, pdb);
  receptor.path = dir_.write("ligand.pdb", pdb.str());
  options.site_spheres = {{Eigen::Vector3d(52, 17, -5), 6.0}};
  const std::string no_protein = test::error_of([&] { dock(ligand, receptor, options); });
  EXPECT_NE(no_protein.find("no protein atoms"), std::string::npos) << no_protein;
  // A description alone has no atoms to build the receptor's grid from.
  matching::MatchInput described;
  described.descriptors.emplace();
  const std::string no_atoms = test::error_of([&] { dock(ligand, described, options); });
  EXPECT_NE(no_atoms.find("a receptor is a protein structure"), std::string::npos) << no_atoms;
  options = {};
  options.site_pocket = 1000;
  receptor.path = pocket_;
  EXPECT_THROW(dock(ligand, receptor, options), InputError);
  options = {};
  options.site_ligand = "0ZN";
  options.max_ligand_to_site = 0.05;
  const std::string too_large = test::error_of([&] { dock(ligand, receptor, options); });
  EXPECT_NE(too_large.find("times the free volume"), std::string::npos) << too_large;
  ligand.site_pocket = 1;
  EXPECT_THROW(check_dock_inputs(ligand, receptor, {}), OptionError);
  // Conformers come from an SDF or MOL2 record's bonds, not from a PDB ligand.
  ligand = {};
  ligand.path = dir_.write("ligand_as.pdb", pdb.str());
  options = {};
  options.conformers = 2;
  const std::string no_bonds =
      test::error_of([&] { check_dock_inputs(ligand, receptor, options); });
  EXPECT_NE(no_bonds.find("SDF or MOL2"), std::string::npos) << no_bonds;
}

}  // namespace
}  // namespace surfcomp::docking
