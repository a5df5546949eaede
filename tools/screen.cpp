// surfcomp screen: one query against a screening library (.sclib), best molecules first, as a
// CSV table; optionally the best hits moved onto the query (SDF).
#include "command.hpp"
#include "command_files.hpp"
#include "console.hpp"
#include "describe_settings.hpp"
#include "options.hpp"
#include "screen_mpi.hpp"
#include "screen_settings.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/matching/site.hpp"
#include "surfcomp/screening/hit_files.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/screen.hpp"

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <memory>
#include <sstream>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp screen QUERY LIB.sclib -o hits.csv [--top N] [--refine C] [--candidates K]\n"
    "                       [--aligned-out hits.sdf] [--threads T]\n"
    "       surfcomp screen STRUCTURE.pdb POCKETS.sclib --site-ligand RES | --site-sphere x,y,z,r\n"
    "                       -o hits.csv [--aligned-out hits.pdb] ...\n"
    "       mpirun -np R surfcomp screen ...   (the library split over R processes)\n\n"
    "Ranks the molecules of a library (surfcomp library build) by how well their surfaces\n"
    "overlay QUERY's, in three stages: every conformer gets a fast score (the overlay score of\n"
    "its stored surface sample at the four principal-axes superpositions onto the query, no\n"
    "refinement); the --refine best conformers of each molecule then get that overlay refined\n"
    "from each superposition, and a molecule counts by its best conformer; the --candidates\n"
    "best molecules' best conformers last get the full match of `surfcomp match` (cliques,\n"
    "refinement), their surfaces rebuilt. hits.csv has one row per molecule, best first: the\n"
    "candidates by their full-match score (stage 3), then the others by their refined score\n"
    "(stage 2; stage 1, the fast score, with --refine 0); the columns\n"
    "rank,entry,name,source,record,conformer,score,stage,shape,chem,atoms,fast_score and\n"
    "t00..t33, the transform moving the hit into QUERY's frame (row-major). The rows do not\n"
    "depend on --threads or on the number of MPI processes.\n\n"
    "QUERY  a molecule (.sdf .mol .mol2 .pdb; --record N of a multi-molecule file) or a .hsi\n"
    "       file built from one; with --site-ligand or --site-sphere, a binding site on a\n"
    "       structure, screened against a pocket library (library build --sites): the overlays\n"
    "       then compare pocket linings as `match` does for sites (all 24 axes orders\n"
    "       in stages 1 and 2), and --aligned-out writes the hits' structures moved onto\n"
    "       QUERY (.pdb, one MODEL per hit).";

}  // namespace

int screen(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, aligned_out;
  double aligned_top = 10;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "output table (.csv)")
      ("aligned-out", po::value(&aligned_out),
       "write the first --aligned-top hits moved onto QUERY (.sdf, bonds kept)")
      ("aligned-top", defaulted(&aligned_top),
       "hits written to --aligned-out");
  // clang-format on
  add_screen_options(described);
  po::variables_map vm;
  if (!parse_command_line(args, described, 2, kUsage, vm)) return 0;
  const auto inputs =
      vm.count("input") ? vm["input"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (inputs.size() != 2) throw OptionError("expected QUERY and LIB (see --help)");
  require_in_range("aligned-top", aligned_top, 1, 1e6);
  screening::QueryScreenOptions settings = screen_options_from(vm);
  const std::filesystem::path query_path = inputs[0], library_path = inputs[1];
  const bool site_query = screening::is_site_query(settings);
  if (site_query && (harmonic::io::is_hsi_file(query_path) || !io::is_molecule_file(query_path))) {
    throw OptionError(query_path.string() +
                      ": a site query needs a molecule file (the structure), not a .hsi or mesh");
  }
  matching::MatchInput query_input;
  query_input.path = query_path;
  query_input = screening::screen_query_input(std::move(query_input), settings);
  const matching::MatchInputOptions query_options = screening::screen_query_options(settings);
  matching::check_match_input(query_input, query_options, "QUERY");
  check_command_files(
      {{{"QUERY", query_path}, {"LIB", library_path}},
       {{"--output", output, {".csv"}, ""},
        site_query
            ? OutputFile{"--aligned-out", aligned_out, {".pdb"}, "site hits are written as PDB"}
            : OutputFile{"--aligned-out", aligned_out, {".sdf"}, "hits are written with bonds"}}});
  const auto limit = limit_threads(settings.query.threads);
  const bool under_mpi = launched_by_mpi();  // before the work: it loads the MPI module
  screening::ScreenOptions& options = settings.screen;
  if (console::progress_shown()) {
    auto first = std::make_shared<console::ProgressLine>("stage 1 (fast scores)", "entries");
    auto second = std::make_shared<console::ProgressLine>("stage 2 (refinements)", "conformers");
    auto third = std::make_shared<console::ProgressLine>("stage 3 (full matches)", "candidates");
    options.progress = [first, second, third](int stage, std::int64_t done, std::int64_t total) {
      (stage == 1 ? *first : stage == 2 ? *second : *third)(done, total);
    };
  }

  const Stopwatch clock;
  const screening::Library library(library_path);
  screening::check_library_kind(library, site_query);  // before the query's surface is built
  console::step(library_path.string() + ": " + std::to_string(library.size()) +
                " entries, format version " + std::to_string(library.version()));
  matching::PreparedInput prepared = matching::prepare_input(query_input, query_options);
  if (!site_query && prepared.molecule) {
    const std::string warning =
        screening::macromolecule_query_warning(*prepared.molecule, query_path.string());
    if (!warning.empty()) {
      std::fprintf(stderr,
                   "surfcomp screen: warning: %s; to screen its binding site, give "
                   "--site-ligand RES or --site-sphere x,y,z,r\n",
                   warning.c_str());
    }
  }
  const screening::ScreenQuery query =
      screening::make_screen_query(std::move(prepared.descriptors), options, prepared.site,
                                   prepared.molecule ? &*prepared.molecule : nullptr);
  const double query_s = clock.elapsed_s();

  screening::ScreenResult result;
  int ranks = 1;
  if (under_mpi) {
    DistributedScreen distributed = screen_distributed(query, library, options);
    if (!distributed.root) return 0;
    result = std::move(distributed.result);
    ranks = distributed.ranks;
  } else {
    result = screening::screen(query, library, options);
  }
  const std::vector<screening::Hit>& hits = result.hits;
  const double total_s = clock.elapsed_s();
  const auto count = static_cast<std::size_t>(aligned_top);
  if (!aligned_out.empty()) {
    io::write_file_atomically(aligned_out, [&](std::ostream& out) {
      if (site_query) {
        screening::write_aligned_sites_pdb(out, library, hits, count, options.read);
      } else {
        screening::write_aligned_hits_sdf(out, library, hits, count);
      }
    });
  }
  try {
    io::write_file_atomically(
        output, [&](std::ostream& out) { screening::write_hits_csv(out, library, hits); });
  } catch (...) {
    if (!aligned_out.empty()) std::filesystem::remove(aligned_out);
    throw;
  }
  console::summary(
      "%s vs %s: %zu entries, %zu hits; query %.2f s, stage 1 %.2f s (%.0f entries/s), stage 2 "
      "%.2f s (refinements), stage 3 %.2f s (%zu candidates), total %.2f s (%d process%s)\n",
      query_path.string().c_str(), library_path.string().c_str(), library.size(), hits.size(),
      query_s, result.stage1_seconds,
      result.stage1_seconds > 0 ? static_cast<double>(library.size()) / result.stage1_seconds : 0.0,
      result.stage2_seconds, result.stage3_seconds, std::min(options.candidates, hits.size()),
      total_s, ranks, ranks == 1 ? "" : "es");
  return 0;
}

}  // namespace surfcomp::tools
