// Screening libraries and the three-stage screen: a library reads back what was written, field
// for field; a damaged or cut library is refused naming the file; a bad record is skipped and
// listed while the others build; a query that is in the library finds itself first with the
// self-overlay's score and the identity; stage 2 refines each molecule's best conformers and
// only raises their scores. Pocket libraries: a site list is read line by line; a
// site entry keeps its spheres; a site query finds its own pocket first, and a library of the
// other kind is refused. A .hsi file becomes an entry keeping its surface and heavy atoms. A
// query without an ionic group ranks by the mean of its score and shape unless asked otherwise.
#include "analytic_meshes.hpp"
#include "pocket_cut.hpp"
#include "test_data.hpp"

#include "surfcomp/core/conformers.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/binary_stream.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/site.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/library_build.hpp"
#include "surfcomp/screening/screen.hpp"

#include "screen_stages.hpp"

#include <gtest/gtest.h>

#include "surfcomp/screening/hit_files.hpp"
#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
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

/// The query is library entry `entry`: it comes first from the full match with the
/// self-overlay's scores, every Tanimoto 1 (within the sampling's rounding), at the identity.
void expect_found_itself_first(const std::vector<screening::Hit>& hits, std::size_t entry) {
  ASSERT_FALSE(hits.empty());
  EXPECT_EQ(hits[0].entry, entry);
  EXPECT_EQ(hits[0].stage, 3);
  EXPECT_NEAR(hits[0].fast_score, 1.0, 1e-6);  // single precision
  EXPECT_NEAR(hits[0].score.score, 1.0, 1e-3);
  EXPECT_NEAR(hits[0].score.shape, 1.0, 1e-3);
  EXPECT_LT((hits[0].score.transform - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff(), 1e-2);
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

/// `residues` alanine residues of chain A (N, CA, C, O, CB), 3.8 A apart along x.
Molecule alanine_chain(int residues) {
  Molecule chain;
  const std::pair<const char*, const char*> atoms[] = {
      {"N", "N"}, {"CA", "C"}, {"C", "C"}, {"O", "O"}, {"CB", "C"}};
  for (int r = 0; r < residues; ++r) {
    for (std::size_t a = 0; a < std::size(atoms); ++a) {
      Atom atom;
      atom.name = atoms[a].first;
      atom.element = atoms[a].second;
      atom.residue_name = "ALA";
      atom.residue_number = r + 1;
      atom.chain = "A";
      atom.position = Eigen::Vector3d(3.8 * r + 0.7 * static_cast<double>(a), 0.0, 0.0);
      chain.atoms.push_back(atom);
    }
  }
  return chain;
}

TEST(ScreenQuery, AMacromoleculeQueryIsNamedAndALigandIsNot) {
  EXPECT_EQ(screening::macromolecule_query_warning(alanine_chain(29), "q.pdb"), "");
  EXPECT_EQ(screening::macromolecule_query_warning(alanine_chain(30), "q.pdb"),
            "q.pdb: the query is a macromolecule (150 heavy atoms, a chain of 30 amino-acid "
            "residues): its whole surface is compared with the library's molecules");
  // 1,001 heavy atoms without residues (an SDF record), and 1,000 with 500 hydrogens.
  Molecule large;
  for (int i = 0; i < 1001; ++i) {
    Atom atom;
    atom.element = "C";
    large.atoms.push_back(atom);
  }
  EXPECT_NE(screening::macromolecule_query_warning(large, "big.sdf")
                .find("big.sdf: the query is a macromolecule (1001 heavy atoms)"),
            std::string::npos);
  large.atoms.pop_back();
  for (int i = 0; i < 500; ++i) {
    Atom atom;
    atom.element = "H";
    large.atoms.push_back(atom);
  }
  EXPECT_EQ(screening::macromolecule_query_warning(large, "big.sdf"), "");
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

TEST(LibraryBuild, ConformersShareTheirMoleculeAsReadingEachWouldGiveIt) {
  screening::LibraryBuildOptions options;
  ConformerOptions conformers;
  conformers.count = 3;
  options.conformers = conformers;
  screening::BuildTimes times;
  const std::vector<screening::LibraryEntry> entries = screening::build_entries(
      smiles_record("CC(C)Cc1ccc(cc1)C(C)C(=O)O", "ibuprofen", 1), options, &times);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_GT(times.conformers, 0.0);
  EXPECT_GT(times.entries, 0.0);
  for (const screening::LibraryEntry& entry : entries) {
    // Each conformer's sample is the one its stored block gives when read whole.
    const Molecule read = io::read_record_molecule(entry.molecule);
    const matching::SurfaceSample sample =
        matching::sample_molecule(read, options.spacing, options.surface);
    EXPECT_TRUE(sample.points == entry.sample.points) << entry.info.conformer;
    EXPECT_TRUE(sample.esp == entry.sample.esp) << entry.info.conformer;
    EXPECT_TRUE(sample.lp == entry.sample.lp) << entry.info.conformer;
    const std::optional<std::vector<Eigen::Vector3d>> positions =
        io::mdl_coordinates(entry.molecule.text);
    ASSERT_TRUE(positions.has_value());
    ASSERT_EQ(positions->size(), read.atoms.size());
    for (std::size_t a = 0; a < read.atoms.size(); ++a)
      EXPECT_EQ((*positions)[a], read.atoms[a].position);
  }
  EXPECT_FALSE(io::mdl_coordinates("title\n\n\n  0  0  0  0  0  0  0  0  0  0999 V3000\n"));
  EXPECT_FALSE(
      io::mdl_coordinates("title\n\n\n  2  0  0  0  0  0  0  0  0  0999 V2000\n"
                          "    0.0000    x.0000    0.0000 C\n"));
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
    // The sample as packed (single precision, in compact clusters), bit for bit.
    const matching::SurfaceSample packed = w.packed.sample();
    EXPECT_TRUE(r.sample.points == packed.points);
    EXPECT_TRUE(r.sample.normals == packed.normals);
    EXPECT_TRUE(r.sample.weights == packed.weights);
    EXPECT_TRUE(r.sample.esp == packed.esp);
    EXPECT_TRUE(r.sample.lp == packed.lp);
    EXPECT_EQ(r.kind, matching::SampleKind::atoms);
    EXPECT_EQ(r.packed.header().self_shape, w.packed.header().self_shape);
    EXPECT_EQ(r.atoms.elements, w.atoms.elements);
    EXPECT_TRUE(r.atoms.points.isApprox(w.atoms.points, 1e-6));
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

/// Writes `entries` as a library of format 3 (the layout before single-precision samples: each
/// entry the molecule, its sample in double precision, the heteroatoms, the site spheres, a
/// described surface; an index of one region), as earlier versions of the program wrote it.
void write_version3_library(const fs::path& path,
                            const std::vector<screening::LibraryEntry>& entries) {
  io::BinaryWriter file, index;
  for (const char c : std::string("SURFCLIB")) file.u8(static_cast<std::uint8_t>(c));
  file.u32(3);
  file.u32(0);
  index.u64(entries.size());
  for (const screening::LibraryEntry& e : entries) {
    io::BinaryWriter w;
    w.u8(0);  // an MDL block
    w.string(e.molecule.text);
    w.double_matrix(e.sample.points);
    w.double_matrix(e.sample.normals);
    w.doubles(e.sample.weights);
    w.doubles(e.sample.esp);
    w.doubles(e.sample.lp);
    w.u64(e.atoms.size());
    for (std::size_t a = 0; a < e.atoms.size(); ++a) {
      w.string(e.atoms.elements[a]);
      for (int k = 0; k < 3; ++k) w.f64(e.atoms.points(k, static_cast<Eigen::Index>(a)));
    }
    w.u64(0);  // site spheres
    w.blob({});
    index.u64(file.bytes().size());
    index.u64(w.bytes().size());
    index.u64(io::fnv1a64(w.bytes().data(), w.bytes().size()));
    index.string(e.info.name);
    index.string(e.info.source);
    index.u32(e.info.record);
    index.u32(e.info.conformer);
    index.u32(e.info.heavy_atoms);
    index.u32(0);
    for (const std::uint8_t b : w.bytes()) file.u8(b);
  }
  index.string("format 3\n");
  const std::uint64_t index_offset = file.bytes().size();
  for (const std::uint8_t b : index.bytes()) file.u8(b);
  file.u64(index_offset);
  file.u64(index.bytes().size());
  file.u64(io::fnv1a64(index.bytes().data(), index.bytes().size()));
  for (const char c : std::string("SCLIBEND")) file.u8(static_cast<std::uint8_t>(c));
  write_bytes(path, std::string(file.bytes().begin(), file.bytes().end()));
}

TEST(Library, FormatThreeIsStillReadAndScreened) {
  const test::TempDir dir;
  const std::vector<io::MoleculeRecord> records =
      screening::read_library_inputs({dir.write("three.sdf", three_molecule_sdf())});
  // Entries as format 3 held them: the full surface's sample, double precision.
  std::vector<screening::LibraryEntry> entries;
  for (const io::MoleculeRecord& record : records) {
    const Molecule molecule = io::read_record_molecule(record);
    screening::LibraryEntry entry;
    entry.info.name = record.name;
    entry.info.source = record.source.string();
    entry.info.record = static_cast<std::uint32_t>(record.record);
    entry.molecule = record;
    entry.sample = matching::sample_surface(molsurf::build_molecular_surface(molecule),
                                            matching::OverlayOptions{}.spacing);
    entry.atoms = matching::sample_atoms(harmonic::surface_atoms(molecule));
    entries.push_back(std::move(entry));
  }
  const fs::path path = dir / "old.sclib";
  write_version3_library(path, entries);
  const screening::Library library(path);
  EXPECT_EQ(library.version(), 3u);
  ASSERT_EQ(library.size(), 3u);
  const screening::LibraryEntry read = library.entry(1);
  EXPECT_TRUE(read.sample.points == entries[1].sample.points);
  EXPECT_EQ(read.kind, matching::SampleKind::surface);
  EXPECT_EQ(library.packed(1, 1.0).view.header.points, entries[1].sample.size());
  // A query made from the same molecule finds its entry first, with the identity.
  const Molecule molecule = io::read_record_molecule(records[1]);
  screening::ScreenOptions options;
  options.top = 0;
  options.candidates = 1;
  const screening::ScreenQuery query = screening::make_screen_query(
      harmonic::describe_surface(molsurf::build_molecular_surface(molecule), molecule), options, {},
      &molecule);
  expect_found_itself_first(screening::screen(query, library, options).hits, 1);
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

/// three_molecule_sdf() built into a library in a temporary folder, with its records.
struct ThreeMoleculeLibrary {
  static fs::path built(const std::vector<io::MoleculeRecord>& records, const fs::path& path) {
    screening::build_library(records, path);
    return path;
  }
  const test::TempDir dir;
  const std::vector<io::MoleculeRecord> records =
      screening::read_library_inputs({dir.write("three.sdf", three_molecule_sdf())});
  const screening::Library library{built(records, dir / "three.sclib")};
};

TEST(Screen, QueryInTheLibraryFindsItselfFirstWithTheIdentity) {
  const ThreeMoleculeLibrary three;
  const std::vector<io::MoleculeRecord>& records = three.records;
  const screening::Library& library = three.library;

  const Molecule molecule = io::read_record_molecule(records[1]);
  screening::ScreenOptions options;
  options.candidates = 2;
  options.top = 0;
  const screening::ScreenQuery query = screening::make_screen_query(
      harmonic::describe_surface(molsurf::build_molecular_surface(molecule), molecule), options, {},
      &molecule);
  const std::vector<screening::Hit> hits = screening::screen(query, library, options).hits;
  ASSERT_EQ(hits.size(), 3u);
  expect_found_itself_first(hits, 1);
  for (std::size_t i = 1; i < hits.size(); ++i) EXPECT_LT(hits[i].score.score, hits[0].score.score);
  EXPECT_EQ(hits[1].stage, 3);
  EXPECT_EQ(hits[2].stage, 2);
}

TEST(Screen, StageTwoRefinesEachMoleculesBestConformersAndNeverLowersTheirScores) {
  const test::TempDir dir;
  const std::vector<io::MoleculeRecord> records{
      smiles_record("CC(=O)Nc1ccc(O)cc1", "paracetamol", 1),
      smiles_record("CC(C)Cc1ccc(cc1)C(C)C(=O)O", "ibuprofen", 2),
      smiles_record("OC(=O)c1ccccc1O", "salicylic_acid", 3)};
  screening::LibraryBuildOptions build;
  ConformerOptions conformers;
  conformers.count = 4;
  conformers.seed = 7;
  build.conformers = conformers;
  const fs::path path = dir / "three.sclib";
  screening::build_library(records, path, build);
  const screening::Library library(path);
  ASSERT_GE(library.size(), 6u);

  // The query: ibuprofen in a conformer of its own, which no entry has exactly.
  conformers.seed = 11;
  conformers.count = 1;
  const Molecule molecule = io::read_record_molecule(
      io::MoleculeRecord{"query.sdf", 1, "ibuprofen", io::RecordFormat::mdl,
                         generate_conformers(records[1], conformers).front()});
  screening::ScreenOptions options;
  options.top = 0;
  options.candidates = 0;
  const screening::ScreenQuery query = screening::make_screen_query(
      harmonic::describe_surface(molsurf::build_molecular_surface(molecule), molecule), options, {},
      &molecule);
  std::vector<screening::HitScore> fast;
  for (std::size_t e = 0; e < library.size(); ++e)
    fast.push_back(screening::fast_score(query, library.entry(e), options));
  // Three molecules, their conformers adjacent.
  std::vector<std::size_t> starts{0};
  while (starts.back() < library.size())
    starts.push_back(screening::molecule_start_at(library, starts.back() + 1));
  ASSERT_EQ(starts.size(), 4u);
  EXPECT_EQ(screening::molecule_start_at(library, starts[1]), starts[1]);

  // With refine 2, a molecule's best is one of its two best conformers by fast score, at its
  // refined score (when that is not lower); with refine 0, its best conformer by fast score.
  // Every molecule is kept (top 0): each one's best, by molecule.
  const auto by_molecule = [&](const screening::StreamedScores& streamed) {
    std::vector<screening::MoleculeScore> all(3);
    for (const screening::Hit& hit : streamed.queries[0].best) {
      const auto m = static_cast<std::size_t>(
          std::upper_bound(starts.begin(), starts.end(), hit.entry) - starts.begin() - 1);
      all[m] = {hit.entry, hit.score.score};
    }
    return all;
  };
  options.refine = 2;
  const screening::StreamedScores streamed_two =
      screening::score_molecules({&query}, library, 0, library.size(), options);
  ASSERT_EQ(streamed_two.queries[0].best.size(), 3u);
  const std::vector<screening::MoleculeScore> two = by_molecule(streamed_two);
  options.refine = 0;
  const std::vector<screening::MoleculeScore> none =
      by_molecule(screening::score_molecules({&query}, library, 0, library.size(), options));
  for (std::size_t m = 0; m < 3; ++m) {
    std::vector<std::size_t> order(starts[m + 1] - starts[m]);
    std::iota(order.begin(), order.end(), starts[m]);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t x, std::size_t y) { return fast[x].score > fast[y].score; });
    if (order.size() == 1) order.push_back(order[0]);
    const screening::MoleculeScore& refined = two[m];
    EXPECT_TRUE(refined.entry == order[0] || refined.entry == order[1]) << "molecule " << m;
    const double expected =
        std::max({fast[order[0]].score, fast[order[1]].score,
                  screening::refined_score(query, library.entry(order[0]), options).score,
                  screening::refined_score(query, library.entry(order[1]), options).score});
    EXPECT_NEAR(refined.score, expected, 1e-12) << "molecule " << m;
    EXPECT_EQ(none[m].entry, order[0]);
    EXPECT_EQ(none[m].score, fast[order[0]].score);
  }

  // The refinement only climbs, and it does climb: the overlay from the principal axes alone is
  // not a local optimum.
  double gain = 0.0;
  for (std::size_t e = 0; e < library.size(); ++e) {
    const screening::HitScore refined = screening::refined_score(query, library.entry(e), options);
    EXPECT_GE(refined.score, fast[e].score) << "entry " << e;
    gain = std::max(gain, refined.score - fast[e].score);
  }
  EXPECT_GT(gain, 0.01);

  // The screen ranks by the refined scores: ibuprofen first, every row from stage 2.
  options.refine = 2;
  const std::vector<screening::Hit> hits = screening::screen(query, library, options).hits;
  ASSERT_EQ(hits.size(), 3u);
  EXPECT_EQ(library.info(hits[0].entry).name, "ibuprofen");
  for (const screening::Hit& hit : hits) {
    EXPECT_EQ(hit.stage, 2);
    EXPECT_GE(hit.score.score, hit.fast_score - 1e-12);
  }
  options.refine = 0;
  for (const screening::Hit& hit : screening::screen(query, library, options).hits)
    EXPECT_EQ(hit.stage, 1);
}

/// The molecule of `smiles` in one ETKDG conformer, read as a query file would be.
Molecule conformer_of(const std::string& smiles, const std::string& name) {
  ConformerOptions one;
  one.count = 1;
  one.seed = 3;
  return io::read_record_molecule(
      io::MoleculeRecord{name + ".sdf", 1, name, io::RecordFormat::mdl,
                         generate_conformers(smiles_record(smiles, name, 1), one).front()});
}

TEST(IonicGroups, AFormalChargeCountsUnlessABondedAtomBalancesIt) {
  EXPECT_TRUE(carries_ionic_group(conformer_of("[O-]C(=O)c1ccccc1O", "salicylate")));
  EXPECT_TRUE(carries_ionic_group(conformer_of("C[NH3+]", "methylammonium")));
  EXPECT_TRUE(carries_ionic_group(conformer_of("[NH3+]CC(=O)[O-]", "glycine_zwitterion")));
  EXPECT_FALSE(carries_ionic_group(conformer_of("[O-][N+](=O)c1ccccc1", "nitrobenzene")));
  EXPECT_FALSE(carries_ionic_group(conformer_of("C[N+]1([O-])CCCCC1", "n_oxide")));
  // Without formal charges (a PQR file), the partial charges' sum decides.
  Molecule pqr;
  pqr.atoms.resize(2);
  pqr.atoms[1].position.x() = 1.5;
  pqr.atoms[0].charge = -0.7;
  pqr.atoms[1].charge = -0.3;
  EXPECT_TRUE(carries_ionic_group(pqr));
  pqr.atoms[1].charge = 0.7;
  EXPECT_FALSE(carries_ionic_group(pqr));
}

// Groups drawn neutral that ionise at pH 7 are found by the reader, at the atom that takes the
// charge (the SMILES order; hydrogens come after the heavy atoms); weaker acids and bases are not.
TEST(IonicGroups, AnAcidOrBaseDrawnNeutralCountsAtTheAtomThatIonises) {
  const std::vector<std::pair<std::string, std::vector<std::size_t>>> cases = {
      {"CC(=O)O", {3}},                       // acetic acid: the hydroxyl O
      {"OC(=O)c1ccccc1O", {0}},               // salicylic acid (not the phenol)
      {"CP(=O)(O)O", {3, 4}},                 // methylphosphonic acid
      {"CS(=O)(=O)O", {4}},                   // methanesulfonic acid
      {"Cc1nn[nH]n1", {4}},                   // 5-methyl-2H-tetrazole
      {"Cc1nnn[nH]1", {5}},                   // 5-methyl-1H-tetrazole
      {"CCN", {2}},                           // ethylamine
      {"CN1CCOCC1", {1}},                     // N-methylmorpholine
      {"NC(=N)c1ccccc1", {2}},                // benzamidine: the imine N
      {"NC(N)=N", {3}},                       // guanidine
      {"Nc1ccccc1", {}},                      // aniline
      {"CC(=O)NC", {}},                       // an amide
      {"NS(=O)(=O)c1ccccc1", {}},             // a sulfonamide
      {"CNC(=O)OC", {}},                      // a carbamate
      {"CC=CN(C)C", {}},                      // an enamine
      {"c1ccncc1", {}},                       // pyridine
      {"Oc1ccccc1", {}},                      // phenol
      {"CN=C1CN=C(c2ccccc2)c2ccccc2N1", {}},  // an N-aryl amidine (weakly basic)
  };
  for (const auto& [smiles, expected] : cases) {
    const Molecule molecule = conformer_of(smiles, "m");
    EXPECT_EQ(molecule.ionisable_atoms, expected) << smiles;
    EXPECT_EQ(carries_ionic_group(molecule), !expected.empty()) << smiles;
  }
}

TEST(Screen, ANeutralQueryRanksByScoreAndShapeAndAnIonicOneByItsScore) {
  const ThreeMoleculeLibrary three;
  const std::vector<io::MoleculeRecord>& records = three.records;
  const screening::Library& library = three.library;
  screening::ScreenOptions options;
  options.candidates = 1;
  options.top = 0;
  const auto query_of = [&](const Molecule& molecule, screening::QueryChemistry chemistry) {
    screening::ScreenOptions asked = options;
    asked.chemistry = chemistry;
    return screening::make_screen_query(
        harmonic::describe_surface(molsurf::build_molecular_surface(molecule), molecule), asked, {},
        &molecule);
  };
  const Molecule neutral = io::read_record_molecule(records[0]);  // paracetamol
  const Molecule salicylate = conformer_of("[O-]C(=O)c1ccccc1O", "salicylate");
  const Molecule acid = io::read_record_molecule(records[1]);  // salicylic acid, drawn neutral
  using screening::QueryChemistry;
  EXPECT_EQ(query_of(neutral, QueryChemistry::automatic).shape_weight,
            screening::neutral_query_shape_weight);
  EXPECT_EQ(query_of(neutral, QueryChemistry::on).shape_weight, 0.0);
  EXPECT_EQ(query_of(salicylate, QueryChemistry::automatic).shape_weight, 0.0);
  EXPECT_EQ(query_of(acid, QueryChemistry::automatic).shape_weight, 0.0);
  EXPECT_EQ(query_of(salicylate, QueryChemistry::off).shape_weight, 1.0);

  // Ranked by shape, every row's score is its shape Tanimoto (stage 3's of the full match's
  // pose) and the rows after the candidates go by it; with chemistry the score is not the
  // shape. The stages overlay with chemistry either way: the same molecules get the full match,
  // and every molecule the same conformer, pose and shape term.
  const screening::ScreenQuery by_shape = query_of(neutral, QueryChemistry::off);
  const std::vector<screening::Hit> shape_hits = screening::screen(by_shape, library, options).hits;
  ASSERT_EQ(shape_hits.size(), 3u);
  expect_found_itself_first(shape_hits, 0);
  for (const screening::Hit& hit : shape_hits) EXPECT_EQ(hit.score.score, hit.score.shape);
  EXPECT_GE(shape_hits[1].score.shape, shape_hits[2].score.shape);
  const screening::ScreenQuery chemical = query_of(neutral, QueryChemistry::on);
  const std::vector<screening::Hit> chemical_hits =
      screening::screen(chemical, library, options).hits;
  ASSERT_EQ(chemical_hits.size(), 3u);
  expect_found_itself_first(chemical_hits, 0);
  EXPECT_GT(std::abs(chemical_hits[1].score.score - chemical_hits[1].score.shape), 1e-3);
  for (const screening::Hit& hit : shape_hits) {
    const auto same = std::find_if(chemical_hits.begin(), chemical_hits.end(),
                                   [&](const screening::Hit& h) { return h.entry == hit.entry; });
    ASSERT_NE(same, chemical_hits.end()) << "entry " << hit.entry;
    EXPECT_EQ(same->stage, hit.stage) << "entry " << hit.entry;
    EXPECT_EQ(same->score.shape, hit.score.shape) << "entry " << hit.entry;
    EXPECT_EQ(same->score.transform, hit.score.transform) << "entry " << hit.entry;
  }
  // `auto` ranks the neutral query by the mean of the two: each row's score is the mean of its
  // shape term and the score the same pose has with chemistry.
  const std::vector<screening::Hit> mean_hits =
      screening::screen(query_of(neutral, QueryChemistry::automatic), library, options).hits;
  ASSERT_EQ(mean_hits.size(), 3u);
  expect_found_itself_first(mean_hits, 0);
  for (const screening::Hit& hit : mean_hits) {
    const auto same = std::find_if(chemical_hits.begin(), chemical_hits.end(),
                                   [&](const screening::Hit& h) { return h.entry == hit.entry; });
    ASSERT_NE(same, chemical_hits.end()) << "entry " << hit.entry;
    EXPECT_NEAR(hit.score.score, 0.5 * (same->score.score + same->score.shape), 1e-12)
        << "entry " << hit.entry;
  }
  EXPECT_GE(mean_hits[1].score.score, mean_hits[2].score.score);

  // Fewer rows than molecules: the candidates are kept by score and the other rows by shape, so
  // the rows are the head of all of them, from one range of the library or merged from two.
  const std::size_t middle = screening::molecule_start_at(library, 1);
  for (const auto& [top, candidates] :
       {std::pair<std::size_t, std::size_t>{2, 1}, {1, 2}, {2, 0}, {1, 0}}) {
    SCOPED_TRACE("top " + std::to_string(top) + ", candidates " + std::to_string(candidates));
    screening::ScreenOptions bounded = options;
    bounded.candidates = candidates;
    bounded.top = 0;
    const std::vector<screening::Hit> all = screening::screen(by_shape, library, bounded).hits;
    bounded.top = top;
    const std::vector<screening::Hit> head = screening::screen(by_shape, library, bounded).hits;
    ASSERT_EQ(head.size(), top);
    for (std::size_t i = 0; i < top; ++i) {
      EXPECT_EQ(head[i].entry, all[i].entry) << "row " << i + 1;
      EXPECT_EQ(head[i].stage, all[i].stage) << "row " << i + 1;
      EXPECT_EQ(head[i].score.score, all[i].score.score) << "row " << i + 1;
    }
    const auto best_of = [&](std::size_t begin, std::size_t end) {
      return screening::score_molecules({&by_shape}, library, begin, end, bounded).queries[0].best;
    };
    const std::vector<screening::Hit> whole = best_of(0, library.size());
    const std::vector<screening::Hit> merged =
        screening::merge_best({best_of(0, middle), best_of(middle, library.size())}, bounded, 1.0);
    ASSERT_EQ(merged.size(), whole.size());
    for (std::size_t i = 0; i < whole.size(); ++i) {
      EXPECT_EQ(merged[i].entry, whole[i].entry) << i;
      EXPECT_EQ(merged[i].score.score, whole[i].score.score) << i;
    }
  }

  // Several queries agree: one with chemistry gives it to all of them; mixed ones are refused.
  std::vector<screening::ScreenQuery> queries;
  queries.push_back(query_of(neutral, QueryChemistry::automatic));
  queries.push_back(query_of(salicylate, QueryChemistry::automatic));
  EXPECT_THROW(
      screening::score_molecules({&queries[0], &queries[1]}, library, 0, library.size(), options),
      InputError);
  screening::agree_on_chemistry(queries);
  EXPECT_EQ(queries[0].shape_weight, 0.0);
  EXPECT_EQ(queries[1].shape_weight, 0.0);
  queries.clear();
  queries.push_back(query_of(neutral, QueryChemistry::automatic));
  queries.push_back(query_of(neutral, QueryChemistry::automatic));
  screening::agree_on_chemistry(queries);
  EXPECT_EQ(queries[0].shape_weight, screening::neutral_query_shape_weight);
  EXPECT_EQ(queries[1].shape_weight, screening::neutral_query_shape_weight);
}

// merge_best and rank_hits by hand: for a query ranked by shape, the candidates are the best by
// score and the rows after them the best of the others by shape, scored by it.
TEST(Screen, AQueryRankedByShapeKeepsItsCandidatesByScoreAndItsOtherRowsByShape) {
  const auto hit = [](std::size_t entry, double score, double shape) {
    screening::Hit h;
    h.entry = entry;
    h.stage = 2;
    h.score.score = score;
    h.score.shape = shape;
    return h;
  };
  // Two ranges' lists: by score the order is 0 1 2 3, by shape 3 1 2 0.
  const std::vector<std::vector<screening::Hit>> parts = {{hit(0, 0.9, 0.5), hit(2, 0.7, 0.6)},
                                                          {hit(1, 0.8, 0.9), hit(3, 0.6, 0.95)}};
  screening::ScreenOptions options;
  options.candidates = 1;
  options.top = 3;
  const auto entries = [](const std::vector<screening::Hit>& hits) {
    std::vector<std::size_t> e;
    for (const screening::Hit& h : hits) e.push_back(h.entry);
    return e;
  };
  EXPECT_EQ(entries(screening::merge_best(parts, options, 0.0)),
            (std::vector<std::size_t>{0, 1, 2}));
  const std::vector<screening::Hit> best = screening::merge_best(parts, options, 1.0);
  EXPECT_EQ(entries(best), (std::vector<std::size_t>{0, 3, 1}));
  EXPECT_EQ(best[1].score.score, 0.6);  // merge_best keeps the overlay score

  screening::HitScore full;
  full.score = 0.55;
  full.shape = 0.55;
  const std::vector<screening::Hit> rows = screening::rank_hits(best, {full}, 0, 1.0);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].stage, 3);
  EXPECT_EQ(rows[0].score.score, 0.55);
  EXPECT_EQ(rows[1].score.score, 0.95);
  EXPECT_EQ(rows[2].score.score, 0.9);
  EXPECT_EQ(rows[1].score.shape, 0.95);
  const std::vector<screening::Hit> scored = screening::rank_hits(best, {full}, 2, 0.0);
  ASSERT_EQ(scored.size(), 2u);
  EXPECT_EQ(scored[1].score.score, 0.6);

  // Every molecule kept (top 0): the same candidate, then all the others by shape.
  options.top = 0;
  EXPECT_EQ(entries(screening::merge_best(parts, options, 1.0)),
            (std::vector<std::size_t>{0, 3, 1, 2}));

  // Two candidates whose full matches' score and shape disagree go by shape.
  screening::HitScore high_score, high_shape;
  high_score.score = 0.9;
  high_score.shape = 0.5;
  high_shape.score = 0.6;
  high_shape.shape = 0.8;
  const std::vector<screening::Hit> two =
      screening::rank_hits(best, {high_score, high_shape}, 0, 1.0);
  EXPECT_EQ(entries(two), (std::vector<std::size_t>{3, 0, 1}));
  EXPECT_EQ(two[0].score.score, 0.8);
  EXPECT_EQ(entries(screening::rank_hits(best, {high_score, high_shape}, 0, 0.0)),
            (std::vector<std::size_t>{0, 3, 1}));
}

// fuse_scores by hand: stage-3 rows replace their molecule's score against their query, max
// takes the best query's (ties to the first), mean the mean, ties go to the lower molecule.
TEST(Screen, FusedScoresAreTheMaximumOrMeanWithStageThreeScoresInTheirPlace) {
  const std::vector<screening::MoleculeScores> molecules{{0, {{0, 0.5}, {1, 0.2}}},
                                                         {2, {{2, 0.3}, {3, 0.9}}},
                                                         {4, {{4, 0.6}, {4, 0.6}}},
                                                         {6, {{6, 0.6}, {7, 0.6}}}};
  screening::Hit full;
  full.entry = 2;
  full.stage = 3;
  full.score.score = 0.95;
  const std::vector<std::vector<screening::Hit>> ranked{{full}, {}};
  const std::vector<screening::FusedHit> max =
      screening::fuse_scores(molecules, ranked, screening::Fusion::max, 0);
  ASSERT_EQ(max.size(), 4u);
  const std::size_t max_entries[] = {2, 4, 6, 0}, max_queries[] = {0, 0, 0, 0};
  const double max_scores[] = {0.95, 0.6, 0.6, 0.5};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(max[i].entry, max_entries[i]) << i;
    EXPECT_EQ(max[i].query, max_queries[i]) << i;
    EXPECT_EQ(max[i].score, max_scores[i]) << i;
  }
  EXPECT_EQ(max[0].scores, (std::vector<double>{0.95, 0.9}));
  const std::vector<screening::FusedHit> mean =
      screening::fuse_scores(molecules, ranked, screening::Fusion::mean, 2);
  ASSERT_EQ(mean.size(), 2u);
  EXPECT_EQ(mean[0].entry, 2u);
  EXPECT_DOUBLE_EQ(mean[0].score, (0.95 + 0.9) / 2);
  EXPECT_EQ(mean[1].entry, 4u);  // 0.6 as molecule 6, which comes after it
  EXPECT_THROW(screening::fuse_scores({{8, {{8, 0.1}}}}, ranked, screening::Fusion::max, 0),
               InputError);
}

TEST(LibraryBuild, HsiFilesBecomeEntriesThatKeepTheirSurfaceAndFindThemselves) {
  const test::TempDir dir;
  const std::vector<io::MoleculeRecord> records =
      screening::read_library_inputs({dir.write("three.sdf", three_molecule_sdf())});
  ASSERT_EQ(records.size(), 3u);
  fs::create_directory(dir / "hsi");
  std::vector<harmonic::SurfaceDescriptors> described;
  for (const io::MoleculeRecord& record : records) {
    const Molecule molecule = io::read_record_molecule(record);
    described.push_back(
        harmonic::describe_surface(molsurf::build_molecular_surface(molecule), molecule));
    harmonic::io::write_hsi(described.back(), dir / "hsi" / (record.name + ".hsi"));
  }
  dir.write("hsi/notes.txt", "not an input: a directory stands for its inputs only\n");
  const std::vector<io::MoleculeRecord> inputs = screening::read_library_inputs({dir / "hsi"});
  ASSERT_EQ(inputs.size(), 3u);  // in name order: ibuprofen, paracetamol, salicylic_acid
  EXPECT_EQ(inputs[2].name, "salicylic_acid");
  EXPECT_EQ(inputs[2].format, io::RecordFormat::descriptors);
  const fs::path path = dir / "hsi.sclib";
  EXPECT_EQ(screening::build_library(inputs, path).entries, 3u);
  const screening::Library library(path);

  // Salicylic acid's entry keeps its file's surface, bit for bit, and heavy atoms (C7 O3), at
  // under a tenth of the file's size (images and patches are rebuilt by the screen).
  const screening::LibraryEntry entry = library.entry(2);
  const harmonic::SurfaceDescriptors& original = described[1];
  const harmonic::SurfaceDescriptors stored = harmonic::io::decode_hsi(entry.surface, "entry");
  EXPECT_TRUE(stored.critical_points.empty());
  EXPECT_TRUE(stored.surface.positions() == original.surface.positions());
  EXPECT_TRUE(stored.surface.property(mesh::property::esp) ==
              original.surface.property(mesh::property::esp));
  EXPECT_EQ(entry.info.heavy_atoms, 10u);
  EXPECT_LT(library.entry_bytes(2) * 10, fs::file_size(dir / "hsi" / "salicylic_acid.hsi"));
  const Molecule atoms = io::read_record_molecule(entry.molecule);
  ASSERT_EQ(atoms.atoms.size(), original.atoms.size());
  for (std::size_t a = 0; a < atoms.atoms.size(); ++a) {
    EXPECT_EQ(atoms.atoms[a].element, original.atoms[a].element);
    EXPECT_LT((atoms.atoms[a].position - original.atoms[a].position).norm(), 1e-4);
  }

  // The molecule as a query finds the entry made from its .hsi first, at the identity.
  const Molecule molecule = io::read_record_molecule(records[1]);
  screening::ScreenOptions options;
  options.top = 0;
  const screening::ScreenQuery query = screening::make_screen_query(
      harmonic::describe_surface(molsurf::build_molecular_surface(molecule), molecule), options, {},
      &molecule);
  expect_found_itself_first(screening::screen(query, library, options).hits, 2);

  // A .hsi made from a mesh (no atoms, no ESP or LP) is skipped with the reason.
  mesh::Surface ball = test::icosphere(5.0, 12);
  molsurf::assign_surface_properties(ball, nullptr);
  harmonic::io::write_hsi(harmonic::describe_surface(std::move(ball)), dir / "ball.hsi");
  const screening::LibraryBuildResult ball_build = screening::build_library(
      screening::read_library_inputs({dir / "ball.hsi"}), dir / "ball.sclib");
  ASSERT_EQ(ball_build.skipped.size(), 1u);
  EXPECT_NE(ball_build.skipped[0].reason.find("keeps no atoms"), std::string::npos)
      << ball_build.skipped[0].reason;
  EXPECT_FALSE(fs::exists(dir / "ball.sclib"));

  // A .hsi has fixed coordinates: asked for conformers, it is skipped with the reason.
  screening::LibraryBuildOptions conformers;
  conformers.conformers = two_conformers();
  const screening::LibraryBuildResult refused =
      screening::build_library({inputs[0]}, dir / "conformers.sclib", conformers);
  ASSERT_EQ(refused.skipped.size(), 1u);
  EXPECT_NE(refused.skipped[0].reason.find("conformers does not apply"), std::string::npos)
      << refused.skipped[0].reason;
}

TEST(SiteList, LinesGiveLigandsSpheresOrPocketsAndABadLineIsNamed) {
  const test::TempDir dir;
  const fs::path list = dir.write("sites.txt",
                                  "# pockets\n"
                                  "\n"
                                  "a.pdb ATP\n"
                                  "b.pdb HEM B\n"
                                  "/abs/c.pdb 1,2,3,4 -1,0.5,2,3.5\n"
                                  "d.cif.gz Pocket 2\n");
  const std::vector<screening::SiteRequest> sites = screening::read_site_list(list);
  ASSERT_EQ(sites.size(), 4u);
  EXPECT_EQ(sites[0].structure, dir / "a.pdb");  // relative to the list's folder
  EXPECT_EQ(sites[0].line, 3u);
  ASSERT_TRUE(sites[0].ligand);
  EXPECT_EQ(sites[0].ligand->residue_name, "ATP");
  EXPECT_FALSE(sites[0].ligand->chain);
  EXPECT_EQ(sites[0].name, "a:ATP");
  ASSERT_TRUE(sites[1].ligand && sites[1].ligand->chain);
  EXPECT_EQ(*sites[1].ligand->chain, "B");
  EXPECT_EQ(sites[1].name, "b:HEM:B");
  EXPECT_EQ(sites[2].structure, fs::path("/abs/c.pdb"));
  EXPECT_FALSE(sites[2].ligand);
  ASSERT_EQ(sites[2].spheres.size(), 2u);
  EXPECT_EQ(sites[2].spheres[1].center, Eigen::Vector3d(-1, 0.5, 2));
  EXPECT_EQ(sites[2].spheres[1].radius, 3.5);
  EXPECT_EQ(sites[2].name, "c:spheres5");
  EXPECT_EQ(sites[3].pocket_rank, 2);
  EXPECT_TRUE(sites[3].pocket && !sites[3].ligand && sites[3].spheres.empty());
  EXPECT_EQ(sites[3].name, "d:pocket2");

  for (const char* bad :
       {"a.pdb\n", "a.pdb 1,2,3,0\n", "a.pdb 1,2,3,4 ATP\n", "a.pdb ATP A extra\n",
        "a.pdb pocket\n", "a.pdb pocket 0\n", "a.pdb pocket 2x\n", "a.pdb pocket 1 2\n"}) {
    const fs::path bad_list = dir.write("bad.txt", std::string("# x\n") + bad);
    try {
      screening::read_site_list(bad_list);
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(bad_list.string() + ":2: "), std::string::npos)
          << e.what();
    }
  }
}

TEST(Library, SiteEntriesKeepTheirSpheres) {
  const test::TempDir dir;
  screening::LibraryEntry entry;
  entry.info = {"pocket", "p.pdb", 3, 0, 120, 2};
  entry.molecule.format = io::RecordFormat::structure;
  // A neighbourhood of 500 atoms, stored compressed and read back to the byte.
  for (int k = 1; k <= 500; ++k) {
    char line[96];
    std::snprintf(line, sizeof line,
                  "ATOM  %5d  CA  ALA A%4d    %8.3f%8.3f%8.3f  1.00  0.00           C\n", k, k,
                  0.37 * k, -0.11 * k, 0.05 * k);
    entry.molecule.text += line;
  }
  entry.molecule.text += "END\n";
  entry.sample.points = Eigen::Matrix3Xd::Random(3, 4);
  entry.sample.normals = Eigen::Matrix3Xd::Random(3, 4);
  entry.sample.weights = Eigen::VectorXd::Ones(4);
  entry.sample.esp = Eigen::VectorXd::Zero(4);
  entry.sample.lp = Eigen::VectorXd::Zero(4);
  entry.atoms.points.resize(3, 0);
  entry.site = {{Eigen::Vector3d(1, 2, 3), 4.0}, {Eigen::Vector3d(-1, 0, 2.5), 3.0}};
  const fs::path path = dir / "sites.sclib";
  screening::write_library(path, {entry});
  const screening::Library library(path);
  EXPECT_EQ(library.version(), screening::library_format_version);
  EXPECT_EQ(library.info(0).site_spheres, 2u);
  const screening::LibraryEntry read = library.entry(0);
  ASSERT_EQ(read.site.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(read.site[k].center, entry.site[k].center);
    EXPECT_EQ(read.site[k].radius, entry.site[k].radius);
  }
  EXPECT_EQ(read.molecule.text, entry.molecule.text);
  EXPECT_EQ(read.molecule.format, io::RecordFormat::structure);
  EXPECT_LT(fs::file_size(path), entry.molecule.text.size() / 2);
}

TEST(Screen, SiteQueryFindsItsOwnPocketFirstAndKindsDoNotMix) {
  SURFCOMP_SHARED_OR_SKIP(pdb_4tmn, "thermolysin/4TMN.pdb");
  SURFCOMP_SHARED_OR_SKIP(pdb_1thl, "thermolysin/1THL.pdb");
  const test::TempDir dir;
  const fs::path pocket_4tmn = dir / "4TMN_pocket.pdb";
  const fs::path pocket_1thl = dir / "1THL_pocket.pdb";
  test::write_pocket(pdb_4tmn, "0PK", 9.0, pocket_4tmn);
  test::write_pocket(pdb_1thl, "0DB", 9.0, pocket_1thl);
  const fs::path list =
      dir.write("sites.txt", pocket_1thl.filename().string() + " 0DB\n" +
                                 pocket_4tmn.filename().string() + " 0PK\n" + "missing.pdb 0PK\n");
  const fs::path path = dir / "pockets.sclib";
  const screening::LibraryBuildResult built =
      screening::build_site_library(screening::read_site_list(list), path);
  EXPECT_EQ(built.entries, 2u);
  ASSERT_EQ(built.skipped.size(), 1u);
  EXPECT_EQ(built.skipped[0].record, 3u);
  const screening::Library library(path);

  // The query: 4TMN's site built as `screen --site-ligand 0PK` builds it.
  const molsurf::BindingSite site =
      molsurf::binding_site(io::read_molecule(pocket_4tmn), LigandSelector{"0PK", {}, {}});
  EXPECT_EQ(library.entry(1).site.size(), site.spheres.size());
  screening::ScreenOptions options;
  options.top = 0;
  const screening::ScreenQuery query = screening::make_screen_query(
      matching::describe_site(molsurf::build_molecular_surface(site.structure), site.structure,
                              site.spheres),
      options, site.spheres, &site.structure);
  const std::vector<screening::Hit> hits = screening::screen(query, library, options).hits;
  ASSERT_EQ(hits.size(), 2u);
  // The stored pocket is the query's own (its structure written and read back as PDB).
  expect_found_itself_first(hits, 1);
  EXPECT_LT(hits[1].score.score, hits[0].score.score);
  // The other pocket's full-match score is the site score: its overlay's (the score without the
  // lining term, the same pose) with the two linings' composition.
  ASSERT_EQ(hits[1].stage, 3);
  screening::ScreenOptions overlay_only = options;
  overlay_only.match.site.lining_weight = 0.0;
  const std::vector<screening::Hit> overlay_hits =
      screening::screen(query, library, overlay_only).hits;
  const screening::LibraryEntry other = library.entry(hits[1].entry);
  const double lining = matching::lining_similarity(
      matching::lining_composition(site.structure, site.spheres).value(),
      matching::lining_composition(io::read_record_molecule(other.molecule), other.site).value());
  ASSERT_EQ(overlay_hits[1].entry, hits[1].entry);
  EXPECT_GT(lining, 0.0);
  EXPECT_NEAR(
      hits[1].score.score,
      matching::site_score(overlay_hits[1].score.score, lining, options.match.site.lining_weight),
      1e-12);

  // A molecule query against a pocket library, and a site query against a molecule library.
  const fs::path sdf = dir.write("three.sdf", three_molecule_sdf());
  const std::vector<io::MoleculeRecord> records = screening::read_library_inputs({sdf});
  const Molecule ligand = io::read_record_molecule(records[0]);
  const screening::ScreenQuery molecule_query = screening::make_screen_query(
      harmonic::describe_surface(molsurf::build_molecular_surface(ligand), ligand), options, {},
      &ligand);
  EXPECT_THROW(screening::screen(molecule_query, library, options), InputError);
  const fs::path molecules = dir / "three.sclib";
  screening::build_library(records, molecules);
  EXPECT_THROW(screening::screen(query, screening::Library(molecules), options), InputError);
}

// Sharded libraries: a build of more records than --shard-records writes an index and a folder
// of shards that read as the one file of the same records, entry for entry; shards built by
// several processes, or resumed after an interruption, have the bytes of an uninterrupted build
// in one process; a resume of other inputs or options, a damaged shard or a missing one is
// refused naming the file, changing nothing; released entries leave resident memory and read the
// same afterwards.
namespace shards {

namespace fs = std::filesystem;

/// Seven SMILES records, the third and fourth unreadable: with two records per shard, shard 2
/// has every record skipped (a log and no file) and shard 4 one record.
std::vector<io::MoleculeRecord> seven_records() {
  const std::pair<const char*, const char*> lines[] = {{"CC(=O)Nc1ccc(O)cc1", "paracetamol"},
                                                       {"OC(=O)c1ccccc1O", "salicylic_acid"},
                                                       {"C1CC", "unclosed_ring"},
                                                       {"C1CC(C", "unclosed_too"},
                                                       {"CC(=O)Oc1ccccc1C(=O)O", "aspirin"},
                                                       {"CC(C)Cc1ccc(cc1)C(C)C(=O)O", "ibuprofen"},
                                                       {"Cn1cnc2c1c(=O)n(C)c(=O)n2C", "caffeine"}};
  std::vector<io::MoleculeRecord> records;
  for (const auto& [smiles, name] : lines) {
    io::MoleculeRecord r;
    r.source = "set.smi";
    r.record = records.size() + 1;
    r.name = name;
    r.format = io::RecordFormat::smiles;
    r.text = smiles;
    records.push_back(r);
  }
  return records;
}

screening::LibraryBuildOptions one_conformer(std::size_t shard_records) {
  screening::LibraryBuildOptions options;
  options.conformers = ConformerOptions{};
  options.conformers->count = 1;
  options.conformers->seed = 3;
  options.shard_records = shard_records;
  return options;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Every file under `folder` (relative name -> bytes).
std::map<std::string, std::string> files_under(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& item : fs::recursive_directory_iterator(folder)) {
    if (item.is_regular_file())
      files[fs::relative(item.path(), folder).string()] = read_bytes(item.path());
  }
  return files;
}

std::string export_sdf(const screening::Library& library) {
  std::ostringstream out;
  screening::write_library_sdf(out, library);
  return out.str();
}

/// Expects `open` to throw an exception of type E whose one-line message names `file` and holds
/// `expected`.
template <class E>
void expect_refused(const std::function<void()>& open, const fs::path& file,
                    const std::string& expected) {
  try {
    open();
    ADD_FAILURE() << "no error naming " << file << " for " << expected;
  } catch (const E& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file.string(), 0), 0u) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(LibraryShards, AShardedLibraryReadsAsTheOneFileOfTheSameRecords) {
  const test::TempDir dir;
  const std::vector<io::MoleculeRecord> records = seven_records();
  const screening::LibraryBuildResult whole =
      screening::build_library(records, dir / "one.sclib", one_conformer(1000));
  const screening::LibraryBuildResult cut =
      screening::build_library(records, dir / "cut.sclib", one_conformer(2));
  EXPECT_EQ(whole.shards, 1u);
  EXPECT_EQ(cut.shards, 4u);
  EXPECT_FALSE(fs::exists(dir / "one.sclib.d"));
  // Shard 2's records were both skipped: a log, no file, and the index lists the other three.
  EXPECT_TRUE(fs::exists(dir / "cut.sclib.d/000002.log"));
  EXPECT_FALSE(fs::exists(dir / "cut.sclib.d/000002.sclib"));
  for (const char* shard : {"000001.sclib", "000003.sclib", "000004.sclib"})
    EXPECT_TRUE(fs::exists(dir / "cut.sclib.d" / shard)) << shard;
  EXPECT_EQ(read_bytes(dir / "cut.sclib").substr(0, 8), "SURFCSET");
  EXPECT_EQ(cut.records, whole.records);
  EXPECT_EQ(cut.entries, 5u);
  EXPECT_EQ(cut.entries, whole.entries);
  ASSERT_EQ(cut.skipped.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(cut.skipped[i].record, whole.skipped[i].record);
    EXPECT_EQ(cut.skipped[i].name, whole.skipped[i].name);
    EXPECT_EQ(cut.skipped[i].reason, whole.skipped[i].reason);
  }

  const screening::Library one(dir / "one.sclib");
  const screening::Library sharded(dir / "cut.sclib");
  EXPECT_EQ(one.shards(), 1u);
  EXPECT_EQ(sharded.shards(), 3u);
  EXPECT_EQ(sharded.path(), dir / "cut.sclib");
  EXPECT_EQ(sharded.version(), screening::library_format_version);
  EXPECT_EQ(sharded.settings(), one.settings());
  EXPECT_EQ(sharded.file_bytes(), cut.bytes);
  EXPECT_EQ(cut.bytes, fs::file_size(dir / "cut.sclib") +
                           fs::file_size(dir / "cut.sclib.d/000001.sclib") +
                           fs::file_size(dir / "cut.sclib.d/000003.sclib") +
                           fs::file_size(dir / "cut.sclib.d/000004.sclib"));
  ASSERT_EQ(sharded.size(), one.size());
  const double sigma = matching::OverlayOptions{}.sigma;
  for (std::size_t i = 0; i < one.size(); ++i) {
    SCOPED_TRACE("entry " + std::to_string(i + 1));
    EXPECT_EQ(sharded.info(i).name, one.info(i).name);
    EXPECT_EQ(sharded.info(i).record, one.info(i).record);
    EXPECT_EQ(sharded.entry_bytes(i), one.entry_bytes(i));
    EXPECT_EQ(sharded.entry(i).molecule.text, one.entry(i).molecule.text);
    // The samples as stored, bit for bit.
    const screening::PackedEntry a = sharded.packed(i, sigma), b = one.packed(i, sigma);
    ASSERT_EQ(a.view.header.points, b.view.header.points);
    EXPECT_EQ(a.view.header.self_shape, b.view.header.self_shape);
    EXPECT_EQ(std::memcmp(a.view.arrays, b.view.arrays, 9 * a.view.padded_points() * 4), 0);
  }
  EXPECT_EQ(sharded.find("caffeine"), std::vector<std::size_t>{4});  // in the last shard
  EXPECT_EQ(export_sdf(sharded), export_sdf(one));
  EXPECT_NO_THROW(sharded.verify());
  EXPECT_THROW(sharded.info(5), std::out_of_range);
}

TEST(LibraryShards, ShardsSplitOverProcessesOrResumedHaveTheBytesOfOneBuild) {
  const test::TempDir dir;
  const std::vector<io::MoleculeRecord> records = seven_records();
  fs::create_directories(dir / "one");
  fs::create_directories(dir / "split");
  screening::build_library(records, dir / "one/lib.sclib", one_conformer(2));

  // A two-process job of which only process 1 ran (shards 2 and 4), then its resume in one
  // process after a SIGKILL left a temporary file.
  screening::ShardedLibraryBuild first(records, dir / "split/lib.sclib", one_conformer(2));
  ASSERT_EQ(first.shards(), 4u);
  first.prepare();
  const screening::LibraryBuildResult odd = first.build(1, 2);
  EXPECT_EQ(odd.records, 3u);  // records 3, 4 and 7
  EXPECT_EQ(odd.entries, 1u);
  EXPECT_THROW(first.finish(), FileError);  // shards 1 and 3 are not finished
  std::ofstream(first.folder() / ".surfcomp-1-0-0123456789abcdef.tmp") << "stale";

  screening::LibraryBuildOptions resume = one_conformer(2);
  resume.resume = true;
  screening::ShardedLibraryBuild second(records, dir / "split/lib.sclib", resume);
  second.prepare();
  EXPECT_FALSE(fs::exists(first.folder() / ".surfcomp-1-0-0123456789abcdef.tmp"));
  const screening::LibraryBuildResult even = second.build();
  EXPECT_EQ(even.records, 4u);  // shards 1 and 3: the finished ones are not built again
  const screening::LibraryBuildResult result = second.finish();
  EXPECT_EQ(result.shards_resumed, 2u);  // shard 2, every record skipped, counts as finished
  EXPECT_EQ(result.entries_resumed, 1u);
  EXPECT_EQ(result.entries, 5u);
  EXPECT_EQ(result.skipped.size(), 2u);
  // The same files, and the same bytes but for the shards' logs, which name their shard.
  const std::map<std::string, std::string> split = files_under(dir / "split");
  const std::map<std::string, std::string> one = files_under(dir / "one");
  std::vector<std::string> names;
  for (const auto& [name, bytes] : one) names.push_back(name);
  std::vector<std::string> split_names;
  for (const auto& [name, bytes] : split) split_names.push_back(name);
  EXPECT_EQ(split_names, names);
  for (const auto& [name, bytes] : one) {
    if (name.size() < 4 || name.compare(name.size() - 4, 4, ".log") != 0) {
      EXPECT_TRUE(split.count(name) && split.at(name) == bytes) << name << " differs";
    }
  }
}

TEST(LibraryShards, AResumeOfOtherInputsOrOptionsOrADamagedShardIsRefusedChangingNothing) {
  const test::TempDir dir;
  const std::vector<io::MoleculeRecord> records = seven_records();
  fs::create_directories(dir / "build");
  const fs::path output = dir / "build/lib.sclib";
  screening::build_library(records, output, one_conformer(2));
  const std::map<std::string, std::string> before = files_under(dir / "build");
  const fs::path manifest = dir / "build/lib.sclib.d/manifest.txt";
  screening::LibraryBuildOptions resume = one_conformer(2);
  resume.resume = true;
  const auto resume_with = [&](const std::vector<io::MoleculeRecord>& inputs,
                               const screening::LibraryBuildOptions& options) {
    return [&inputs, &options, &output] {
      screening::ShardedLibraryBuild(inputs, output, options).prepare();
    };
  };

  // Without resume the folder is in the way.
  expect_refused<FileError>(resume_with(records, one_conformer(2)), dir / "build/lib.sclib.d",
                            "continue that build with resume");
  screening::LibraryBuildOptions other_seed = resume;
  other_seed.conformers->seed = 4;
  expect_refused<InputError>(resume_with(records, other_seed), manifest,
                             "'settings conformers 1 (ETKDGv3 seed 3");
  screening::LibraryBuildOptions other_size = resume;
  other_size.shard_records = 3;
  expect_refused<InputError>(resume_with(records, other_size), manifest, "'shard-records 2'");
  std::vector<io::MoleculeRecord> other_records = records;
  other_records[5].text = "CC(C)Cc1ccc(cc1)C(C)C(=O)[O-]";
  expect_refused<InputError>(resume_with(other_records, resume), manifest, "'shard 000003");
  EXPECT_EQ(files_under(dir / "build"), before);

  // A flipped byte in the molecule text of shard 3's first entry: its checksum tells.
  const fs::path shard = dir / "build/lib.sclib.d/000003.sclib";
  std::string damaged = before.at("lib.sclib.d/000003.sclib");
  damaged[100] = static_cast<char>(damaged[100] ^ 0x10);
  std::ofstream(shard, std::ios::binary | std::ios::trunc) << damaged;
  expect_refused<FormatError>(resume_with(records, resume), shard, "checksum");
  EXPECT_EQ(read_bytes(shard), damaged);
  EXPECT_EQ(read_bytes(output), before.at("lib.sclib"));
}

TEST(LibraryShards, AMissingCutOrDamagedShardIsRefusedNamingIt) {
  const test::TempDir dir;
  const fs::path index = dir / "lib.sclib";
  screening::build_library(seven_records(), index, one_conformer(2));
  const fs::path shard = dir / "lib.sclib.d/000003.sclib";
  const std::string good = read_bytes(shard);
  const auto open = [&index] { const screening::Library library(index); };

  fs::remove(shard);
  expect_refused<FileError>(open, shard, "no such file");
  std::ofstream(shard, std::ios::binary) << good.substr(0, good.size() - 100);
  expect_refused<FormatError>(open, shard, "the index " + index.string() + " lists");
  // A flipped byte in the shard's own index: the library opens (a shard's index is read when
  // the shard is), and reading an entry of the shard fails its index checksum.
  std::string damaged = good;
  damaged[damaged.size() - 40] = static_cast<char>(damaged[damaged.size() - 40] ^ 0x21);
  std::ofstream(shard, std::ios::binary | std::ios::trunc) << damaged;
  expect_refused<FormatError>(
      [&index] {
        const screening::Library library(index);
        for (std::size_t e = 0; e < library.size(); ++e) library.info(e);
      },
      shard, "checksum");
  // A flipped byte in the index itself (its settings).
  std::ofstream(shard, std::ios::binary | std::ios::trunc) << good;
  const std::string index_bytes = read_bytes(index);
  std::string other = index_bytes;
  other[other.size() - 30] = static_cast<char>(other[other.size() - 30] ^ 0x01);
  std::ofstream(index, std::ios::binary | std::ios::trunc) << other;
  expect_refused<FormatError>(open, index, "checksum");
  std::ofstream(index, std::ios::binary | std::ios::trunc) << index_bytes;
  EXPECT_NO_THROW(open());
}

// A sharded library keeps a few shards open however many it reads, and release() closes them;
// a shard closed is opened again, reading the same.
TEST(LibraryShards, OnlyAFewShardsStayOpenAndReleaseClosesThem) {
  const test::TempDir dir;
  screening::LibraryBuildOptions options = one_conformer(1);
  screening::build_library(seven_records(), dir / "lib.sclib", options);
  const screening::Library library(dir / "lib.sclib");
  ASSERT_EQ(library.shards(), 5u);
  EXPECT_EQ(library.open_shards(), 0u);  // opening reads no shard's index
  std::vector<std::string> names;
  for (std::size_t e = 0; e < library.size(); ++e) names.push_back(library.info(e).name);
  EXPECT_EQ(library.open_shards(), 4u);
  {
    const double sigma = screening::Library(dir / "lib.sclib").packed(0, 1.0).view.header.sigma;
    const screening::PackedEntry pinned = library.packed(0, sigma);
    ASSERT_EQ(pinned.owned, nullptr);  // a view into the shard's mapping
    library.release(0, library.size());
    EXPECT_EQ(library.open_shards(), 0u);
    // The shard stays mapped while the view lives: its arrays read as a fresh copy's.
    const screening::Library other(dir / "lib.sclib");
    const screening::PackedEntry fresh = other.packed(0, sigma);
    ASSERT_EQ(fresh.view.header.points, pinned.view.header.points);
    EXPECT_EQ(std::memcmp(pinned.view.arrays, fresh.view.arrays,
                          9 * std::size_t{pinned.view.padded_points()} * sizeof(float)),
              0);
  }
  library.release(1, 3);  // closed shards: nothing to do
  for (std::size_t e = 0; e < library.size(); ++e) EXPECT_EQ(library.info(e).name, names[e]);
  library.release(2, 3);  // shard 3 of one entry
  EXPECT_EQ(library.open_shards(), 3u);
  EXPECT_EQ(names, (std::vector<std::string>{"paracetamol", "salicylic_acid", "aspirin",
                                             "ibuprofen", "caffeine"}));
}

/// The processes of a screen as threads of one test: gather and broadcast meet at a barrier.
class ThreadExchange final : public screening::Exchange {
 public:
  /// What the threads share.
  struct Meeting {
    explicit Meeting(int n) : processes(n), parts(static_cast<std::size_t>(n)) {}
    /// Returns when every process has come.
    void wait() {
      std::unique_lock<std::mutex> lock(mutex);
      const std::uint64_t mine = round;
      if (++arrived == processes) {
        arrived = 0;
        ++round;
        changed.notify_all();
      } else {
        changed.wait(lock, [&] { return round != mine; });
      }
    }
    int processes;
    std::mutex mutex;
    std::condition_variable changed;
    int arrived = 0;
    std::uint64_t round = 0;
    std::vector<std::vector<double>> parts;
    std::vector<std::uint64_t> values;
  };
  ThreadExchange(Meeting& meeting, int process) : meeting_(meeting), process_(process) {}
  int process() const override { return process_; }
  int processes() const override { return meeting_.processes; }
  std::vector<double> gather(const std::vector<double>& local) override {
    {
      const std::lock_guard<std::mutex> lock(meeting_.mutex);
      meeting_.parts[static_cast<std::size_t>(process_)] = local;
    }
    meeting_.wait();
    std::vector<double> all;
    if (process_ == 0) {
      for (const std::vector<double>& part : meeting_.parts)
        all.insert(all.end(), part.begin(), part.end());
    }
    meeting_.wait();  // the parts are free for the next gather
    return all;
  }
  std::vector<std::uint64_t> broadcast(std::vector<std::uint64_t> values) override {
    if (process_ == 0) {
      const std::lock_guard<std::mutex> lock(meeting_.mutex);
      meeting_.values = std::move(values);
    }
    meeting_.wait();
    std::vector<std::uint64_t> out = meeting_.values;
    meeting_.wait();
    return out;
  }

 private:
  Meeting& meeting_;
  int process_;
};

// The screen engine split over 2, 3, 5 or 7 processes (more than the library's molecules: some
// slices are empty) gives process 0 the rows and fused ranking of one process, bit for bit, and
// the others none.
TEST(ScreenEngine, AnyNumberOfProcessesGivesTheOneProcessRows) {
  const test::TempDir dir;
  screening::build_library(seven_records(), dir / "lib.sclib", one_conformer(2));
  const screening::Library library(dir / "lib.sclib");
  ASSERT_EQ(library.size(), 5u);
  screening::ScreenOptions options;
  options.candidates = 2;
  options.chemistry = screening::QueryChemistry::on;
  const auto query_of = [&](std::size_t e) {
    const Molecule molecule = io::read_record_molecule(library.entry(e).molecule);
    return screening::make_screen_query(
        harmonic::describe_surface(molsurf::build_molecular_surface(molecule), molecule), options,
        {}, &molecule);
  };
  const screening::ScreenQuery paracetamol = query_of(0), ibuprofen = query_of(3);
  const std::vector<const screening::ScreenQuery*> queries{&paracetamol, &ibuprofen};
  for (const std::size_t top : {0, 3}) {
    options.top = top;
    const screening::MultiScreenResult one = screening::screen_queries(queries, library, options);
    ASSERT_EQ(one.hits.size(), 2u);
    ASSERT_EQ(one.fused.size(), top == 0 ? 5u : top);
    for (const int processes : {2, 3, 5, 7}) {
      SCOPED_TRACE(std::to_string(processes) + " processes, top " + std::to_string(top));
      ThreadExchange::Meeting meeting(processes);
      std::vector<screening::MultiScreenResult> results(static_cast<std::size_t>(processes));
      std::vector<std::thread> threads;
      for (int p = 0; p < processes; ++p) {
        threads.emplace_back([&, p] {
          ThreadExchange exchange(meeting, p);
          results[static_cast<std::size_t>(p)] =
              screening::screen_queries(queries, library, options, exchange);
        });
      }
      for (std::thread& thread : threads) thread.join();
      const screening::MultiScreenResult& root = results.front();
      ASSERT_EQ(root.hits.size(), one.hits.size());
      for (std::size_t q = 0; q < one.hits.size(); ++q) {
        ASSERT_EQ(root.hits[q].size(), one.hits[q].size());
        for (std::size_t i = 0; i < one.hits[q].size(); ++i) {
          const screening::Hit &a = root.hits[q][i], &b = one.hits[q][i];
          EXPECT_EQ(a.entry, b.entry);
          EXPECT_EQ(a.stage, b.stage);
          EXPECT_EQ(a.score.score, b.score.score);
          EXPECT_EQ(a.fast_score, b.fast_score);
          EXPECT_EQ(a.score.transform, b.score.transform);
        }
      }
      ASSERT_EQ(root.fused.size(), one.fused.size());
      for (std::size_t i = 0; i < one.fused.size(); ++i) {
        EXPECT_EQ(root.fused[i].entry, one.fused[i].entry);
        EXPECT_EQ(root.fused[i].scores, one.fused[i].scores);
      }
      for (std::size_t p = 1; p < results.size(); ++p) {
        EXPECT_TRUE(results[p].hits.empty());
        EXPECT_TRUE(results[p].fused.empty());
      }
    }
  }
}

// A screen of several queries keeps a bounded list of molecules for its fused ranking: with
// fewer kept than the library's molecules, its rows are the first rows of the whole ranking.
TEST(LibraryShards, ABoundedFusedRankingIsTheHeadOfTheWholeOne) {
  const test::TempDir dir;
  screening::build_library(seven_records(), dir / "lib.sclib", one_conformer(2));
  const screening::Library library(dir / "lib.sclib");
  ASSERT_EQ(library.size(), 5u);  // five molecules of one conformer
  screening::ScreenOptions options;
  options.candidates = 1;
  options.chemistry = screening::QueryChemistry::on;  // ibuprofen is an acid, paracetamol not
  const auto query_of = [&](std::size_t e) {
    const Molecule molecule = io::read_record_molecule(library.entry(e).molecule);
    return screening::make_screen_query(
        harmonic::describe_surface(molsurf::build_molecular_surface(molecule), molecule), options,
        {}, &molecule);
  };
  const screening::ScreenQuery paracetamol = query_of(0), ibuprofen = query_of(3);
  // What stages 1 and 2 keep: the fused_molecules() best by fused score and each query's best.
  options.top = 0;
  const std::vector<screening::MoleculeScores> every =
      screening::score_molecules({&paracetamol, &ibuprofen}, library, 0, 5, options).molecules;
  ASSERT_EQ(every.size(), 5u);
  for (const screening::Fusion fusion : {screening::Fusion::max, screening::Fusion::mean}) {
    for (const std::size_t top : {1, 2}) {
      options.fusion = fusion;
      options.top = top;
      const screening::StreamedScores kept =
          screening::score_molecules({&paracetamol, &ibuprofen}, library, 0, 5, options);
      std::vector<std::pair<double, std::size_t>> by_fused;  // (-fused score, molecule)
      for (const screening::MoleculeScores& m : every) {
        const double a = m.scores[0].score, b = m.scores[1].score;
        by_fused.emplace_back(fusion == screening::Fusion::max ? -std::max(a, b) : -(a + b) / 2,
                              m.molecule);
      }
      std::sort(by_fused.begin(), by_fused.end());
      std::set<std::size_t> expected;
      // The top, and each query's candidates after stage 3, can come from these.
      const std::size_t fused_kept = top + 2 * options.candidates;
      EXPECT_EQ(screening::fused_molecules(options, 2), fused_kept);
      for (std::size_t i = 0; i < fused_kept; ++i) expected.insert(by_fused[i].second);
      for (const screening::QueryScores& query : kept.queries) {
        for (const screening::Hit& hit : query.best)
          expected.insert(hit.entry);  // one conformer: the entry is the molecule
      }
      ASSERT_LT(expected.size(), 5u);
      std::set<std::size_t> found;
      for (const screening::MoleculeScores& m : kept.molecules) {
        found.insert(m.molecule);
        EXPECT_EQ(m.scores[0].score, every[m.molecule].scores[0].score);
        EXPECT_EQ(m.scores[1].score, every[m.molecule].scores[1].score);
      }
      EXPECT_EQ(found, expected) << "top " << top;
    }
  }
  // The fused table against the whole one, also with more candidates than rows (their full
  // matches count where their rows are not shown), ranked by score, by shape and by their mean
  // (the weight `auto` gives two queries without an ionic group).
  for (const double weight : {0.0, 1.0, screening::neutral_query_shape_weight}) {
    options.chemistry =
        weight == 0.0 ? screening::QueryChemistry::on : screening::QueryChemistry::off;
    screening::ScreenQuery first = query_of(0), second = query_of(3);
    first.shape_weight = second.shape_weight = weight;
    for (const screening::Fusion fusion : {screening::Fusion::max, screening::Fusion::mean}) {
      for (const auto& [top, candidates] :
           {std::pair<std::size_t, std::size_t>{1, 1}, {2, 1}, {1, 2}}) {
        options.fusion = fusion;
        options.candidates = candidates;
        options.top = 0;
        const std::vector<screening::FusedHit> whole =
            screening::screen_queries({&first, &second}, library, options).fused;
        ASSERT_EQ(whole.size(), 5u);
        options.top = top;
        const std::vector<screening::FusedHit> head =
            screening::screen_queries({&first, &second}, library, options).fused;
        ASSERT_EQ(head.size(), top);
        for (std::size_t i = 0; i < top; ++i) {
          SCOPED_TRACE("top " + std::to_string(top) + ", candidates " + std::to_string(candidates) +
                       ", shape weight " + std::to_string(weight));
          EXPECT_EQ(head[i].entry, whole[i].entry) << i;
          EXPECT_EQ(head[i].query, whole[i].query) << i;
          EXPECT_EQ(head[i].score, whole[i].score) << i;
          EXPECT_EQ(head[i].scores, whole[i].scores) << i;
        }
      }
    }
  }
}

/// The resident size of this process's mapping of `file`, kB (/proc/self/smaps).
std::size_t resident_kb(const fs::path& file) {
  std::ifstream smaps("/proc/self/smaps");
  const std::string name = fs::canonical(file).string();
  bool in_file = false;
  for (std::string line; std::getline(smaps, line);) {
    const bool header = line.find('-') < line.find(' ') && line.find(':') > line.find(' ');
    if (header)
      in_file = line.size() >= name.size() &&
                line.compare(line.size() - name.size(), name.size(), name) == 0;
    if (in_file && line.rfind("Rss:", 0) == 0) return std::stoul(line.substr(4));
  }
  return 0;
}

TEST(Library, ReleasedEntriesLeaveResidentMemoryAndReadTheSame) {
  const test::TempDir dir;
  const fs::path path = dir / "lib.sclib";
  screening::LibraryBuildOptions options = one_conformer(1000);
  options.conformers->count = 4;  // 20 entries, several pages of records and of samples
  screening::build_library(seven_records(), path, options);
  const screening::Library library(path);
  ASSERT_EQ(library.size(), 20u);
  const std::string sdf = export_sdf(library);  // touches every record
  library.verify();                             // and every sample
  const std::size_t touched = resident_kb(path);
  ASSERT_GT(touched, 0u) << "no mapping of " << path << " in /proc/self/smaps";
  library.release(0, library.size());
  const std::size_t released = resident_kb(path);
  // What stays is the header's, the index's and the regions' boundary pages.
  EXPECT_LT(released, touched);
  EXPECT_LE(released, 4 * 4 + fs::file_size(path) / 1024 / 4) << "of " << touched << " kB";
  EXPECT_EQ(export_sdf(library), sdf);  // read again from the file
  EXPECT_NO_THROW(library.verify());
  EXPECT_THROW(library.release(3, 2), std::out_of_range);
  EXPECT_THROW(library.release(0, 21), std::out_of_range);
}

}  // namespace shards

}  // namespace
}  // namespace surfcomp
