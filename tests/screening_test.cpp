// Screening libraries and the two-stage screen: a library reads back what was written, field
// for field; a damaged or cut library is refused naming the file; a bad record is skipped and
// listed while the others build; a query that is in the library finds itself first with the
// self-overlay's score and the identity.
#include "test_data.hpp"

#include "surfcomp/core/conformers.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/mesh/molecular_surface.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/library_build.hpp"
#include "surfcomp/screening/screen.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

namespace surfcomp {
namespace {

namespace fs = std::filesystem;

io::MoleculeRecord smiles_record(const std::string& smiles, const std::string& name,
                                 std::size_t record) {
  io::MoleculeRecord r;
  r.source = "test.smi";
  r.record = record;
  r.name = name;
  r.format = io::RecordFormat::smiles;
  r.text = smiles;
  return r;
}

ConformerOptions two_conformers() {
  ConformerOptions options;
  options.count = 2;
  options.seed = 7;
  return options;
}

/// An SDF text of three small molecules, one conformer each (ETKDG), hydrogens explicit.
std::string three_molecule_sdf() {
  std::string sdf;
  ConformerOptions one;
  one.count = 1;
  const std::vector<std::pair<std::string, std::string>> molecules{
      {"CC(=O)Nc1ccc(O)cc1", "paracetamol"},
      {"OC(=O)c1ccccc1O", "salicylic_acid"},
      {"CC(C)Cc1ccc(cc1)C(C)C(=O)O", "ibuprofen"}};
  for (std::size_t i = 0; i < molecules.size(); ++i)
    sdf += generate_conformers(smiles_record(molecules[i].first, molecules[i].second, i + 1), one)
               .front();
  return sdf;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

TEST(Conformers, SameSeedSameConformersAndCountAsked) {
  const io::MoleculeRecord record = smiles_record("CC(=O)Nc1ccc(O)cc1", "paracetamol", 1);
  const std::vector<std::string> a = generate_conformers(record, two_conformers());
  const std::vector<std::string> b = generate_conformers(record, two_conformers());
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a, b);
  EXPECT_NE(a[0], a[1]);
  // Hydrogens are explicit: C8H9NO2 has 20 atoms.
  const Molecule molecule =
      io::read_record_molecule({record.source, 1, "p", io::RecordFormat::mdl, a[0]});
  EXPECT_EQ(molecule.atoms.size(), 20u);
  EXPECT_THROW(generate_conformers(smiles_record("C1CC", "broken", 2), two_conformers()),
               InputError);
}

TEST(MoleculeRecords, DatListNamesByIdColumn) {
  const test::TempDir dir;
  const fs::path path = dir.write("list.dat",
                                  "# Mol_Title\tID\tSMILES\nZINC1\tDUD_x_A_1\tCCO\n"
                                  "ZINC2\tDUD_x_D_2\tc1ccccc1\n");
  const std::vector<io::MoleculeRecord> records = io::read_molecule_records(path);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].name, "DUD_x_D_2");
  EXPECT_EQ(records[1].text, "c1ccccc1");
  EXPECT_EQ(records[1].record, 2u);
  EXPECT_EQ(records[1].format, io::RecordFormat::smiles);
}

TEST(Library, RoundTripKeepsEveryFieldAndFindsByName) {
  const test::TempDir dir;
  screening::LibraryBuildOptions options;
  options.conformers = two_conformers();
  std::vector<screening::LibraryEntry> entries =
      screening::build_entries(smiles_record("CC(=O)Nc1ccc(O)cc1", "paracetamol", 1), options);
  for (auto& e :
       screening::build_entries(smiles_record("OC(=O)c1ccccc1O", "salicylic", 2), options))
    entries.push_back(std::move(e));
  ASSERT_EQ(entries.size(), 4u);
  const fs::path path = dir / "round.sclib";
  screening::write_library(path, entries, "settings text\n");

  const screening::Library library(path);
  EXPECT_EQ(library.version(), screening::library_format_version);
  EXPECT_EQ(library.settings(), "settings text\n");
  EXPECT_EQ(library.file_bytes(), fs::file_size(path));
  ASSERT_EQ(library.size(), entries.size());
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const screening::LibraryEntry& w = entries[i];
    const screening::LibraryEntry r = library.entry(i);
    EXPECT_EQ(r.info.name, w.info.name);
    EXPECT_EQ(r.info.source, w.info.source);
    EXPECT_EQ(r.info.record, w.info.record);
    EXPECT_EQ(r.info.conformer, w.info.conformer);
    EXPECT_EQ(r.info.heavy_atoms, w.info.heavy_atoms);
    EXPECT_EQ(r.molecule.text, w.molecule.text);
    EXPECT_EQ(r.molecule.format, w.molecule.format);
    EXPECT_TRUE(r.sample.points == w.sample.points);
    EXPECT_TRUE(r.sample.normals == w.sample.normals);
    EXPECT_TRUE(r.sample.weights == w.sample.weights);
    EXPECT_TRUE(r.sample.esp == w.sample.esp);
    EXPECT_TRUE(r.sample.lp == w.sample.lp);
    EXPECT_EQ(r.atoms.elements, w.atoms.elements);
    EXPECT_TRUE(r.atoms.points == w.atoms.points);
  }
  EXPECT_EQ(entries[0].info.conformer, 1u);
  EXPECT_EQ(entries[1].info.conformer, 2u);
  EXPECT_EQ(entries[0].info.heavy_atoms, 11u);  // paracetamol: C8 N O2
  EXPECT_GT(entries[0].sample.size(), 50u);
  EXPECT_EQ(library.find("salicylic"), (std::vector<std::size_t>{2, 3}));
  EXPECT_TRUE(library.find("absent").empty());
}

/// Expects constructing the library or decoding entry `entry` to throw a FormatError whose
/// one-line message names `path` and holds `expected`.
void expect_refused(const fs::path& path, const std::string& expected, int entry = -1) {
  try {
    const screening::Library library(path);
    if (entry >= 0) library.entry(static_cast<std::size_t>(entry));
    ADD_FAILURE() << "no error for " << expected;
  } catch (const FormatError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(Library, TruncatedOrCorruptIsRefusedNamingTheFile) {
  const test::TempDir dir;
  screening::LibraryBuildOptions options;
  options.conformers = two_conformers();
  const fs::path path = dir / "good.sclib";
  screening::write_library(
      path, screening::build_entries(smiles_record("CC(=O)Nc1ccc(O)cc1", "p", 1), options));
  const std::string good = read_bytes(path);

  const fs::path cut = dir / "cut.sclib";
  write_bytes(cut, good.substr(0, good.size() / 2));
  expect_refused(cut, "truncated");
  write_bytes(cut, good.substr(0, 20));
  expect_refused(cut, "too short");

  const fs::path damaged = dir / "damaged.sclib";
  std::string bytes = good;
  bytes[100] = static_cast<char>(bytes[100] ^ 0x5a);  // inside the first entry
  write_bytes(damaged, bytes);
  expect_refused(damaged, "checksum", 0);

  bytes = good;
  bytes[bytes.size() - 40] = static_cast<char>(bytes[bytes.size() - 40] ^ 0x5a);  // the index
  write_bytes(damaged, bytes);
  expect_refused(damaged, "checksum");

  bytes = good;
  bytes[0] = 'X';
  write_bytes(damaged, bytes);
  expect_refused(damaged, "magic");

  bytes = good;
  bytes[8] = 9;  // version
  write_bytes(damaged, bytes);
  expect_refused(damaged, "version 9");
}

TEST(LibraryBuild, BadRecordIsSkippedAndListedWhileTheOthersBuild) {
  const test::TempDir dir;
  std::string sdf = three_molecule_sdf();
  // A record between the first and second whose counts line is garbage.
  const std::size_t second = sdf.find("$$$$\n") + 5;
  sdf.insert(second, "broken\n  test\n\nthis is no counts line\nM  END\n$$$$\n");
  const fs::path input = dir.write("mixed.sdf", sdf);
  const std::vector<io::MoleculeRecord> records = screening::read_library_inputs({input});
  ASSERT_EQ(records.size(), 4u);
  const fs::path output = dir / "mixed.sclib";
  const screening::LibraryBuildResult result = screening::build_library(records, output);
  EXPECT_EQ(result.records, 4u);
  EXPECT_EQ(result.entries, 3u);
  ASSERT_EQ(result.skipped.size(), 1u);
  EXPECT_EQ(result.skipped[0].record, 2u);
  EXPECT_EQ(result.skipped[0].name, "broken");
  EXPECT_FALSE(result.skipped[0].reason.empty());
  const screening::Library library(output);
  ASSERT_EQ(library.size(), 3u);
  EXPECT_EQ(library.info(0).record, 1u);
  EXPECT_EQ(library.info(1).record, 3u);
  EXPECT_EQ(library.info(2).name, "ibuprofen");
  EXPECT_EQ(library.info(2).conformer, 0u);
  EXPECT_EQ(result.bytes, fs::file_size(output));
}

TEST(Screen, QueryInTheLibraryFindsItselfFirstWithTheIdentity) {
  const test::TempDir dir;
  const fs::path input = dir.write("three.sdf", three_molecule_sdf());
  const std::vector<io::MoleculeRecord> records = screening::read_library_inputs({input});
  const fs::path path = dir / "three.sclib";
  screening::build_library(records, path);
  const screening::Library library(path);

  const Molecule molecule = io::read_record_molecule(records[1]);
  screening::ScreenOptions options;
  options.candidates = 2;
  options.top = 0;
  const screening::ScreenQuery query = screening::make_screen_query(
      harmonic::describe_surface(mesh::build_molecular_surface(molecule), molecule), options);
  const std::vector<screening::Hit> hits = screening::screen(query, library, options).hits;
  ASSERT_EQ(hits.size(), 3u);
  EXPECT_EQ(hits[0].entry, 1u);
  EXPECT_EQ(hits[0].stage, 2);
  // The self-overlay: every Tanimoto 1 (within the sampling's rounding), the identity pose.
  EXPECT_NEAR(hits[0].fast_score, 1.0, 1e-9);
  EXPECT_NEAR(hits[0].score.score, 1.0, 1e-3);
  EXPECT_NEAR(hits[0].score.shape, 1.0, 1e-3);
  EXPECT_LT((hits[0].score.transform - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff(), 1e-2);
  for (std::size_t i = 1; i < hits.size(); ++i) EXPECT_LT(hits[i].score.score, hits[0].score.score);
  EXPECT_EQ(hits[1].stage, 2);
  EXPECT_EQ(hits[2].stage, 1);
}

}  // namespace
}  // namespace surfcomp
