// `surfcomp library` and `surfcomp screen` as a user runs them: the library and the hits do not
// depend on --threads or on the number of MPI processes, a query taken from the library finds
// itself first, a damaged library and a SMILES list without conformers are refused with one
// line, and a bad record is skipped and logged. Pocket libraries: a site query finds its own
// pocket first and writes the hits' structures as PDB models; queries and libraries of the other
// kind, and --sites with INPUTs, are refused with one line, as is a run under MPI without the MPI
// module. A build interrupted by a signal leaves no file behind. Several queries in one pass give
// each query the rows of its own screen and fuse them as defined; a screen's peak memory does not
// grow with the library.
#include "pocket_cut.hpp"
#include "program_run.hpp"
#include "test_data.hpp"

#include "surfcomp/core/conformers.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/library_build.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/inotify.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

const fs::path kProgram = test::program_path();

using test::file_bytes;
using test::ProgramRun;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> fields_of(const std::string& row) {
  std::vector<std::string> fields;
  std::istringstream in(row);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

/// Writes the records `numbers` (1-based) of the SD file `from` into `to`, in that order.
void write_records(const std::string& from, const std::vector<int>& numbers, const std::string& to);

/// One library of three molecules, two conformers each, shared by the tests of the suite.
class CliScreen : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("surfcomp_cli_screen_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "set.smi") << "# three molecules and a bad line\n"
                                       "CC(=O)Nc1ccc(O)cc1 paracetamol\n"
                                       "C1CC unclosed_ring\n"
                                       "OC(=O)c1ccccc1O salicylic_acid\n"
                                       "CC(C)Cc1ccc(cc1)C(C)C(=O)O ibuprofen\n";
    const ProgramRun built =
        run("library build set.smi -o lib.sclib --conformers 2 --seed 3 --threads 2");
    ASSERT_EQ(built.status, 0) << built.err;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  /// `PREFIX surfcomp ARGUMENTS` in the suite's directory (test::run_program).
  static ProgramRun run(const std::string& arguments, const std::string& prefix = "") {
    return test::run_program(arguments, {dir_, prefix});
  }

  static fs::path dir_;

 public:
  static const fs::path& directory() { return dir_; }
};

fs::path CliScreen::dir_;

void write_records(const std::string& from, const std::vector<int>& numbers,
                   const std::string& to) {
  const std::string text = file_bytes(CliScreen::directory() / from);
  std::vector<std::string> records;
  for (std::size_t at = 0, end; (end = text.find("$$$$\n", at)) != std::string::npos; at = end + 5)
    records.push_back(text.substr(at, end + 5 - at));
  std::ofstream out(CliScreen::directory() / to);
  for (const int number : numbers) out << records.at(static_cast<std::size_t>(number - 1));
}

/// The rows of a hits table by molecule name: its score column (7th).
std::map<std::string, double> scores_by_name(const std::string& table) {
  std::map<std::string, double> scores;
  const std::vector<std::string> rows = lines_of(table);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::vector<std::string> fields = fields_of(rows[i]);
    scores[fields.at(2)] = std::stod(fields.at(6));
  }
  return scores;
}

// Several queries in one pass: each query's table is what its own screen writes, the fused
// table ranks every molecule by the maximum (or the mean) of its scores against the queries,
// and a multi-record query file is a list of queries.
TEST_F(CliScreen, SeveralQueriesInOnePassEqualTheirOwnScreensAndFuseAsDefined) {
  ASSERT_EQ(run("library export lib.sclib -o fuse.sdf").status, 0);
  write_records("fuse.sdf", {1}, "fuse_q1.sdf");  // paracetamol, salicylic acid, ibuprofen
  write_records("fuse.sdf", {3}, "fuse_q3.sdf");
  write_records("fuse.sdf", {6}, "fuse_q6.sdf");
  write_records("fuse.sdf", {1, 3, 6}, "fuse_three.sdf");
  const std::string options = " --candidates 1 --top 0 --threads 2";
  // The two acids carry an ionic group at pH 7 and paracetamol does not: screened together, all
  // three rank by the score, as each does alone with --chemistry on.
  for (const char* q : {"1", "3", "6"}) {
    const ProgramRun r = run(std::string("screen fuse_q") + q + ".sdf lib.sclib -o single" + q +
                             ".csv --chemistry on" + options);
    ASSERT_EQ(r.status, 0) << r.err;
  }
  ProgramRun r = run("screen fuse_q1.sdf fuse_q3.sdf fuse_q6.sdf lib.sclib -o fused.csv" + options);
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("screen fuse_three.sdf lib.sclib -o listed.csv --fusion mean" + options);
  ASSERT_EQ(r.status, 0) << r.err;
  const char* singles[] = {"single1.csv", "single3.csv", "single6.csv"};
  std::vector<std::map<std::string, double>> single;
  for (int q = 0; q < 3; ++q) {
    const std::string own = file_bytes(dir_ / singles[q]);
    const std::string k = std::to_string(q + 1);
    EXPECT_EQ(file_bytes(dir_ / ("fused.query" + k + ".csv")), own) << "query " << k;
    EXPECT_EQ(file_bytes(dir_ / ("listed.query" + k + ".csv")), own) << "query " << k;
    single.push_back(scores_by_name(own));
  }
  for (const auto& [table, mean] : {std::pair{"fused.csv", false}, std::pair{"listed.csv", true}}) {
    const std::vector<std::string> rows = lines_of(file_bytes(dir_ / table));
    ASSERT_EQ(rows.size(), 4u) << table;  // header and three molecules
    EXPECT_EQ(rows[0],
              "rank,entry,name,source,record,conformer,score,query,score_1,score_2,score_3");
    double previous = 2.0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      const std::vector<std::string> f = fields_of(rows[i]);
      ASSERT_EQ(f.size(), 11u) << rows[i];
      double best = -1.0, sum = 0.0;
      std::size_t best_query = 0;
      for (std::size_t q = 0; q < 3; ++q) {
        const double s = std::stod(f[8 + q]);
        EXPECT_NEAR(s, single[q].at(f[2]), 1e-6) << table << " " << rows[i];
        if (s > best) {
          best = s;
          best_query = q + 1;
        }
        sum += s;
      }
      const double score = std::stod(f[6]);
      EXPECT_NEAR(score, mean ? sum / 3.0 : best, 2e-6) << table << " " << rows[i];
      EXPECT_EQ(f[7], std::to_string(best_query)) << rows[i];
      EXPECT_LE(score, previous) << table << ": rows out of order";
      previous = score;
    }
  }
  // Each query finds itself: in the max fusion its own molecule scores about 1 against it.
  EXPECT_NEAR(single[1].at("salicylic_acid"), 1.0, 1e-3);
}

// A query record that cannot be read stops the screen before any work, naming the record.
TEST_F(CliScreen, AnUnreadableQueryRecordStopsTheScreenNamingIt) {
  ASSERT_EQ(run("library export lib.sclib -o bad_query.sdf").status, 0);
  write_records("bad_query.sdf", {1}, "bad_queries.sdf");
  std::ofstream(dir_ / "bad_queries.sdf", std::ios::app)
      << "broken\n  surfcomp\n\n  2  1  0  0  0  0  0  0  0  0999 V2000\n"
         "    0.0000    0.0000    0.0000 C   0  0\nM  END\n$$$$\n";
  const ProgramRun r = run("screen bad_queries.sdf lib.sclib -o bad.csv");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("query 2 (bad_queries.sdf record 2)"), std::string::npos) << r.err;
  EXPECT_EQ(lines_of(r.err).size(), 1u) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "bad.query1.csv"));
}

TEST_F(CliScreen, LibraryIsTheSameWithOneThreadAndTheBadRecordIsLogged) {
  const ProgramRun built =
      run("library build set.smi -o one.sclib --conformers 2 --seed 3 --threads 1");
  ASSERT_EQ(built.status, 0) << built.err;
  EXPECT_EQ(file_bytes(dir_ / "one.sclib"), file_bytes(dir_ / "lib.sclib"));
  const std::string log = file_bytes(dir_ / "lib.sclib.log");
  EXPECT_NE(log.find("set.smi\t2\tunclosed_ring\t"), std::string::npos) << log;
  EXPECT_EQ(lines_of(log).size(), 3u) << log;  // two comment lines, one skipped record
}

TEST_F(CliScreen, HitsAreTheSameWithOneAndTwoThreadsAndTheQueryFindsItselfFirst) {
  ASSERT_EQ(run("library export lib.sclib -o all.sdf").status, 0);
  const std::string all = file_bytes(dir_ / "all.sdf");
  EXPECT_NE(all.find(">  <surfcomp_conformer>\n2\n"), std::string::npos);
  EXPECT_NE(all.find(">  <surfcomp_name>\nibuprofen\n"), std::string::npos);
  // The query: entry 3, the first conformer of salicylic acid.
  for (const char* threads : {"1", "2"}) {
    const ProgramRun r = run(
        std::string("screen all.sdf lib.sclib --record 3 --candidates 2 --top 0 ") +
        "--aligned-out hits" + threads + ".sdf -o hits" + threads + ".csv --threads " + threads);
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const std::string hits = file_bytes(dir_ / "hits1.csv");
  EXPECT_EQ(hits, file_bytes(dir_ / "hits2.csv"));
  EXPECT_EQ(file_bytes(dir_ / "hits1.sdf"), file_bytes(dir_ / "hits2.sdf"));
  const std::vector<std::string> rows = lines_of(hits);
  ASSERT_EQ(rows.size(), 4u);  // header and the three molecules
  EXPECT_EQ(rows[0].rfind("rank,entry,name,source,record,conformer,score,stage,shape,chem,atoms,"
                          "fast_score,t00,t01,t02,t03,t10",
                          0),
            0u);
  EXPECT_EQ(rows[1].rfind("1,3,salicylic_acid,set.smi,3,1,", 0), 0u) << rows[1];
  // Columns 8 (stage): the two candidates come from the full match, the third molecule from
  // the refined overlay.
  EXPECT_EQ(fields_of(rows[1])[7], "3");
  EXPECT_EQ(fields_of(rows[2])[7], "3");
  EXPECT_EQ(fields_of(rows[3])[7], "2");
  EXPECT_EQ(fields_of(rows[1]).size(), 28u);
  const std::string aligned = file_bytes(dir_ / "hits1.sdf");
  std::size_t records = 0;
  for (std::size_t at = aligned.find("$$$$"); at != std::string::npos;
       at = aligned.find("$$$$", at + 4))
    ++records;
  EXPECT_EQ(records, 3u);
}

TEST_F(CliScreen, HsiFilesMakeALibraryThatTheirMoleculesFind) {
  ASSERT_EQ(run("library export lib.sclib -o hsi_set.sdf").status, 0);
  fs::create_directories(dir_ / "hsi");
  for (const char* record : {"1", "3"}) {  // paracetamol's and salicylic acid's first conformers
    const ProgramRun r = run(std::string("hsi-build hsi_set.sdf --record ") + record +
                             " -o hsi/entry" + record + ".hsi");
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const ProgramRun built = run("library build hsi -o hsi.sclib");
  ASSERT_EQ(built.status, 0) << built.err;
  const ProgramRun screened =
      run("screen hsi_set.sdf hsi.sclib --record 3 --top 0 -o hsi.csv --aligned-out hsi.sdf");
  ASSERT_EQ(screened.status, 0) << screened.err;
  const std::vector<std::string> rows = lines_of(file_bytes(dir_ / "hsi.csv"));
  ASSERT_EQ(rows.size(), 3u);  // header and the two entries
  EXPECT_EQ(rows[1].rfind("1,2,entry3,hsi/entry3.hsi,1,0,", 0), 0u) << rows[1];
  EXPECT_NEAR(std::stod(fields_of(rows[1])[6]), 1.0, 1e-3) << rows[1];  // score
  EXPECT_EQ(fields_of(rows[1])[7], "3");                                // from the full match
  // The hit's heavy atoms, without bonds: salicylic acid's 10.
  const std::string aligned = file_bytes(dir_ / "hsi.sdf");
  EXPECT_NE(aligned.find(" 10  0  0  0  0  0  0  0  0  0999 V2000"), std::string::npos) << aligned;
  // A .hsi has fixed coordinates: asked for conformers, it is skipped and logged; with every
  // record skipped, the build fails with one line and writes no library (nor replaces one).
  ASSERT_EQ(run("library build hsi -o kept.sclib").status, 0);
  const std::string kept = file_bytes(dir_ / "kept.sclib");
  EXPECT_EQ(run("library build hsi -o kept.sclib --conformers 2").status, 1);
  EXPECT_EQ(file_bytes(dir_ / "kept.sclib"), kept);
  const ProgramRun conformers = run("library build hsi -o conformers.sclib --conformers 2");
  EXPECT_EQ(conformers.status, 1);
  EXPECT_NE(conformers.err.find("conformers.sclib: no entry was built; all 2 records were skipped"),
            std::string::npos)
      << conformers.err;
  EXPECT_EQ(lines_of(conformers.err).size(), 1u) << conformers.err;
  EXPECT_FALSE(fs::exists(dir_ / "conformers.sclib"));
  EXPECT_NE(file_bytes(dir_ / "conformers.sclib.log").find("--conformers does not apply"),
            std::string::npos);
}

TEST_F(CliScreen, HitsAreTheSameUnderMpiWithOneTwoAndFourProcesses) {
#ifndef SURFCOMP_MPIEXEC
  GTEST_SKIP() << "surfcomp was built without MPI";
#else
  ASSERT_EQ(run("library export lib.sclib -o mpi.sdf").status, 0);
  write_records("mpi.sdf", {1}, "mpi_q1.sdf");
  write_records("mpi.sdf", {4}, "mpi_q4.sdf");
  ASSERT_EQ(run("screen mpi_q1.sdf lib.sclib --candidates 2 --top 0 -o serial.csv").status, 0);
  ASSERT_EQ(
      run("screen mpi_q1.sdf mpi_q4.sdf lib.sclib --candidates 2 --top 0 -o serial_two.csv").status,
      0);
  ASSERT_EQ(
      run("screen mpi_q1.sdf lib.sclib --chemistry off --candidates 1 --top 2 -o serial_head.csv")
          .status,
      0);
  for (const char* ranks : {"1", "2", "4"}) {
    const std::string one = "mpi" + std::string(ranks) + ".csv";
    const std::string two = "mpi_two" + std::string(ranks) + ".csv";
    const std::string mpirun =
        std::string(SURFCOMP_MPIEXEC) + " --allow-run-as-root --oversubscribe -np " + ranks + " ";
    ProgramRun r = run(
        "screen mpi_q1.sdf lib.sclib --candidates 2 --top 0 -o " + one + " --threads 1", mpirun);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(file_bytes(dir_ / one), file_bytes(dir_ / "serial.csv")) << ranks << " processes";
    // Two queries in one pass: the fused table and each query's the same as in one process.
    r = run(
        "screen mpi_q1.sdf mpi_q4.sdf lib.sclib --candidates 2 --top 0 -o " + two + " --threads 1",
        mpirun);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(file_bytes(dir_ / two), file_bytes(dir_ / "serial_two.csv")) << ranks;
    for (const char* q : {"1", "2"}) {
      EXPECT_EQ(file_bytes(dir_ / ("mpi_two" + std::string(ranks) + ".query" + q + ".csv")),
                file_bytes(dir_ / ("serial_two.query" + std::string(q) + ".csv")))
          << ranks << " processes, query " << q;
    }
    // Fewer rows than molecules, ranked by shape: the ranks' kept lists merge to one process's.
    const std::string head = "mpi_head" + std::string(ranks) + ".csv";
    r = run("screen mpi_q1.sdf lib.sclib --chemistry off --candidates 1 --top 2 -o " + head +
                " --threads 1",
            mpirun);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(file_bytes(dir_ / head), file_bytes(dir_ / "serial_head.csv")) << ranks;
  }
#endif
}

// The program loads Open MPI (its MPI module) only under an MPI launcher, which it tells from
// the environment; without the module it stops with one line before any work.
TEST_F(CliScreen, MissingMpiModuleUnderMpiIsRefusedWithOneLine) {
#ifndef SURFCOMP_MPIEXEC
  GTEST_SKIP() << "surfcomp was built without MPI";
#else
  ASSERT_EQ(run("library export lib.sclib -o nompi.sdf").status, 0);
  const ProgramRun r = run("screen nompi.sdf lib.sclib --record 1 -o nompi.csv",
                           "SURFCOMP_MODULE_DIR=" + dir_.string() + " OMPI_COMM_WORLD_SIZE=1 ");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("MPI launcher"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("libsurfcomp_mpi.so: not found in " + dir_.string()), std::string::npos)
      << r.err;
  EXPECT_EQ(lines_of(r.err).size(), 1u) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "nompi.csv"));
#endif
}

TEST_F(CliScreen, DamagedOrCutLibraryIsRefusedWithOneLine) {
  ASSERT_EQ(run("library export lib.sclib -o query.sdf").status, 0);
  const std::string good = file_bytes(dir_ / "lib.sclib");
  std::string damaged = good;
  damaged[damaged.size() - 40] = static_cast<char>(damaged[damaged.size() - 40] ^ 0x21);
  std::ofstream(dir_ / "damaged.sclib", std::ios::binary) << damaged;
  std::ofstream(dir_ / "cut.sclib", std::ios::binary) << good.substr(0, good.size() - 100);
  for (const char* name : {"damaged.sclib", "cut.sclib"}) {
    for (const std::string& command :
         {std::string("library info ") + name,
          std::string("screen query.sdf ") + name + " --record 1 -o never.csv"}) {
      const ProgramRun r = run(command);
      EXPECT_NE(r.status, 0) << command;
      EXPECT_EQ(lines_of(r.err).size(), 1u) << r.err;
      EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
    }
  }
  EXPECT_FALSE(fs::exists(dir_ / "never.csv"));
}

TEST_F(CliScreen, SmilesWithoutConformersAreRefusedBeforeAnyWork) {
  const ProgramRun r = run("library build set.smi -o nothing.sclib");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--conformers"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "nothing.sclib"));
}

TEST_F(CliScreen, InputsWithoutRecordsAreNamedAndNothingIsWritten) {
  std::ofstream(dir_ / "empty.sdf").close();
  std::ofstream(dir_ / "comment.smi") << "# a comment and a blank line\n\n";
  std::ofstream(dir_ / "no_sites.txt") << "# no site\n";
  const std::pair<std::string, std::string> cases[] = {
      {"library build empty.sdf -o empty.sclib", "empty.sdf: holds no molecule record"},
      {"library build comment.smi empty.sdf -o empty.sclib --conformers 1",
       "comment.smi, empty.sdf: hold no molecule record"},
      {"library build --sites no_sites.txt -o empty.sclib", "no_sites.txt: lists no site"},
  };
  for (const auto& [arguments, expected] : cases) {
    const ProgramRun r = run(arguments);
    EXPECT_EQ(r.status, 1) << arguments;
    EXPECT_NE(r.err.find(expected), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line: " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "empty.sclib")) << arguments;
    EXPECT_FALSE(fs::exists(dir_ / "empty.sclib.log")) << arguments;
  }
}

TEST_F(CliScreen, AMacromoleculeQueryIsScreenedWithAWarningThatNamesTheSiteOptions) {
  // 30 alanine residues of one chain (150 heavy atoms): a polymer chain, not a ligand.
  {
    std::ofstream pdb(dir_ / "ala30.pdb");
    const char* names[] = {"N", "CA", "C", "O", "CB"};
    const char* elements[] = {"N", "C", "C", "O", "C"};
    int serial = 1;
    for (int r = 0; r < 30; ++r) {
      for (int a = 0; a < 5; ++a, ++serial) {
        char line[96];
        std::snprintf(line, sizeof line,
                      "ATOM  %5d  %-3s ALA A%4d    %8.3f%8.3f%8.3f  1.00  0.00           %s\n",
                      serial, names[a], r + 1, 3.8 * r + 0.7 * a, 1.2 * std::sin(1.3 * a),
                      1.2 * std::cos(1.3 * a), elements[a]);
        pdb << line;
      }
    }
    pdb << "END\n";
  }
  const ProgramRun r = run("screen ala30.pdb lib.sclib -o ala30_hits.csv");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: ala30.pdb: the query is a macromolecule (150 heavy atoms, a "
                       "chain of 30 amino-acid residues)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("--site-ligand RES, --site-sphere x,y,z,r or --site-pocket N"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(lines_of(file_bytes(dir_ / "ala30_hits.csv")).size(), 4u);  // header, 3 molecules
  // A ligand query says nothing.
  std::ofstream(dir_ / "aspirin.smi") << "CC(=O)Oc1ccccc1C(=O)O aspirin\n";
  ASSERT_EQ(run("library build aspirin.smi -o aspirin.sclib --conformers 1").status, 0);
  const ProgramRun quiet = run("library export aspirin.sclib -o aspirin.sdf");
  ASSERT_EQ(quiet.status, 0) << quiet.err;
  const ProgramRun ligand = run("screen aspirin.sdf lib.sclib -o aspirin_hits.csv");
  EXPECT_EQ(ligand.status, 0) << ligand.err;
  EXPECT_EQ(ligand.err.find("macromolecule"), std::string::npos) << ligand.err;
}

/// A program started in the background with default signal actions and nothing blocked; killed
/// and reaped when it goes out of scope unless it was reaped before.
class BackgroundProgram {
 public:
  explicit BackgroundProgram(const std::vector<std::string>& arguments) {
    std::vector<char*> argv;
    for (const std::string& argument : arguments)
      argv.push_back(const_cast<char*>(argument.c_str()));
    argv.push_back(nullptr);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none;
    sigemptyset(&none);
    sigset_t ours;
    sigemptyset(&ours);
    for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&ours, signal_number);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setsigdefault(&attributes, &ours);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    if (::posix_spawn(&pid_, argv[0], nullptr, &attributes, argv.data(), environ) != 0) pid_ = -1;
    posix_spawnattr_destroy(&attributes);
  }
  ~BackgroundProgram() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    int ignored = 0;
    ::waitpid(pid_, &ignored, 0);
  }
  BackgroundProgram(const BackgroundProgram&) = delete;
  BackgroundProgram& operator=(const BackgroundProgram&) = delete;

  bool started() const { return pid_ > 0; }
  /// False once the program was reaped (never kill(-1, ...), which signals every process).
  bool signal(int signal_number) const { return pid_ > 0 && ::kill(pid_, signal_number) == 0; }
  /// The wait status once the program has ended (blocking on its pidfd, at most `seconds`, a
  /// bound for a broken build), or nothing if it still runs then.
  std::optional<int> wait(double seconds) {
    if (pid_ <= 0) return std::nullopt;
    const int pidfd = static_cast<int>(::syscall(SYS_pidfd_open, pid_, 0));
    if (pidfd < 0) return std::nullopt;
    pollfd ended{pidfd, POLLIN, 0};
    const int ready = ::poll(&ended, 1, static_cast<int>(seconds * 1000));
    ::close(pidfd);
    int status = 0;
    if (ready != 1 || ::waitpid(pid_, &status, 0) != pid_) return std::nullopt;
    pid_ = -1;
    return status;
  }
  /// Whether the program still runs (not yet ended, or ended but not reaped).
  bool running() const {
    siginfo_t info{};
    return pid_ > 0 &&
           ::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
           info.si_pid == 0;
  }

 private:
  pid_t pid_ = -1;
};

/// Tells of the files created and written in a folder (inotify), but `ignored`, so that a test
/// waits on what a program does rather than on the clock.
class FolderWatch {
 public:
  FolderWatch(const fs::path& folder, std::string ignored)
      : fd_(::inotify_init1(IN_NONBLOCK)), ignored_(std::move(ignored)) {
    if (fd_ >= 0) ::inotify_add_watch(fd_, folder.c_str(), IN_CREATE | IN_MODIFY);
  }
  ~FolderWatch() {
    if (fd_ >= 0) ::close(fd_);
  }
  FolderWatch(const FolderWatch&) = delete;
  FolderWatch& operator=(const FolderWatch&) = delete;

  /// Blocks until a file of the folder is created (`mask` IN_CREATE) or written (IN_MODIFY),
  /// at most `seconds` (a bound for a broken program); false when none was.
  bool next(std::uint32_t mask, double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    alignas(inotify_event) char buffer[4096];
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now());
      pollfd event{fd_, POLLIN, 0};
      if (left.count() <= 0 || ::poll(&event, 1, static_cast<int>(left.count())) != 1) return false;
      const ssize_t size = ::read(fd_, buffer, sizeof buffer);
      for (ssize_t at = 0; at < size;) {
        const auto* e = reinterpret_cast<const inotify_event*>(buffer + at);
        if ((e->mask & mask) != 0 && (e->len == 0 || ignored_ != e->name)) return true;
        at += static_cast<ssize_t>(sizeof(inotify_event) + e->len);
      }
    }
  }

 private:
  int fd_;
  std::string ignored_;
};

/// Starts a long library build in `folder` (1,600 conformers: tens of seconds), through `sh -c
/// SHELL_PREFIX exec surfcomp ...`, and waits until it has created its temporary file and
/// written entries into it. `watch` watches `folder` (made by the caller).
std::unique_ptr<BackgroundProgram> start_long_build(const fs::path& folder,
                                                    const std::string& shell_prefix,
                                                    FolderWatch& watch) {
  std::ofstream list(folder / "many.smi");
  for (int i = 0; i < 400; ++i) list << "CC(C)Cc1ccc(cc1)C(C)C(=O)O ibuprofen_" << i << "\n";
  list.close();
  const std::string command = shell_prefix + "exec " + kProgram.string() + " library build " +
                              (folder / "many.smi").string() + " -o " +
                              (folder / "many.sclib").string() + " --conformers 4 --threads 1 -q";
  auto program =
      std::make_unique<BackgroundProgram>(std::vector<std::string>{"/bin/sh", "-c", command});
  if (!program->started() || !watch.next(IN_CREATE, 120) || !watch.next(IN_MODIFY, 120))
    return nullptr;
  return program;
}

std::vector<std::string> files_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& file : fs::directory_iterator(folder)) {
    names.push_back(file.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST_F(CliScreen, AnInterruptedBuildLeavesNoFileBehind) {
  for (const int signal_number : {SIGINT, SIGTERM}) {
    const fs::path folder = dir_ / ("interrupted_" + std::to_string(signal_number));
    fs::create_directories(folder);
    FolderWatch watch(folder, "many.smi");
    auto build = start_long_build(folder, "", watch);
    ASSERT_TRUE(build) << "the build did not start writing within 120 s";
    ASSERT_TRUE(build->signal(signal_number));
    const std::optional<int> status = build->wait(60);
    ASSERT_TRUE(status) << "the build runs on 60 s after signal " << signal_number;
    EXPECT_TRUE(WIFSIGNALED(*status) && WTERMSIG(*status) == signal_number)
        << "the build did not end by signal " << signal_number << ": status " << *status;
    EXPECT_EQ(files_in(folder), std::vector<std::string>{"many.smi"});
  }
}

TEST_F(CliScreen, ASignalIgnoredAtStartStaysIgnored) {
  const fs::path folder = dir_ / "nohup";
  fs::create_directories(folder);
  FolderWatch watch(folder, "many.smi");
  auto build = start_long_build(folder, "trap '' HUP; ", watch);  // as nohup starts it
  ASSERT_TRUE(build) << "the build did not start writing within 120 s";
  ASSERT_TRUE(build->signal(SIGHUP));
  // The build goes on writing entries after the hangup: two writes that grow its temporary
  // beyond its size at the signal (the second begun after the build had taken the signal, as a
  // pending signal is taken on the way back from the first write), and it still runs.
  const auto temporary_bytes = [&folder] {
    std::uintmax_t bytes = 0;
    for (const auto& file : fs::directory_iterator(folder)) {
      if (file.path().filename() != "many.smi") bytes = fs::file_size(file.path());
    }
    return bytes;
  };
  std::uintmax_t before = temporary_bytes();
  for (int write = 0; write < 2; ++write) {
    while (temporary_bytes() <= before) {
      ASSERT_TRUE(watch.next(IN_MODIFY, 120)) << "the build wrote nothing after the hangup";
    }
    before = temporary_bytes();
  }
  EXPECT_TRUE(build->running()) << "a hangup ended a build started to ignore it";
  EXPECT_EQ(files_in(folder).size(), 2u);  // the list and the temporary
  ASSERT_TRUE(build->signal(SIGINT));
  ASSERT_TRUE(build->wait(60));
  EXPECT_EQ(files_in(folder), std::vector<std::string>{"many.smi"});
}

TEST_F(CliScreen, SiteQueryFindsItsOwnPocketInAPocketLibrary) {
  SURFCOMP_SHARED_OR_SKIP(pdb_4tmn, "thermolysin/4TMN.pdb");
  SURFCOMP_SHARED_OR_SKIP(pdb_1thl, "thermolysin/1THL.pdb");
  test::write_pocket(pdb_4tmn, "0PK", 9.0, dir_ / "4TMN_pocket.pdb");
  test::write_pocket(pdb_1thl, "0DB", 9.0, dir_ / "1THL_pocket.pdb");
  std::ofstream(dir_ / "sites.txt") << "# two thermolysin pockets\n"
                                       "1THL_pocket.pdb 0DB\n"
                                       "4TMN_pocket.pdb 0PK\n";
  const ProgramRun built = run("library build --sites sites.txt -o pockets.sclib --threads 2");
  ASSERT_EQ(built.status, 0) << built.err;
  const ProgramRun screened =
      run("screen 4TMN_pocket.pdb pockets.sclib --site-ligand 0PK -o sites.csv --aligned-out "
          "sites_hits.pdb");
  ASSERT_EQ(screened.status, 0) << screened.err;
  const std::vector<std::string> rows = lines_of(file_bytes(dir_ / "sites.csv"));
  ASSERT_EQ(rows.size(), 3u);
  const std::vector<std::string> first = fields_of(rows[1]);
  EXPECT_EQ(first[2], "4TMN_pocket:0PK");
  EXPECT_NEAR(std::stod(first[6]), 1.0, 1e-3);  // score: the pocket overlays itself
  const std::string models = file_bytes(dir_ / "sites_hits.pdb");
  std::size_t count = 0;
  for (const std::string& line : lines_of(models)) count += line.rfind("MODEL", 0) == 0 ? 1 : 0;
  EXPECT_EQ(count, 2u);

  // The other kind of query or library, and --sites with INPUTs: one line, no output.
  for (const auto& [arguments, status, words] :
       std::vector<std::tuple<std::string, int, std::string>>{
           {"screen 4TMN_pocket.pdb lib.sclib --site-ligand 0PK -o x.csv", 1, "pocket library"},
           {"screen 4TMN_pocket.pdb pockets.sclib -o x.csv", 1, "site query"},
           {"screen 4TMN_pocket.pdb pockets.sclib --site-ligand 0PK -o x.csv --aligned-out x.sdf",
            2, "PDB"},
           {"library build set.smi --sites sites.txt -o x.sclib", 2, "no INPUT"}}) {
    const ProgramRun r = run(arguments);
    EXPECT_EQ(r.status, status) << arguments << "\n" << r.err;
    EXPECT_EQ(lines_of(r.err).size(), 1u) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "x.csv")) << arguments;
    EXPECT_FALSE(fs::exists(dir_ / "x.sclib")) << arguments;
  }
}

TEST_F(CliScreen, AReceptorScreenRanksEachMoleculeByItsFitIntoThePocket) {
  SURFCOMP_SHARED_OR_SKIP(pdb_4tmn, "thermolysin/4TMN.pdb");
  test::write_pocket(pdb_4tmn, "0PK", 12.0, dir_ / "4TMN_receptor.pdb");
  const std::string quick =
      " --fast-chains 2 --fast-steps 3 --search-chains 4 --search-steps 5 --refine-top 3";
  const ProgramRun screened =
      run("screen --receptor 4TMN_receptor.pdb lib.sclib --site-ligand 0PK -o receptor.csv "
          "--candidates 1" +
          quick);
  ASSERT_EQ(screened.status, 0) << screened.err;
  const std::vector<std::string> rows = lines_of(file_bytes(dir_ / "receptor.csv"));
  ASSERT_EQ(rows.size(), 4u);  // the header and the library's three molecules
  EXPECT_EQ(rows[0].rfind("rank,entry,name,source,record,conformer,score,stage,contact", 0), 0u);
  std::set<std::string> names;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::vector<std::string> fields = fields_of(rows[i]);
    ASSERT_EQ(fields.size(), 31u) << rows[i];
    names.insert(fields[2]);
    EXPECT_EQ(fields[7], i == 1 ? "2" : "1");  // the one candidate's full dock first
  }
  EXPECT_EQ(names.size(), 3u);

  // What a receptor screen cannot do: one line, no output.
  for (const auto& [arguments, status, words] :
       std::vector<std::tuple<std::string, int, std::string>>{
           {"screen --receptor lib.sclib lib.sclib --site-ligand 0PK -o x.csv", 2,
            "RECEPTOR lib.sclib"},
           {"screen --receptor 4TMN_receptor.pdb lib.sclib --site-pocket 1000 -o x.csv", 1, "1000"},
           {"screen --receptor 4TMN_receptor.pdb lib.sclib --conformers 2 -o x.csv", 2,
            "conformers"},
           {"screen --receptor 4TMN_receptor.pdb lib.sclib --site-ligand 0PK -o x.txt", 2,
            ".csv"}}) {
    const ProgramRun r = run(arguments + quick);
    EXPECT_EQ(r.status, status) << arguments << "\n" << r.err;
    EXPECT_EQ(lines_of(r.err).size(), 1u) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "x.csv")) << arguments;
  }
}

/// The largest resident set (bytes) of the children this process has waited for so far.
long peak_child_rss_bytes() {
  rusage usage{};
  ::getrusage(RUSAGE_CHILDREN, &usage);
  return usage.ru_maxrss * 1024L;
}

/// `copies` copies of `entry`, each its own molecule, written as a library at `path`.
void write_copies(const screening::LibraryEntry& entry, std::size_t copies, const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  screening::LibraryWriter writer(out, "copies");
  screening::LibraryEntry copy = entry;
  for (std::size_t i = 0; i < copies; ++i) {
    copy.info.name = "copy" + std::to_string(i + 1);
    copy.info.record = static_cast<std::uint32_t>(i + 1);
    writer.add(copy);
  }
  writer.finish();
}

// A screen keeps its memory bounded whatever the library's size: it streams the library (the
// pages of the entries it has scored are released) and keeps only each query's best molecules.
// A library of one entry and one of many copies of it, several times a screen's working set,
// are screened and the two runs' peak resident memory compared.
TEST(CliScreenMemory, PeakMemoryDoesNotGrowWithTheLibrary) {
  const fs::path dir =
      fs::temp_directory_path() / ("surfcomp_memory_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  io::MoleculeRecord record;
  record.source = "memory.smi";
  record.record = 1;
  record.name = "ibuprofen";
  record.format = io::RecordFormat::smiles;
  record.text = "CC(C)Cc1ccc(cc1)C(C)C(=O)O";
  screening::LibraryBuildOptions build;
  build.conformers = ConformerOptions{};
  build.conformers->count = 1;
  const std::vector<screening::LibraryEntry> entries = screening::build_entries(record, build);
  ASSERT_EQ(entries.size(), 1u);
  { std::ofstream(dir / "query.sdf") << entries.front().molecule.text; }
  constexpr std::size_t kCopies = 12000;
  write_copies(entries.front(), 1, dir / "one.sclib");
  write_copies(entries.front(), kCopies, dir / "many.sclib");
  const auto library_bytes = static_cast<long>(fs::file_size(dir / "many.sclib"));
  ASSERT_GT(library_bytes, 60L << 20) << "the library must be well above a block's pages";

  // Stage 1 alone reads every entry's sample; --top bounds the rows kept.
  const std::string options = " --refine 0 --candidates 0 --top 10 --threads 2 -o hits.csv";
  const test::ProgramRun small =
      test::run_program("screen query.sdf one.sclib" + options, {dir, ""});
  ASSERT_EQ(small.status, 0) << small.err;
  const long small_rss = peak_child_rss_bytes();
  const test::ProgramRun large =
      test::run_program("screen query.sdf many.sclib" + options, {dir, ""});
  ASSERT_EQ(large.status, 0) << large.err;
  const long large_rss = peak_child_rss_bytes();
  std::printf("peak RSS: %.1f MB with 1 entry, %.1f MB with %zu (library %.1f MB)\n",
              static_cast<double>(small_rss) / 1e6, static_cast<double>(large_rss) / 1e6, kCopies,
              static_cast<double>(library_bytes) / 1e6);
  // Reading the whole mapping would add the library's size; with the pages released only a
  // block of entries, the index and AddressSanitizer's shadow of the bytes read (an eighth of
  // the library) are added.
  EXPECT_LT(large_rss - small_rss, library_bytes / 3)
      << "peak RSS " << large_rss << " B against " << small_rss << " B for one entry";
  // The copies all score as the query itself.
  std::ifstream hits(dir / "hits.csv");
  std::string header, first;
  std::getline(hits, header);
  std::getline(hits, first);
  ASSERT_EQ(first.rfind("1,1,copy1,memory.smi,1,1,", 0), 0u) << first;
  EXPECT_NEAR(std::stod(first.substr(first.find(",1,1,") + 5)), 1.0, 1e-4) << first;
  fs::remove_all(dir);
}

// `surfcomp library build --shard-records N` as a user runs it: the index, shards and log do not
// depend on --threads or on the number of MPI processes; a build killed by SIGKILL continues
// with --resume to the bytes of an uninterrupted build; a resume with other options, and a
// missing or damaged shard, are refused with one line naming the file, changing nothing; a
// sharded library exports and describes as the one file of the same inputs.
namespace library_shards {

namespace fs = std::filesystem;

using test::file_bytes;
using test::files_under;
using test::ProgramRun;

std::vector<std::string> names_of(const std::map<std::string, std::string>& files) {
  std::vector<std::string> names;
  for (const auto& [name, bytes] : files) names.push_back(name);
  return names;
}

std::size_t lines_in(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

/// Seven SMILES, the third and fourth unreadable: with two records per shard, shard 2 has
/// every record skipped (a log, no library file).
class CliLibraryShards : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("surfcomp_cli_shards_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "set.smi") << "CC(=O)Nc1ccc(O)cc1 paracetamol\n"
                                       "OC(=O)c1ccccc1O salicylic_acid\n"
                                       "C1CC unclosed_ring\n"
                                       "C1CC(C unclosed_too\n"
                                       "CC(=O)Oc1ccccc1C(=O)O aspirin\n"
                                       "CC(C)Cc1ccc(cc1)C(C)C(=O)O ibuprofen\n"
                                       "Cn1cnc2c1c(=O)n(C)c(=O)n2C caffeine\n";
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  /// `PREFIX surfcomp ARGUMENTS` in the folder `folder` of the suite's directory (made if
  /// needed), whose inputs are ../set.smi: builds in different folders store the same sources.
  static ProgramRun run(const std::string& folder, const std::string& arguments,
                        const std::string& prefix = "") {
    fs::create_directories(dir_ / folder);
    return test::run_program(arguments, {dir_ / folder, prefix});
  }

  static fs::path dir_;
};

fs::path CliLibraryShards::dir_;

constexpr const char* kBuild = "library build ../set.smi -o lib.sclib --conformers 1 --seed 3 ";

TEST_F(CliLibraryShards, BytesDoNotDependOnThreadsOrProcesses) {
  for (const char* threads : {"1", "2"}) {
    const ProgramRun r = run(std::string("threads") + threads,
                             std::string(kBuild) + "--shard-records 2 --threads " + threads);
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const std::map<std::string, std::string> serial = files_under(dir_ / "threads1");
  EXPECT_EQ(names_of(serial),
            (std::vector<std::string>{"lib.sclib", "lib.sclib.d/000001.log",
                                      "lib.sclib.d/000001.sclib", "lib.sclib.d/000002.log",
                                      "lib.sclib.d/000003.log", "lib.sclib.d/000003.sclib",
                                      "lib.sclib.d/000004.log", "lib.sclib.d/000004.sclib",
                                      "lib.sclib.d/manifest.txt", "lib.sclib.log"}));
  EXPECT_TRUE(files_under(dir_ / "threads2") == serial) << "--threads 2 differs";
#ifndef SURFCOMP_MPIEXEC
  GTEST_SKIP() << "surfcomp was built without MPI: the build under mpirun is not tested";
#else
  for (const char* ranks : {"1", "2", "4"}) {
    const std::string folder = std::string("mpi") + ranks;
    const ProgramRun r = run(
        folder, std::string(kBuild) + "--shard-records 2 --threads 1",
        std::string(SURFCOMP_MPIEXEC) + " --allow-run-as-root --oversubscribe -np " + ranks + " ");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("5 entries in 4 shards"), std::string::npos) << r.out;
    EXPECT_TRUE(files_under(dir_ / folder) == serial) << ranks << " processes differ";
  }
#endif
}

/// Runs `surfcomp ARGUMENTS` in `folder` and kills it (SIGKILL) as soon as `marker` exists,
/// looking every millisecond. Returns whether the kill ended it (false: it had ended first).
bool kill_once_exists(const fs::path& folder, const std::vector<std::string>& arguments,
                      const fs::path& marker) {
  const std::string program = test::program_path().string();
  std::vector<char*> argv{const_cast<char*>(program.c_str())};
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    if (::chdir(folder.c_str()) != 0 || null < 0) ::_exit(127);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  while (!fs::exists(marker)) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;
    ::usleep(1000);
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

TEST_F(CliLibraryShards, AKilledBuildResumesToTheBytesOfAnUninterruptedOne) {
  // One record per shard and two conformers each: the first shard is done in a fraction of
  // the build, which goes on for several more shards.
  const std::string options = "--conformers 2 --seed 3 --shard-records 1 --threads 1";
  const std::string build = "library build ../set.smi -o lib.sclib " + options;
  ASSERT_EQ(run("whole", build).status, 0);
  fs::create_directories(dir_ / "killed");
  const bool killed =
      kill_once_exists(dir_ / "killed",
                       {"library", "build", "../set.smi", "-o", "lib.sclib", "--conformers", "2",
                        "--seed", "3", "--shard-records", "1", "--threads", "1", "-q"},
                       dir_ / "killed/lib.sclib.d/000001.log");
  if (!killed) std::printf("note: the build ended before the kill; its resume is tested\n");

  const std::map<std::string, std::string> left = files_under(dir_ / "killed");
  const ProgramRun refused = run("killed", build);
  EXPECT_EQ(refused.status, 1);
  EXPECT_EQ(lines_in(refused.err), 1u) << refused.err;
  EXPECT_NE(refused.err.find("lib.sclib.d: "), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--resume"), std::string::npos) << refused.err;
  EXPECT_TRUE(files_under(dir_ / "killed") == left) << "a refused build changed the folder";

  const ProgramRun resumed = run("killed", build + " --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  // Index, shards, their logs, the manifest and the log: the same files and bytes (a
  // temporary file the kill left is gone).
  const std::map<std::string, std::string> whole = files_under(dir_ / "whole");
  EXPECT_EQ(names_of(files_under(dir_ / "killed")), names_of(whole));
  EXPECT_TRUE(files_under(dir_ / "killed") == whole) << "the resumed build differs";
}

TEST_F(CliLibraryShards, OtherOptionsAndAMissingOrDamagedShardAreRefusedNamingTheFile) {
  ASSERT_EQ(run("lib", std::string(kBuild) + "--shard-records 2").status, 0);
  ASSERT_EQ(run("lib", "library export lib.sclib -o query.sdf").status, 0);
  const std::map<std::string, std::string> built = files_under(dir_ / "lib");
  const ProgramRun other = run("lib",
                               "library build ../set.smi -o lib.sclib --conformers 2 "
                               "--seed 3 --shard-records 2 --resume");
  EXPECT_EQ(other.status, 1);
  EXPECT_EQ(lines_in(other.err), 1u) << other.err;
  EXPECT_NE(other.err.find("lib.sclib.d/manifest.txt:5: "), std::string::npos) << other.err;
  EXPECT_TRUE(files_under(dir_ / "lib") == built) << "a refused resume changed the files";

  const fs::path shard = dir_ / "lib/lib.sclib.d/000003.sclib";
  const std::string good = file_bytes(shard);
  std::string damaged = good;
  damaged[damaged.size() - 40] = static_cast<char>(damaged[damaged.size() - 40] ^ 0x21);
  for (const std::string& bytes : {std::string(), damaged}) {
    fs::remove(shard);
    if (!bytes.empty()) std::ofstream(shard, std::ios::binary) << bytes;
    for (const char* command :
         {"library info lib.sclib", "screen query.sdf lib.sclib --record 1 -o hits.csv"}) {
      const ProgramRun r = run("lib", command);
      EXPECT_EQ(r.status, 1) << command;
      EXPECT_EQ(lines_in(r.err), 1u) << r.err;
      EXPECT_NE(r.err.find("lib.sclib.d/000003.sclib: "), std::string::npos) << r.err;
      EXPECT_FALSE(fs::exists(dir_ / "lib/hits.csv"));
    }
  }
}

TEST_F(CliLibraryShards, AShardedLibraryExportsAndDescribesAsTheOneFile) {
  ASSERT_EQ(run("one", kBuild).status, 0);
  ASSERT_EQ(run("cut", std::string(kBuild) + "--shard-records 2").status, 0);
  for (const char* folder : {"one", "cut"})
    ASSERT_EQ(run(folder, "library export lib.sclib -o all.sdf").status, 0);
  EXPECT_EQ(file_bytes(dir_ / "cut/all.sdf"), file_bytes(dir_ / "one/all.sdf"));
  EXPECT_EQ(file_bytes(dir_ / "cut/lib.sclib.log"), file_bytes(dir_ / "one/lib.sclib.log"));
  EXPECT_FALSE(fs::exists(dir_ / "one/lib.sclib.d"));
  const ProgramRun one = run("one", "library info lib.sclib");
  const ProgramRun cut = run("cut", "library info lib.sclib");
  EXPECT_NE(one.out.find("5 entries, 5 molecules, 1 shard, "), std::string::npos) << one.out;
  EXPECT_NE(cut.out.find("5 entries, 5 molecules, 3 shards, "), std::string::npos) << cut.out;
  EXPECT_EQ(one.out.substr(one.out.find("settings:")), cut.out.substr(cut.out.find("settings:")));

  const ProgramRun help = run("one", "library build --help");
  for (const char* documented : {"--shard-records", "--resume", "mpirun -np R"})
    EXPECT_NE(help.out.find(documented), std::string::npos) << documented;
}

}  // namespace library_shards

}  // namespace
}  // namespace surfcomp
