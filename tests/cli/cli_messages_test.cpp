// The words of the program's refusals: a sample of hostile inputs and options, tried as a new
// user would, each refused with one line that names the user's file or option and no C++ type,
// field, function or namespace.
#include "program_run.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

/// One bad run: the command line and a word its message must hold (the file or the option).
struct BadRun {
  std::string arguments;
  std::string named;
};

/// What in a message would be the program's internals rather than the user's words: a scope
/// (Options::field, std::), a call (name()), a type name ending as the library's option and
/// error types do, or a snake_case word that is no file name (one the user typed would be
/// hyphenated on the command line).
std::string internal_words(const std::string& message) {
  static const std::regex patterns[] = {
      std::regex(R"(\b[A-Za-z_]\w*::\w)"),
      std::regex(R"(\b[a-z_]\w*\(\))"),
      std::regex(R"(\b[A-Z][a-z]+(?:[A-Z][a-z]+)*(Options|Error|Model|Kernel|Weights|Scheme)\b)"),
      std::regex(R"(\b[a-z]+\.[a-z]+_[a-z_]+\b)"),
      std::regex(R"((^|[\s'"(])[a-z]+_[a-z_]+(?=[\s'",:;=.)]|$))"),
  };
  for (const std::regex& pattern : patterns) {
    std::smatch found;
    if (std::regex_search(message, found, pattern)) return found.str();
  }
  return "";
}

class CliMessages : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("surfcomp_messages_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    write("empty.sdf", "");
    write("garbage.sdf", "this is not a molecule\nat all\n");
    write("truncated.sdf",
          "water\n  surfcomp\n\n  3  2  0  0  0  0  0  0  0  0999 V2000\n"
          "    0.0000    0.0000    0.0000 O   0  0\n");
    write("nan.pqr",
          "ATOM      1  O   HOH     1       0.000   0.000   0.000   nan 1.52\n"
          "ATOM      2  H1  HOH     1       0.957   0.000   0.000  0.417 1.20\n");
    write("huge.pqr",
          "ATOM      1  O   HOH     1       0.000   0.000   0.000 1e30 1.52\n"
          "ATOM      2  H1  HOH     1       0.957   0.000   0.000  0.417 1.20\n");
    write("open.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n");
    write("nonmanifold.off",
          "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 -1 0\n3 0 1 2\n3 0 1 3\n3 0 1 4\n");
    write("water.sdf",
          "water\n  surfcomp\n\n  3  2  0  0  0  0  0  0  0  0999 V2000\n"
          "    0.0000    0.0000    0.0000 O   0  0  0  0  0  0  0  0  0  0  0  0\n"
          "    0.9570    0.0000    0.0000 H   0  0  0  0  0  0  0  0  0  0  0  0\n"
          "   -0.2400    0.9270    0.0000 H   0  0  0  0  0  0  0  0  0  0  0  0\n"
          "  1  2  1  0\n  1  3  1  0\nM  END\n$$$$\n");
    write("not.sclib", "not a library\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
  }

  fs::path dir_;
};

TEST_F(CliMessages, RefusalsSpeakTheUsersWords) {
  const std::vector<BadRun> corpus = {
      {"surf-build missing.sdf -o s.ply", "missing.sdf"},
      {"surf-build empty.sdf -o s.ply", "empty.sdf"},
      {"surf-build garbage.sdf -o s.ply", "garbage.sdf"},
      {"surf-build truncated.sdf -o s.ply", "truncated.sdf"},
      {"surf-build nan.pqr -o s.ply", "nan.pqr"},
      {"surf-build huge.pqr -o s.ply", "huge.pqr"},
      {"surf-build water.sdf -o s.txt", "s.txt"},
      {"surf-build water.sdf -o s.ply --density 100", "--density"},
      {"surf-build water.sdf -o s.ply --probe-radius -1", "--probe-radius"},
      {"surf-build water.sdf -o s.ply --probe-radius abc", "--probe-radius"},
      {"surf-build water.sdf -o s.ply --charges best", "--charges"},
      {"surf-build water.sdf -o s.ply --lp-kernel gauss", "--lp-kernel"},
      {"surf-build water.sdf -o s.ply --max-grid-cells 10", "--max-grid-cells"},
      {"surf-build water.sdf -o s.ply --max-vertices 10", "water.sdf"},
      {"surf-build water.sdf -o s.ply --max-vertices 10", "--max-vertices"},
      {"surf-build water.sdf -o s.ply --ligand LIG", "--ligand"},
      {"surf-build water.sdf -o s.ply --ligand LIG", "water.sdf"},
      {"surf-build water.sdf -o s.ply --record 3", "water.sdf"},
      {"surf-build water.sdf -o s.ply --ligand LIG:A:one", "--ligand"},
      {"surf-build water.sdf -o s.ply --ligand LIG:A:one", "RESIDUE[:CHAIN[:NUMBER]]"},
      {"cp-detect water.sdf -o c.json --molecule water.sdf", "--molecule"},
      {"cp-detect nonmanifold.off -o c.json", "nonmanifold.off"},
      {"cp-detect water.sdf -o c.json --critical-point-radius 0", "--critical-point-radius"},
      {"hsi-build water.sdf -o w.hsi --weights springy", "--weights"},
      {"hsi-build water.sdf -o w.hsi --image-rings 0", "--image-rings"},
      {"hsi-build water.sdf -o w.hsi --max-image-bytes 10", "--max-image-bytes"},
      {"match water.sdf garbage.sdf", "garbage.sdf"},
      {"match water.sdf water.sdf --fuzzy-threshold 2", "--fuzzy-threshold"},
      {"match water.sdf water.sdf --overlay-sigma 0", "--overlay-sigma"},
      {"match water.sdf water.sdf --principal-axes-starts 5", "--principal-axes-starts"},
      {"match water.sdf water.sdf --ranking best", "--ranking"},
      {"match water.sdf water.sdf --site-sphere 1,2,3", "--site-sphere"},
      {"match water.sdf water.sdf --max-cliques 0", "--max-cliques"},
      {"match water.sdf water.sdf --refine-top -1", "--refine-top"},
      {"match water.sdf water.sdf --no-such-option", "--no-such-option"},
      {"match water.sdf water.sdf --site-ligand HOH", "HOH"},
      {"match water.sdf water.sdf --site-ligand HOH:A:1", "HOH"},
      {"match water.sdf water.sdf --site-ligand :A", "--site-ligand"},
      {"screen water.sdf not.sclib -o h.csv", "not.sclib"},
      {"screen water.sdf not.sclib -o h.csv --top -1", "--top"},
      {"library build empty.sdf -o l.sclib", "empty.sdf"},
      {"library build water.sdf -o l.sclib --conformers -2", "--conformers"},
      {"library build water.sdf -o l.sclib --threads 5000", "--threads"},
      {"library info not.sclib", "not.sclib"},
  };
  for (const BadRun& bad : corpus) {
    SCOPED_TRACE(bad.arguments);
    const test::ProgramRun run = test::run_program(bad.arguments, {dir_, ""});
    EXPECT_NE(run.status, 0) << run.err;
    ASSERT_FALSE(run.err.empty());
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << "not one line: " << run.err;
    EXPECT_NE(run.err.find(bad.named), std::string::npos) << run.err;
    EXPECT_EQ(internal_words(run.err), "") << run.err;
  }
}

TEST(CliMessagesPattern, CatchesTheProgramsInternals) {
  EXPECT_EQ(internal_words("<ses>: too many cells (SesOptions::max_grid_cells)"), "SesOptions::m");
  EXPECT_EQ(internal_words("principal_curvatures: vertex 3 has no defined normal"),
            "principal_curvatures");
  EXPECT_EQ(internal_words("use ChargeModel::mmff"), "ChargeModel::m");
  EXPECT_EQ(internal_words("refused by SesOptions"), "SesOptions");
  EXPECT_EQ(internal_words("match options: graph.fuzzy_threshold = 2"), "graph.fuzzy_threshold");
  EXPECT_EQ(internal_words("more than max_nodes = 3"), " max_nodes");
  EXPECT_EQ(internal_words("failed: bond_pin->getEndAtomIdx()"), "getEndAtomIdx()");
  EXPECT_EQ(internal_words("failed: bond_pin is null"), " bond_pin");
  EXPECT_EQ(internal_words("l.pdb: 3 atoms; --max-grid-cells 10 is too small"), "");
  EXPECT_EQ(internal_words("ligand_1.sdf:4: a bond to atom 7 of 3"), "");
}

}  // namespace
}  // namespace surfcomp
