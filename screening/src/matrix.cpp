#include "surfcomp/screening/matrix.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/matching/match.hpp"
#include "surfcomp/matching/rigid_fit.hpp"
#include "surfcomp/screening/screen.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <mutex>
#include <new>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

namespace surfcomp::screening {
namespace {

/// A set's records, before any is read: each file's records in order, each file checked as
/// `match` checks its inputs (its extension, the options that apply to it); a file without a
/// record is noted in `left_out`.
std::vector<io::MoleculeRecord> set_records(const std::vector<std::filesystem::path>& files,
                                            const MatrixOptions& options,
                                            std::vector<std::string>& left_out) {
  std::vector<io::MoleculeRecord> records;
  for (const std::filesystem::path& file : files) {
    if (!io::is_molecule_file(file)) {
      throw InputError(file.string() +
                       ": not a molecule file (a matrix compares molecules with coordinates: " +
                       io::molecule_extensions(io::MoleculeUse::molecule) + ")");
    }
    matching::MatchInput input;
    input.path = file;
    matching::check_match_input(input, options.inputs, "SET");
    std::vector<io::MoleculeRecord> read = io::read_molecule_records(file);
    if (read.empty()) left_out.push_back(file.string() + ": no molecule");
    records.insert(records.end(), std::make_move_iterator(read.begin()),
                   std::make_move_iterator(read.end()));
  }
  return records;
}

/// The files' names for a message: "a.sdf, b.sdf".
std::string names_of(const std::vector<std::filesystem::path>& files) {
  std::string out;
  for (const std::filesystem::path& file : files) out += (out.empty() ? "" : ", ") + file.string();
  return out;
}

/// A record as messages name it: "FILE record N (NAME)".
std::string record_name(const MatrixMember& member) {
  return member.source.string() + " record " + std::to_string(member.record) + " (" + member.name +
         ")";
}

struct Described {
  std::vector<MatrixMember> members;
  /// Each molecule's descriptors (the full match) and, unless exact, its packed samples (the
  /// refined overlay).
  std::vector<ScreenQuery> queries;
};

/// The screen's options of the refined overlays: the match's overlay options, every start refined.
ScreenOptions screen_options(const MatrixOptions& options) {
  ScreenOptions screen;
  screen.match = options.inputs.match;
  screen.refine_starts = 0;
  return screen;
}

/// Each record read and described once (in parallel), those that fail left out with a line.
Described describe_records(const std::vector<io::MoleculeRecord>& records,
                           const MatrixOptions& options, std::vector<std::string>& left_out) {
  std::vector<std::optional<ScreenQuery>> prepared(records.size());
  std::vector<std::string> why(records.size());
  matching::MatchInputOptions quiet = options.inputs;
  // Neither is told apart by molecule, and several molecules are described at once.
  quiet.log = nullptr;
  quiet.descriptors.progress = nullptr;
  const ScreenOptions screen = screen_options(options);
  tbb::parallel_for(std::size_t{0}, records.size(), [&](std::size_t k) {
    try {
      matching::MatchInput input;
      input.molecule = io::read_record_molecule(records[k], options.inputs.input.read);
      harmonic::SurfaceDescriptors described =
          std::move(matching::prepare_input(input, quiet).descriptors);
      if (options.exact) {  // the full matches alone: no sample to pack
        prepared[k].emplace();
        prepared[k]->descriptors = std::move(described);
      } else {
        prepared[k] = make_screen_query(std::move(described), screen);
      }
    } catch (const OptionError&) {
      throw;  // an option that cannot run, not a record that cannot be read
    } catch (const Error& error) {
      why[k] = error.what();
    } catch (const std::bad_alloc&) {
      why[k] = "out of memory";
    }
  });
  Described out;
  for (std::size_t k = 0; k < records.size(); ++k) {
    const io::MoleculeRecord& record = records[k];
    if (!prepared[k]) {
      left_out.push_back(record.source.string() + " record " + std::to_string(record.record) +
                         " (" + record.name + "): " + why[k]);
      continue;
    }
    out.members.push_back({record.name, record.source, record.record});
    out.queries.push_back(std::move(*prepared[k]));
  }
  return out;
}

/// The pairs (row, column) of each row's `count` best columns by `score` (a NaN last, ties to the
/// lower column), or of every column with `every`; all against all, a pair once, as (lower,
/// higher), and the diagonal only with `every` or `diagonal`. In order.
std::vector<std::pair<std::size_t, std::size_t>> best_pairs(const Eigen::MatrixXd& score,
                                                            bool symmetric, std::size_t count,
                                                            bool every, bool diagonal = false) {
  const auto n = static_cast<std::size_t>(score.rows()), m = static_cast<std::size_t>(score.cols());
  std::set<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::size_t> columns;
    for (std::size_t j = symmetric && every ? i : 0; j < m; ++j)
      if (!symmetric || j != i || every) columns.push_back(j);
    if (!every) {
      const auto value = [&](std::size_t j) {
        return score(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
      };
      const std::size_t k = std::min(count, columns.size());
      std::partial_sort(columns.begin(), columns.begin() + static_cast<std::ptrdiff_t>(k),
                        columns.end(), [&](std::size_t x, std::size_t y) {
                          if (std::isnan(value(x)) != std::isnan(value(y)))
                            return !std::isnan(value(x));
                          if (value(x) != value(y)) return value(x) > value(y);
                          return x < y;
                        });
      columns.resize(k);
      if (symmetric && diagonal) columns.push_back(i);
    }
    for (const std::size_t j : columns)
      pairs.emplace(symmetric ? std::min(i, j) : i, symmetric ? std::max(i, j) : j);
  }
  return {pairs.begin(), pairs.end()};
}

using Pair = std::pair<std::size_t, std::size_t>;

/// A cell of the matrix as a stage computes it; stage 0: no alignment found.
struct Cell {
  double score = 0.0;
  std::uint8_t stage = 0;
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
};

/// A cell as the processes exchange it: its score, its stage and, with `transforms`, the
/// transform's 16 numbers, row-major.
void put_cell(const Cell& cell, bool transforms, double* out) {
  out[0] = cell.score;
  out[1] = cell.stage;
  if (!transforms) return;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) out[2 + 4 * a + b] = cell.transform(a, b);
}

Cell get_cell(const double* in, bool transforms) {
  Cell cell{in[0], static_cast<std::uint8_t>(in[1]), Eigen::Matrix4d::Identity()};
  if (!transforms) return cell;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) cell.transform(a, b) = in[2 + 4 * a + b];
  return cell;
}

/// The pairs of every row of an n x m matrix that is process's (row mod processes), each row's
/// columns in order (all against all, from the diagonal on).
std::vector<Pair> row_share(std::size_t n, std::size_t m, bool symmetric, int process,
                            int processes) {
  std::vector<Pair> pairs;
  for (auto i = static_cast<std::size_t>(process); i < n; i += static_cast<std::size_t>(processes))
    for (std::size_t j = symmetric ? i : 0; j < m; ++j) pairs.emplace_back(i, j);
  return pairs;
}

/// The pairs of a list that are process's: the k-th to process k mod processes.
std::vector<Pair> share(const std::vector<Pair>& pairs, int process, int processes) {
  std::vector<Pair> mine;
  for (auto k = static_cast<std::size_t>(process); k < pairs.size();
       k += static_cast<std::size_t>(processes))
    mine.push_back(pairs[k]);
  return mine;
}

/// Process 0's pairs, on every process.
std::vector<Pair> broadcast_pairs(Exchange& exchange, const std::vector<Pair>& pairs) {
  std::vector<std::uint64_t> flat;
  flat.reserve(2 * pairs.size());
  for (const auto& [i, j] : pairs) {
    flat.push_back(i);
    flat.push_back(j);
  }
  flat = exchange.broadcast(std::move(flat));
  std::vector<Pair> out(flat.size() / 2);
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = {flat[2 * k], flat[2 * k + 1]};
  return out;
}

}  // namespace

const options::Table<MatrixOptions>& matrix_option_table() {
  using M = MatrixOptions;
  static const options::Table<M> table = [] {
    options::Table<M> t;
    options::append(t, molsurf::surface_input_option_table(),
                    [](auto& m) -> auto& { return m.inputs.input; },
                    {"record", "molecule", "repair", "scale", "unit"});
    options::append(
        t, harmonic::descriptor_option_table(),
        [](auto& m) -> auto& { return m.inputs.descriptors; },
        {"critical-point-radius", "disc-radius", "image-rings", "image-sectors", "weights"});
    options::append(t, matching::match_option_table(),
                    [](auto& m) -> auto& { return m.inputs.match; },
                    {"site-overlay-radius", "site-chem-weight", "site-lining-weight",
                     "site-principal-axes-starts"});
    t.push_back(options::field<M>(
        {"refined-overlays", options::Kind::integer,
         "each molecule's best neighbours, by the overlay at the principal-axes superpositions, "
         "whose overlay is refined (0: every pair's)",
         "", 0, 1e6},
        [](auto& m) -> auto& { return m.refined_overlays; }));
    t.push_back(options::field<M>(
        {"full-matches", options::Kind::integer,
         "each molecule's best neighbours, by the overlay after refinement, given the full "
         "match (0: none)",
         "", 0, 1e6},
        [](auto& m) -> auto& { return m.full_matches; }));
    t.push_back(options::field<M>(
        {"exact", options::Kind::flag,
         "give every pair the full match, not only each molecule's best by the refined overlay "
         "(slow: tens of ms a pair of ligands)"},
        [](auto& m) -> auto& { return m.exact; }));
    t.push_back(options::field<M>(
        {"max-pairs", options::Kind::integer,
         "refuse a matrix of more pairs than this, before any work", "", 1, 1e12},
        [](auto& m) -> auto& { return m.max_pairs; }));
    t.push_back(options::threads_option<M>([](auto& m) -> auto& { return m.inputs.threads; }));
    return t;
  }();
  return table;
}

SimilarityMatrix similarity_matrix(const std::vector<std::filesystem::path>& set,
                                   const std::vector<std::filesystem::path>& against,
                                   const MatrixOptions& options) {
  SingleProcess alone;
  return similarity_matrix(set, against, options, alone);
}

SimilarityMatrix similarity_matrix(const std::vector<std::filesystem::path>& set,
                                   const std::vector<std::filesystem::path>& against,
                                   const MatrixOptions& options, Exchange& exchange) {
  options::check_all(matrix_option_table(), options);
  matching::validate(options.inputs.match);
  SimilarityMatrix out;
  const std::vector<io::MoleculeRecord> row_records = set_records(set, options, out.left_out);
  const std::vector<io::MoleculeRecord> column_records =
      set_records(against, options, out.left_out);
  const bool symmetric = against.empty();
  if (row_records.empty()) throw InputError(names_of(set) + ": no molecule");
  if (!symmetric && column_records.empty()) throw InputError(names_of(against) + ": no molecule");
  if (symmetric && row_records.size() == 1) {
    throw InputError(row_records.front().source.string() +
                     ": a set of one molecule has no pair to compare");
  }
  const auto pairs_of = [&](std::size_t rows, std::size_t columns) {
    return symmetric ? static_cast<double>(rows) * static_cast<double>(rows + 1) / 2.0
                     : static_cast<double>(rows) * static_cast<double>(columns);
  };
  const double asked = pairs_of(row_records.size(), column_records.size());
  if (asked > static_cast<double>(options.max_pairs)) {
    char line[160];
    std::snprintf(line, sizeof line, "%.0f pairs (%zu x %zu molecules) is more than %s %lld", asked,
                  row_records.size(), symmetric ? row_records.size() : column_records.size(),
                  options::named("max_pairs").c_str(), static_cast<long long>(options.max_pairs));
    throw InputError(line);
  }

  out.symmetric = symmetric;
  Stopwatch clock;
  std::vector<std::string> row_failures, column_failures;
  Described rows = describe_records(row_records, options, row_failures);
  Described columns;
  if (!symmetric) columns = describe_records(column_records, options, column_failures);
  out.describe_ms = clock.elapsed_ms();
  const Described& cols = symmetric ? rows : columns;
  const auto too_few = [](const std::vector<std::filesystem::path>& files,
                          const std::vector<std::string>& failures) {
    return InputError(names_of(files) + ": too few molecules could be read and described (" +
                      std::to_string(failures.size()) +
                      " left out; the first: " + failures.front() + ")");
  };
  if (rows.queries.empty() || (symmetric && rows.queries.size() < 2))
    throw too_few(set, row_failures);
  if (cols.queries.empty()) throw too_few(against, column_failures);
  out.left_out.insert(out.left_out.end(), row_failures.begin(), row_failures.end());
  out.left_out.insert(out.left_out.end(), column_failures.begin(), column_failures.end());

  clock.restart();
  const std::size_t n = rows.queries.size(), m = cols.queries.size();
  const bool root = exchange.process() == 0;
  if (root) {
    out.score = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m));
    out.stage.setZero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m));
    if (options.transforms) out.transforms.assign(n * m, Eigen::Matrix4d::Identity());
  }
  // A cell and, all against all, its mirror: the same score and stage, the inverse transform.
  const auto set_cell = [&](std::size_t i, std::size_t j, const Cell& cell) {
    const auto r = static_cast<Eigen::Index>(i), c = static_cast<Eigen::Index>(j);
    out.score(r, c) = cell.score;
    out.stage(r, c) = cell.stage;
    if (symmetric) {
      out.score(c, r) = cell.score;
      out.stage(c, r) = cell.stage;
    }
    if (!options.transforms) return;
    out.transforms[i * m + j] = cell.transform;
    if (symmetric && i != j) {
      out.transforms[j * m + i] =
          matching::RigidTransform::from_matrix(cell.transform).inverse().matrix();
    }
  };
  // The pairs that failed (row, column, why), and how many pairs' clique searches were cut; few,
  // so kept apart from the matrix's cells.
  std::vector<std::tuple<std::size_t, std::size_t, std::string>> failed;
  std::size_t cuts = 0;
  // One stage over the processes: this process's pairs, `mine`, computed in parallel, then every
  // process's cells gathered and set on process 0 (`theirs(r)`: process r's pairs, in order).
  const auto run_stage = [&](std::uint8_t stage, const std::vector<Pair>& mine, const auto& compute,
                             const auto& theirs) {
    const std::size_t width = options.transforms ? 18 : 2;
    std::vector<double> local(mine.size() * width);
    std::vector<std::string> why(mine.size());
    std::atomic<std::size_t> cut{0}, done{0};
    std::mutex tell;
    tbb::parallel_for(std::size_t{0}, mine.size(), [&](std::size_t k) {
      Cell cell;
      try {
        cell = compute(mine[k].first, mine[k].second, cut);
      } catch (const Error& error) {
        cell = {std::numeric_limits<double>::quiet_NaN(), stage, Eigen::Matrix4d::Identity()};
        why[k] = error.what();
      }
      put_cell(cell, options.transforms, local.data() + k * width);
      if (!options.progress) return;
      const std::lock_guard<std::mutex> lock(tell);
      options.progress(++done, mine.size());
    });
    // After the cells: the cut count, the failures, then each failure's pair and text.
    std::vector<double> notes{static_cast<double>(cut.load()), 0.0};
    for (std::size_t k = 0; k < why.size(); ++k) {
      if (why[k].empty()) continue;
      notes[1] += 1.0;
      notes.push_back(static_cast<double>(k));
      notes.push_back(static_cast<double>(why[k].size()));
      for (const char c : why[k]) notes.push_back(static_cast<unsigned char>(c));
    }
    const std::vector<double> cells = exchange.gather(local);
    const std::vector<double> said = exchange.gather(notes);
    if (!root) return;
    std::size_t at = 0, note = 0;
    for (int process = 0; process < exchange.processes(); ++process) {
      const std::vector<Pair> pairs = theirs(process);
      for (const auto& [i, j] : pairs) {
        const Cell cell = get_cell(cells.data() + at, options.transforms);
        if (cell.stage != 0) set_cell(i, j, cell);  // 0: no alignment, the cell stays
        at += width;
      }
      cuts += static_cast<std::size_t>(said[note++]);
      const auto failures = static_cast<std::size_t>(said[note++]);
      for (std::size_t f = 0; f < failures; ++f) {
        const auto k = static_cast<std::size_t>(said[note++]);
        const auto length = static_cast<std::size_t>(said[note++]);
        std::string text;
        for (std::size_t c = 0; c < length; ++c)
          text += static_cast<char>(static_cast<unsigned char>(said[note++]));
        failed.emplace_back(pairs[k].first, pairs[k].second, std::move(text));
      }
    }
  };
  // A stage of pairs process 0 chose: the list told to every process, each taking its share.
  const auto run_chosen = [&](std::uint8_t stage, const std::function<std::vector<Pair>()>& choose,
                              const auto& compute) {
    const std::vector<Pair> pairs =
        broadcast_pairs(exchange, root ? choose() : std::vector<Pair>{});
    run_stage(stage, share(pairs, exchange.process(), exchange.processes()), compute,
              [&](int process) { return share(pairs, process, exchange.processes()); });
    return pairs.size();
  };

  const ScreenOptions screen = screen_options(options);
  const auto sample = [&](std::size_t j) { return cols.queries[j].packed->sample().view(); };
  const auto fast = [&](std::size_t i, std::size_t j, std::atomic<std::size_t>&) {
    const HitScore hit = fast_score(rows.queries[i], sample(j), screen);
    return Cell{hit.score, 1, hit.transform};
  };
  const auto refined = [&](std::size_t i, std::size_t j, std::atomic<std::size_t>&) {
    const HitScore hit = refined_score(rows.queries[i], sample(j), screen);
    return Cell{hit.score, 2, hit.transform};
  };
  if (!options.exact) {
    // Every pair, a row at a time to each process: stage 1, or stage 2 when every pair gets it.
    const auto rows_of = [&](int process) {
      return row_share(n, m, symmetric, process, exchange.processes());
    };
    const std::vector<Pair> mine = rows_of(exchange.process());
    if (options.refined_overlays == 0) {
      run_stage(2, mine, refined, rows_of);
    } else {
      run_stage(1, mine, fast, rows_of);
      run_chosen(
          2,
          [&] { return best_pairs(out.score, symmetric, options.refined_overlays, false, true); },
          refined);
    }
  }
  // The matrix keeps the top score alone: no alignment's coverage is measured.
  matching::MatchOptions full_match = options.inputs.match;
  full_match.coverage_distance = 0.0;
  const std::size_t full_matches = run_chosen(
      3, [&] { return best_pairs(out.score, symmetric, options.full_matches, options.exact); },
      [&](std::size_t i, std::size_t j, std::atomic<std::size_t>& cut) {
        const matching::MatchResult result = matching::match_surfaces(
            rows.queries[i].descriptors, cols.queries[j].descriptors, full_match);
        if (!result.cliques_complete) ++cut;
        if (result.alignments.empty()) return Cell{};  // the former stage's cell stays
        const matching::Alignment& top = result.alignments.front();
        return Cell{top.overlay.score, 3, top.transform};
      });
  std::sort(failed.begin(), failed.end());  // in pair order, whatever the processes and threads
  for (const auto& [i, j, why] : failed) {
    out.warnings.push_back(record_name(rows.members[i]) + " and " + record_name(cols.members[j]) +
                           ": not matched (its score is nan): " + why);
  }
  if (cuts > 0) {
    out.warnings.push_back(std::to_string(cuts) + " of " + std::to_string(full_matches) +
                           " full matches: the clique search stopped at its budget (" +
                           options::named("max_clique_work") + ", " +
                           options::named("max_cliques") + "): alignments may be missing");
  }
  out.match_ms = clock.elapsed_ms();
  out.rows = std::move(rows.members);
  out.columns = symmetric ? out.rows : std::move(columns.members);
  return out;
}

void write_matrix_csv(std::ostream& out, const SimilarityMatrix& matrix) {
  const auto field = [](const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (const char c : text) {
      if (c == '"') quoted += '"';
      quoted += c;
    }
    return quoted + "\"";
  };
  out << "name";
  for (const MatrixMember& column : matrix.columns) out << ',' << field(column.name);
  out << '\n';
  char number[32];
  for (std::size_t i = 0; i < matrix.rows.size(); ++i) {
    out << field(matrix.rows[i].name);
    for (std::size_t j = 0; j < matrix.columns.size(); ++j) {
      std::snprintf(number, sizeof number, ",%.4f",
                    matrix.score(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
      out << number;
    }
    out << '\n';
  }
}

}  // namespace surfcomp::screening
