// Memory of a screen over a library larger than any built so far: writes a library of N entries
// by cycling through the entries of SOURCE (each copy's records renumbered, so that every copy
// is a distinct molecule), for `/usr/bin/time -v surfcomp screen QUERY OUT ...` to measure the
// peak resident memory (docs/screening.md#memory).
//
// Usage: library_scale_bench SOURCE.sclib N OUT.sclib
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/screening/library.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: library_scale_bench SOURCE.sclib N OUT.sclib\n");
    return 2;
  }
  try {
    using namespace surfcomp;
    const screening::Library source(argv[1]);
    const std::size_t count = std::strtoull(argv[2], nullptr, 10);
    if (source.size() == 0 || count == 0) throw InputError("need a non-empty SOURCE and N > 0");
    std::uint32_t records = 0;
    for (std::size_t e = 0; e < source.size(); ++e)
      records = std::max(records, source.info(e).record);
    io::write_file_atomically(argv[3], [&](std::ostream& out) {
      screening::LibraryWriter writer(out, source.settings());
      for (std::size_t i = 0; i < count; ++i) {
        screening::LibraryEntry entry = source.entry(i % source.size());
        entry.info.record += static_cast<std::uint32_t>(i / source.size()) * records;
        writer.add(entry);
      }
      writer.finish();
    });
    std::printf("%s: %zu entries from %s\n", argv[3], count, argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "library_scale_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
