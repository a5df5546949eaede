// The surfcomp program as a user runs it: the match output contract (result.json), the aligned
// PROBE, bad input giving a one-line error, a non-zero exit and no output file, the former
// names of renamed options, and --help's defaults.
#include "program_run.hpp"
#include "test_data.hpp"

#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/mesh/io/ply.hpp"
#include "surfcomp/mesh/surface.hpp"

#include <Eigen/Dense>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <sstream>
#include <vector>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

using test::file_bytes;
using test::ProgramRun;

/// Each test runs the program in a temporary directory of its own (its outputs), so that
/// ctest -j runs the tests side by side.
class Cli : public ::testing::Test {
 protected:
  /// `surfcomp ARGUMENTS` (test::run_program).
  static ProgramRun run(const std::string& arguments) { return test::run_program(arguments); }

  /// `name` in the test's directory.
  fs::path scratch(const std::string& name) const { return dir_ / name; }

 private:
  const test::TempDir dir_;
};

TEST_F(Cli, MatchWritesTheFirstDistinctPosesWithTheirCoverage) {
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(probe, "thermolysin/ligands-common-frame/4TMN_ligand.sdf");
  const fs::path some = scratch("top.json"), all = scratch("all.json");
  const std::string pair = "match " + ref.string() + " " + probe.string();
  const ProgramRun r = run(pair + " --top 3 -o " + some.string());
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(run(pair + " --all-alignments -o " + all.string()).status, 0);
  std::ifstream some_in(some), all_in(all);
  const nlohmann::json top = nlohmann::json::parse(some_in);
  const nlohmann::json every = nlohmann::json::parse(all_in);
  // The first three alignments that repeat no better one, as the whole list marks them.
  std::vector<nlohmann::json> distinct;
  for (const auto& a : every["alignments"]) {
    if (!a["repeat_of"].is_null()) {
      EXPECT_LT(a["repeat_of"].get<int>(), a["rank"].get<int>());
      EXPECT_TRUE(every["alignments"][a["repeat_of"].get<int>() - 1]["repeat_of"].is_null());
    } else if (distinct.size() < 3) {
      distinct.push_back(a);
    }
  }
  ASSERT_EQ(top["alignments"].size(), 3u);
  EXPECT_EQ(top["alignments_found"], every["alignments_found"]);
  EXPECT_LT(every["alignments_found"]["distinct"].get<std::size_t>(), every["alignments"].size());
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& a = top["alignments"][k];
    EXPECT_EQ(a["rank"], distinct[k]["rank"]);
    EXPECT_EQ(a["transform"], distinct[k]["transform"]);
    // Scored poses are measured: fractions of area.
    for (const char* key : {"score", "reference", "probe"}) {
      EXPECT_GT(a["coverage"][key].get<double>(), 0.0) << key;
      EXPECT_LE(a["coverage"][key].get<double>(), 1.0) << key;
    }
    // The critical points the pairs index are in the file.
    for (const auto& p : a["cp_pairs"]) {
      EXPECT_LT(p[0].get<std::size_t>(), top["critical_points"]["reference"].size());
      EXPECT_LT(p[1].get<std::size_t>(), top["critical_points"]["probe"].size());
    }
  }
  EXPECT_EQ(top["critical_points"]["reference"][0]["type"].get<std::string>().empty(), false);
}

TEST_F(Cli, MatchWritesTheResultContract) {
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(probe, "thermolysin/ligands-common-frame/4TMN_ligand.sdf");
  const fs::path json = scratch("result.json");
  const fs::path aligned = scratch("aligned.sdf");
  const ProgramRun r = run("match " + ref.string() + " " + probe.string() + " -o " + json.string() +
                           " --aligned-out " + aligned.string() + " --trace --all-alignments");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(json);
  const nlohmann::json doc = nlohmann::json::parse(in);
  for (const char* key : {"alignments", "trace", "timing_ms", "parameters"}) {
    EXPECT_TRUE(doc.contains(key)) << key;
  }
  const auto& alignments = doc["alignments"];
  ASSERT_GE(alignments.size(), 1u);
  int expected_rank = 1;
  std::size_t from_axes = 0;
  for (const auto& a : alignments) {
    EXPECT_EQ(a["rank"].get<int>(), expected_rank++);
    ASSERT_EQ(a["transform"].size(), 4u);
    // A rigid transform, row-major: orthonormal rotation, last row 0 0 0 1.
    Eigen::Matrix3d rotation;
    for (int i = 0; i < 4; ++i) {
      ASSERT_EQ(a["transform"][i].size(), 4u);
      for (int j = 0; j < 3 && i < 3; ++j) rotation(i, j) = a["transform"][i][j].get<double>();
    }
    EXPECT_NEAR((rotation * rotation.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-9);
    EXPECT_NEAR(rotation.determinant(), 1.0, 1e-9);
    EXPECT_EQ(a["transform"][3], nlohmann::json({0.0, 0.0, 0.0, 1.0}));
    EXPECT_TRUE(a["r_chem"].is_number());
    EXPECT_TRUE(a["consensus"].is_number());
    for (const char* key : {"score", "shape", "chem", "atoms"})
      EXPECT_TRUE(a["overlay"][key].is_number()) << key;
    if (a["source"] == "principal_axes") {  // no CP correspondences, no place in the tree
      ++from_axes;
      EXPECT_TRUE(a["refined"].get<bool>());
      EXPECT_EQ(a["n_points"].get<int>(), 0);
      EXPECT_TRUE(a["cp_pairs"].empty());
      EXPECT_TRUE(a["parent"].is_null());
      EXPECT_TRUE(a["children"].empty());
      continue;
    }
    EXPECT_EQ(a["source"], "cliques");
    EXPECT_LE(a["rmsd"].get<double>(), 4.0);
    EXPECT_GT(a["n_points"].get<int>(), 0);
    EXPECT_GE(a["cp_pairs"].size(), 2u);
    for (const auto& pair : a["cp_pairs"]) EXPECT_EQ(pair.size(), 2u);
    EXPECT_TRUE(a["parent"].is_null() || a["parent"].get<int>() >= 1);
    for (const auto& child : a["children"]) {
      // The tree links agree both ways.
      EXPECT_EQ(alignments[child.get<int>() - 1]["parent"], a["rank"]);
    }
  }
  EXPECT_GT(from_axes, 0u);
  EXPECT_LE(from_axes, 24u);
  // Both inputs are molecules: the top pose is judged on their heteroatoms too.
  EXPECT_GT(alignments[0]["overlay"]["atoms"].get<double>(), 0.0);
  EXPECT_LE(alignments[0]["overlay"]["atoms"].get<double>(), 1.0);
  EXPECT_EQ(doc["parameters"]["overlay_atom_weight"], 14.0);
  EXPECT_EQ(doc["parameters"]["overlay_tolerance"], 0.1);
  EXPECT_EQ(doc["parameters"]["polish_top"], 5);
  EXPECT_EQ(doc["parameters"]["atom_polish_sigma"], 0.5);
  EXPECT_EQ(doc["parameters"]["atom_polish_weight"], 1.0);
  // The scored alignments go by overlay score + weight atom fit.
  EXPECT_GT(alignments[0]["atom_fit"].get<double>(), 0.0);
  EXPECT_LE(alignments[0]["atom_fit"].get<double>(), 1.0);
  EXPECT_GE(
      alignments[0]["overlay"]["score"].get<double>() + alignments[0]["atom_fit"].get<double>(),
      alignments[1]["overlay"]["score"].get<double>() + alignments[1]["atom_fit"].get<double>());
  // The table's first row shows the same atom fit in its column of that name.
  std::istringstream table(r.out);
  std::vector<std::string> header, first;
  for (std::string line; std::getline(table, line);) {
    std::istringstream words(line);
    std::vector<std::string> row{std::istream_iterator<std::string>(words), {}};
    if (!row.empty() && row[0] == "rank") header = row;
    if (!header.empty() && !row.empty() && row[0] == "1") first = row;
  }
  const auto column = std::find(header.begin(), header.end(), "atom_fit");
  ASSERT_NE(column, header.end()) << r.out;
  const auto index = static_cast<std::size_t>(column - header.begin());
  ASSERT_GT(first.size(), index) << r.out;
  EXPECT_NEAR(std::stod(first[index]), alignments[0]["atom_fit"].get<double>(), 5e-4);
  EXPECT_EQ(doc["parameters"]["principal_axes_starts"], 24);
  EXPECT_EQ(doc["parameters"]["site_principal_axes_starts"], 24);
  EXPECT_TRUE(doc["parameters"]["site_overlay_radius"].is_number());
  const auto& trace = doc["trace"];
  ASSERT_EQ(trace.size(), 5u);
  EXPECT_EQ(trace[0]["stage"], "critical points");
  for (std::size_t i = 1; i < trace.size(); ++i) {
    EXPECT_LE(trace[i]["nodes"].get<int>(), trace[i - 1]["nodes"].get<int>());
  }
  EXPECT_TRUE(fs::exists(aligned));
  EXPECT_GT(fs::file_size(aligned), 1000u);
}

// A .hsi file built from a molecule keeps its heavy atoms: matching the .hsi files gives the
// alignments that matching the molecules gives, atom term included.
TEST_F(Cli, HsiFilesMatchAsTheirMoleculesDo) {
  SURFCOMP_SHARED_OR_SKIP(ref, "thermolysin/ligands-common-frame/3TMN_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(probe, "thermolysin/ligands-common-frame/1TMN_ligand.sdf");
  const fs::path ref_hsi = scratch("3TMN.hsi");
  const fs::path probe_hsi = scratch("1TMN.hsi");
  ASSERT_EQ(run("hsi-build " + ref.string() + " -o " + ref_hsi.string()).status, 0);
  ASSERT_EQ(run("hsi-build " + probe.string() + " -o " + probe_hsi.string()).status, 0);
  const fs::path from_molecules = scratch("molecules.json");
  const fs::path from_hsi = scratch("hsi.json");
  ASSERT_EQ(
      run("match " + ref.string() + " " + probe.string() + " -o " + from_molecules.string()).status,
      0);
  ASSERT_EQ(run("match " + ref_hsi.string() + " " + probe_hsi.string() + " -o " + from_hsi.string())
                .status,
            0);
  std::ifstream a_in(from_molecules), b_in(from_hsi);
  const nlohmann::json a = nlohmann::json::parse(a_in), b = nlohmann::json::parse(b_in);
  ASSERT_EQ(a["alignments"].size(), b["alignments"].size());
  ASSERT_GE(a["alignments"].size(), 1u);
  const auto& top_a = a["alignments"][0];
  const auto& top_b = b["alignments"][0];
  EXPECT_GT(top_a["overlay"]["atoms"].get<double>(), 0.0);
  EXPECT_NEAR(top_a["overlay"]["atoms"].get<double>(), top_b["overlay"]["atoms"].get<double>(),
              1e-12);
  EXPECT_NEAR(top_a["overlay"]["score"].get<double>(), top_b["overlay"]["score"].get<double>(),
              1e-12);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      EXPECT_NEAR(top_a["transform"][i][j].get<double>(), top_b["transform"][i][j].get<double>(),
                  1e-9);
    }
  }
  // A mesh carries no atoms: the match says the atom term is off, and still runs.
  const fs::path mesh = scratch("1TMN.ply");
  ASSERT_EQ(run("surf-build " + probe.string() + " -o " + mesh.string()).status, 0);
  const ProgramRun with_mesh =
      run("match " + ref.string() + " " + mesh.string() + " -o " + scratch("mesh.json").string());
  EXPECT_EQ(with_mesh.status, 0) << with_mesh.err;
  EXPECT_NE(with_mesh.err.find("1TMN.ply carries no atoms"), std::string::npos) << with_mesh.err;
}

TEST_F(Cli, BadInputGivesOneLineErrorAndNoOutput) {
  SURFCOMP_SHARED_OR_SKIP(ligand, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(protein, "thermolysin/1THL.pdb");
  const fs::path json = scratch("bad.json");
  const fs::path hsi_a = scratch("a.hsi");
  const fs::path hsi_b = scratch("b.hsi");
  ASSERT_EQ(run("hsi-build " + ligand.string() + " -o " + hsi_a.string()).status, 0);
  ASSERT_EQ(
      run("hsi-build " + ligand.string() + " -o " + hsi_b.string() + " --patch-radius 6").status,
      0);
  struct Case {
    std::string arguments, expected;
  };
  const Case cases[] = {
      {"match /nonexistent/a.sdf " + ligand.string(), "a.sdf"},
      {"match " + protein.string() + " " + protein.string() + " --site-ligand XYZ", "XYZ"},
      {"match " + protein.string() + " " + protein.string() + " --site-sphere 0,0,0,1",
       "no atom lies within"},
      {"match " + protein.string() + " " + protein.string() +
           " --site-sphere 8.335,52.235,-0.041,0.5",
       "no critical point"},
      {"match " + hsi_a.string() + " " + hsi_b.string(), "different parameters"},
      {"match " + ligand.string() + " " + ligand.string() + " --site-sphere 1,2", "x,y,z,r"},
      {"match " + ligand.string(), "REF and PROBE"},
      {"surf-build " + ligand.string() + " --probe-radius nan", "probe-radius"},
      {"surf-build " + ligand.string() + " --density 100",
       "--density: value 100 is outside [0.05, 20]"},
      {"match " + ligand.string() + " " + ligand.string() + " --principal-axes-starts 5",
       "principal-axes-starts"},
      {"match " + ligand.string() + " " + ligand.string() + " --site-principal-axes-starts 3",
       "site-principal-axes-starts"},
      {"match " + ligand.string() + " " + ligand.string() + " --site-overlay-radius 0",
       "site-overlay-radius"},
      {"match " + ligand.string() + " " + ligand.string() + " --site-chem-weight -1",
       "site-chem-weight"},
      {"match " + ligand.string() + " " + ligand.string() + " --overlay-atom-weight -1",
       "overlay-atom-weight"},
      {"match " + ligand.string() + " " + ligand.string() + " --overlay-tolerance -0.1",
       "overlay-tolerance"},
      {"match " + ligand.string() + " " + ligand.string() + " --polish-top -1", "polish-top"},
  };
  for (const Case& c : cases) {
    const ProgramRun r = run(c.arguments + " -o " + json.string());
    EXPECT_NE(r.status, 0) << c.arguments;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.arguments << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line: " << r.err;
    EXPECT_FALSE(fs::exists(json)) << c.arguments;
  }
}

TEST_F(Cli, ABadProbeIsRefusedBeforeTheReferenceSurfaceIsBuilt) {
  SURFCOMP_SHARED_OR_SKIP(reference, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  const fs::path garbage = scratch("garbage.sdf");
  std::ofstream(garbage) << "garbage\nnot a molfile\n";
  // --verbose logs each side's surface as it is built: none may be logged before the refusal.
  const ProgramRun r = run("match " + reference.string() + " " + garbage.string() + " -v -o " +
                           scratch("r.json").string());
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("error: " + garbage.string() + ": "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("surface of"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(scratch("r.json")));
}

TEST_F(Cli, NoAlignmentStillWritesTheJsonAndSaysTheProbeWasNotMoved) {
  SURFCOMP_SHARED_OR_SKIP(reference, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(probe, "thermolysin/ligands-common-frame/4TMN_ligand.sdf");
  // An image threshold no pair of images reaches and no principal-axes starts: no alignment.
  const fs::path json = scratch("none.json");
  const fs::path aligned = scratch("none.sdf");
  const ProgramRun r = run("match " + reference.string() + " " + probe.string() +
                           " --image-threshold 0.999 --principal-axes-starts 0 -o " +
                           json.string() + " --aligned-out " + aligned.string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: no alignment found: " + aligned.string() + " not written"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(aligned));
  ASSERT_TRUE(fs::exists(json));
  std::ifstream in(json);
  const nlohmann::json document = nlohmann::json::parse(in);
  EXPECT_TRUE(document.at("alignments").empty());
}

/// What `surfcomp ARGUMENTS` prints on stdout.
std::string program_output(const std::string& arguments) {
  return test::run_program(arguments).out;
}

/// The renamed options and their former names (tools/options.cpp), as a subcommand takes them.
struct Renamed {
  const char* old_name;
  const char* new_name;
  const char* value;
};

// The options renamed so that a flag, its field and its JSON key say the same thing: the new
// names work; each former name still works, sets the same option and prints one deprecation
// note; giving both names is a syntax error; --help lists only the new names.
TEST_F(Cli, RenamedOptionsKeepTheirFormerNamesAsDeprecatedAliases) {
  SURFCOMP_SHARED_OR_SKIP(ligand, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  const Renamed build_options[] = {{"grid-rings", "image-rings", "12"},
                                   {"grid-sectors", "image-sectors", "90"},
                                   {"radius", "critical-point-radius", "2.4"},
                                   {"probe", "probe-radius", "1.3"}};
  const Renamed match_options[] = {{"fuzzy", "fuzzy-threshold", "0.25"},
                                   {"hsi-r", "image-threshold", "0.45"},
                                   {"axes-starts", "principal-axes-starts", "4"},
                                   {"site-axes-starts", "site-principal-axes-starts", "0"}};
  const auto flags = [](const auto& options, bool former) {
    std::string text;
    for (const Renamed& o : options)
      text += std::string(" --") + (former ? o.old_name : o.new_name) + " " + o.value;
    return text;
  };
  const auto note = [](const Renamed& o) {
    return std::string("note: --") + o.old_name + " is deprecated; use --" + o.new_name + "\n";
  };

  // hsi-build: the same .hsi file, byte for byte, under either names.
  const fs::path new_hsi = scratch("new.hsi"), old_hsi = scratch("old.hsi");
  const ProgramRun build_new =
      run("hsi-build " + ligand.string() + " -o " + new_hsi.string() + flags(build_options, false));
  ASSERT_EQ(build_new.status, 0) << build_new.err;
  EXPECT_EQ(build_new.err, "");
  const ProgramRun build_old =
      run("hsi-build " + ligand.string() + " -o " + old_hsi.string() + flags(build_options, true));
  ASSERT_EQ(build_old.status, 0) << build_old.err;
  std::string notes;
  for (const Renamed& o : build_options) notes += note(o);
  EXPECT_EQ(build_old.err, notes);
  EXPECT_EQ(file_bytes(new_hsi), file_bytes(old_hsi));
  const harmonic::SurfaceDescriptors built = harmonic::io::read_hsi(new_hsi);
  EXPECT_EQ(built.options.image.rings, 12);
  EXPECT_EQ(built.options.image.sectors, 90);
  EXPECT_EQ(built.options.critical_points.radius, 2.4);

  // match: the same parameters and alignments under either names.
  const fs::path new_json = scratch("new.json"), old_json = scratch("old.json");
  const std::string inputs = new_hsi.string() + " " + new_hsi.string();
  const ProgramRun match_new =
      run("match " + inputs + " -o " + new_json.string() + flags(match_options, false));
  ASSERT_EQ(match_new.status, 0) << match_new.err;
  EXPECT_EQ(match_new.err, "");
  const ProgramRun match_old =
      run("match " + inputs + " -o " + old_json.string() + flags(match_options, true));
  ASSERT_EQ(match_old.status, 0) << match_old.err;
  notes.clear();
  for (const Renamed& o : match_options) notes += note(o);
  EXPECT_EQ(match_old.err, notes);
  std::ifstream new_in(new_json), old_in(old_json);
  const nlohmann::json by_new = nlohmann::json::parse(new_in),
                       by_old = nlohmann::json::parse(old_in);
  EXPECT_EQ(by_new["parameters"], by_old["parameters"]);
  EXPECT_EQ(by_new["alignments"], by_old["alignments"]);
  const nlohmann::json& parameters = by_new["parameters"];
  EXPECT_EQ(parameters["fuzzy_threshold"], 0.25);
  EXPECT_EQ(parameters["image_threshold"], 0.45);
  EXPECT_EQ(parameters["principal_axes_starts"], 4);
  EXPECT_EQ(parameters["site_principal_axes_starts"], 0);
  EXPECT_EQ(parameters["image_rings"], 12);
  EXPECT_EQ(parameters["image_sectors"], 90);
  EXPECT_EQ(parameters["critical_point_radius"], 2.4);

  // cp-detect and surf-build take their renamed options' former names too.
  const ProgramRun detect = run("cp-detect " + ligand.string() + " -o " +
                                scratch("cps.json").string() + " --radius 2.4 --probe 1.3");
  EXPECT_EQ(detect.status, 0) << detect.err;
  EXPECT_EQ(detect.err, note(build_options[2]) + note(build_options[3]));

  // Both names of one option: refused before any work, one line, exit 2, no output.
  const auto expect_refused = [&](const std::string& command, const std::string& arguments,
                                  const fs::path& output, const Renamed& o) {
    const ProgramRun r = run(command + " " + arguments + " -o " + output.string() + " --" +
                             o.old_name + " " + o.value + " --" + o.new_name + " " + o.value);
    EXPECT_EQ(r.status, 2) << o.old_name << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line: " << r.err;
    const std::string expected =
        std::string("--") + o.old_name + " is the former name of --" + o.new_name;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(output)) << o.old_name;
  };
  for (const Renamed& o : build_options) {
    expect_refused("hsi-build", ligand.string(), scratch("refused.hsi"), o);
  }
  for (const Renamed& o : match_options) {
    expect_refused("match", inputs, scratch("refused.json"), o);
  }
  expect_refused("cp-detect", ligand.string(), scratch("refused.json"), build_options[2]);
  expect_refused("surf-build", ligand.string(), scratch("refused.ply"), build_options[3]);

  // --help shows the new names only.
  for (const auto& [command, options] :
       {std::pair<const char*, const Renamed*>{"hsi-build", build_options},
        std::pair<const char*, const Renamed*>{"match", match_options}}) {
    const std::string help = program_output(std::string(command) + " --help");
    ASSERT_NE(help.find("--help"), std::string::npos) << command;
    for (int i = 0; i < 4; ++i) {
      const Renamed& o = options[i];
      EXPECT_NE(help.find(std::string("--") + o.new_name + " "), std::string::npos) << o.new_name;
      EXPECT_EQ(help.find(std::string("--") + o.old_name + " "), std::string::npos) << o.old_name;
    }
  }
}

// --help shows each default as a user would write it: the shortest decimal that reads back as
// the default (1.4, not 1.3999999999999999).
TEST_F(Cli, HelpShowsDefaultsInTheirShortestForm) {
  for (const std::string command : {"surf-build", "match", "hsi-build"}) {
    const ProgramRun r = run(command + " --help");
    ASSERT_EQ(r.status, 0) << command;
    const std::string& help = r.out;
    EXPECT_EQ(help.find("99999"), std::string::npos) << command << "\n" << help;
    EXPECT_EQ(help.find("00000001"), std::string::npos) << command << "\n" << help;
    EXPECT_NE(help.find("--probe-radius arg (=1.4)"), std::string::npos) << command << "\n" << help;
  }
}

// --quiet leaves stdout and stderr empty on success; --verbose adds each step on stderr.
TEST_F(Cli, QuietSaysNothingAndVerboseSaysEachStep) {
  const fs::path data = fs::path(SURFCOMP_SOURCE_DIR) / "datasets" / "cache" / "rdkit-data";
  if (!fs::exists(data / "4i23_1C9.pdb")) SURFCOMP_DATA_ABSENT(data.string() + " is not fetched");
  const std::string pair =
      (data / "4i23_1C9.pdb").string() + " " + (data / "4i24_1C9.pdb").string();
  const ProgramRun quiet = run("match " + pair + " -q -o " + scratch("q.json").string());
  ASSERT_EQ(quiet.status, 0) << quiet.err;
  EXPECT_EQ(quiet.out, "");
  EXPECT_EQ(quiet.err, "");
  EXPECT_TRUE(fs::exists(scratch("q.json")));
  const ProgramRun verbose = run("match " + pair + " --verbose");
  ASSERT_EQ(verbose.status, 0) << verbose.err;
  // Each long stage of a surface says when it starts and ends, also when stderr is a log.
  for (const char* expected : {"] REF ", "22 atoms, surface of", "] PROBE ", "imaged", "] match: ",
                               "] SES: 4 stages", "] SES done", "] ESP done", "] curvature done"})
    EXPECT_NE(verbose.err.find(expected), std::string::npos) << expected << "\n" << verbose.err;
  EXPECT_NE(verbose.out.find("alignments"), std::string::npos);
  const ProgramRun both = run("match " + pair + " -q -v");
  EXPECT_NE(both.status, 0);
  EXPECT_NE(both.err.find("cannot be combined"), std::string::npos) << both.err;
}

/// A bumpy closed mesh `size` across about 2, as an OFF file: an octahedron subdivided `levels`
/// times onto the sphere, its radius modulated by smooth waves (peaks and valleys).
void write_blob_off(const fs::path& path, double size, int levels) {
  std::vector<Eigen::Vector3d> v = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  std::vector<Eigen::Vector3i> f = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                    {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto found = middle.find(key);
      if (found != middle.end()) return found->second;
      v.push_back((v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]).normalized());
      return middle[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<Eigen::Vector3i> next;
    for (const Eigen::Vector3i& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.insert(next.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
    }
    f = next;
  }
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << v.size() << " " << f.size() << " 0\n";
  for (const Eigen::Vector3d& p : v) {
    const double r = 1.0 + 0.18 * std::sin(3.0 * p.x() + 0.4) * std::cos(2.0 * p.y() - 0.3) +
                     0.12 * std::cos(4.0 * p.z() + 1.3 * p.x() + 0.2 * p.y());
    out << size * r * p.x() << " " << size * r * p.y() << " " << size * r * p.z() << "\n";
  }
  for (const Eigen::Vector3i& t : f) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
}

TEST_F(Cli, StageToolsDescribeAMeshAtItsOwnScale) {
  // The same mesh in metres and in millimetres: the same critical points (vertices), with
  // positions in each file's coordinates, and the unit in the JSON.
  std::vector<std::vector<int>> vertices;
  std::vector<double> units, first_x;
  for (const double size : {0.05, 50.0}) {
    const fs::path off = scratch("blob" + std::to_string(vertices.size()) + ".off");
    const fs::path json = scratch("cps" + std::to_string(vertices.size()) + ".json");
    write_blob_off(off, size, 5);
    const ProgramRun r = run("cp-detect " + off.string() + " -o " + json.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("units of"), std::string::npos) << r.out;
    std::ifstream in(json);
    const nlohmann::json document = nlohmann::json::parse(in);
    std::vector<int> found;
    for (const auto& point : document["critical_points"]) found.push_back(point["vertex"]);
    vertices.push_back(found);
    units.push_back(document["parameters"]["length_unit"]);
    const auto& position = document["critical_points"][0]["position"];
    first_x.push_back(std::hypot(double(position[0]), double(position[1]), double(position[2])));

    const ProgramRun built = run("surf-build " + off.string() + " -o " + scratch("s.ply").string());
    ASSERT_EQ(built.status, 0) << built.err;
    EXPECT_NE(built.out.find("length unit"), std::string::npos) << built.out;
    EXPECT_EQ(built.out.find("A^2"), std::string::npos)
        << "a general mesh is not in A: " << built.out;
  }
  ASSERT_GE(vertices.front().size(), 4u);
  EXPECT_EQ(vertices.front(), vertices.back());
  EXPECT_NEAR(units.back() / units.front(), 1000.0, 1e-6);
  EXPECT_NEAR(first_x.back() / first_x.front(), 1000.0, 1e-6);

  // --unit takes a positive length; hsi-build and patch-map describe the mesh as cp-detect does.
  const fs::path off = scratch("blob0.off");
  for (const char* unit : {"0", "nan", "-1"}) {
    const ProgramRun r =
        run("cp-detect " + off.string() + " --unit " + unit + " -o " + scratch("u.json").string());
    EXPECT_EQ(r.status, 2) << unit;
    EXPECT_NE(r.err.find("--unit"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(scratch("u.json")));
  }
  const ProgramRun hsi = run("hsi-build " + off.string() + " -o " + scratch("b.hsi").string());
  ASSERT_EQ(hsi.status, 0) << hsi.err;
  const harmonic::SurfaceDescriptors stored = harmonic::io::read_hsi(scratch("b.hsi"));
  EXPECT_NEAR(stored.length_unit, units.front(), 1e-12 * units.front());
  std::vector<int> described;
  for (const auto& cp : stored.critical_points) described.push_back(cp.point.vertex);
  EXPECT_EQ(described, vertices.front());
  const ProgramRun maps =
      run("patch-map " + off.string() + " --cp 0 -o " + scratch("maps").string() + "/");
  ASSERT_EQ(maps.status, 0) << maps.err;
  EXPECT_TRUE(fs::exists(scratch("maps") / "patch_maps.json"));

  // A mesh over the stated vertex limit is refused in one line, with or without --repair.
  const std::size_t n_vertices = harmonic::io::read_hsi(scratch("b.hsi")).surface.n_vertices();
  for (const char* repair : {"", " --repair"}) {
    const ProgramRun over =
        run("cp-detect " + off.string() + " --max-vertices " + std::to_string(n_vertices - 1) +
            repair + " -o " + scratch("over.json").string());
    EXPECT_EQ(over.status, 1) << over.err;
    EXPECT_NE(over.err.find(off.string() + ": " + std::to_string(n_vertices) +
                            " vertices, more than --max-vertices"),
              std::string::npos)
        << over.err;
    EXPECT_EQ(std::count(over.err.begin(), over.err.end(), '\n'), 1) << over.err;
    EXPECT_FALSE(fs::exists(scratch("over.json")));
  }
}

TEST_F(Cli, MatrixWritesTheSetsScoresAndRefusesWhatCannotRun) {
  SURFCOMP_SHARED_OR_SKIP(first, "thermolysin/ligands-original/ligand1THL.sdf");
  SURFCOMP_SHARED_OR_SKIP(second, "thermolysin/ligands-original/ligand1TMN.sdf");
  const fs::path csv = scratch("similarity.csv");
  const ProgramRun r =
      run("matrix " + first.string() + " " + second.string() + " -o " + csv.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(csv);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(std::count(lines[0].begin(), lines[0].end(), ','), 2) << lines[0];
  // The diagonal is the self-match, the pair's score is match's (checked in matrix_test).
  EXPECT_NE(lines[1].find(",1.0000,"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].rfind(",1.0000"), std::string::npos) << lines[2];
  fs::remove(csv);
  struct Case {
    std::string arguments, expected;
  };
  const Case cases[] = {
      {"matrix " + first.string(), "a set of one molecule has no pair"},
      {"matrix " + first.string() + " " + second.string() + " --max-pairs 2",
       "3 pairs (2 x 2 molecules) is more than --max-pairs 2"},
      {"matrix /nonexistent/a.sdf " + first.string(), "a.sdf"},
      {"matrix " + first.string() + " --against " + second.string() + " --fuzzy-threshold 2",
       "fuzzy-threshold"},
  };
  for (const Case& c : cases) {
    const ProgramRun bad = run(c.arguments + " -o " + csv.string());
    EXPECT_NE(bad.status, 0) << c.arguments;
    EXPECT_NE(bad.err.find(c.expected), std::string::npos) << c.arguments << "\n" << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << "not one line: " << bad.err;
    EXPECT_FALSE(fs::exists(csv)) << c.arguments;
  }
  const ProgramRun no_output = run("matrix " + first.string() + " " + second.string());
  EXPECT_EQ(no_output.status, 2);
  EXPECT_NE(no_output.err.find("--output"), std::string::npos) << no_output.err;
}

// The processes of an MPI job split the pairs of every stage; rank 0 writes the same matrix (or
// neighbours) as one process, a failed full match's warning included.
TEST_F(Cli, MatrixIsTheSameUnderMpiWithOneTwoAndThreeProcesses) {
#ifndef SURFCOMP_MPIEXEC
  GTEST_SKIP() << "surfcomp was built without MPI";
#else
  std::string set;
  for (const char* name : {"1THL", "1TMN", "1TLP", "3TMN", "4TMN"}) {
    SURFCOMP_SHARED_OR_SKIP(ligand,
                            "thermolysin/ligands-original/ligand" + std::string(name) + ".sdf");
    set += " " + ligand.string();
  }
  // Stage 1 for every pair, two refined a row, one full match a row; and a limit that makes a
  // full match fail.
  const std::string options = " --refined-overlays 2 --full-matches 1 --threads 1";
  const std::string failing = " --max-graph-nodes 30 --full-matches 2 --threads 1";
  const fs::path serial = scratch("serial.csv"), serial_failing = scratch("serial_failing.csv");
  const fs::path serial_best = scratch("serial_best.csv");
  ASSERT_EQ(run("matrix" + set + " -o " + serial.string() + options).status, 0);
  ASSERT_EQ(
      run("matrix" + set + " -o " + serial_best.string() + options + " --neighbours 2").status, 0);
  const ProgramRun alone = run("matrix" + set + " -o " + serial_failing.string() + failing);
  ASSERT_EQ(alone.status, 0) << alone.err;
  ASSERT_NE(alone.err.find("not matched (its score is nan)"), std::string::npos) << alone.err;
  for (const char* ranks : {"1", "2", "3"}) {
    const std::string mpirun =
        std::string(SURFCOMP_MPIEXEC) + " --allow-run-as-root --oversubscribe -np " + ranks + " ";
    const fs::path csv = scratch("mpi" + std::string(ranks) + ".csv");
    ProgramRun r =
        test::run_program("matrix" + set + " -o " + csv.string() + options, {{}, mpirun});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(file_bytes(csv), file_bytes(serial)) << ranks << " processes";
    r = test::run_program("matrix" + set + " -o " + csv.string() + options + " --neighbours 2",
                          {{}, mpirun});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(file_bytes(csv), file_bytes(serial_best)) << ranks << " processes";
    r = test::run_program("matrix" + set + " -o " + csv.string() + failing, {{}, mpirun});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(file_bytes(csv), file_bytes(serial_failing)) << ranks << " processes";
    const auto warnings = [](const std::string& err) {
      std::string out;
      for (std::size_t at = err.find("warning:"); at != std::string::npos;
           at = err.find("warning:", at + 1))
        out += err.substr(at, err.find('\n', at) - at) + "\n";
      return out;
    };
    EXPECT_EQ(warnings(r.err), warnings(alone.err)) << ranks << " processes";
  }
#endif
}

// --ses-method edt builds the distance-transform SES: a closed surface of the same topology,
// its area and volume near the exact SES's; an unknown method is refused before any work.
TEST_F(Cli, SurfBuildTakesTheDistanceTransformSes) {
  SURFCOMP_SHARED_OR_SKIP(ligand, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  const fs::path exact_ply = scratch("exact.ply"), edt_ply = scratch("edt.ply");
  ASSERT_EQ(run("surf-build " + ligand.string() + " -o " + exact_ply.string()).status, 0);
  const ProgramRun edt =
      run("surf-build " + ligand.string() + " --ses-method edt -o " + edt_ply.string());
  ASSERT_EQ(edt.status, 0) << edt.err;
  const mesh::SurfaceMeasures exact = mesh::measure_surface(mesh::io::read_ply(exact_ply));
  const mesh::SurfaceMeasures fast = mesh::measure_surface(mesh::io::read_ply(edt_ply));
  std::cout << "1THL ligand: exact area " << exact.area << " volume " << exact.volume
            << "; edt area " << fast.area << " volume " << fast.volume << "\n";
  EXPECT_EQ(fast.boundary_edges, 0);
  EXPECT_EQ(fast.euler_characteristic, exact.euler_characteristic);
  // Measured: area -3.1 %, volume +4.3 %; the grid bridges crevices thinner than a voxel.
  EXPECT_NEAR(fast.area, exact.area, 0.04 * exact.area);
  EXPECT_NEAR(fast.volume, exact.volume, 0.055 * exact.volume);
  EXPECT_NE(file_bytes(edt_ply), file_bytes(exact_ply));

  const fs::path refused = scratch("refused.ply");
  const ProgramRun bad =
      run("surf-build " + ligand.string() + " --ses-method fast -o " + refused.string());
  EXPECT_EQ(bad.status, 2) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_NE(bad.err.find("--ses-method"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(refused));
}

}  // namespace
}  // namespace surfcomp
