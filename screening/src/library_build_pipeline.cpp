// A library build's pipeline: items built in parallel (TBB), written in their order, at most a
// batch of them in flight; an item whose build throws is skipped and listed.
#include "library_build_items.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/stopwatch.hpp"

#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <tbb/parallel_pipeline.h>
#include <utility>
#include <vector>

namespace surfcomp::screening {

std::string detail::one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return text;
}

LibraryBuildResult detail::build_in_order(const BuildItems& items, std::size_t begin,
                                          std::size_t end, const std::filesystem::path& output,
                                          const std::string& settings,
                                          const LibraryBuildOptions& options) {
  const Stopwatch clock;
  const std::size_t count = end - begin;
  LibraryBuildResult result;
  result.records = count;
  // A pipeline: items go out in order, are built in parallel and are written in order, at
  // most options.batch of them in flight.
  struct Built {
    std::size_t index = 0;
    std::vector<LibraryEntry> entries;
    std::vector<SkippedRecord> skipped;
    BuildTimes times;
    std::string error;
  };
  struct NothingBuilt {};  // abandons the output: no library of nothing, an old file kept
  try {
    io::write_file_atomically(output, [&](std::ostream& out) {
      LibraryWriter writer(out, settings, options.sigma);
      std::size_t next = 0;
      tbb::parallel_pipeline(
          options.batch,
          tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                              [&](tbb::flow_control& control) -> std::size_t {
                                                if (next == count) {
                                                  control.stop();
                                                  return 0;
                                                }
                                                return next++;
                                              }) &
              tbb::make_filter<std::size_t, std::shared_ptr<Built>>(
                  tbb::filter_mode::parallel,
                  [&](std::size_t index) {
                    auto built = std::make_shared<Built>();
                    built->index = index;
                    try {
                      built->entries = items.build(begin + index, built->times, built->skipped);
                    } catch (const std::bad_alloc&) {
                      built->error = "out of memory";
                    } catch (const std::exception& e) {
                      built->error = detail::one_line(e.what());
                      if (built->error.empty()) built->error = "unknown error";
                    }
                    return built;
                  }) &
              tbb::make_filter<std::shared_ptr<Built>, void>(
                  tbb::filter_mode::serial_in_order, [&](const std::shared_ptr<Built>& built) {
                    result.times.conformers += built->times.conformers;
                    result.times.entries += built->times.entries;
                    result.skipped.insert(result.skipped.end(), built->skipped.begin(),
                                          built->skipped.end());
                    if (!built->error.empty()) {
                      detail::ItemOrigin o = items.origin(begin + built->index);
                      result.skipped.push_back(
                          {std::move(o.source), o.record, std::move(o.name), built->error});
                    } else {
                      for (const LibraryEntry& entry : built->entries) writer.add(entry);
                    }
                    if (options.progress) {
                      options.progress({built->index + 1, count, writer.size(),
                                        result.skipped.size(), clock.elapsed_s()});
                    }
                  }));
      if (writer.size() == 0) throw NothingBuilt{};
      writer.finish();
      result.entries = writer.size();
      result.bytes = writer.bytes();
    });
  } catch (const NothingBuilt&) {
  }
  result.seconds = clock.elapsed_s();
  return result;
}

detail::BuildItems detail::record_items(const std::vector<io::MoleculeRecord>& records,
                                        const LibraryBuildOptions& options) {
  detail::BuildItems items;
  items.count = records.size();
  items.build = [&records, &options](std::size_t i, BuildTimes& times,
                                     std::vector<SkippedRecord>&) {
    return build_entries(records[i], options, &times);
  };
  items.origin = [&records](std::size_t i) {
    return detail::ItemOrigin{records[i].source.string(), records[i].record, records[i].name};
  };
  items.identity = [&records](std::size_t i, io::BinaryWriter& bytes) {
    bytes.string(records[i].source.string());
    bytes.u64(records[i].record);
    bytes.string(records[i].name);
    bytes.u8(static_cast<std::uint8_t>(records[i].format));
    bytes.string(records[i].text);
  };
  items.settings = build_settings(options);
  items.noun = "molecule record";
  return items;
}

}  // namespace surfcomp::screening
