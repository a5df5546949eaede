// The structure-based screen (screen --receptor) on thermolysin: five inhibitors screened into
// 1TMN's pocket (carved around its inhibitor, which the site takes out) give one row per
// molecule, the full docks first and each stage ordered, poses inside the site, the same rows
// whatever the threads, and a refusal for what a receptor screen cannot do.
#include "pocket_cut.hpp"
#include "test_data.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/screening/library_build.hpp"
#include "surfcomp/screening/receptor_screen.hpp"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp::screening {
namespace {

class ThermolysinScreen : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto structure = test::shared_dataset("thermolysin/1TMN.pdb");
    if (!structure) SURFCOMP_DATA_ABSENT(test::shared_absent_message("thermolysin/1TMN.pdb"));
    test::write_pocket(*structure, "0ZN", 16.0, pocket_);
    std::vector<std::filesystem::path> inputs;
    for (const char* entry : {"1THL", "1TLP", "1TMN", "3TMN", "4TMN"}) {
      const auto ligand =
          test::shared_dataset(std::string("thermolysin/ligands-original/ligand") + entry + ".sdf");
      if (ligand) inputs.push_back(*ligand);
    }
    ASSERT_EQ(inputs.size(), 5u);
    build_library(read_library_inputs(inputs), library_path_);
    options_.dock.site_ligand = "0ZN";
    options_.fast_chains = 4;
    options_.fast_steps = 5;
    options_.candidates = 2;
    options_.dock.search.chains = 6;
    options_.dock.search.steps = 10;
    options_.dock.refine_top = 5;
  }

  test::TempDir dir_;
  std::filesystem::path pocket_ = dir_ / "pocket.pdb", library_path_ = dir_ / "inhibitors.sclib";
  ReceptorScreenOptions options_;
};

TEST_F(ThermolysinScreen, RanksEachMoleculeOnceWithTheFullDocksFirst) {
  const Library library(library_path_);
  matching::MatchInput receptor;
  receptor.path = pocket_;
  const ReceptorScreenResult screened = receptor_screen(receptor, library, options_);
  ASSERT_EQ(screened.hits.size(), 5u);
  std::vector<bool> seen(library.size(), false);
  const double tolerance = options_.dock.complementarity.clash_tolerance;
  for (std::size_t k = 0; k < screened.hits.size(); ++k) {
    const ReceptorHit& hit = screened.hits[k];
    EXPECT_FALSE(seen.at(hit.entry));
    seen[hit.entry] = true;
    EXPECT_EQ(hit.stage, k < 2 ? 2 : 1);
    EXPECT_LT(hit.score.outside, 1.0);  // the pose's centre in the site
    const Eigen::Matrix3d rotation = hit.transform.topLeftCorner<3, 3>();
    EXPECT_NEAR(rotation.determinant(), 1.0, 1e-9);
    if (k > 0 && screened.hits[k - 1].stage == hit.stage) {
      const ReceptorHit& before = screened.hits[k - 1];
      const bool a = before.score.deepest > 2 * tolerance, b = hit.score.deepest > 2 * tolerance;
      EXPECT_TRUE(a < b || (a == b && before.score.score >= hit.score.score));
    }
  }
  // A candidate's row is what `dock` gives its molecule: the same best pose and score.
  const LibraryEntry top = library.entry(screened.hits[0].entry);
  matching::MatchInput ligand;
  ligand.molecule = io::read_record_molecule(top.molecule);
  docking::DockOptions one = options_.dock;
  one.poses = 1;
  const docking::DockResult docked = docking::dock(ligand, receptor, one);
  ASSERT_EQ(docked.poses.size(), 1u);
  EXPECT_NEAR(docked.poses[0].score.score, screened.hits[0].score.score, 1e-9);
  EXPECT_TRUE(docked.poses[0].transform.isApprox(screened.hits[0].transform, 1e-9));
  std::ostringstream csv;
  write_receptor_hits_csv(csv, library, screened.hits);
  const std::string text = csv.str();
  EXPECT_EQ(text.rfind("rank,entry,name,source,record,conformer,score,stage,contact", 0), 0u);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 6);

  // The same rows on one thread.
  const ThreadLimit single(1);
  const ReceptorScreenResult again = receptor_screen(receptor, library, options_);
  std::ostringstream csv_again;
  write_receptor_hits_csv(csv_again, library, again.hits);
  EXPECT_EQ(csv_again.str(), text);
}

TEST_F(ThermolysinScreen, RankedByTotalTheRowsGoByScoreTimesArea) {
  const Library library(library_path_);
  matching::MatchInput receptor;
  receptor.path = pocket_;
  ReceptorScreenOptions options = options_;
  options.candidates = 0;
  options.ranking = ReceptorRanking::total;
  const ReceptorScreenResult screened = receptor_screen(receptor, library, options);
  ASSERT_EQ(screened.hits.size(), 5u);
  const double limit = 2.0 * options.dock.complementarity.clash_tolerance;
  for (std::size_t k = 0; k < screened.hits.size(); ++k) {
    const ReceptorHit& hit = screened.hits[k];
    EXPECT_EQ(hit.stage, 1);
    // The area of the stored sample is the molecule's surface area, as its built surface has it.
    matching::MatchInput ligand;
    ligand.molecule = io::read_record_molecule(library.entry(hit.entry).molecule);
    const double built =
        mesh::measure_surface(matching::prepare_input(ligand, {}).descriptors.surface).area;
    EXPECT_NEAR(hit.area, built, 0.1 * built) << hit.entry;
    if (k == 0) continue;
    const ReceptorHit& before = screened.hits[k - 1];
    const bool a = before.score.deepest > limit, b = hit.score.deepest > limit;
    EXPECT_TRUE(a < b ||
                (a == b && before.score.score * before.area >= hit.score.score * hit.area));
  }
}

TEST_F(ThermolysinScreen, WhatAReceptorScreenCannotDoIsRefused) {
  const Library library(library_path_);
  matching::MatchInput receptor;
  receptor.path = pocket_;
  ReceptorScreenOptions options = options_;
  options.dock.conformers = 2;
  const std::string conformers =
      test::error_of([&] { receptor_screen(receptor, library, options); });
  EXPECT_NE(conformers.find("the library holds the conformers"), std::string::npos) << conformers;
  options = options_;
  options.dock.local_only = true;
  const std::string local = test::error_of([&] { receptor_screen(receptor, library, options); });
  EXPECT_NE(local.find("does not apply to a screen: a library's conformers have no pose"),
            std::string::npos)
      << local;
  options = options_;
  options.fast_chains = 0;
  EXPECT_THROW(receptor_screen(receptor, library, options), OptionError);
  options = options_;
  options.dock.site_pocket = 1000;
  options.dock.site_ligand.clear();
  EXPECT_THROW(receptor_screen(receptor, library, options), InputError);
}

}  // namespace
}  // namespace surfcomp::screening
