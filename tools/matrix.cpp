// surfcomp matrix: every molecule of a set described once and compared with every other (or
// with a second set), as a CSV similarity matrix.
#include "command.hpp"
#include "console.hpp"
#include "options.hpp"
#include "screen_mpi.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/thread_limit.hpp"
#include "surfcomp/screening/matrix.hpp"

#include <cstdio>
#include <memory>
#include <string>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp matrix SET... [--against SET...] -o similarity.csv [options]\n\n"
    "Reads and describes every molecule of the SET files once (each record of an SDF or MOL2\n"
    "file; a PDB, mmCIF or PQR file is one molecule), then compares every pair coarse to fine,\n"
    "as a screen ranks: each pair's overlay at the principal-axes superpositions, each\n"
    "molecule's --refined-overlays best neighbours' overlays refined, then its --full-matches\n"
    "best aligned as `surfcomp match` aligns two molecules (--exact: every pair). Writes the\n"
    "overlay scores (0-1) as a matrix: all against all, symmetric, its diagonal each molecule's\n"
    "self-overlay; or with --against, SET's molecules (rows) against those of the --against\n"
    "files (columns). With --neighbours K, writes each molecule's K best neighbours instead, a\n"
    "line each (row, name, rank, column, neighbour, score, stage): memory then grows with the\n"
    "molecules, not the pairs, for sets whose matrix would not fit. A record that cannot be\n"
    "read or described is left out, with a note naming it; a pair whose full match fails (a\n"
    "limit such as --max-graph-nodes) scores nan, with a warning naming it. Under mpirun, the\n"
    "pairs are split over the processes (each describes every molecule) and rank 0 writes the\n"
    "same file.";

}  // namespace

int matrix(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output;
  std::vector<std::string> against;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output), "write the matrix as CSV (.csv): a row per molecule")
      ("against", po::value(&against)->multitoken(),
       "compare SET's molecules with these files' (rows x columns) instead of all against all");
  // clang-format on
  add_table_options(described, screening::matrix_option_table());
  po::variables_map vm;
  if (!parse_command_line(args, described, -1, kUsage, vm)) return 0;
  const auto inputs =
      vm.count("input") ? vm["input"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (inputs.empty()) throw OptionError("expected one or more SET files (see --help)");
  if (output.empty()) throw OptionError("expected --output FILE.csv (see --help)");
  screening::MatrixOptions options;
  apply_table_options(screening::matrix_option_table(), vm, options);
  std::vector<io::InputFile> files;
  files.reserve(inputs.size() + against.size());
  for (const std::string& input : inputs) files.push_back({"SET", input});
  for (const std::string& input : against) files.push_back({"--against", input});
  io::check_command_files({files, {{"--output", output, {".csv"}, ""}}});
  if (console::progress_shown()) {
    auto line = std::make_shared<console::ProgressLine>("matrix", "pairs");
    options.progress = [line](std::size_t done, std::size_t total) {
      (*line)(static_cast<std::int64_t>(done), static_cast<std::int64_t>(total));
    };
  }

  const ThreadLimit limit(options.inputs.threads);
  const bool under_mpi = launched_by_mpi();  // before the work: it loads the MPI module
  const std::vector<std::filesystem::path> set(inputs.begin(), inputs.end());
  const std::vector<std::filesystem::path> others(against.begin(), against.end());
  screening::SimilarityMatrix matrix;
  int ranks = 1;
  if (under_mpi) {
    DistributedMatrix distributed = matrix_distributed(set, others, options);
    if (!distributed.root) return 0;
    matrix = std::move(distributed.matrix);
    ranks = distributed.ranks;
  } else {
    matrix = screening::similarity_matrix(set, others, options);
  }
  for (const std::string& line : matrix.left_out) console::note("left out: " + line);
  for (const std::string& line : matrix.warnings)
    std::fprintf(stderr, "surfcomp matrix: warning: %s\n", line.c_str());
  console::summary(
      "%zu x %zu molecules (%zu left out): described in %.0f ms, matched in %.0f ms%s\n",
      matrix.rows.size(), matrix.columns.size(), matrix.left_out.size(), matrix.describe_ms,
      matrix.match_ms, ranks > 1 ? (" over " + std::to_string(ranks) + " processes").c_str() : "");
  io::write_file_atomically(output, [&](std::ostream& out) {
    if (options.neighbours > 0) {
      screening::write_neighbours_csv(out, matrix);
    } else {
      screening::write_matrix_csv(out, matrix);
    }
  });
  return 0;
}

}  // namespace surfcomp::tools
