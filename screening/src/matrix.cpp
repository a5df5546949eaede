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
#include <cstdio>
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

/// The pairs (row, column) given the full match: every pair with `exact`; otherwise each row's
/// `full_matches` best columns by `score` (a NaN last, ties to the lower column; all against all,
/// not the diagonal, and a pair once, as (lower, higher)). In order.
std::vector<std::pair<std::size_t, std::size_t>> full_match_pairs(const Eigen::MatrixXd& score,
                                                                  bool symmetric,
                                                                  const MatrixOptions& options) {
  const auto n = static_cast<std::size_t>(score.rows()), m = static_cast<std::size_t>(score.cols());
  std::set<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::size_t> columns;
    for (std::size_t j = 0; j < m; ++j)
      if (options.exact ? (!symmetric || j >= i) : (!symmetric || j != i)) columns.push_back(j);
    if (!options.exact) {
      const auto value = [&](std::size_t j) {
        return score(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
      };
      const std::size_t k = std::min(options.full_matches, columns.size());
      std::partial_sort(columns.begin(), columns.begin() + static_cast<std::ptrdiff_t>(k),
                        columns.end(), [&](std::size_t x, std::size_t y) {
                          if (std::isnan(value(x)) != std::isnan(value(y)))
                            return !std::isnan(value(x));
                          if (value(x) != value(y)) return value(x) > value(y);
                          return x < y;
                        });
      columns.resize(k);
    }
    for (const std::size_t j : columns)
      pairs.emplace(symmetric ? std::min(i, j) : i, symmetric ? std::max(i, j) : j);
  }
  return {pairs.begin(), pairs.end()};
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
        {"full-matches", options::Kind::integer,
         "each molecule's best neighbours, by the refined overlay, given the full match (0: "
         "none)",
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
  out.score = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m));
  out.full.setConstant(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m), false);
  if (options.transforms) out.transforms.assign(n * m, Eigen::Matrix4d::Identity());
  // A cell and, all against all, its mirror: the same score, the inverse transform.
  const auto set_cell = [&](std::size_t i, std::size_t j, double score,
                            const Eigen::Matrix4d& transform) {
    const auto r = static_cast<Eigen::Index>(i), c = static_cast<Eigen::Index>(j);
    out.score(r, c) = score;
    if (symmetric) out.score(c, r) = score;
    if (!options.transforms) return;
    out.transforms[i * m + j] = transform;
    if (symmetric && i != j) {
      out.transforms[j * m + i] =
          matching::RigidTransform::from_matrix(transform).inverse().matrix();
    }
  };
  std::size_t done = 0, total = 0;
  std::mutex tell;  // failed, done and the progress callback
  const auto told = [&] {
    if (!options.progress) return;
    const std::lock_guard<std::mutex> lock(tell);
    options.progress(++done, total);
  };

  if (!options.exact) {
    const ScreenOptions screen = screen_options(options);
    total = symmetric ? n * (n + 1) / 2 : n * m;
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
      tbb::parallel_for(symmetric ? i : std::size_t{0}, m, [&](std::size_t j) {
        const HitScore hit =
            refined_score(rows.queries[i], cols.queries[j].packed->sample().view(), screen);
        set_cell(i, j, hit.score, hit.transform);
        told();
      });
    });
  }

  const std::vector<std::pair<std::size_t, std::size_t>> pairs =
      full_match_pairs(out.score, symmetric, options);
  done = 0;
  total = pairs.size();
  // The pairs that failed (row, column, why), in the order they ended, and how many pairs'
  // clique searches were cut; few, so kept apart from the matrix's cells.
  std::vector<std::tuple<std::size_t, std::size_t, std::string>> failed;
  std::atomic<std::size_t> cuts{0};
  // The matrix keeps the top score alone: no alignment's coverage is measured.
  matching::MatchOptions full_match = options.inputs.match;
  full_match.coverage_distance = 0.0;
  tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
    const auto [i, j] = pairs[k];
    try {
      const matching::MatchResult result = matching::match_surfaces(
          rows.queries[i].descriptors, cols.queries[j].descriptors, full_match);
      if (!result.cliques_complete) ++cuts;
      // Without an alignment the refined overlay's stays (0 with exact).
      if (!result.alignments.empty()) {
        const matching::Alignment& top = result.alignments.front();
        set_cell(i, j, top.overlay.score, top.transform);
        out.full(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = true;
        if (symmetric) out.full(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(i)) = true;
      }
    } catch (const Error& error) {
      set_cell(i, j, std::numeric_limits<double>::quiet_NaN(), Eigen::Matrix4d::Identity());
      const std::lock_guard<std::mutex> lock(tell);
      failed.emplace_back(i, j, error.what());
    }
    told();
  });
  std::sort(failed.begin(), failed.end());  // in pair order, whatever the threads
  for (const auto& [i, j, why] : failed) {
    out.warnings.push_back(record_name(rows.members[i]) + " and " + record_name(cols.members[j]) +
                           ": not matched (its score is nan): " + why);
  }
  if (cuts > 0) {
    out.warnings.push_back(std::to_string(cuts.load()) + " of " + std::to_string(pairs.size()) +
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
