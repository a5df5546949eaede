// surfcomp library: build a screening library (.sclib) from molecule files, describe one, or
// export its conformers as SDF.
#include "command.hpp"
#include "command_files.hpp"
#include "console.hpp"
#include "describe_settings.hpp"
#include "options.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/screening/hit_files.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/library_build.hpp"

#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <utility>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp library build INPUT... -o LIB.sclib [--conformers N] [--seed S]\n"
    "                              [--threads T]\n"
    "       surfcomp library build --sites LIST -o POCKETS.sclib [--site-radius R] [--threads T]\n"
    "       surfcomp library info LIB.sclib\n"
    "       surfcomp library export LIB.sclib -o OUT.sdf\n\n"
    "build   reads every molecule of the INPUTs (SDF/MOL/MOL2 files of one or many records,\n"
    "        PDB files, SMILES lists .smi and tab-separated .dat/.dat.gz with a header line\n"
    "        '# Mol_Title ID SMILES', .hsi files, directories of these), generates\n"
    "        --conformers N ETKDG + MMFF conformers of each (seeded by --seed; without\n"
    "        --conformers a record's own coordinates are used, and SMILES lists are refused),\n"
    "        builds each conformer's surface as `surfcomp match` does and stores the molecule\n"
    "        and its overlay samples. Records that cannot be read, embedded or surfaced are\n"
    "        skipped and listed in LIB.sclib.log (when all are, the build fails and leaves only\n"
    "        the log). A .hsi INPUT (surfcomp hsi-build from a molecule) becomes one entry\n"
    "        keeping its surface and heavy atoms (no bonds; no --conformers; at most 999 heavy\n"
    "        atoms); screen describes that surface again.\n"
    "        Entries keep the input order; the file does not depend on --threads.\n"
    "info    prints the library's version, entries, molecules, sizes and build settings.\n"
    "export  writes every entry's molecule in its conformation, with the SD tags\n"
    "        surfcomp_entry (1-based), surfcomp_name and surfcomp_conformer.";

std::string duration(double seconds) {
  const long s = std::lround(seconds);
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  return text;
}

/// A progress line on stderr when it is a terminal (entries done, rate, time left), else none.
std::function<void(const screening::BuildProgress&)> progress_line() {
  if (!console::progress_shown()) return {};
  return [last = -1.0](const screening::BuildProgress& p) mutable {
    if (p.records_done < p.records && p.seconds - last < 0.5) return;
    last = p.seconds;
    const double rate = p.seconds > 0 ? static_cast<double>(p.entries) / p.seconds : 0.0;
    const double left = p.records_done > 0
                            ? p.seconds * static_cast<double>(p.records - p.records_done) /
                                  static_cast<double>(p.records_done)
                            : 0.0;
    std::fprintf(stderr, "\r\033[Klibrary: %zu/%zu records, %zu entries, %.1f entries/s, %s left",
                 p.records_done, p.records, p.entries, rate, duration(left).c_str());
    if (p.records_done == p.records) std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  };
}

/// Writes LIB.sclib.log (the skipped records and why) and prints the build's summary line.
void write_log_and_summary(const std::filesystem::path& library, const std::filesystem::path& log,
                           const screening::LibraryBuildResult& result) {
  io::write_file_atomically(log, [&](std::ostream& out) {
    out << "# surfcomp library build -> " << library.string() << ": " << result.records
        << " records, " << result.entries << " entries, " << result.skipped.size()
        << " skipped\n# source\trecord\tname\treason\n";
    for (const auto& s : result.skipped)
      out << s.source << '\t' << s.record << '\t' << s.name << '\t' << s.reason << '\n';
  });
  if (result.entries == 0) {  // an empty library would only fail later, further from the cause
    throw InputError(library.string() + ": no entry was built; all " +
                     std::to_string(result.records) + " records were skipped (reasons in " +
                     log.string() + ")");
  }
  console::summary(
      "%s: %zu records -> %zu entries, %zu skipped (see %s), %.1f MB, %.1f s (%.1f entries/s)\n",
      library.string().c_str(), result.records, result.entries, result.skipped.size(),
      log.string().c_str(), static_cast<double>(result.bytes) / 1e6, result.seconds,
      result.seconds > 0 ? static_cast<double>(result.entries) / result.seconds : 0.0);
  const double per_entry = 1e3 / static_cast<double>(result.entries);
  if (result.times.conformers > 0.0) {
    console::summary(
        "  core time per entry: %.2f ms conformers (RDKit ETKDG + MMFF), %.2f ms "
        "surfcomp (reading, sample, packing)\n",
        result.times.conformers * per_entry, result.times.entries * per_entry);
  } else {
    console::summary("  core time per entry: %.2f ms (reading, sample, packing)\n",
                     result.times.entries * per_entry);
  }
}

/// `library build --sites LIST`: a pocket library.
int build_sites(const boost::program_options::variables_map& vm, const std::string& list,
                const std::string& output, screening::LibraryBuildOptions options, int threads) {
  if (vm.count("input")) throw OptionError("--sites takes no INPUT: the sites are in its list");
  if (options.conformers) throw OptionError("--conformers does not apply to --sites");
  const auto limit = limit_threads(threads);
  const std::filesystem::path library = output;
  const std::filesystem::path log = output + ".log";
  check_command_files(
      {{{"--sites", list}}, {{"--output", library, {".sclib"}, ""}, {"the log", log, {}, ""}}});
  options.progress = progress_line();
  const std::vector<screening::SiteRequest> sites = screening::read_site_list(list);
  const screening::LibraryBuildResult result =
      screening::build_site_library(sites, library, options);
  write_log_and_summary(library, log, result);
  return 0;
}

int build(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, sites;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "output library (.sclib)")
      ("sites", po::value(&sites), "build a pocket library from this site list (no INPUT)");
  // clang-format on
  add_table_options(described, screening::library_build_option_table());
  add_threads_option(described);
  po::variables_map vm;
  if (!parse_command_line(args, described, -1, kUsage, vm)) return 0;
  screening::LibraryBuildOptions options;
  apply_table_options(screening::library_build_option_table(), vm, options);
  const int threads = threads_from(vm);
  if (!sites.empty()) return build_sites(vm, sites, output, std::move(options), threads);
  if (!vm.count("input")) throw OptionError("missing INPUT (see --help)");
  std::vector<std::filesystem::path> inputs;
  for (const auto& input : vm["input"].as<std::vector<std::string>>()) inputs.emplace_back(input);
  const auto limit = limit_threads(threads);
  const std::filesystem::path library = output;
  const std::filesystem::path log = output + ".log";
  CommandFiles files;
  for (const auto& input : inputs) files.inputs.push_back({"INPUT", input});
  files.outputs.push_back({"--output", library, {".sclib"}, ""});
  files.outputs.push_back({"the log", log, {}, ""});
  check_command_files(files);

  const std::vector<io::MoleculeRecord> records = screening::read_library_inputs(inputs);
  if (!options.conformers) {
    for (const io::MoleculeRecord& record : records) {
      if (record.format == io::RecordFormat::smiles) {
        throw OptionError(record.source.string() +
                          ": SMILES records have no coordinates; give --conformers N");
      }
    }
  }
  options.progress = progress_line();
  const screening::LibraryBuildResult result = screening::build_library(records, library, options);
  write_log_and_summary(library, log, result);
  return 0;
}

int info(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  po::options_description described("options");
  described.add_options()("help,h", "print this help");
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, kUsage, vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing LIB (see --help)");
  const screening::Library library(vm["input"].as<std::vector<std::string>>().front());
  const screening::LibrarySummary summary = screening::summarize_library(library);
  const double mean =
      summary.entries > 0 ? static_cast<double>(summary.file_bytes) / summary.entries : 0.0;
  console::summary(
      "%s: format version %u, %zu entries, %zu molecules, %.2f MB (%.1f KB per entry, "
      "largest %.1f KB)\n",
      library.path().string().c_str(), library.version(), summary.entries, summary.molecules,
      static_cast<double>(summary.file_bytes) / 1e6, mean / 1e3,
      static_cast<double>(summary.largest_entry_bytes) / 1e3);
  for (const auto& [source, count] : summary.entries_per_source)
    console::summary("  %s: %zu entries\n", source.c_str(), count);
  console::summary("settings:\n%s", library.settings().c_str());
  return 0;
}

int export_sdf(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output;
  po::options_description described("options");
  described.add_options()("help,h", "print this help")("output,o", po::value(&output)->required(),
                                                       "output SDF file");
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, kUsage, vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing LIB (see --help)");
  const std::filesystem::path path = vm["input"].as<std::vector<std::string>>().front();
  check_command_files({{{"LIB", path}}, {{"--output", output, {".sdf"}, ""}}});
  const screening::Library library(path);
  io::write_file_atomically(output,
                            [&](std::ostream& out) { screening::write_library_sdf(out, library); });
  console::summary("%s: %zu entries -> %s\n", path.string().c_str(), library.size(),
                   output.c_str());
  return 0;
}

}  // namespace

int library(const std::vector<std::string>& args) {
  if (args.empty() || args.front() == "--help" || args.front() == "-h") {
    (args.empty() ? std::cerr : std::cout) << kUsage << "\n";
    return args.empty() ? 2 : 0;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (args.front() == "build") return build(rest);
  if (args.front() == "info") return info(rest);
  if (args.front() == "export") return export_sdf(rest);
  throw OptionError("unknown library action '" + args.front() + "' (build, info or export)");
}

}  // namespace surfcomp::tools
