// The similarity matrix: exact, its entries are `surfcomp match`'s top overlay scores and
// transforms, pair by pair; by default the refined overlays of a screen's stage 2, each row's
// best then given match's; with refined_overlays, a screen's stage 1 and each row's best by it
// refined; all against all it is symmetric, its diagonal the self-match (score 1
// at the identity); the same with one thread and two; a record that cannot be read is left out and
// named while the others are compared; an empty set, a set of one, too many pairs and a file
// that is not a molecule file are refused before any work.
#include "test_data.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/screening/matrix.hpp"
#include "surfcomp/screening/screen.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

/// Three thermolysin inhibitors (each an SDF file of one record), or none when the shared data
/// sets are absent.
std::vector<fs::path> thermolysin_ligands() {
  std::vector<fs::path> files;
  for (const char* entry : {"1THL", "1TLP", "1TMN"}) {
    const auto path =
        test::shared_dataset(std::string("thermolysin/ligands-original/ligand") + entry + ".sdf");
    if (!path) return {};
    files.push_back(*path);
  }
  return files;
}

std::string text_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Each file's molecule described alone, as a screen query (a screen's stages 1 and 2).
std::vector<screening::ScreenQuery> screen_queries(const std::vector<fs::path>& files) {
  std::vector<screening::ScreenQuery> queries;
  for (const fs::path& file : files) {
    matching::MatchInput input;
    input.path = file;
    queries.push_back(
        screening::make_screen_query(matching::prepare_input(input, {}).descriptors, {}));
  }
  return queries;
}

class Matrix : public ::testing::Test {
 protected:
  void SetUp() override {
    ligands_ = thermolysin_ligands();
    if (ligands_.empty()) SURFCOMP_DATA_ABSENT(test::shared_absent_message("thermolysin"));
  }
  std::vector<fs::path> ligands_;
};

TEST_F(Matrix, ExactEntriesAreTheTopScoresAndTransformsOfMatch) {
  screening::MatrixOptions options;
  options.transforms = true;
  options.exact = true;
  const screening::SimilarityMatrix matrix = screening::similarity_matrix(ligands_, {}, options);
  ASSERT_EQ(matrix.rows.size(), 3u);
  ASSERT_TRUE(matrix.symmetric);
  EXPECT_TRUE(matrix.left_out.empty());
  EXPECT_TRUE((matrix.stage.array() == 3).all());
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = i; j < 3; ++j) {
      matching::MatchInput reference, probe;
      reference.path = ligands_[i];
      probe.path = ligands_[j];
      const matching::InputMatch pair = matching::match_inputs(reference, probe);
      ASSERT_FALSE(pair.result.alignments.empty());
      const matching::Alignment& top = pair.result.alignments.front();
      const auto r = static_cast<Eigen::Index>(i), c = static_cast<Eigen::Index>(j);
      EXPECT_NEAR(matrix.score(r, c), top.overlay.score, 1e-12) << i << ", " << j;
      EXPECT_EQ(matrix.score(r, c), matrix.score(c, r));
      EXPECT_TRUE(matrix.transforms[i * 3 + j].isApprox(top.transform, 1e-12));
      // The mirrored entry moves row i's molecule onto column j's: the inverse.
      EXPECT_TRUE((matrix.transforms[j * 3 + i] * matrix.transforms[i * 3 + j])
                      .isApprox(Eigen::Matrix4d::Identity(), 1e-12));
      if (i == j) {
        // A self-match: the identity, at the self-overlay's score.
        EXPECT_NEAR(matrix.score(r, r), 1.0, 1e-6);
        EXPECT_TRUE(top.transform.isApprox(Eigen::Matrix4d::Identity(), 1e-6));
      } else {
        // The reverse pair, matched on its own, scores within what the fits' order moves.
        probe.path = ligands_[i];
        reference.path = ligands_[j];
        const matching::InputMatch reverse = matching::match_inputs(reference, probe);
        // Not equal: the fits and their refinements start from the other side (0.0015 apart
        // at most, measured on these three).
        EXPECT_NEAR(matrix.score(r, c), reverse.result.alignments.front().overlay.score, 2e-3);
        EXPECT_LT(matrix.score(r, c), 0.99);
      }
    }
  }
}

TEST_F(Matrix, OneAndTwoThreadsGiveTheSameMatrix) {
  screening::MatrixOptions options;
  options.transforms = true;
  std::vector<std::pair<std::size_t, std::size_t>> told;
  options.progress = [&](std::size_t done, std::size_t total) { told.emplace_back(done, total); };
  screening::SimilarityMatrix one, two;
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = screening::similarity_matrix(ligands_, {}, options);
  }
  {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = screening::similarity_matrix(ligands_, {}, options);
  }
  EXPECT_EQ(one.score, two.score);
  ASSERT_EQ(one.transforms.size(), two.transforms.size());
  for (std::size_t k = 0; k < one.transforms.size(); ++k)
    EXPECT_EQ(one.transforms[k], two.transforms[k]) << k;
  // Each run tells 1 to 6 of its six refined overlays, then 1 to 3 of its three full matches
  // (every pair off the diagonal is among its rows' two best), in order.
  ASSERT_EQ(told.size(), 18u);
  for (std::size_t k = 0; k < told.size(); ++k) {
    const std::size_t at = k % 9;
    EXPECT_EQ(told[k], at < 6 ? std::make_pair(at + 1, std::size_t{6})
                              : std::make_pair(at - 5, std::size_t{3}))
        << k;
  }
}

TEST_F(Matrix, TheRefinedOverlayRanksAndEachRowsBestGetsTheFullMatch) {
  screening::MatrixOptions options;
  options.transforms = true;
  options.full_matches = 0;
  const screening::SimilarityMatrix refined = screening::similarity_matrix(ligands_, {}, options);
  EXPECT_TRUE((refined.stage.array() == 2).all());
  // Each entry is a screen's stage 2 of the column's molecule against the row's, described alone.
  const std::vector<screening::ScreenQuery> queries = screen_queries(ligands_);
  screening::ScreenOptions every_start;
  every_start.refine_starts = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = i; j < 3; ++j) {
      const screening::HitScore hit =
          screening::refined_score(queries[i], queries[j].packed->sample().view(), every_start);
      const auto r = static_cast<Eigen::Index>(i), c = static_cast<Eigen::Index>(j);
      EXPECT_NEAR(refined.score(r, c), hit.score, 1e-12) << i << ", " << j;
      EXPECT_EQ(refined.score(c, r), refined.score(r, c));
      EXPECT_TRUE(refined.transforms[i * 3 + j].isApprox(hit.transform, 1e-12));
      // A self-overlay: the identity at score 1, in single precision.
      if (i == j) {
        EXPECT_NEAR(hit.score, 1.0, 1e-5);
        EXPECT_TRUE(hit.transform.isApprox(Eigen::Matrix4d::Identity(), 1e-5));
      }
    }
  }
  // One candidate a row: the row's best off the diagonal gets match's score, the rest stay.
  options.full_matches = 1;
  const screening::SimilarityMatrix one = screening::similarity_matrix(ligands_, {}, options);
  options.exact = true;
  const screening::SimilarityMatrix exact = screening::similarity_matrix(ligands_, {}, options);
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic> best =
      Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic>::Constant(3, 3, 2);
  for (Eigen::Index i = 0; i < 3; ++i) {
    Eigen::VectorXd row = refined.score.row(i);
    row(i) = -1.0;
    Eigen::Index j = 0;
    row.maxCoeff(&j);
    best(i, j) = best(j, i) = 3;
  }
  EXPECT_EQ(one.stage, best);
  for (Eigen::Index i = 0; i < 3; ++i) {
    for (Eigen::Index j = 0; j < 3; ++j) {
      EXPECT_EQ(one.score(i, j), best(i, j) == 3 ? exact.score(i, j) : refined.score(i, j))
          << i << ", " << j;
    }
  }
}

TEST_F(Matrix, WithRefinedOverlaysEachRowsBestByStageOneIsRefined) {
  // Four molecules (a record twice, from another file), so that a row has neighbours left out.
  test::TempDir dir;
  std::vector<fs::path> set = ligands_;
  set.push_back(dir.write("again.sdf", text_of(ligands_[2])));
  screening::MatrixOptions options;
  options.transforms = true;
  options.full_matches = 0;
  const screening::SimilarityMatrix every = screening::similarity_matrix(set, {}, options);
  options.refined_overlays = 1;
  const screening::SimilarityMatrix one = screening::similarity_matrix(set, {}, options);
  const std::vector<screening::ScreenQuery> queries = screen_queries(set);
  screening::ScreenOptions every_start;
  every_start.refine_starts = 0;
  Eigen::MatrixXd fast(4, 4);
  for (Eigen::Index i = 0; i < 4; ++i) {
    for (Eigen::Index j = i; j < 4; ++j) {
      fast(i, j) = fast(j, i) =
          screening::fast_score(queries[static_cast<std::size_t>(i)],
                                queries[static_cast<std::size_t>(j)].packed->sample().view(),
                                every_start)
              .score;
    }
  }
  // Refined: the diagonal and each row's best by stage 1 (and its mirror); stage 1 elsewhere.
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic> stage =
      Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic>::Constant(4, 4, 1);
  for (Eigen::Index i = 0; i < 4; ++i) {
    Eigen::VectorXd row = fast.row(i);
    row(i) = -1.0;
    Eigen::Index j = 0;
    row.maxCoeff(&j);
    stage(i, j) = stage(j, i) = stage(i, i) = 2;
  }
  EXPECT_EQ(one.stage, stage);
  EXPECT_GT((stage.array() == 1).count(), 0);  // some pairs are left at stage 1
  for (Eigen::Index i = 0; i < 4; ++i) {
    for (Eigen::Index j = 0; j < 4; ++j) {
      // A refined cell is every pair's; a stage-1 cell is the fast score, no better.
      if (stage(i, j) == 2) {
        EXPECT_EQ(one.score(i, j), every.score(i, j)) << i << ", " << j;
      } else {
        EXPECT_NEAR(one.score(i, j), fast(i, j), 1e-12) << i << ", " << j;
        EXPECT_LE(one.score(i, j), every.score(i, j) + 1e-12) << i << ", " << j;
      }
    }
  }
  // The copy's pair is its best, at the self-overlay's 1.
  EXPECT_NEAR(one.score(2, 3), 1.0, 1e-5);
}

// Each row's K best of the whole matrix, the same cells, all against all and against a second
// set; with every stage at work (stage 1 for most pairs, two refined and one full match a row).
TEST_F(Matrix, NeighboursAreEachRowsBestOfTheWholeMatrix) {
  test::TempDir dir;
  std::vector<fs::path> set = ligands_;
  set.push_back(dir.write("again.sdf", text_of(ligands_[0])));
  screening::MatrixOptions options;
  options.transforms = true;
  options.refined_overlays = 1;
  options.full_matches = 1;
  for (const bool symmetric : {true, false}) {
    const std::vector<fs::path> against =
        symmetric ? std::vector<fs::path>{} : std::vector<fs::path>{set[1], set[3]};
    options.neighbours = 0;
    const screening::SimilarityMatrix whole = screening::similarity_matrix(set, against, options);
    options.neighbours = 2;
    const screening::SimilarityMatrix best = screening::similarity_matrix(set, against, options);
    EXPECT_EQ(best.score.size(), 0);
    ASSERT_EQ(best.neighbours.size(), whole.rows.size());
    for (std::size_t i = 0; i < whole.rows.size(); ++i) {
      std::vector<std::size_t> order;
      for (std::size_t j = 0; j < whole.columns.size(); ++j)
        if (!symmetric || j != i) order.push_back(j);
      const auto r = static_cast<Eigen::Index>(i);
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return whole.score(r, static_cast<Eigen::Index>(a)) >
               whole.score(r, static_cast<Eigen::Index>(b));
      });
      ASSERT_EQ(best.neighbours[i].size(), 2u) << i;
      for (std::size_t k = 0; k < 2; ++k) {
        const screening::Neighbour& next = best.neighbours[i][k];
        const auto c = static_cast<Eigen::Index>(order[k]);
        EXPECT_EQ(next.column, order[k]) << symmetric << ": " << i << ", " << k;
        EXPECT_EQ(next.score, whole.score(r, c)) << symmetric << ": " << i << ", " << k;
        EXPECT_EQ(next.stage, whole.stage(r, c));
        EXPECT_TRUE(
            next.transform.isApprox(whole.transforms[i * whole.columns.size() + order[k]], 1e-12));
      }
    }
    // The copy is the first row's best neighbour, at the self-overlay's 1.
    if (symmetric) {
      EXPECT_EQ(best.neighbours[0][0].column, 3u);
      EXPECT_NEAR(best.neighbours[0][0].score, 1.0, 1e-5);
    }
  }
  std::ostringstream csv;
  options.neighbours = 1;
  screening::write_neighbours_csv(csv, screening::similarity_matrix(set, {}, options));
  std::istringstream lines(csv.str());
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "row,name,rank,column,neighbour,score,stage");
  std::getline(lines, line);
  EXPECT_EQ(line.substr(0, line.find(',')), "1");
  EXPECT_NE(line.find(",1,4,"), std::string::npos) << line;  // rank 1: the copy, column 4
  options.exact = true;
  EXPECT_THROW(screening::similarity_matrix(set, {}, options), OptionError);
}

// Twelve molecules, with room in each row for fewer cells than its columns: cells are let go and
// the bound on them decides each row, which still equals the whole matrix's.
TEST_F(Matrix, NeighboursLetGoOfCellsAndStillAreTheWholeMatrixs) {
  const auto series = test::shared_dataset("sutherland/therm_3dqsar.sdf");
  if (!series) SURFCOMP_DATA_ABSENT(test::shared_absent_message("sutherland"));
  std::string twelve;
  {
    std::istringstream all(text_of(*series));
    int records = 0;
    for (std::string line; records < 12 && std::getline(all, line);) {
      twelve += line + "\n";
      if (line == "$$$$") ++records;
    }
  }
  test::TempDir dir;
  const std::vector<fs::path> set{dir.write("twelve.sdf", twelve)};
  for (const std::size_t refined : {std::size_t{0}, std::size_t{2}}) {
    screening::MatrixOptions options;
    options.refined_overlays = refined;
    options.full_matches = 1;  // room for 2 (1 + 1) + refined cells of 11 a row
    const screening::SimilarityMatrix whole = screening::similarity_matrix(set, {}, options);
    ASSERT_EQ(whole.rows.size(), 12u);
    options.neighbours = 1;
    const screening::SimilarityMatrix best = screening::similarity_matrix(set, {}, options);
    for (Eigen::Index i = 0; i < 12; ++i) {
      Eigen::VectorXd row = whole.score.row(i);
      row(i) = -1.0;
      Eigen::Index j = 0;
      row.maxCoeff(&j);
      const auto at = static_cast<std::size_t>(i);
      ASSERT_EQ(best.neighbours[at].size(), 1u);
      EXPECT_EQ(best.neighbours[at][0].column, static_cast<std::size_t>(j)) << refined << ": " << i;
      EXPECT_EQ(best.neighbours[at][0].score, whole.score(i, j)) << refined << ": " << i;
      EXPECT_EQ(best.neighbours[at][0].stage, whole.stage(i, j));
    }
  }
}

TEST_F(Matrix, AgainstASecondSetGivesItsRowsAndColumns) {
  test::TempDir dir;
  // One file of two records: both are read, in order.
  const fs::path both = dir.write("two.sdf", text_of(ligands_[1]) + text_of(ligands_[2]));
  screening::MatrixOptions options;
  options.transforms = true;
  const screening::SimilarityMatrix all = screening::similarity_matrix(ligands_, {}, options);
  const screening::SimilarityMatrix against =
      screening::similarity_matrix({ligands_[0]}, {both}, options);
  EXPECT_FALSE(against.symmetric);
  ASSERT_EQ(against.score.rows(), 1);
  ASSERT_EQ(against.score.cols(), 2);
  EXPECT_EQ(against.columns[1].record, 2u);
  EXPECT_EQ(against.columns[1].source, both);
  EXPECT_EQ(against.score(0, 0), all.score(0, 1));
  EXPECT_EQ(against.score(0, 1), all.score(0, 2));
  ASSERT_EQ(against.transforms.size(), 2u);
  EXPECT_EQ(against.transforms[0], all.transforms[1]);
  EXPECT_EQ(against.transforms[1], all.transforms[2]);
}

TEST_F(Matrix, APairThatCannotBeMatchedIsNamedAndScoresNan) {
  screening::MatrixOptions options;
  options.exact = true;
  options.inputs.match.graph.max_nodes = 1;  // every pair has more critical-point pairs
  const screening::SimilarityMatrix matrix =
      screening::similarity_matrix({ligands_[0], ligands_[2]}, {}, options);
  EXPECT_TRUE(matrix.score.array().isNaN().all()) << matrix.score;
  ASSERT_EQ(matrix.warnings.size(), 3u);
  EXPECT_NE(matrix.warnings[1].find("ligand1THL.sdf record 1 ("), std::string::npos);
  EXPECT_NE(matrix.warnings[1].find("ligand1TMN.sdf record 1 ("), std::string::npos)
      << matrix.warnings[1];
  // A clique search cut at its budget is told, as match tells it.
  options.inputs.match.graph.max_nodes = matching::MatchOptions{}.graph.max_nodes;
  options.inputs.match.max_clique_work = 1;
  const screening::SimilarityMatrix cut =
      screening::similarity_matrix({ligands_[0], ligands_[2]}, {}, options);
  ASSERT_EQ(cut.warnings.size(), 1u);
  EXPECT_NE(cut.warnings[0].find("of 3 full matches: the clique search stopped"), std::string::npos)
      << cut.warnings[0];
}

TEST_F(Matrix, AnUnreadableRecordIsLeftOutAndNamed) {
  test::TempDir dir;
  const fs::path set =
      dir.write("set.sdf", text_of(ligands_[0]) + "broken\n  no atoms here\n\nM  END\n$$$$\n" +
                               text_of(ligands_[2]));
  const screening::SimilarityMatrix matrix = screening::similarity_matrix({set});
  ASSERT_EQ(matrix.rows.size(), 2u);
  EXPECT_EQ(matrix.rows[1].record, 3u);
  ASSERT_EQ(matrix.left_out.size(), 1u);
  EXPECT_NE(matrix.left_out[0].find("set.sdf record 2 (broken)"), std::string::npos)
      << matrix.left_out[0];
  EXPECT_GT(matrix.score(0, 1), 0.0);
}

TEST_F(Matrix, ImpossibleSetsAreRefusedBeforeAnyWork) {
  test::TempDir dir;
  const fs::path empty = dir.write("empty.sdf", "");
  EXPECT_NE(
      test::error_of([&] { screening::similarity_matrix({empty}); }).find("empty.sdf: no molecule"),
      std::string::npos);
  EXPECT_NE(test::error_of([&] {
              screening::similarity_matrix({ligands_[0]});
            }).find("a set of one molecule has no pair"),
            std::string::npos);
  screening::MatrixOptions few;
  few.max_pairs = 5;  // three molecules make six pairs with the diagonal
  EXPECT_NE(test::error_of([&] {
              screening::similarity_matrix(ligands_, {}, few);
            }).find("6 pairs (3 x 3 molecules) is more than max_pairs 5"),
            std::string::npos);
  screening::MatrixOptions bad_ligand;
  bad_ligand.inputs.input.read.ligand = "???";  // an option, not a record, that cannot be read
  EXPECT_THROW(screening::similarity_matrix(ligands_, {}, bad_ligand), OptionError);
  const fs::path mesh = dir.write("a.ply", "ply\n");
  EXPECT_NE(test::error_of([&] {
              screening::similarity_matrix({ligands_[0], mesh});
            }).find("a.ply: not a molecule file"),
            std::string::npos);
}

TEST_F(Matrix, TheCsvHasAHeaderAndARowPerMolecule) {
  screening::SimilarityMatrix matrix;
  matrix.rows = {{"a,b", "x.sdf", 1}, {"c", "x.sdf", 2}};
  matrix.columns = matrix.rows;
  matrix.score.resize(2, 2);
  matrix.score << 1.0, 0.25, 0.25, 1.0;
  std::ostringstream out;
  screening::write_matrix_csv(out, matrix);
  EXPECT_EQ(out.str(), "name,\"a,b\",c\n\"a,b\",1.0000,0.2500\nc,0.2500,1.0000\n");
}

}  // namespace
}  // namespace surfcomp
