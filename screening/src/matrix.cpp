#include "surfcomp/screening/matrix.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/matching/match.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <limits>
#include <mutex>
#include <new>
#include <optional>
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
  std::vector<matching::PreparedInput> inputs;
};

/// Each record read and described once (in parallel), those that fail left out with a line.
Described describe_records(const std::vector<io::MoleculeRecord>& records,
                           const MatrixOptions& options, std::vector<std::string>& left_out) {
  std::vector<std::optional<matching::PreparedInput>> prepared(records.size());
  std::vector<std::string> why(records.size());
  matching::MatchInputOptions quiet = options.inputs;
  // Neither is told apart by molecule, and several molecules are described at once.
  quiet.log = nullptr;
  quiet.descriptors.progress = nullptr;
  tbb::parallel_for(std::size_t{0}, records.size(), [&](std::size_t k) {
    try {
      matching::MatchInput input;
      input.molecule = io::read_record_molecule(records[k], options.inputs.input.read);
      prepared[k] = matching::prepare_input(input, quiet);
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
    out.inputs.push_back(std::move(*prepared[k]));
  }
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
  if (rows.inputs.empty() || (symmetric && rows.inputs.size() < 2))
    throw too_few(set, row_failures);
  if (cols.inputs.empty()) throw too_few(against, column_failures);
  out.left_out.insert(out.left_out.end(), row_failures.begin(), row_failures.end());
  out.left_out.insert(out.left_out.end(), column_failures.begin(), column_failures.end());

  clock.restart();
  const std::size_t n = rows.inputs.size(), m = cols.inputs.size();
  const std::size_t total = symmetric ? n * (n + 1) / 2 : n * m;
  out.score = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m));
  if (options.transforms) out.transforms.assign(n * m, Eigen::Matrix4d::Identity());
  // The pairs that failed (row, column, why), in the order they ended, and how many pairs'
  // clique searches were cut; few, so kept apart from the matrix's cells.
  std::vector<std::tuple<std::size_t, std::size_t, std::string>> failed;
  std::atomic<std::size_t> cuts{0};
  std::size_t done = 0;
  std::mutex tell;  // failed, done and the progress callback
  const auto match_pair = [&](std::size_t i, std::size_t j) {
    const auto r = static_cast<Eigen::Index>(i), c = static_cast<Eigen::Index>(j);
    try {
      const matching::MatchResult result = matching::match_surfaces(
          rows.inputs[i].descriptors, cols.inputs[j].descriptors, options.inputs.match);
      if (!result.cliques_complete) ++cuts;
      if (!result.alignments.empty()) {
        const matching::Alignment& top = result.alignments.front();
        out.score(r, c) = top.overlay.score;
        if (symmetric) out.score(c, r) = top.overlay.score;
        if (options.transforms) {
          out.transforms[i * m + j] = top.transform;
          if (symmetric && i != j) {  // the rigid inverse: R^T, -R^T t
            Eigen::Matrix4d inverse = Eigen::Matrix4d::Identity();
            inverse.topLeftCorner<3, 3>() = top.transform.topLeftCorner<3, 3>().transpose();
            inverse.topRightCorner<3, 1>() =
                -inverse.topLeftCorner<3, 3>() * top.transform.topRightCorner<3, 1>();
            out.transforms[j * m + i] = inverse;
          }
        }
      }
    } catch (const Error& error) {
      out.score(r, c) = std::numeric_limits<double>::quiet_NaN();
      if (symmetric) out.score(c, r) = out.score(r, c);
      const std::lock_guard<std::mutex> lock(tell);
      failed.emplace_back(i, j, error.what());
    }
    if (options.progress) {
      const std::lock_guard<std::mutex> lock(tell);
      options.progress(++done, total);
    }
  };
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    tbb::parallel_for(symmetric ? i : std::size_t{0}, m, [&](std::size_t j) { match_pair(i, j); });
  });
  std::sort(failed.begin(), failed.end());  // in pair order, whatever the threads
  for (const auto& [i, j, why] : failed) {
    out.warnings.push_back(record_name(rows.members[i]) + " and " + record_name(cols.members[j]) +
                           ": not matched (its score is nan): " + why);
  }
  if (cuts > 0) {
    out.warnings.push_back(std::to_string(cuts.load()) + " of " + std::to_string(total) +
                           " pairs: the clique search stopped at its budget (" +
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
