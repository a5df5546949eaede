// `surfcomp pockets`, `library build --pockets` and `--site-pocket` as a user runs them: the
// JSON and the PDB of 1THL's pockets agree; a structure without a pocket gives an empty list and
// exit 0, one without protein atoms or a --min-plddt that removes everything one line naming the
// file and no output, and a pocket library with nothing to build one line naming the structure; a
// pocket library of three structures, sharded, built alike by one process and by two under
// mpirun, screens the query's own pocket first and refuses a resume with other pockets; the site
// z-score sets related sites apart; a pocket match of a structure onto its mmCIF copy is the
// identity, in match and in the report.
#include "pocket_cut.hpp"
#include "program_run.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

using test::file_bytes;
using test::files_under;
using test::ProgramRun;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// The comma-separated fields of a CSV row (no quoted fields in these tables).
std::vector<std::string> fields_of(const std::string& row) {
  std::vector<std::string> fields;
  std::istringstream in(row);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

class CliPockets : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("surfcomp_cli_pockets_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  ProgramRun run(const std::string& arguments) const {
    return test::run_program(arguments, {dir_, ""});
  }
  fs::path dir_;
};

TEST_F(CliPockets, JsonAndPdbDescribeTheSamePockets) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/1THL.pdb");
  const ProgramRun r = run("pockets " + pdb.string() + " -o p.json --pdb-out p.pdb");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("pockets"), std::string::npos) << r.out;
  const nlohmann::json document = nlohmann::json::parse(file_bytes(dir_ / "p.json"));
  const auto& pockets = document.at("pockets");
  ASSERT_GE(pockets.size(), 3u);
  std::size_t spheres = 0;
  for (std::size_t k = 0; k < pockets.size(); ++k) {
    EXPECT_EQ(pockets[k].at("rank").get<int>(), static_cast<int>(k + 1));
    if (k > 0) {
      EXPECT_LE(pockets[k].at("score").get<double>(), pockets[k - 1].at("score").get<double>());
    }
    EXPECT_GT(pockets[k].at("volume").get<double>(), 0.0);
    EXPECT_FALSE(pockets[k].at("lining_residues").empty());
    spheres += pockets[k].at("spheres").size();
  }
  std::size_t records = 0;
  for (const std::string& line : lines_of(file_bytes(dir_ / "p.pdb")))
    records += line.rfind("HETATM", 0) == 0 ? 1 : 0;
  EXPECT_EQ(records, spheres);
  std::size_t atom_records = 0;
  for (const std::string& line : lines_of(file_bytes(pdb)))
    atom_records += line.rfind("ATOM  ", 0) == 0 ? 1 : 0;
  EXPECT_EQ(document.at("protein_atoms").get<std::size_t>(), atom_records);
}

TEST_F(CliPockets, EmptyAndRefusedStructures) {
  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/1THL.pdb");
  SURFCOMP_SHARED_OR_SKIP(ligand, "thermolysin/ligand1THL.pdb");
  // Three residues of 1THL: no pocket, an empty list and exit 0.
  std::ofstream(dir_ / "few.pdb") << [&] {
    std::string kept;
    for (const std::string& line : lines_of(file_bytes(pdb))) {
      if (line.rfind("ATOM  ", 0) == 0 && std::stoi(line.substr(22, 4)) <= 3) kept += line + "\n";
    }
    return kept;
  }();
  const ProgramRun none = run("pockets few.pdb -o none.json");
  ASSERT_EQ(none.status, 0) << none.err;
  EXPECT_NE(none.out.find("no pocket found"), std::string::npos) << none.out;
  EXPECT_TRUE(nlohmann::json::parse(file_bytes(dir_ / "none.json")).at("pockets").empty());

  for (const auto& [arguments, words] : std::vector<std::pair<std::string, std::string>>{
           {"pockets " + ligand.string() + " -o x.json", "no protein atom"},
           {"pockets " + pdb.string() + " -o x.json --min-plddt 99", "no residue has a pLDDT"},
           {"pockets few.sdf -o x.json", "not a structure file"},
           {"pockets " + pdb.string() + " -o x.json --pocket-min-radius 7", "--pocket-max-radius"},
           {"pockets " + pdb.string() + " -o x.json --max-atoms 100", "--max-atoms"}}) {
    const ProgramRun r = run(arguments);
    EXPECT_NE(r.status, 0) << arguments;
    EXPECT_EQ(lines_of(r.err).size(), 1u) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "x.json")) << arguments;
  }

  // A pocket library that would be empty fails on one line naming the structure and why, and
  // leaves only its log: a structure without a pocket, a pocket rank beyond the structure's
  // pockets, a listed structure that is missing.
  std::ofstream(dir_ / "beyond.txt") << pdb.string() << " pocket 500\n";
  std::ofstream(dir_ / "missing.txt") << "absent.pdb pocket 1\n";
  for (const auto& [arguments, words] : std::vector<std::pair<std::string, std::string>>{
           {"library build --pockets few.pdb -o lib.sclib", "few.pdb: no pocket found"},
           {"library build --sites beyond.txt -o lib.sclib", "pocket 500 was asked for"},
           {"library build --sites missing.txt -o lib.sclib", "absent.pdb: no such file"}}) {
    const ProgramRun r = run(arguments);
    EXPECT_NE(r.status, 0) << arguments;
    EXPECT_EQ(lines_of(r.err).size(), 1u) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "lib.sclib")) << arguments;
  }
  EXPECT_NE(file_bytes(dir_ / "lib.sclib.log").find("absent.pdb"), std::string::npos);
}

TEST_F(CliPockets, APocketLibraryOfThreeStructuresScreensItsOwnPocketFirst) {
  SURFCOMP_SHARED_OR_SKIP(pdb_1thl, "thermolysin/1THL.pdb");
  SURFCOMP_SHARED_OR_SKIP(pdb_4tmn, "thermolysin/4TMN.pdb");
  SURFCOMP_SHARED_OR_SKIP(pdb_1a0i, "kahraman-dev/pdb/1A0I.pdb");
  // Each structure cut to its ligand's neighbourhood, so that its pockets surface in seconds.
  test::write_pocket(pdb_1thl, "0DB", 12.0, dir_ / "therm_a.pdb");
  test::write_pocket(pdb_4tmn, "0PK", 12.0, dir_ / "therm_b.pdb");
  test::write_pocket(pdb_1a0i, "ATP", 12.0, dir_ / "ligase.pdb");
  // Two structures per shard: an index and two shards, which the screen reads as one library.
  const std::string build =
      "library build --pockets ../therm_a.pdb ../therm_b.pdb ../ligase.pdb -o pockets.sclib "
      "--pocket-min-spheres 30 --shard-records 2 ";
  fs::create_directories(dir_ / "serial");
  const ProgramRun built = test::run_program(build + "--threads 2", {dir_ / "serial", ""});
  ASSERT_EQ(built.status, 0) << built.err;
  EXPECT_NE(built.out.find("in 2 shards"), std::string::npos) << built.out;
  const std::map<std::string, std::string> serial = files_under(dir_ / "serial");
  EXPECT_EQ(serial.size(), 7u);  // index, log, manifest, two shards and their logs
  // Pockets detected otherwise do not join it: a resume with another detection is refused.
  const ProgramRun mixed = test::run_program(
      "library build --pockets ../therm_a.pdb ../therm_b.pdb ../ligase.pdb -o pockets.sclib "
      "--pocket-min-spheres 31 --shard-records 2 --resume",
      {dir_ / "serial", ""});
  EXPECT_NE(mixed.status, 0);
  EXPECT_NE(mixed.err.find("another build's inputs or options"), std::string::npos) << mixed.err;
  EXPECT_TRUE(files_under(dir_ / "serial") == serial) << "a refused resume changed the files";
#ifdef SURFCOMP_MPIEXEC
  // Under mpirun the processes share the shards, to the same bytes.
  fs::create_directories(dir_ / "mpi");
  const ProgramRun shared = test::run_program(
      build + "--threads 1", {dir_ / "mpi", std::string(SURFCOMP_MPIEXEC) +
                                                " --allow-run-as-root --oversubscribe -np 2 "});
  ASSERT_EQ(shared.status, 0) << shared.err;
  EXPECT_TRUE(files_under(dir_ / "mpi") == serial) << "2 processes differ";
#endif
  fs::rename(dir_ / "serial/pockets.sclib", dir_ / "pockets.sclib");
  fs::rename(dir_ / "serial/pockets.sclib.d", dir_ / "pockets.sclib.d");
  const ProgramRun screened =
      run("screen therm_b.pdb pockets.sclib --site-pocket 1 --pocket-min-spheres 30 -o hits.csv");
  ASSERT_EQ(screened.status, 0) << screened.err;
  const std::vector<std::string> rows = lines_of(file_bytes(dir_ / "hits.csv"));
  ASSERT_GE(rows.size(), 4u);  // a header and a pocket of each structure at least
  const std::vector<std::string> first = fields_of(rows[1]);
  EXPECT_EQ(first[2], "therm_b:pocket1");
  EXPECT_NEAR(std::stod(first[6]), 1.0, 1e-3);  // the pocket overlays itself
  // The entries keep their sites' neighbourhoods: a screen that wants more of the structure is
  // refused before any work, naming the library.
  for (const char* margin : {"0", "30"}) {
    const ProgramRun wider =
        run(std::string("screen therm_b.pdb pockets.sclib --site-pocket 1 --pocket-min-spheres 30 "
                        "-o wide.csv --site-margin ") +
            margin);
    EXPECT_NE(wider.status, 0) << margin;
    EXPECT_EQ(lines_of(wider.err).size(), 1u) << wider.err;
    EXPECT_NE(wider.err.find("pockets.sclib: its sites keep the atoms within 20 A"),
              std::string::npos)
        << wider.err;
    EXPECT_FALSE(fs::exists(dir_ / "wide.csv"));
  }

  // A site list's `STRUCTURE pocket N` is the same site: the query finds it at the same score.
  std::ofstream(dir_ / "list.txt") << "therm_b.pdb pocket 1\n";
  ASSERT_EQ(run("library build --sites list.txt -o listed.sclib --pocket-min-spheres 30").status,
            0);
  ASSERT_EQ(run("screen therm_b.pdb listed.sclib --site-pocket 1 --pocket-min-spheres 30 -o "
                "listed.csv")
                .status,
            0);
  const std::vector<std::string> listed = lines_of(file_bytes(dir_ / "listed.csv"));
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(fields_of(listed[1])[2], "therm_b:pocket1");
  EXPECT_EQ(fields_of(listed[1])[6], first[6]);
}

// The site z-score reads as its documentation says: far above unrelated sites' for two
// thermolysin sites, within the unrelated pairs' spread for thermolysin's site against a
// kinase's ATP site.
TEST_F(CliPockets, TheSiteZScoreSetsRelatedSitesApartFromUnrelatedOnes) {
  SURFCOMP_SHARED_OR_SKIP(pdb_1thl, "thermolysin/1THL.pdb");
  SURFCOMP_SHARED_OR_SKIP(pdb_4tmn, "thermolysin/4TMN.pdb");
  SURFCOMP_SHARED_OR_SKIP(pdb_1a0i, "kahraman-dev/pdb/1A0I.pdb");
  test::write_pocket(pdb_1thl, "0DB", 12.0, dir_ / "therm_a.pdb");
  test::write_pocket(pdb_4tmn, "0PK", 12.0, dir_ / "therm_b.pdb");
  test::write_pocket(pdb_1a0i, "ATP", 12.0, dir_ / "ligase.pdb");
  const auto z_of = [&](const std::string& arguments) {
    const ProgramRun r = run("match " + arguments + " -o z.json");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("site z-score"), std::string::npos) << r.out;
    const nlohmann::json site = nlohmann::json::parse(file_bytes(dir_ / "z.json")).at("site");
    return site.at("z_score").get<double>();
  };
  const double related =
      z_of("therm_b.pdb therm_a.pdb --ref-site-ligand 0PK --probe-site-ligand 0DB");
  const double unrelated =
      z_of("therm_b.pdb ligase.pdb --ref-site-ligand 0PK --probe-site-ligand ATP");
  EXPECT_GT(related, 5.0);              // 6.97 measured
  EXPECT_LT(std::abs(unrelated), 1.0);  // -0.23 measured
}

TEST_F(CliPockets, APocketMatchOntoTheMmcifCopyIsTheIdentity) {
  SURFCOMP_SHARED_OR_SKIP(pdb_4tmn, "thermolysin/4TMN.pdb");
  test::write_pocket(pdb_4tmn, "0PK", 12.0, dir_ / "site.pdb");
  // The mmCIF copy, written by gemmi's own converter from the PDB file.
  ASSERT_EQ(std::system(("gemmi convert " + (dir_ / "site.pdb").string() + " " +
                         (dir_ / "site.cif").string())
                            .c_str()),
            0);
  const ProgramRun r = run("match site.pdb site.cif --site-pocket 1 -o m.json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json result = nlohmann::json::parse(file_bytes(dir_ / "m.json"));
  const auto& top = result.at("alignments").at(0);
  EXPECT_NEAR(top.at("rmsd").get<double>(), 0.0, 1e-6);
  // The same lining residues on both sides: lining similarity 1, and the site score is the
  // overlay's and the lining's weighted mean.
  const auto& site = result.at("site");
  EXPECT_DOUBLE_EQ(site.at("lining").get<double>(), 1.0);
  const double w = site.at("lining_weight").get<double>();
  EXPECT_NEAR(site.at("score").get<double>(),
              (top.at("overlay").at("score").get<double>() + w) / (1.0 + w), 1e-12);
  // The same surface points with the same interactions, overlaid by the identity.
  EXPECT_DOUBLE_EQ(site.at("interactions").get<double>(), 1.0);
  EXPECT_NEAR(site.at("fields").at("similarity").get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(site.at("fields").at("coverage").get<double>(), 1.0, 1e-12);
  // The report takes the pocket as match does: its page holds the same site figures and marks
  // the pocket linings.
  const ProgramRun report = run("report site.pdb site.cif --site-pocket 1 -o r.html");
  ASSERT_EQ(report.status, 0) << report.err;
  const std::string page = file_bytes(dir_ / "r.html");
  const std::string key = "\"lining\":";
  const std::size_t at = page.find(key, page.find("\"site\":{\"fields\":"));
  ASSERT_NE(at, std::string::npos);
  EXPECT_NEAR(std::stod(page.substr(at + key.size(), 24)), 1.0, 1e-12);
  EXPECT_NE(page.find("\"site_lining\":["), std::string::npos);
}

}  // namespace
}  // namespace surfcomp
