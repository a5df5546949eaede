// surfcomp screen --receptor: a library's molecules ranked by how well they fit a receptor's
// site (screening/receptor_screen.hpp), as a CSV table.
#include "screen_receptor.hpp"

#include "command.hpp"
#include "console.hpp"
#include "options.hpp"
#include "surface_input.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/screening/receptor_screen.hpp"

#include <algorithm>
#include <memory>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp screen --receptor RECEPTOR LIB.sclib -o hits.csv [--site-ligand RES |\n"
    "                       --site-sphere x,y,z,r | --site-pocket N] [--candidates K] [options]\n\n"
    "Ranks the molecules of a library (surfcomp library build) by how well they fit\n"
    "RECEPTOR's pocket, as `surfcomp dock` places a ligand (docs/method.md section 15), in two\n"
    "stages: every conformer gets a fast dock, a short Monte Carlo search of the site\n"
    "(--fast-chains chains of --fast-steps moves, each a local optimisation of the\n"
    "complementarity score) with the surface sample the library stores, and a molecule counts\n"
    "by its best conformer; the --candidates best molecules' best conformers then get the full\n"
    "dock (surfaces built, the complementary match and the full search), and rank by its best\n"
    "pose above every other molecule. The pocket is given as to `dock`; none: pocket 1. A pose\n"
    "that sinks the ligand deeper than twice --clash-tolerance into the receptor ranks after\n"
    "every one that does not. hits.csv has one row per molecule, best first, with the columns\n"
    "rank,entry,name,source,record,conformer,score,stage,contact,clash,esp,lp,deepest,\n"
    "fast_score and t00..t33 (the transform moving the entry into RECEPTOR's frame). The rows\n"
    "do not depend on --threads.\n\n"
    "RECEPTOR  a protein structure (.pdb .ent .cif .cif.gz .pqr)\n"
    "LIB       a library of molecules (.sclib, or a sharded library's index)";

}  // namespace

bool asks_receptor_screen(const std::vector<std::string>& args) {
  return std::any_of(args.begin(), args.end(), [](const std::string& a) {
    return a == "--receptor" || a.rfind("--receptor=", 0) == 0;
  });
}

int screen_receptor(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, receptor_path;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("receptor", po::value(&receptor_path)->required(), "the receptor's structure")
      ("output,o", po::value(&output)->required(), "the hits table (.csv)");
  // clang-format on
  add_table_options(described, screening::receptor_screen_option_table());
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, kUsage, vm)) return 0;
  const auto inputs =
      vm.count("input") ? vm["input"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (inputs.size() != 1) throw OptionError("expected --receptor RECEPTOR and LIB (see --help)");
  screening::ReceptorScreenOptions options;
  apply_table_options(screening::receptor_screen_option_table(), vm, options);
  screening::validate(options);
  show_surface_progress(options.dock.inputs.input.surface);
  matching::MatchInput receptor;
  receptor.path = receptor_path;
  io::check_command_files(
      {{{"RECEPTOR", receptor_path}, {"LIB", inputs[0]}}, {{"--output", output, {".csv"}, ""}}});
  const screening::Library library(inputs[0]);
  const ThreadLimit limit(options.dock.inputs.threads);
  if (console::progress_shown()) {
    auto first = std::make_shared<console::ProgressLine>("stage 1 (fast docks)", "entries");
    auto second = std::make_shared<console::ProgressLine>("stage 2 (full docks)", "candidates");
    options.progress = [first, second](int stage, std::int64_t done, std::int64_t total) {
      (stage == 2 ? *second : *first)(done, total);
    };
  }
  const screening::ReceptorScreenResult screened =
      screening::receptor_screen(receptor, library, options);
  for (const std::string& note : screened.notes) console::note(note);
  double total_ms = 0.0;
  for (const auto& [step, ms] : screened.timing_ms) total_ms += ms;
  console::summary("%s against %s's site: %zu molecules ranked, %.0f ms\n", inputs[0].c_str(),
                   receptor_path.c_str(), screened.hits.size(), total_ms);
  io::write_file_atomically(output, [&](std::ostream& out) {
    screening::write_receptor_hits_csv(out, library, screened.hits);
  });
  return 0;
}

}  // namespace surfcomp::tools
