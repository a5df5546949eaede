// surfcomp match's resource limits as a user meets them: a clique search cut by
// --max-clique-work or --max-cliques says so on stderr and in result.json and still answers; a
// limit that is no positive integer is a command-line error; a graph above --max-graph-nodes, or
// shape images above --max-image-bytes, are refused in one line, as is a mesh without the ESP
// and LP the match compares.
#include "program_run.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

using test::ProgramRun;

/// `surfcomp ARGUMENTS` (test::run_program).
ProgramRun run(const std::string& arguments) { return test::run_program(arguments); }

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(MatchBudgetCli, ACutCliqueSearchIsReportedAndTheMatchStillAnswers) {
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(probe, "thermolysin/ligands-common-frame/4TMN_ligand.sdf");
  const test::TempDir dir;
  const std::string pair = ref.string() + " " + probe.string();

  const ProgramRun full = run("match " + pair + " -o " + (dir / "full.json").string());
  ASSERT_EQ(full.status, 0) << full.err;
  EXPECT_EQ(full.err.find("warning"), std::string::npos) << full.err;
  std::ifstream full_in(dir / "full.json");
  const nlohmann::json full_doc = nlohmann::json::parse(full_in);
  EXPECT_TRUE(full_doc["cliques"]["complete"].get<bool>());
  EXPECT_TRUE(full_doc["warnings"].empty());
  EXPECT_EQ(full_doc["parameters"]["max_clique_work"], 100000000);
  EXPECT_EQ(full_doc["parameters"]["max_cliques"], 1000);
  EXPECT_EQ(full_doc["parameters"]["max_graph_nodes"], 20000);
  const auto work = full_doc["cliques"]["work"].get<std::int64_t>();
  const auto count = full_doc["cliques"]["count"].get<std::size_t>();
  ASSERT_GT(work, 1);
  ASSERT_GT(count, 1u);

  const ProgramRun cut = run("match " + pair + " --max-clique-work " + std::to_string(work / 2) +
                             " -o " + (dir / "cut.json").string());
  ASSERT_EQ(cut.status, 0) << cut.err;
  EXPECT_EQ(lines(cut.err), 1u) << cut.err;
  EXPECT_EQ(cut.err.rfind("surfcomp match: warning: clique search stopped after ", 0), 0u)
      << cut.err;
  EXPECT_NE(cut.err.find("(--max-clique-work " + std::to_string(work / 2) + ")"), std::string::npos)
      << cut.err;
  std::ifstream cut_in(dir / "cut.json");
  const nlohmann::json cut_doc = nlohmann::json::parse(cut_in);
  EXPECT_FALSE(cut_doc["cliques"]["complete"].get<bool>());
  EXPECT_GT(cut_doc["cliques"]["work"].get<std::int64_t>(), work / 2);
  EXPECT_LT(cut_doc["cliques"]["count"].get<std::size_t>(), count);
  ASSERT_EQ(cut_doc["warnings"].size(), 1u);
  EXPECT_EQ("surfcomp match: warning: " + cut_doc["warnings"][0].get<std::string>() + "\n",
            cut.err);
  EXPECT_FALSE(cut_doc["alignments"].empty());  // the principal-axes starts at least

  // The clique budget is a budget, not a fault: a note, no warning.
  const ProgramRun capped = run("match " + pair + " --max-cliques 1");
  ASSERT_EQ(capped.status, 0) << capped.err;
  EXPECT_EQ(capped.err,
            "note: the clique budget took the first 1 cliques the search found (--max-cliques)\n");
}

TEST(MatchBudgetCli, ALimitThatIsNoPositiveIntegerIsACommandLineError) {
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  const test::TempDir dir;
  for (const std::string option : {"--max-clique-work", "--max-cliques", "--max-graph-nodes"}) {
    for (const std::string value : {"0", "-5", "1.5", "lots", "99999999999999999999"}) {
      const fs::path out = dir / "result.json";
      const ProgramRun r = run("match " + ref.string() + " " + ref.string() + " " + option + "=" +
                               value + " -o " + out.string());
      EXPECT_EQ(r.status, 2) << option << " " << value << ": " << r.err;
      EXPECT_EQ(lines(r.err), 1u) << r.err;
      EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
      EXPECT_FALSE(fs::exists(out));
    }
  }
}

TEST(MatchBudgetCli, AGraphAboveTheNodeLimitIsRefusedInOneLine) {
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(probe, "thermolysin/ligands-common-frame/4TMN_ligand.sdf");
  const test::TempDir dir;
  const fs::path out = dir / "result.json";
  const ProgramRun r = run("match " + ref.string() + " " + probe.string() +
                           " --max-graph-nodes 3 -o " + out.string());
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("more than the limit of 3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-graph-nodes"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(MatchBudgetCli, ImagesAboveTheByteLimitAreRefusedInOneLine) {
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(probe, "thermolysin/ligands-common-frame/4TMN_ligand.sdf");
  const test::TempDir dir;
  const fs::path out = dir / "result.json";
  // One default image (16 x 180 samples of 37 bytes) is 106,560 bytes: a ligand needs several.
  const ProgramRun r = run("match " + ref.string() + " " + probe.string() +
                           " --max-image-bytes 106560 -o " + out.string());
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("1THL_ligand.sdf"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-image-bytes"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// MaSIF's meshes carry 'charge', 'hbond' and 'hphob' but no 'esp' or 'lp': refused when read,
// before either side's descriptors are computed, not after the graph.
TEST(MatchBudgetCli, AMeshWithoutEspIsMatchedByShapeAloneInAngstroms) {
  SURFCOMP_SHARED_OR_SKIP(mesh, "surfaces/masif/1EWY_A.ply");
  SURFCOMP_SHARED_OR_SKIP(ligand, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  const test::TempDir dir;
  const fs::path out = dir / "result.json";
  const ProgramRun r = run("match " + ligand.string() + " " + mesh.string() + " -o " +
                           out.string() + " --max-cliques 200");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(
      r.err.find("note: " + mesh.string() + " carries no ESP and LP: matched by shape alone\n"),
      std::string::npos)
      << r.err;
  std::ifstream in(out);
  const nlohmann::json doc = nlohmann::json::parse(in);
  EXPECT_TRUE(doc["shape_only"].get<bool>());
  // The ligand is a molecule: lengths stay in A however large the mesh is.
  EXPECT_EQ(doc["scale"]["unit"].get<double>(), 1.0);
  EXPECT_EQ(doc["scale"]["from"], "none");
  EXPECT_EQ(doc["parameters"]["overlay_chem_weight"].get<double>(), 0.0);
  ASSERT_FALSE(doc["alignments"].empty());
  for (const auto& a : doc["alignments"]) {
    EXPECT_EQ(a["overlay"]["chem"].get<double>(), 0.0);
    EXPECT_EQ(a["r_chem"].get<double>(), 0.0);
  }
}

}  // namespace
}  // namespace surfcomp
