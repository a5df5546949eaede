// surfcomp library: build a screening library (.sclib) from molecule files (one file, or an index
// of shards that the processes of an MPI job share), describe one, or export its conformers as
// SDF.
#include "command.hpp"
#include "console.hpp"
#include "describe_settings.hpp"
#include "mpi_loader.hpp"
#include "options.hpp"
#include "screen_mpi.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/screening/hit_files.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/library_build.hpp"
#include "surfcomp/screening/shape_screen.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp library build INPUT... -o LIB.sclib [--conformers N] [--seed S]\n"
    "                              [--shard-records N] [--resume] [--threads T]\n"
    "       mpirun -np R surfcomp library build INPUT... -o LIB.sclib ...   (shards over R\n"
    "                                                                     processes)\n"
    "       surfcomp library build --sites LIST -o POCKETS.sclib [--site-radius R] [--threads T]\n"
    "       surfcomp library build --pockets STRUCTURE... -o POCKETS.sclib [--threads T]\n"
    "       mpirun -np R surfcomp library build --pockets STRUCTURE... -o POCKETS.sclib\n"
    "                                            --shard-records N ...\n"
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
    "        atoms); screen describes that surface again. Mesh INPUTs (.ply .stl .off .obj\n"
    "        .vert; folders of them) make a library of meshes instead, one entry each (the mesh\n"
    "        as read, --repair: repaired first), which `surfcomp screen SCAN.ply LIB` screens\n"
    "        by shape; molecules and meshes do not mix in one library.\n"
    "        Entries keep the input order; the file does not depend on --threads.\n"
    "        More records than --shard-records N make a sharded library: LIB.sclib is then an\n"
    "        index of shards of N consecutive records each (LIB.sclib.d/000001.sclib, ...), which\n"
    "        screen, info and export read as one library. Under mpirun the R processes share\n"
    "        the shards (process k builds shards k + 1, k + 1 + R, ...), each with --threads;\n"
    "        the index and shards do not depend on R or --threads. A build that was stopped\n"
    "        continues with --resume (the same INPUTs and options): the finished shards are\n"
    "        checked and kept, the others built. Without --resume an existing LIB.sclib.d is\n"
    "        refused.\n"
    "        --sites: each line of LIST is a site (STRUCTURE LIGAND [CHAIN], STRUCTURE\n"
    "        x,y,z,r ... or STRUCTURE pocket N) and one entry. --pockets: the INPUTs are "
    "structures (PDB, mmCIF;\n"
    "        folders of them): every pocket `surfcomp pockets` finds in each is one site entry,\n"
    "        named STEM:pocketN (structures without a pocket are listed in the log). Both shard,\n"
    "        resume and share out under mpirun as above, a site or a structure counting as one\n"
    "        record.\n"
    "info    prints the library's version, entries, molecules, shards, sizes and build settings.\n"
    "export  writes every entry's molecule in its conformation, with the SD tags\n"
    "        surfcomp_entry (1-based), surfcomp_name and surfcomp_conformer.";

std::string duration(double seconds) {
  const long s = std::lround(seconds);
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  return text;
}

/// A progress line on stderr when it is a terminal (entries done, rate, time left), else none.
/// `who` starts it: "library", or a process of an MPI job.
std::function<void(const screening::BuildProgress&)> progress_line(
    const std::string& who = "library") {
  if (!console::progress_shown()) return {};
  return [who, last = -1.0](const screening::BuildProgress& p) mutable {
    if (p.records_done < p.records && p.seconds - last < 0.5) return;
    last = p.seconds;
    const double rate = p.seconds > 0 ? static_cast<double>(p.entries) / p.seconds : 0.0;
    const double left = p.records_done > 0
                            ? p.seconds * static_cast<double>(p.records - p.records_done) /
                                  static_cast<double>(p.records_done)
                            : 0.0;
    std::fprintf(stderr, "\r\033[K%s: %zu/%zu records, %zu entries, %.1f entries/s, %s left",
                 who.c_str(), p.records_done, p.records, p.entries, rate, duration(left).c_str());
    if (p.records_done == p.records) std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  };
}

/// Writes LIB.sclib.log (the skipped records and why) and prints the build's summary line.
void write_log_and_summary(const std::filesystem::path& library, const std::filesystem::path& log,
                           const screening::LibraryBuildResult& result) {
  io::write_file_atomically(
      log, [&](std::ostream& out) { screening::write_build_log(out, library, result); });
  if (result.entries == 0) {  // an empty library would only fail later, further from the cause
    // The first reason, with its file, on the line itself: often the only one.
    std::string first;
    if (!result.skipped.empty()) {
      const screening::SkippedRecord& skipped = result.skipped.front();
      const std::string& source = skipped.source;
      first =
          skipped.reason.rfind(source, 0) == 0 ? skipped.reason : source + ": " + skipped.reason;
      first = "; first, " + first;
    }
    throw InputError(library.string() + ": no entry was built; all " +
                     std::to_string(result.records) + " records were skipped" + first +
                     " (reasons in " + log.string() + ")");
  }
  std::string shards;
  if (result.shards > 1) {
    shards = " in " + std::to_string(result.shards) + " shards of " +
             screening::shard_folder(library).string();
  }
  // A resumed build's rate and core times are those of the entries it built.
  const std::size_t built = result.entries - result.entries_resumed;
  char rate[64] = "nothing left to build";
  if (built > 0) {
    std::snprintf(rate, sizeof rate, "%.1f entries/s",
                  result.seconds > 0 ? static_cast<double>(built) / result.seconds : 0.0);
  }
  console::summary("%s: %zu records -> %zu entries%s, %zu skipped (see %s), %.1f MB, %.1f s (%s)\n",
                   library.string().c_str(), result.records, result.entries, shards.c_str(),
                   result.skipped.size(), log.string().c_str(),
                   static_cast<double>(result.bytes) / 1e6, result.seconds, rate);
  if (result.shards_resumed > 0) {
    console::summary("  resumed: %zu of the shards (%zu entries) were finished before\n",
                     result.shards_resumed, result.entries_resumed);
  }
  if (built == 0) return;
  const double per_entry = 1e3 / static_cast<double>(built);
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

/// Makes the plan of a build (ShardedLibraryBuild) in `plan`, with the options given.
using BuildPlan = std::function<void(std::optional<screening::ShardedLibraryBuild>& plan,
                                     screening::LibraryBuildOptions options)>;

/// ShardedLibraryBuild over the ranks of an MPI job: rank 0 creates or checks the shard folder
/// (prepare) before any rank builds, every rank builds its shards (k % ranks == rank) with its own
/// threads, and rank 0, once every rank is done (the gather of their core times is the barrier),
/// writes the index (finish). Inputs of one shard make one library file, built by rank 0. Returns
/// the build's result on rank 0, none on the others. A refusal on rank 0 (an existing folder,
/// another build's manifest, a damaged shard) is thrown there after every rank has finalised MPI,
/// so that it ends the job with one line; any other error prints its rank and aborts the job.
std::optional<screening::LibraryBuildResult> build_under_mpi(
    const BuildPlan& make_plan, screening::LibraryBuildOptions options) {
  int rank = 0, ranks = 1;
  mpi().init(&rank, &ranks);
  const Stopwatch clock;
  options.progress = progress_line(ranks == 1 ? "library"
                                              : "library, process " + std::to_string(rank + 1) +
                                                    " of " + std::to_string(ranks));
  std::optional<screening::ShardedLibraryBuild> build;
  std::exception_ptr refused;
  try {
    make_plan(build, options);
    if (rank == 0 && build->shards() > 1) build->prepare();
  } catch (const std::exception&) {
    refused = std::current_exception();
  }
  std::uint64_t ready = refused ? 0 : 1;  // rank 0's
  mpi().broadcast_uint64(&ready, 1);
  if (ready == 0) {
    mpi().finalize();
    if (rank == 0) std::rethrow_exception(refused);
    return std::nullopt;
  }
  screening::LibraryBuildResult built;
  try {
    if (refused) std::rethrow_exception(refused);  // this rank's plan failed, rank 0's did not
    if (build->shards() > 1) {
      built = build->build(static_cast<std::size_t>(rank), static_cast<std::size_t>(ranks));
    } else if (rank == 0) {
      built = build->run();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "surfcomp library: rank %d: error: %s\n", rank, e.what());
    mpi().abort(1);
  }
  const std::vector<double> times{built.times.conformers, built.times.entries};
  std::vector<double> all(rank == 0 ? times.size() * static_cast<std::size_t>(ranks) : 0);
  std::vector<int> counts(static_cast<std::size_t>(ranks), 2), at(counts.size());
  for (std::size_t r = 0; r < at.size(); ++r) at[r] = static_cast<int>(2 * r);
  mpi().gather_doubles(times.data(), 2, all.data(), counts.data(), at.data());
  mpi().finalize();
  if (rank != 0) return std::nullopt;
  if (build->shards() == 1) return built;
  screening::LibraryBuildResult result = build->finish();
  for (std::size_t r = 0; r < all.size(); r += 2) {
    result.times.conformers += all[r];
    result.times.entries += all[r + 1];
  }
  result.seconds = clock.elapsed_s();
  return result;
}

/// Runs the build `make_plan` plans, under MPI when mpirun started this process (`under_mpi`),
/// then writes its log and says what it made.
int run_build(const BuildPlan& make_plan, const std::filesystem::path& library,
              screening::LibraryBuildOptions options, bool under_mpi) {
  const std::filesystem::path log = library.string() + ".log";
  if (under_mpi) {
    const std::optional<screening::LibraryBuildResult> result =
        build_under_mpi(make_plan, std::move(options));
    if (result) write_log_and_summary(library, log, *result);
    return 0;
  }
  options.progress = progress_line();
  std::optional<screening::ShardedLibraryBuild> build;
  make_plan(build, std::move(options));
  write_log_and_summary(library, log, build->run());
  return 0;
}

/// The INPUT paths, checked with the library `output` and its log that the build writes (an
/// input named `role` in messages).
std::vector<std::filesystem::path> checked_inputs(const boost::program_options::variables_map& vm,
                                                  const std::string& output, const char* role) {
  std::vector<std::filesystem::path> inputs;
  for (const auto& input : vm["input"].as<std::vector<std::string>>()) inputs.emplace_back(input);
  io::CommandFiles files;
  for (const auto& input : inputs) files.inputs.push_back({role, input});
  files.outputs.push_back({"--output", output, {".sclib"}, ""});
  files.outputs.push_back({"the log", output + ".log", {}, ""});
  io::check_command_files(files);
  return inputs;
}

int build(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, sites;
  bool pockets = false;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "output library (.sclib)")
      ("sites", po::value(&sites), "build a pocket library from this site list (no INPUT)")
      ("pockets", po::bool_switch(&pockets),
       "build a pocket library of every pocket `surfcomp pockets` finds in the INPUT structures");
  // clang-format on
  add_table_options(described, screening::library_build_option_table());
  add_threads_option(described);
  po::variables_map vm;
  if (!parse_command_line(args, described, -1, kUsage, vm)) return 0;
  screening::LibraryBuildOptions options;
  apply_table_options(screening::library_build_option_table(), vm, options);
  const int threads = threads_from(vm);
  if (!sites.empty() && pockets) throw OptionError("give --sites LIST or --pockets, not both");
  if ((!sites.empty() || pockets) && options.conformers)
    throw OptionError(std::string("--conformers does not apply to ") +
                      (pockets ? "--pockets" : "--sites"));
  const std::filesystem::path library = output;
  if (!sites.empty()) {
    if (vm.count("input")) throw OptionError("--sites takes no INPUT: the sites are in its list");
    io::check_command_files(
        {{{"--sites", sites}},
         {{"--output", library, {".sclib"}, ""}, {"the log", output + ".log", {}, ""}}});
    const ThreadLimit limit(threads);
    const bool under_mpi = launched_by_mpi();  // before the work: it loads the MPI module
    const std::vector<screening::SiteRequest> requests = screening::read_site_list(sites);
    return run_build([&](auto& plan, auto settings) { plan.emplace(requests, library, settings); },
                     library, std::move(options), under_mpi);
  }
  if (!vm.count("input")) {
    throw OptionError(pockets ? "--pockets needs STRUCTURE files or folders"
                              : "missing INPUT (see --help)");
  }
  const std::vector<std::filesystem::path> inputs =
      checked_inputs(vm, output, pockets ? "STRUCTURE" : "INPUT");
  const ThreadLimit limit(threads);
  const bool under_mpi = launched_by_mpi();  // before the work: it loads the MPI module
  if (pockets) {
    const screening::PocketStructures structures{screening::structure_files(inputs)};
    return run_build(
        [&](auto& plan, auto settings) { plan.emplace(structures, library, settings); }, library,
        std::move(options), under_mpi);
  }

  const std::vector<io::MoleculeRecord> records = screening::read_library_inputs(inputs);
  if (!options.conformers) {
    for (const io::MoleculeRecord& record : records) {
      if (record.format == io::RecordFormat::smiles) {
        throw OptionError(record.source.string() +
                          ": SMILES records have no coordinates; give --conformers N");
      }
    }
  } else if (records.front().format == io::RecordFormat::mesh) {  // one kind: the build's check
    throw OptionError(records.front().source.string() +
                      ": a mesh has fixed coordinates; --conformers applies to molecules");
  }
  return run_build([&](auto& plan, auto settings) { plan.emplace(records, library, settings); },
                   library, std::move(options), under_mpi);
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
      "%s: format version %u, %zu entries, %zu %s, %zu shard%s, %.2f MB (%.1f KB per "
      "entry, largest %.1f KB)\n",
      library.path().string().c_str(), library.version(), summary.entries, summary.molecules,
      screening::is_mesh_library(library) ? "meshes" : "molecules", library.shards(),
      library.shards() == 1 ? "" : "s", static_cast<double>(summary.file_bytes) / 1e6, mean / 1e3,
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
  io::check_command_files({{{"LIB", path}}, {{"--output", output, {".sdf"}, ""}}});
  const screening::Library library(path);
  if (screening::is_mesh_library(library)) {
    throw InputError(path.string() +
                     ": a library of meshes has no molecules to export (`library info` lists "
                     "its mesh files)");
  }
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
