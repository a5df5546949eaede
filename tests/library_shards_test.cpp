// Sharded libraries: a build of more records than --shard-records writes an index and a folder
// of shards that read as the one file of the same records, entry for entry; shards built by
// several processes, or resumed after an interruption, have the bytes of an uninterrupted build
// in one process; a resume of other inputs or options, a damaged shard or a missing one is
// refused naming the file, changing nothing; released entries leave resident memory and read the
// same afterwards.
#include "test_data.hpp"

#include "surfcomp/core/conformers.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/screening/hit_files.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/library_build.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp {
namespace {

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

  // Without --resume the folder is in the way.
  expect_refused<FileError>(resume_with(records, one_conformer(2)), dir / "build/lib.sclib.d",
                            "--resume");
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
  // A flipped byte in the shard's own index: its index checksum fails.
  std::string damaged = good;
  damaged[damaged.size() - 40] = static_cast<char>(damaged[damaged.size() - 40] ^ 0x21);
  std::ofstream(shard, std::ios::binary | std::ios::trunc) << damaged;
  expect_refused<FormatError>(open, shard, "checksum");
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

}  // namespace
}  // namespace surfcomp
