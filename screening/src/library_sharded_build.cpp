// A library build in shards: the items cut into shards of shard_records, each its own library
// file and log in shard_folder, so that a build can be resumed and spread over processes, and
// the shards' index written last.
#include "library_build_items.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/core/stopwatch.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::screening {

void detail::check_build_options(const LibraryBuildOptions& options) {
  if (!(options.spacing > 0.0) || !std::isfinite(options.spacing))
    throw OptionError("library spacing must be finite and > 0, got " +
                      std::to_string(options.spacing));
  if (!(options.sigma > 0.0) || !std::isfinite(options.sigma))
    throw OptionError("library sigma must be finite and > 0, got " + std::to_string(options.sigma));
  if (options.batch < 1) throw OptionError("library build batch must be at least 1");
  if (options.shard_records < 1)
    throw OptionError(options::named("shard_records") + " must be at least 1, got 0");
  if (!(options.lining_radius > 0.0) || !std::isfinite(options.lining_radius))
    throw OptionError(options::named("site_overlay_radius") + " must be finite and > 0, got " +
                      std::to_string(options.lining_radius));
  if (!(options.site.sphere_radius > 0.0) || !std::isfinite(options.site.sphere_radius))
    throw OptionError(options::named("site_radius") + " must be finite and > 0, got " +
                      std::to_string(options.site.sphere_radius));
  if (!(options.site.surface_margin >= 0.0) || !std::isfinite(options.site.surface_margin))
    throw OptionError(options::named("site_margin") + " must be finite and >= 0, got " +
                      std::to_string(options.site.surface_margin));
  if (options.conformers) {
    const ConformerOptions& c = *options.conformers;
    if (c.count < 1)
      throw OptionError(options::named("conformers") + " must be at least 1, got " +
                        std::to_string(c.count));
    if (c.seed < 0)
      throw OptionError(options::named("seed") + " must be >= 0, got " + std::to_string(c.seed));
    if (c.mmff_iterations < 0) throw OptionError("MMFF iterations must be >= 0");
  }
}

LibraryBuildResult build_library(const std::vector<io::MoleculeRecord>& records,
                                 const std::filesystem::path& output,
                                 const LibraryBuildOptions& options) {
  return ShardedLibraryBuild(records, output, options).run();
}

std::filesystem::path shard_folder(const std::filesystem::path& output) {
  return output.parent_path() / (output.filename().string() + ".d");
}

struct ShardedLibraryBuild::Impl {
  Impl(std::filesystem::path output_, LibraryBuildOptions options_)
      : output(std::move(output_)), options(std::move(options_)) {}

  /// Plans the build of `items_` (made with this object's options): checks the options, cuts
  /// the items into shards and hashes each shard's inputs. Throws OptionError for options
  /// outside their domain, InputError when there is no item.
  void plan(detail::BuildItems items_);

  detail::BuildItems items;
  std::filesystem::path output, folder;
  LibraryBuildOptions options;
  std::string settings;               // items.settings: the index's, and each shard's first lines
  std::size_t count = 0;              // shards
  std::vector<std::uint64_t> hashes;  // input_hash of each shard (more than one shard)
  std::size_t resumed = 0, resumed_entries = 0;

  std::size_t begin(std::size_t k) const { return k * options.shard_records; }
  std::size_t end(std::size_t k) const {
    return std::min(items.count, (k + 1) * options.shard_records);
  }
  std::filesystem::path file(std::size_t k, const char* extension) const {
    char name[32];
    std::snprintf(name, sizeof name, "%06zu%s", k + 1, extension);
    return folder / name;
  }
  std::filesystem::path library_file(std::size_t k) const { return file(k, ".sclib"); }
  std::filesystem::path log_file(std::size_t k) const { return file(k, ".log"); }
  std::filesystem::path manifest_file() const { return folder / "manifest.txt"; }

  /// Shard k's settings: the build's, then its number, records and input hash.
  std::string shard_settings(std::size_t k) const {
    return settings + "shard " + std::to_string(k + 1) + " of " + std::to_string(count) +
           ": records " + std::to_string(begin(k) + 1) + "-" + std::to_string(end(k)) + " of " +
           std::to_string(items.count) + ", inputs " + detail::hex64(hashes[k]) + "\n";
  }
  std::string manifest() const {
    std::ostringstream text;
    text << "surfcomp library build manifest 1\nrecords " << items.count << "\nshard-records "
         << options.shard_records << "\nshards " << count << "\n";
    std::istringstream lines(settings);
    for (std::string line; std::getline(lines, line);) text << "settings " << line << "\n";
    for (std::size_t k = 0; k < count; ++k) {
      text << "shard " << library_file(k).stem().string() << " records " << begin(k) + 1 << "-"
           << end(k) << " inputs " << detail::hex64(hashes[k]) << "\n";
    }
    return text.str();
  }
  /// Shard k's log when the shard is finished (its log written and, unless all its records
  /// were skipped, its library file there), else none.
  std::optional<LibraryBuildResult> finished(std::size_t k) const {
    if (!std::filesystem::exists(log_file(k))) return std::nullopt;
    LibraryBuildResult log = detail::read_build_log(log_file(k));
    if (log.entries > 0 && !std::filesystem::exists(library_file(k))) return std::nullopt;
    return log;
  }
  /// Throws InputError naming the manifest unless it is this build's.
  void check_manifest() const;
  /// Throws what opening or verifying the first bad shard file throws, or FormatError naming it
  /// when its settings are not its own.
  void verify_shards() const;
};

void ShardedLibraryBuild::Impl::check_manifest() const {
  const std::filesystem::path path = manifest_file();
  const std::string advice =
      "; resume with the same inputs and options, or remove " + folder.string() + " to start again";
  if (!std::filesystem::exists(path))
    throw InputError(path.string() + ": missing, so the folder holds no build to resume" + advice);
  std::istringstream found(io::read_input_file(path)), expected(manifest());
  std::string was, now;
  for (std::size_t number = 1;; ++number) {
    const bool more_found = static_cast<bool>(std::getline(found, was));
    const bool more_expected = static_cast<bool>(std::getline(expected, now));
    if (!more_found && !more_expected) return;
    if (more_found && more_expected && was == now) continue;
    throw InputError(path.string() + ":" + std::to_string(number) +
                     ": records another build's inputs or options ('" + (more_found ? was : "") +
                     "' where this build has '" + (more_expected ? now : "") + "')" + advice);
  }
}

void ShardedLibraryBuild::Impl::verify_shards() const {
  // The shards are checked in parallel; the first bad one in shard order is reported.
  std::vector<std::exception_ptr> errors(count);
  tbb::parallel_for(std::size_t{0}, count, [&](std::size_t k) {
    const std::filesystem::path path = library_file(k);
    if (!std::filesystem::exists(path)) return;
    try {
      const Library shard(path);
      // A shard of an earlier format (whole structures in its site entries) is not mixed in.
      if (shard.version() != library_format_version) {
        throw FormatError(path.string(), "format version " + std::to_string(shard.version()) +
                                             ", written by an earlier surfcomp; remove " +
                                             folder.string() + " to build again");
      }
      if (shard.shards() != 1 || shard.settings() != shard_settings(k)) {
        throw FormatError(path.string(), "its settings are not those of shard " +
                                             std::to_string(k + 1) + " of this build");
      }
      shard.verify();
    } catch (...) {
      errors[k] = std::current_exception();
    }
  });
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

void ShardedLibraryBuild::Impl::plan(detail::BuildItems items_) {
  detail::check_build_options(options);
  items = std::move(items_);
  if (items.count == 0)
    throw InputError(output.string() + ": no " + items.noun + " to build it from");
  folder = shard_folder(output);
  settings = items.settings;
  count = (items.count + options.shard_records - 1) / options.shard_records;
  if (count == 1) return;  // one library file: no shard to name
  hashes.resize(count);
  tbb::parallel_for(std::size_t{0}, count, [&](std::size_t k) {
    hashes[k] = detail::input_hash(items, begin(k), end(k));
  });
}

ShardedLibraryBuild::ShardedLibraryBuild(const std::vector<io::MoleculeRecord>& records,
                                         std::filesystem::path output, LibraryBuildOptions options)
    : impl_(std::make_unique<Impl>(std::move(output), std::move(options))) {
  impl_->plan(detail::record_items(records, impl_->options));
}

ShardedLibraryBuild::~ShardedLibraryBuild() = default;

std::size_t ShardedLibraryBuild::shards() const { return impl_->count; }

const std::filesystem::path& ShardedLibraryBuild::folder() const { return impl_->folder; }

void ShardedLibraryBuild::prepare() {
  namespace fs = std::filesystem;
  Impl& m = *impl_;
  if (!fs::exists(m.folder)) {
    std::error_code error;
    if (!fs::create_directory(m.folder, error) && error) {
      throw FileError(m.folder.string(),
                      "cannot create the folder of the shards (" + error.message() + ")");
    }
    io::write_file_atomically(m.manifest_file(), [&](std::ostream& out) { out << m.manifest(); });
    return;
  }
  if (!m.options.resume) {
    throw FileError(m.folder.string(),
                    "the shard folder of an earlier build is in the way; continue that build "
                    "with " +
                        options::named("resume") + ", or remove the folder");
  }
  if (!fs::is_directory(m.folder)) throw FileError(m.folder.string(), "not a folder; remove it");
  m.check_manifest();
  m.verify_shards();
  for (std::size_t k = 0; k < m.count; ++k) {
    if (const std::optional<LibraryBuildResult> log = m.finished(k)) {
      ++m.resumed;
      m.resumed_entries += log->entries;
    }
  }
  for (const fs::directory_entry& item : fs::directory_iterator(m.folder)) {
    std::error_code ignored;
    if (item.is_regular_file() && io::is_temporary_file(item.path()))
      fs::remove(item.path(), ignored);
  }
}

LibraryBuildResult ShardedLibraryBuild::build(std::size_t rank, std::size_t ranks) {
  if (ranks == 0 || rank >= ranks)
    throw std::invalid_argument("ShardedLibraryBuild::build: rank outside [0, ranks)");
  const Impl& m = *impl_;
  const Stopwatch clock;
  std::vector<std::size_t> unfinished;
  std::size_t records = 0;
  for (std::size_t k = rank; k < m.count; k += ranks) {
    if (m.finished(k)) continue;
    unfinished.push_back(k);
    records += m.end(k) - m.begin(k);
  }
  LibraryBuildResult result;
  result.shards = m.count;
  for (const std::size_t k : unfinished) {
    LibraryBuildOptions options = m.options;
    if (m.options.progress) {
      options.progress = [&](const BuildProgress& p) {
        m.options.progress({result.records + p.records_done, records, result.entries + p.entries,
                            result.skipped.size() + p.skipped, clock.elapsed_s()});
      };
    }
    const std::filesystem::path file = m.library_file(k);
    const LibraryBuildResult shard =
        detail::build_in_order(m.items, m.begin(k), m.end(k), file, m.shard_settings(k), options);
    io::write_file_atomically(m.log_file(k),
                              [&](std::ostream& out) { write_build_log(out, file, shard); });
    result.records += shard.records;
    result.entries += shard.entries;
    result.bytes += shard.bytes;
    result.skipped.insert(result.skipped.end(), shard.skipped.begin(), shard.skipped.end());
    result.times.conformers += shard.times.conformers;
    result.times.entries += shard.times.entries;
  }
  result.seconds = clock.elapsed_s();
  return result;
}

LibraryBuildResult ShardedLibraryBuild::finish() const {
  const Impl& m = *impl_;
  LibraryBuildResult result;
  result.records = m.items.count;
  result.shards = m.count;
  result.shards_resumed = m.resumed;
  result.entries_resumed = m.resumed_entries;
  std::vector<std::filesystem::path> listed;
  for (std::size_t k = 0; k < m.count; ++k) {
    const std::optional<LibraryBuildResult> log = m.finished(k);
    if (!log) {
      throw FileError(m.log_file(k).string(), "shard " + std::to_string(k + 1) + " of " +
                                                  std::to_string(m.count) + " is not finished");
    }
    result.entries += log->entries;
    result.skipped.insert(result.skipped.end(), log->skipped.begin(), log->skipped.end());
    if (log->entries > 0) listed.push_back(m.folder.filename() / m.library_file(k).filename());
  }
  if (result.entries == 0) return result;
  write_library_index(m.output, listed, m.settings);
  result.bytes = std::filesystem::file_size(m.output);
  for (const std::filesystem::path& shard : listed)
    result.bytes += std::filesystem::file_size(m.output.parent_path() / shard);
  return result;
}

LibraryBuildResult ShardedLibraryBuild::run() {
  Impl& m = *impl_;
  if (m.count == 1)
    return detail::build_in_order(m.items, 0, m.items.count, m.output, m.settings, m.options);
  const Stopwatch clock;
  prepare();
  const LibraryBuildResult built = build();
  LibraryBuildResult result = finish();
  result.times = built.times;
  result.seconds = clock.elapsed_s();
  return result;
}

ShardedLibraryBuild::ShardedLibraryBuild(const std::vector<SiteRequest>& sites,
                                         std::filesystem::path output, LibraryBuildOptions options)
    : impl_(std::make_unique<Impl>(std::move(output), std::move(options))) {
  detail::check_site_options(impl_->options);
  impl_->plan(detail::site_items(sites, impl_->options));
}

ShardedLibraryBuild::ShardedLibraryBuild(const PocketStructures& structures,
                                         std::filesystem::path output, LibraryBuildOptions options)
    : impl_(std::make_unique<Impl>(std::move(output), std::move(options))) {
  detail::check_site_options(impl_->options);
  impl_->plan(detail::pocket_items(structures.files, impl_->options));
}

}  // namespace surfcomp::screening
