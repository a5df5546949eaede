// The surfcomp program's promise about its files: an output never replaces an input or another
// output, every option and output is checked before any work, a refused run leaves its inputs
// byte for byte and no file behind, and its one-line message names the files and the problem
// (exit status 2 for a command line that cannot run as given, 1 for a file that cannot be
// written or read).
#include "program_run.hpp"
#include "test_data.hpp"

#include "surfcomp/harmonic/io/hsi_file.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

using test::file_bytes;
using test::ProgramRun;

/// Each test runs the program inside a temporary directory of its own, so that relative names
/// ("./l.pdb") mean files of that directory and ctest -j runs the tests side by side.
class CliOutputs : public ::testing::Test {
 protected:
  /// `surfcomp ARGUMENTS` in the test's directory (test::run_program, which keeps the streams
  /// outside it, whose listing the tests compare).
  ProgramRun run(const std::string& arguments) const {
    return test::run_program(arguments, {dir_path(), ""});
  }

  /// Copies a shared data set file into the test's directory as `name`.
  void copy_in(const fs::path& from, const std::string& name) const {
    fs::copy_file(from, dir_ / name, fs::copy_options::overwrite_existing);
    fs::permissions(dir_ / name, fs::perms::owner_read | fs::perms::owner_write);
  }

  fs::path dir_path() const { return fs::path(dir_ / "x").parent_path(); }
  std::string dir_name() const { return dir_path().filename().string(); }

  /// Every file of the test's directory with its bytes (links as their targets' bytes).
  std::map<std::string, std::string> listing() const {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::directory_iterator(dir_path())) {
      files[entry.path().filename().string()] =
          fs::is_directory(entry.path()) ? "<dir>" : file_bytes(entry.path());
    }
    return files;
  }

  /// Runs `arguments`, which the program must refuse with `status` and one line holding each
  /// of `expected`, leaving the directory (its inputs and every other file) as it was.
  void expect_refused(const std::string& arguments, int status,
                      const std::vector<std::string>& expected) const {
    const auto before = listing();
    const ProgramRun r = run(arguments);
    EXPECT_EQ(r.status, status) << arguments << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1)
        << arguments << "\nnot one line: " << r.err;
    for (const std::string& text : expected) {
      EXPECT_NE(r.err.find(text), std::string::npos)
          << arguments << "\nexpected '" << text << "' in: " << r.err;
    }
    const auto after = listing();
    EXPECT_EQ(after.size(), before.size()) << arguments << ": files were added or removed";
    for (const auto& [name, bytes] : before) {
      const auto found = after.find(name);
      ASSERT_NE(found, after.end()) << arguments << ": " << name << " is gone";
      EXPECT_TRUE(found->second == bytes) << arguments << ": " << name << " changed";
    }
  }

 private:
  const test::TempDir dir_;
};

// The cases of the report: an output onto an input, given by the same name, by another
// spelling of it or through a symbolic link, in every subcommand that writes.
TEST_F(CliOutputs, AnOutputIsNeverAnInput) {
  SURFCOMP_SHARED_OR_SKIP(ligand_pdb, "thermolysin/ligand1THL.pdb");
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(probe, "thermolysin/ligands-common-frame/4TMN_ligand.sdf");
  copy_in(ligand_pdb, "l.pdb");
  copy_in(ref, "r.sdf");
  copy_in(probe, "p.sdf");
  fs::create_symlink("l.pdb", dir_path() / "link.pdb");
  const std::string refused = "refusing to overwrite an input";
  expect_refused("cp-detect l.pdb -o l.pdb", 2, {"--output l.pdb", "INPUT l.pdb", refused});
  expect_refused("cp-detect l.pdb -o ./l.pdb", 2, {"--output ./l.pdb", "INPUT l.pdb", refused});
  expect_refused("cp-detect ./l.pdb -o ../" + dir_name() + "/l.pdb", 2, {"INPUT ./l.pdb"});
  expect_refused("cp-detect l.pdb -o link.pdb", 2, {"--output link.pdb", "INPUT l.pdb"});
  expect_refused("cp-detect l.pdb -o cps.json --points-out l.pdb", 2,
                 {"--points-out l.pdb", "INPUT l.pdb", refused});
  expect_refused("match r.sdf p.sdf -o r.sdf", 2, {"--output r.sdf", "REF r.sdf", refused});
  expect_refused("match r.sdf p.sdf --aligned-out p.sdf", 2,
                 {"--aligned-out p.sdf", "PROBE p.sdf", refused});
  expect_refused("match r.sdf p.sdf --aligned-out ./r.sdf", 2,
                 {"--aligned-out ./r.sdf", "REF r.sdf"});
  expect_refused("surf-build l.pdb -o m.ply --molecule l.pdb", 2, {"--molecule"});

  // A .hsi file and a mesh are inputs like any other.
  ASSERT_EQ(run("hsi-build r.sdf -o r.hsi").status, 0);
  ASSERT_EQ(run("surf-build r.sdf -o r.ply").status, 0);
  expect_refused("cp-detect r.hsi -o r.hsi", 2, {"--output r.hsi", "INPUT r.hsi", refused});
  expect_refused("surf-build r.ply -o ./r.ply", 2, {"--output ./r.ply", "INPUT r.ply", refused});
  expect_refused("match r.hsi p.sdf -o r.hsi", 2, {"REF r.hsi", refused});
  expect_refused("match r.sdf r.ply --aligned-out r.ply", 2, {"PROBE r.ply", refused});
  // patch-map writes cpI.obj files: an OBJ INPUT of that name in the folder is refused.
  ASSERT_EQ(run("surf-build r.sdf -o cp0.obj").status, 0);
  expect_refused("patch-map cp0.obj --cp 0 -o .", 2, {"cp0.obj", refused});
}

// patch-map writes a folder of files: when it cannot write them all, the folder keeps what an
// earlier run left there, untouched.
TEST_F(CliOutputs, APatchMapThatCannotWriteLeavesTheFolderAsItWas) {
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  copy_in(ref, "r.sdf");
  ASSERT_EQ(run("patch-map r.sdf --cp 0 -o maps").status, 0);
  const fs::path maps = dir_path() / "maps";
  fs::create_directory(maps / "cp1.obj");  // where the next run would write a file
  const auto contents = [&] {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::directory_iterator(maps))
      files[entry.path().filename().string()] =
          fs::is_directory(entry.path()) ? "<dir>" : file_bytes(entry.path());
    return files;
  };
  const auto before = contents();
  ASSERT_EQ(before.size(), 6u);  // cp0's four files, patch_maps.json, the folder cp1.obj
  expect_refused("patch-map r.sdf --cp 0 --cp 1 --patch-radius 6 -o maps", 1,
                 {"cp1.obj", "not a regular file"});
  EXPECT_EQ(contents(), before);
}

// Names that are not UTF-8 (a Latin-1 file name) reach the JSON result as U+FFFD, not as an
// internal error.
TEST_F(CliOutputs, ANameThatIsNotUtf8StillGivesAResultFile) {
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(probe, "thermolysin/ligands-common-frame/4TMN_ligand.sdf");
  copy_in(ref, "r\xe9.sdf");
  copy_in(probe, "p.sdf");
  const ProgramRun r = run("match r\xe9.sdf p.sdf -o out.json --refine-top 2");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string json = file_bytes(dir_path() / "out.json");
  EXPECT_NE(json.find("\"r\xef\xbf\xbd.sdf\""), std::string::npos) << json.substr(0, 200);
}

TEST_F(CliOutputs, TwoOutputsAreNeverOneFile) {
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(probe, "thermolysin/ligands-common-frame/4TMN_ligand.sdf");
  copy_in(ref, "r.sdf");
  copy_in(probe, "p.sdf");
  fs::create_directory(dir_path() / "sub");
  const std::string own_name = "give each output its own name";
  expect_refused("cp-detect r.sdf -o cps.pdb --points-out cps.pdb", 2,
                 {"--output cps.pdb", "--points-out cps.pdb", own_name});
  expect_refused("cp-detect r.sdf -o cps.pdb --points-out ./sub/../cps.pdb", 2,
                 {"--output cps.pdb", "--points-out ./sub/../cps.pdb", own_name});
  expect_refused("match r.sdf p.sdf -o out.html --report ./out.html", 2, {"--report ./out.html"});
  expect_refused("match r.sdf p.sdf -o out.sdf --aligned-out ./out.sdf", 2,
                 {"--output out.sdf", "--aligned-out ./out.sdf", own_name});
  // An existing output file is the same file under both names too, and stays as it was.
  std::ofstream(dir_path() / "old.pdb") << "old\n";
  expect_refused("cp-detect r.sdf -o old.pdb --points-out ./old.pdb", 2, {own_name});
}

// Formats, folders and option values are refused before anything is read or built: the inputs
// named here do not exist, so a message about them would mean the check came too late.
TEST_F(CliOutputs, OptionsAndOutputsAreCheckedBeforeAnyWork) {
  expect_refused("match r.sdf p.sdf --rmsd-cut 0", 2, {"--rmsd-cut", "0", "(0, 100]"});
  expect_refused("match r.sdf p.sdf --site-sphere 1,2", 2, {"--site-sphere '1,2'", "x,y,z,r"});
  expect_refused("match r.sdf p.ply --aligned-out moved.pdb", 2,
                 {"--aligned-out moved.pdb", "use .ply", "PROBE is not a molecule"});
  expect_refused("match r.sdf p.pdb --aligned-out moved.sdf", 2,
                 {"--aligned-out moved.sdf", "use .pdb or .ply"});
  expect_refused("match r.sdf p.sdf --aligned-out moved.xyz", 2,
                 {"--aligned-out moved.xyz", "use .sdf, .pdb or .ply"});
  expect_refused("match r.sdf p.sdf --aligned-out missing/moved.sdf", 1,
                 {"missing/moved.sdf", "the folder missing does not exist", "--aligned-out"});
  expect_refused("match r.hsi p.pdb --site-ligand 0DB", 2, {"REF r.hsi", "not a .hsi file"});
  expect_refused("match r.pdb p.pdb --site-ligand HOH", 2,
                 {"--site-ligand HOH", "waters", "dropped", "--site-sphere"});
  expect_refused("match r.pdb p.pdb --probe-site-ligand wat", 2,
                 {"--probe-site-ligand wat", "waters"});
  expect_refused("match r.pdb p.ply --ligand 0DB", 2, {"--ligand", "not a mesh"});
  expect_refused("surf-build l.sdf -o l.vert", 2, {"--output l.vert", "use .ply, .off or .obj"});
  expect_refused("surf-build l.sdf -o missing/l.ply", 1, {"the folder missing does not exist"});
  expect_refused("hsi-build l.sdf -o l.hsx", 2, {"--output l.hsx", "use .hsi"});
  expect_refused("match r.sdf p.sdf --report r.htm", 2, {"--report r.htm", "use .html"});
  expect_refused("report r.sdf p.sdf -o r.json", 2, {"--output r.json", "use .html"});
  expect_refused("report r.sdf p.sdf", 2, {"--output"});
  expect_refused("cp-detect l.sdf -o cps.json --points-out cps.xyz", 2,
                 {"--points-out cps.xyz", "use .pdb or .ply"});
  expect_refused("cp-detect l.sdf -o missing/cps.json", 1, {"the folder missing does not exist"});
  fs::create_directory(dir_path() / "folder.json");
  expect_refused("cp-detect l.sdf -o folder.json", 1,
                 {"folder.json", "exists and is not a regular file"});
  expect_refused("cp-detect l.xyz -o cps.json", 1, {"l.xyz", "unknown input format"});
}

// Every numeric option of every subcommand is range-checked by the option check itself, naming
// the option as the user wrote it (never an internal field or function), with exit status 2.
TEST_F(CliOutputs, NumericOptionsAreRangeCheckedByName) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"surf-build l.sdf -o l.ply", "--probe-radius -1"},
      {"surf-build l.sdf -o l.ply", "--density 0"},
      {"surf-build l.sdf -o l.ply", "--voxel -1"},
      {"surf-build l.sdf -o l.ply", "--eps 0"},
      {"cp-detect l.sdf -o c.json", "--critical-point-radius 0"},
      {"cp-detect l.sdf -o c.json", "--disc-radius -1"},
      {"hsi-build l.sdf -o l.hsi", "--patch-radius 0"},
      {"hsi-build l.sdf -o l.hsi", "--image-rings 0"},
      {"hsi-build l.sdf -o l.hsi", "--image-sectors 0"},
      {"hsi-build l.sdf -o l.hsi", "--threads -1"},
      {"match r.sdf p.sdf", "--top 0"},
      {"match r.sdf p.sdf", "--site-radius 0"},
      {"match r.sdf p.sdf", "--fuzzy-threshold 2"},
      {"match r.sdf p.sdf", "--image-threshold nan"},
      {"match r.sdf p.sdf", "--distance-tolerance -1"},
      {"match r.sdf p.sdf", "--min-distance -1"},
      {"match r.sdf p.sdf", "--overlap-tolerance 181"},
      {"match r.sdf p.sdf", "--rmsd-cut 0"},
      {"match r.sdf p.sdf", "--rmsd-cut inf"},
      {"match r.sdf p.sdf", "--refine-top -1"},
      {"match r.sdf p.sdf", "--overlay-sigma 0"},
      {"match r.sdf p.sdf", "--overlay-chem-weight -1"},
      {"match r.sdf p.sdf", "--patch-radius 0"},
      {"report r.sdf p.sdf -o r.html", "--top -1"},
      {"report r.sdf p.sdf -o r.html", "--max-display-vertices 3"},
      {"report r.sdf p.sdf -o r.html", "--overlay-sigma 0"},
  };
  for (const auto& [command, option] : cases) {
    const std::string name = option.substr(0, option.find(' '));
    expect_refused(command + " " + option, 2, {name + ": value"});
  }
}

TEST_F(CliOutputs, MessagesNameTheFileTheUserGave) {
  // An empty MSMS pair: named by its .vert file.
  std::ofstream(dir_path() / "e.vert").flush();
  std::ofstream(dir_path() / "e.face").flush();
  expect_refused("surf-build e.vert -o e.ply", 1, {"e.vert"});
  // A .hsi file whose surface has no faces: named by the file, not by the stored source.
  harmonic::SurfaceDescriptors empty;
  empty.surface = mesh::Surface::from_arrays(Eigen::MatrixX3d::Zero(3, 3), Eigen::MatrixX3i(0, 3),
                                             "stored-source.sdf");
  harmonic::io::write_hsi(empty, dir_path() / "empty.hsi");
  expect_refused("cp-detect empty.hsi -o cps.json", 1, {"empty.hsi", "no faces"});
  const ProgramRun r = run("cp-detect empty.hsi -o cps.json");
  EXPECT_EQ(r.err.find("stored-source"), std::string::npos) << r.err;
}

// The temporary file of an atomic write has a short name of its own, so an output name as long
// as the file system allows is written, and nothing but the outputs is left.
TEST_F(CliOutputs, LongOutputNamesAreWritten) {
  SURFCOMP_SHARED_OR_SKIP(ligand, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  copy_in(ligand, "l.sdf");
  const std::string stem(250 - 5, 'a');
  const ProgramRun r = run("cp-detect l.sdf -o " + stem + ".json --points-out " + stem + ".pdb");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::set<std::string> expected = {"l.sdf", stem + ".json", stem + ".pdb"};
  std::set<std::string> names;
  for (const auto& [name, bytes] : listing()) names.insert(name);
  EXPECT_EQ(names, expected);
  EXPECT_GT(fs::file_size(dir_path() / (stem + ".pdb")), 100u);
}

// A folder the user cannot write to is refused before the work (root may write anywhere).
TEST_F(CliOutputs, AnUnwritableFolderIsRefusedFirst) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: every folder is writable";
  SURFCOMP_SHARED_OR_SKIP(ligand, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  copy_in(ligand, "l.sdf");
  fs::create_directory(dir_path() / "locked");
  fs::permissions(dir_path() / "locked", fs::perms::owner_read | fs::perms::owner_exec);
  expect_refused("surf-build l.sdf -o locked/l.ply", 1,
                 {"locked/l.ply", "the folder locked is not writable"});
  fs::permissions(dir_path() / "locked", fs::perms::owner_all);
}

}  // namespace
}  // namespace surfcomp
