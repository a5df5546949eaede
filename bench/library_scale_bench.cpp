// Memory of a screen over a library larger than any built so far: writes a library of N entries
// by cycling through the entries of SOURCE (each copy's records renumbered, so that every copy
// is a distinct molecule), for `/usr/bin/time -v surfcomp screen QUERY OUT ...` to measure the
// peak resident memory (docs/screening.md#memory). With SHARD_ENTRIES, a sharded library as
// `library build` writes one: OUT.sclib an index over OUT.sclib.d/000001.sclib ..., each shard
// whole molecules, a new one begun at the first molecule after SHARD_ENTRIES entries.
//
// Usage: library_scale_bench SOURCE.sclib N OUT.sclib [SHARD_ENTRIES]
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/screening/library.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: library_scale_bench SOURCE.sclib N OUT.sclib [SHARD_ENTRIES]\n");
    return 2;
  }
  try {
    using namespace surfcomp;
    const screening::Library source(argv[1]);
    const std::size_t count = std::strtoull(argv[2], nullptr, 10);
    const std::size_t shard_entries = argc == 5 ? std::strtoull(argv[4], nullptr, 10) : 0;
    if (source.size() == 0 || count == 0) throw InputError("need a non-empty SOURCE and N > 0");
    if (argc == 5 && shard_entries == 0) throw InputError("need SHARD_ENTRIES > 0");
    std::uint32_t records = 0;
    for (std::size_t e = 0; e < source.size(); ++e)
      records = std::max(records, source.info(e).record);
    const auto entry_of = [&](std::size_t i) {
      screening::LibraryEntry entry = source.entry(i % source.size());
      entry.info.record += static_cast<std::uint32_t>(i / source.size()) * records;
      return entry;
    };
    const std::filesystem::path out_path = argv[3];
    if (shard_entries == 0) {
      io::write_file_atomically(out_path, [&](std::ostream& out) {
        screening::LibraryWriter writer(out, source.settings());
        for (std::size_t i = 0; i < count; ++i) writer.add(entry_of(i));
        writer.finish();
      });
      std::printf("%s: %zu entries from %s\n", argv[3], count, argv[1]);
      return 0;
    }
    const std::filesystem::path folder = out_path.string() + ".d";
    std::filesystem::create_directories(folder);
    std::vector<std::filesystem::path> shards;
    std::ofstream out;
    std::unique_ptr<screening::LibraryWriter> writer;
    const auto close_shard = [&] {
      writer->finish();
      writer.reset();
      out.close();
      if (!out) throw FileError((folder / shards.back()).string(), "cannot write");
    };
    screening::LibraryEntryInfo previous;
    for (std::size_t i = 0; i < count; ++i) {
      screening::LibraryEntry entry = entry_of(i);
      const bool new_molecule = i == 0 || entry.info.record != previous.record ||
                                entry.info.name != previous.name ||
                                entry.info.source != previous.source;
      if (writer != nullptr && new_molecule && writer->size() >= shard_entries) close_shard();
      if (writer == nullptr) {
        char name[32];
        std::snprintf(name, sizeof name, "%06zu.sclib", shards.size() + 1);
        shards.emplace_back(out_path.filename().string() + ".d/" + name);
        out.open(out_path.parent_path() / shards.back(), std::ios::binary | std::ios::trunc);
        writer = std::make_unique<screening::LibraryWriter>(out, source.settings());
      }
      previous = entry.info;
      writer->add(entry);
    }
    close_shard();
    screening::write_library_index(out_path, shards, source.settings());
    std::printf("%s: %zu entries from %s in %zu shards\n", argv[3], count, argv[1], shards.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "library_scale_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
