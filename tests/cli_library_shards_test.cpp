// `surfcomp library build --shard-records N` as a user runs it: the index, shards and log do not
// depend on --threads or on the number of MPI processes; a build killed by SIGKILL continues
// with --resume to the bytes of an uninterrupted build; a resume with other options, and a
// missing or damaged shard, are refused with one line naming the file, changing nothing; a
// sharded library exports and describes as the one file of the same inputs.
#include "program_run.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

using test::file_bytes;
using test::ProgramRun;

/// Every file under `folder` (relative name -> bytes).
std::map<std::string, std::string> files_under(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& item : fs::recursive_directory_iterator(folder)) {
    if (item.is_regular_file())
      files[fs::relative(item.path(), folder).string()] = file_bytes(item.path());
  }
  return files;
}

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

}  // namespace
}  // namespace surfcomp
