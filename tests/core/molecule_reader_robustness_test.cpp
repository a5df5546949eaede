// Seeded random truncations and corruptions of small valid SDF, MOL2, PDB and PQR files: every
// read must either return a valid Molecule or throw a surfcomp::Error — never another exception
// type, never a crash (CI runs this suite under ASan+UBSan: ctest -R ReaderRobustness).
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/molecule.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp::io {
namespace {

namespace fs = std::filesystem;

// Cases per format: 150, or $SURFCOMP_FUZZ_CASES for a longer hunt.
int cases_per_format() {
  const char* env = std::getenv("SURFCOMP_FUZZ_CASES");
  return env != nullptr && std::atoi(env) > 0 ? std::atoi(env) : 150;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// The ligand's HETATM, CONECT and END records only, so that corruptions hit atoms.
std::string pdb_atoms_only(const std::string& pdb) {
  std::vector<std::string> kept;
  for (const std::string& line : lines_of(pdb)) {
    if (line.rfind("HETATM", 0) == 0 || line.rfind("CONECT", 0) == 0 || line == "END") {
      kept.push_back(line);
    }
  }
  return joined(kept);
}

// A PQR of the same ligand: PDB columns re-written as whitespace fields, charge 0.1 * (serial
// mod 3 - 1) e, radius 1.7 A.
std::string pqr_from_pdb(const std::string& pdb) {
  std::string text;
  char line[128];
  int serial = 0;
  for (const std::string& record : lines_of(pdb)) {
    if (record.rfind("HETATM", 0) != 0 || record.size() < 54) continue;
    ++serial;
    const std::string name = record.substr(12, 4);
    const std::string residue = record.substr(17, 3);
    std::snprintf(line, sizeof line, "HETATM %5d %-4s %s A %4d %8s %8s %8s %7.4f %6.4f\n", serial,
                  name.c_str(), residue.c_str(), std::stoi(record.substr(22, 4)),
                  record.substr(30, 8).c_str(), record.substr(38, 8).c_str(),
                  record.substr(46, 8).c_str(), 0.1 * (serial % 3 - 1), 1.7);
    text += line;
  }
  return text + "END\n";
}

// One random damage to `text`, described in `what`.
std::string corrupt(const std::string& text, std::mt19937& rng, std::string& what) {
  std::string out = text;
  auto position = [&](std::size_t size) {
    return std::uniform_int_distribution<std::size_t>(0, size == 0 ? 0 : size - 1)(rng);
  };
  const char interesting[] = "0123456789 .-+\n\t@$MENDnaif";
  switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
    case 0: {
      const std::size_t at = position(out.size());
      out.resize(at);
      what = "truncated at byte " + std::to_string(at);
      break;
    }
    case 1: {
      const int count = std::uniform_int_distribution<int>(1, 8)(rng);
      what = std::to_string(count) + " random bytes";
      for (int i = 0; i < count && !out.empty(); ++i) {
        out[position(out.size())] =
            static_cast<char>(std::uniform_int_distribution<int>(0, 255)(rng));
      }
      break;
    }
    case 2: {
      const int count = std::uniform_int_distribution<int>(1, 4)(rng);
      what = std::to_string(count) + " format characters";
      for (int i = 0; i < count && !out.empty(); ++i) {
        out[position(out.size())] = interesting[position(sizeof interesting - 1)];
      }
      break;
    }
    case 3: {
      auto lines = lines_of(out);
      const std::size_t at = position(lines.size());
      if (!lines.empty()) lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(at));
      out = joined(lines);
      what = "line " + std::to_string(at + 1) + " deleted";
      break;
    }
    case 4: {
      auto lines = lines_of(out);
      const std::size_t at = position(lines.size());
      if (!lines.empty()) lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(at), lines[at]);
      out = joined(lines);
      what = "line " + std::to_string(at + 1) + " duplicated";
      break;
    }
    default: {
      const std::size_t at = position(out.size());
      std::string chunk(std::uniform_int_distribution<std::size_t>(1, 40)(rng), ' ');
      for (char& c : chunk) c = static_cast<char>(std::uniform_int_distribution<int>(0, 255)(rng));
      out.insert(at, chunk);
      what = std::to_string(chunk.size()) + " random bytes inserted at " + std::to_string(at);
      break;
    }
  }
  return out;
}

struct Tally {
  int read = 0;
  int rejected = 0;
};

// Reads `cases` corruptions of `valid` (written as `name`) under each of `option_sets`.
Tally fuzz(const std::string& valid, const std::string& name,
           const std::vector<MoleculeReadOptions>& option_sets, unsigned seed) {
  const fs::path dir = fs::temp_directory_path() / ("surfcomp_fuzz_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / name;
  std::mt19937 rng(seed);
  Tally tally;
  for (int i = 0, n = cases_per_format(); i < n; ++i) {
    std::string what;
    const std::string damaged = corrupt(valid, rng, what);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << damaged;
    const MoleculeReadOptions& options =
        option_sets[static_cast<std::size_t>(i) % option_sets.size()];
    SCOPED_TRACE("seed " + std::to_string(seed) + ", case " + std::to_string(i) + ": " + what);
    try {
      const Molecule molecule = read_molecule(file, options);
      EXPECT_NO_THROW(validate_molecule(molecule));
      EXPECT_FALSE(molecule.atoms.empty());
      ++tally.read;
    } catch (const Error&) {
      ++tally.rejected;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "non-surfcomp exception: " << e.what();
    } catch (...) {
      ADD_FAILURE() << "unknown exception type";
    }
  }
  std::error_code ignored;
  fs::remove_all(dir, ignored);
  std::printf("%s: %d read, %d rejected (seed %u)\n", name.c_str(), tally.read, tally.rejected,
              seed);
  return tally;
}

MoleculeReadOptions with(ChargeModel charges, const std::string& ligand = "") {
  MoleculeReadOptions options;
  options.charges = charges;
  options.ligand = ligand;
  return options;
}

void expect_both_outcomes(const Tally& tally) {
  // The corruptions are mild enough that some files still read, and harsh enough that some
  // do not: otherwise the test would exercise only one path.
  EXPECT_GT(tally.read, 0);
  EXPECT_GT(tally.rejected, 0);
}

TEST(MoleculeReaderRobustness, CorruptedSdf) {
  SURFCOMP_SHARED_OR_SKIP(path, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  expect_both_outcomes(fuzz(read_text(path), "ligand.sdf",
                            {with(ChargeModel::file), with(ChargeModel::mmff)}, 1001));
}

TEST(MoleculeReaderRobustness, CorruptedMol2) {
  SURFCOMP_SHARED_OR_SKIP(path, "thermolysin/ligands-common-frame/1THL_ligand.mol2");
  expect_both_outcomes(fuzz(read_text(path), "ligand.mol2",
                            {with(ChargeModel::file), with(ChargeModel::gasteiger)}, 1002));
}

TEST(MoleculeReaderRobustness, CorruptedPdb) {
  SURFCOMP_SHARED_OR_SKIP(path, "thermolysin/ligands-common-frame/1THL_ligand.pdb");
  expect_both_outcomes(fuzz(
      pdb_atoms_only(read_text(path)), "ligand.pdb",
      {with(ChargeModel::file), with(ChargeModel::file, "0DB"), with(ChargeModel::mmff, "0DB")},
      1003));
}

TEST(MoleculeReaderRobustness, CorruptedPqr) {
  SURFCOMP_SHARED_OR_SKIP(path, "thermolysin/ligands-common-frame/1THL_ligand.pdb");
  const std::string pqr = pqr_from_pdb(read_text(path));
  ASSERT_EQ(lines_of(pqr).size(), 36u);  // 35 atoms and END
  expect_both_outcomes(
      fuzz(pqr, "ligand.pqr", {with(ChargeModel::file), with(ChargeModel::file, "0DB")}, 1004));
}

}  // namespace
}  // namespace surfcomp::io
