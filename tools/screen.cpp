// surfcomp screen: one query against a screening library (.sclib), best molecules first, as a
// CSV table; optionally the best hits moved onto the query (SDF).
#include "command.hpp"
#include "console.hpp"
#include "describe_settings.hpp"
#include "options.hpp"
#include "screen_mpi.hpp"
#include "screen_receptor.hpp"
#include "screen_settings.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/matching/site.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/molsurf/load_surface.hpp"
#include "surfcomp/screening/hit_files.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/screen.hpp"
#include "surfcomp/screening/shape_screen.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <memory>
#include <sstream>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp screen QUERY... LIB.sclib -o hits.csv [--top N] [--refine C] [--candidates "
    "K]\n"
    "                       [--fusion max|mean] [--aligned-out hits.sdf] [--threads T]\n"
    "       surfcomp screen STRUCTURE.pdb POCKETS.sclib --site-ligand RES | --site-sphere x,y,z,r\n"
    "                       | --site-pocket N -o hits.csv [--aligned-out hits.pdb] ...\n"
    "       mpirun -np R surfcomp screen ...   (the library split over R processes)\n"
    "       surfcomp screen SCAN.ply MESHES.sclib -o hits.csv [--top N] [--scale auto|none]\n"
    "                       [--unit L] [--repair] [--threads T]\n"
    "       surfcomp screen --receptor RECEPTOR.pdb LIB.sclib -o hits.csv [--site-ligand RES]\n"
    "                       ...   (ranked by fit into its pocket: --receptor R --help)\n\n"
    "Ranks the molecules of a library (surfcomp library build) by how well their surfaces\n"
    "overlay QUERY's, in three stages: every conformer gets a fast score (the overlay score of\n"
    "its stored surface sample at the four principal-axes superpositions onto the query, no\n"
    "refinement); the --refine best conformers of each molecule then get that overlay refined\n"
    "from each superposition, and a molecule counts by its best conformer; the --candidates\n"
    "best molecules' best conformers last get the full match of `surfcomp match` (cliques,\n"
    "refinement), their surfaces rebuilt. The library is read in sequence, once for all the\n"
    "queries, and only each query's best molecules are kept: memory does not grow with the\n"
    "library's size. hits.csv has one row per molecule, best first: the candidates by their\n"
    "full-match score (stage 3), then the others by their refined score (stage 2; stage 1,\n"
    "the fast score, with --refine 0), both by the value --chemistry ranks by; the columns\n"
    "rank,entry,name,source,record,conformer,score,stage,shape,chem,atoms,fast_score and\n"
    "t00..t33, the transform moving the hit into QUERY's frame (row-major). The rows do not\n"
    "depend on --threads or on the number of MPI processes. The score weighs ESP, LP and\n"
    "heteroatoms beside shape, and ranks the hits of a query that carries an ionic group\n"
    "(--chemistry auto); the hits of a query without one are found and posed with chemistry\n"
    "all the same, but ranked by the mean of that score and the shape Tanimoto of their pose\n"
    "(the score column).\n\n"
    "QUERY  a molecule (.sdf .mol .mol2 .pdb) or a .hsi file built from one; with\n"
    "       --site-ligand, --site-sphere or --site-pocket (a pocket `surfcomp pockets` finds), a\n"
    "       binding site on a structure (PDB or mmCIF), screened against a pocket library\n"
    "       (library build --sites or --pockets): the overlays then compare pocket linings\n"
    "       as `match` does for sites (all 24 axes orders in stages 1 and 2), and --aligned-out\n"
    "       writes the hits' site neighbourhoods (the atoms each entry keeps) moved onto QUERY\n"
    "       (.pdb, one MODEL per hit).\n"
    "       Several QUERY files, or a file of several molecules (without --record, which picks\n"
    "       one), are several queries screened in one pass: each query's rows go to\n"
    "       hits.queryK.csv (K = 1, 2, ... in the order given; the same rows as a screen of that\n"
    "       query alone, all with chemistry when one query carries an ionic group) and\n"
    "       hits.csv ranks the molecules by their fused score (--top rows),\n"
    "       --fusion max (the best of its scores against the queries) or mean, with the columns\n"
    "       rank,entry,name,source,record,conformer,score,query (the best query) and\n"
    "       score_1..score_K. Every query is read and described before the library is: a\n"
    "       query record that cannot be read stops the command, naming it, before any\n"
    "       screening work and without output. --aligned-out takes one query.\n\n"
    "A mesh QUERY (a partial scan, say) is screened by shape against a library of meshes\n"
    "(library build MESH...): each entry is matched with it as `surfcomp match ENTRY QUERY`\n"
    "would (each pair in the larger mesh's unit under --scale auto, or in --unit L), and the\n"
    "entries are ranked by the fraction of QUERY's area that lies within one unit of QUERY's\n"
    "own (1/12 of its RMS radius, or --unit) of the entry, under the best of the pair's three\n"
    "best distinct poses. hits.csv has the columns\n"
    "rank,entry,name,source,score (that fraction),entry_coverage (the entry's fraction within\n"
    "it of QUERY),overlay (the pose's shape Tanimoto),unit (the pair's),t00..t33 (the\n"
    "transform moving the entry into QUERY's frame),note (why a pair was not matched: an entry\n"
    "narrower than QUERY cannot hold it as a part, or the match failed).";

/// One query of a screen: a file, and its record in a multi-molecule file (0: its only one).
struct QuerySpec {
  std::filesystem::path path;
  std::size_t record = 0;
  std::string label() const {
    return path.string() + (record > 0 ? " record " + std::to_string(record) : "");
  }
};

/// The queries the QUERY files stand for: each file once with --record, else every record of a
/// multi-molecule file (SDF, MOL2) and each other file once.
std::vector<QuerySpec> query_specs(const std::vector<std::string>& files, std::size_t record) {
  if (record > 0 && files.size() > 1)
    throw OptionError("--record picks a record of one QUERY file; several QUERY files were given");
  std::vector<QuerySpec> specs;
  for (const std::string& file : files) {
    const std::filesystem::path path = file;
    std::size_t records = 1;
    if (record == 0 && io::is_record_file(path) && !harmonic::io::is_hsi_file(path) &&
        std::filesystem::is_regular_file(path))
      records = io::read_molecule_records(path).size();
    if (records <= 1) {
      specs.push_back({path, record});
    } else {
      for (std::size_t r = 1; r <= records; ++r) specs.push_back({path, r});
    }
  }
  return specs;
}

/// Throws OptionError for an option given on the command line that a shape screen does not
/// read: every option of molecule and site screens but --top and --threads, and --aligned-out.
void refuse_molecule_options(const boost::program_options::variables_map& vm,
                             const std::filesystem::path& query) {
  std::vector<std::string> names{"aligned-out", "aligned-top"};
  for (const auto& option : screening::screen_option_table()) {
    if (option.spec.name != "top" && option.spec.name != "threads")
      names.push_back(option.spec.name);
  }
  for (const std::string& name : names) {
    if (vm.count(name) && !vm[name].defaulted()) {
      throw OptionError("--" + name + " applies to molecule and site queries, not to " +
                        query.string() + " (a mesh, screened by shape against meshes)");
    }
  }
}

/// `surfcomp screen SCAN LIB`: a mesh query screened by shape against a library of meshes.
int screen_mesh(const std::filesystem::path& query_path, const screening::Library& library,
                const std::filesystem::path& output,
                const boost::program_options::variables_map& vm,
                const screening::QueryScreenOptions& settings) {
  refuse_molecule_options(vm, query_path);
  if (launched_by_mpi())
    throw OptionError("a mesh query is screened in one process (--threads T), not under mpirun");
  const ThreadLimit limit(settings.query.threads);
  screening::ShapeScreenOptions options;
  options.inputs = settings.query;
  options.top = static_cast<std::size_t>(settings.screen.top);
  if (console::progress_shown()) {
    auto line = std::make_shared<console::ProgressLine>("shape screen (matches)", "entries");
    options.progress = [line](std::int64_t done, std::int64_t total) { (*line)(done, total); };
  }
  const Stopwatch clock;
  molsurf::check_surface_input(query_path, settings.query.input);
  console::step(library.path().string() + ": " + std::to_string(library.size()) + " meshes");
  molsurf::LoadedSurface query = molsurf::read_mesh_input(query_path, settings.query.input);
  for (const std::string& note : query.notes) console::note(note);
  const std::vector<screening::ShapeHit> hits =
      screening::screen_shapes(query.surface, library, options);
  io::write_file_atomically(
      output, [&](std::ostream& out) { screening::write_shape_hits_csv(out, library, hits); });
  const auto unmatched = std::count_if(
      hits.begin(), hits.end(), [](const screening::ShapeHit& hit) { return !hit.note.empty(); });
  const std::string not_matched =
      unmatched ? ", " + std::to_string(unmatched) + " not matched (see the note column)" : "";
  const std::string top = hits.empty() ? "-" : library.info(hits.front().entry).name;
  console::summary("%s vs %s: %zu meshes, %zu rows%s; top %s (%.3f of the query on it); %.2f s\n",
                   query_path.string().c_str(), library.path().string().c_str(), library.size(),
                   hits.size(), not_matched.c_str(), top.c_str(),
                   hits.empty() ? 0.0 : hits.front().score, clock.elapsed_s());
  return 0;
}

/// `output` with ".queryK" before its extension: the table of query K (1-based).
std::filesystem::path query_table(const std::filesystem::path& output, std::size_t k) {
  std::filesystem::path table = output;
  table.replace_filename(output.stem().string() + ".query" + std::to_string(k) +
                         output.extension().string());
  return table;
}

/// Each query read and described (prepare_input) as a screen query, their chemistry agreed on;
/// an error names the query when there are several. Warns when a whole structure is screened
/// without a site.
std::vector<screening::ScreenQuery> describe_queries(const std::vector<QuerySpec>& specs,
                                                     const screening::QueryScreenOptions& settings,
                                                     bool site_query) {
  std::vector<screening::ScreenQuery> queries;
  for (const QuerySpec& spec : specs) {
    matching::MatchInput query_input;
    query_input.path = spec.path;
    query_input = screening::screen_query_input(std::move(query_input), settings);
    matching::MatchInputOptions query_options = screening::screen_query_options(settings);
    query_options.input.read.record = spec.record;
    try {
      matching::check_match_input(query_input, query_options, "QUERY");
      matching::PreparedInput prepared = matching::prepare_input(query_input, query_options);
      if (!site_query && prepared.molecule) {
        const std::string warning =
            screening::macromolecule_query_warning(*prepared.molecule, spec.label());
        if (!warning.empty()) {
          std::fprintf(stderr,
                       "surfcomp screen: warning: %s; to screen its binding site, give "
                       "--site-ligand RES, --site-sphere x,y,z,r or --site-pocket N\n",
                       warning.c_str());
        }
      }
      queries.push_back(screening::make_screen_query(
          std::move(prepared.descriptors), settings.screen, prepared.site,
          prepared.molecule ? &*prepared.molecule : nullptr));
    } catch (const Error& e) {
      if (specs.size() == 1) throw;
      throw InputError("query " + std::to_string(queries.size() + 1) + " (" + spec.label() +
                       "): " + e.what());
    }
  }
  screening::agree_on_chemistry(queries);
  return queries;
}

/// Where a screen's rows go: the table (the fused ranking with several queries, each query's
/// own beside it), and the first aligned_top hits moved onto the one query.
struct ScreenFiles {
  std::filesystem::path output, aligned_out;
  std::size_t aligned_top = 10;
};

/// Writes the screen's files, each whole or not at all: an error removes those written.
void write_screen_files(const screening::MultiScreenResult& result,
                        const screening::Library& library, const ScreenFiles& files,
                        bool site_query, const io::MoleculeReadOptions& read) {
  const bool several = result.hits.size() > 1;
  std::vector<std::filesystem::path> written;
  try {
    if (!files.aligned_out.empty()) {
      const std::vector<screening::Hit>& hits = result.hits.front();
      io::write_file_atomically(files.aligned_out, [&](std::ostream& out) {
        if (site_query) {
          screening::write_aligned_sites_pdb(out, library, hits, files.aligned_top, read);
        } else {
          screening::write_aligned_hits_sdf(out, library, hits, files.aligned_top);
        }
      });
      written.emplace_back(files.aligned_out);
    }
    for (std::size_t q = 0; several && q < result.hits.size(); ++q) {
      io::write_file_atomically(query_table(files.output, q + 1), [&](std::ostream& out) {
        screening::write_hits_csv(out, library, result.hits[q]);
      });
      written.push_back(query_table(files.output, q + 1));
    }
    io::write_file_atomically(files.output, [&](std::ostream& out) {
      if (several) {
        screening::write_fused_csv(out, library, result.fused);
      } else {
        screening::write_hits_csv(out, library, result.hits.front());
      }
    });
  } catch (...) {
    for (const std::filesystem::path& path : written) std::filesystem::remove(path);
    throw;
  }
}

}  // namespace

int screen(const std::vector<std::string>& args) {
  if (asks_receptor_screen(args)) return screen_receptor(args);
  namespace po = boost::program_options;
  std::string output, aligned_out;
  double aligned_top = 10;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(),
       "output table (.csv); with several queries their fused ranking")
      ("aligned-out", po::value(&aligned_out),
       "write the first --aligned-top hits moved onto QUERY (.sdf, bonds kept; one query)")
      ("aligned-top", defaulted(&aligned_top),
       "hits written to --aligned-out");
  // clang-format on
  add_screen_options(described);
  po::variables_map vm;
  if (!parse_command_line(args, described, -1, kUsage, vm)) return 0;
  const auto inputs =
      vm.count("input") ? vm["input"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (inputs.size() < 2) throw OptionError("expected QUERY... and LIB (see --help)");
  require_in_range("aligned-top", aligned_top, 1, 1e6);
  screening::QueryScreenOptions settings = screen_options_from(vm);
  const std::filesystem::path library_path = inputs.back();
  const bool site_query = screening::is_site_query(settings);
  const std::vector<std::string> query_files(inputs.begin(), inputs.end() - 1);
  // A library of meshes is screened by shape, with one mesh; any other library as before (a
  // mesh with ESP and LP is a molecule's surface).
  const screening::Library library(library_path);
  if (screening::is_mesh_library(library)) {
    if (query_files.size() > 1 || !mesh::io::is_mesh_file(query_files.front())) {
      throw InputError(library_path.string() +
                       ": a library of meshes: its query is one mesh, screened by shape");
    }
    io::CommandFiles files;
    files.inputs.push_back({"QUERY", query_files.front()});
    files.outputs.push_back({"--output", output, {".csv"}, ""});
    io::check_command_files(files);
    return screen_mesh(query_files.front(), library, output, vm, settings);
  }
  for (const std::string& file : query_files) {
    if (site_query && (harmonic::io::is_hsi_file(file) || !io::is_molecule_file(file))) {
      throw OptionError(file +
                        ": a site query needs a molecule file (the structure), not a .hsi or mesh");
    }
  }
  io::CommandFiles files;
  for (const std::string& file : query_files) files.inputs.push_back({"QUERY", file});
  files.inputs.push_back({"LIB", library_path});
  files.outputs.push_back({"--output", output, {".csv"}, ""});
  files.outputs.push_back(
      site_query
          ? io::OutputFile{"--aligned-out", aligned_out, {".pdb"}, "site hits are written as PDB"}
          : io::OutputFile{"--aligned-out", aligned_out, {".sdf"}, "hits are written with bonds"});
  io::check_command_files(files);
  const std::vector<QuerySpec> specs = query_specs(query_files, settings.query.input.read.record);
  const bool several = specs.size() > 1;
  if (several && !aligned_out.empty())
    throw OptionError("--aligned-out writes the hits of one query; " +
                      std::to_string(specs.size()) + " queries were given");
  io::CommandFiles tables;
  for (std::size_t q = 0; several && q < specs.size(); ++q)
    tables.outputs.push_back({"a query's table", query_table(output, q + 1), {".csv"}, ""});
  io::check_command_files(tables);
  const ThreadLimit limit(settings.query.threads);
  const bool under_mpi = launched_by_mpi();  // before the work: it loads the MPI module
  screening::ScreenOptions& options = settings.screen;
  if (console::progress_shown()) {
    auto first = std::make_shared<console::ProgressLine>("stages 1-2 (scores)", "entries");
    auto third = std::make_shared<console::ProgressLine>("stage 3 (full matches)", "candidates");
    options.progress = [first, third](int stage, std::int64_t done, std::int64_t total) {
      (stage == 3 ? *third : *first)(done, total);
    };
  }

  const Stopwatch clock;
  screening::check_library_kind(library, site_query);  // before the query's surface is built
  console::step(library_path.string() + ": " + std::to_string(library.size()) +
                " entries, format version " + std::to_string(library.version()));
  // Every query is read and described before the library is: a query that cannot be stops the
  // command before any screening work.
  const std::vector<screening::ScreenQuery> queries = describe_queries(specs, settings, site_query);
  std::vector<const screening::ScreenQuery*> query_list(queries.size());
  for (std::size_t q = 0; q < queries.size(); ++q) query_list[q] = &queries[q];
  const double query_s = clock.elapsed_s();

  screening::MultiScreenResult result;
  int ranks = 1;
  if (under_mpi) {
    DistributedScreen distributed = screen_distributed(query_list, library, options);
    if (!distributed.root) return 0;
    result = std::move(distributed.result);
    ranks = distributed.ranks;
  } else {
    result = screening::screen_queries(query_list, library, options);
  }
  const double total_s = clock.elapsed_s();
  write_screen_files(result, library, {output, aligned_out, static_cast<std::size_t>(aligned_top)},
                     site_query, options.read);
  if (!queries.empty() && queries.front().shape_weight > 0.0) {
    console::summary(
        "%s: hits ranked by %s of their pose (%s; --chemistry on ranks by the score with ESP, "
        "LP and heteroatoms)\n",
        several ? "the queries" : specs.front().label().c_str(),
        queries.front().shape_weight == 1.0
            ? "the shape Tanimoto"
            : "the mean of the overlay score and the shape Tanimoto",
        options.chemistry == screening::QueryChemistry::off
            ? "--chemistry off"
            : (several ? "none carries an ionic group" : "no ionic group"));
  }
  const std::size_t rows = several ? result.fused.size() : result.hits.front().size();
  console::summary(
      "%s vs %s: %zu entries, %zu quer%s, %zu rows; queries %.2f s, stages 1-2 %.2f s (stage 1 "
      "%.0f entries/s), stage 3 %.2f s, total %.2f s (%d process%s)\n",
      several ? (std::to_string(specs.size()) + " queries").c_str() : specs.front().label().c_str(),
      library_path.string().c_str(), library.size(), specs.size(), several ? "ies" : "y", rows,
      query_s, result.stage1_seconds + result.stage2_seconds,
      result.stage1_seconds > 0
          ? static_cast<double>(library.size() * specs.size()) / result.stage1_seconds
          : 0.0,
      result.stage3_seconds, total_s, ranks, ranks == 1 ? "" : "es");
  return 0;
}

}  // namespace surfcomp::tools
