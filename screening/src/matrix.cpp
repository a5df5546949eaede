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
#include <mutex>
#include <optional>
#include <utility>

namespace surfcomp::screening {
namespace {

/// A set's records, before any is read: each file's records in order.
std::vector<io::MoleculeRecord> set_records(const std::vector<std::filesystem::path>& files) {
  std::vector<io::MoleculeRecord> records;
  for (const std::filesystem::path& file : files) {
    if (!io::is_molecule_file(file)) {
      throw InputError(file.string() +
                       ": not a molecule file (a matrix compares molecules with coordinates: " +
                       io::molecule_extensions(io::MoleculeUse::molecule) + ")");
    }
    std::vector<io::MoleculeRecord> read = io::read_molecule_records(file);
    records.insert(records.end(), std::make_move_iterator(read.begin()),
                   std::make_move_iterator(read.end()));
  }
  return records;
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
  quiet.log = nullptr;  // the log is not thread-safe; each record's steps are not told apart
  tbb::parallel_for(std::size_t{0}, records.size(), [&](std::size_t k) {
    try {
      matching::MatchInput input;
      input.molecule = io::read_record_molecule(records[k], options.inputs.input.read);
      prepared[k] = matching::prepare_input(input, quiet);
    } catch (const InputError& error) {
      why[k] = error.what();
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
  const std::vector<io::MoleculeRecord> row_records = set_records(set);
  const std::vector<io::MoleculeRecord> column_records = set_records(against);
  const bool symmetric = against.empty();
  if (row_records.empty()) throw InputError("the set holds no molecule");
  if (!symmetric && column_records.empty())
    throw InputError("the set to compare against holds no molecule");
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

  SimilarityMatrix out;
  out.symmetric = symmetric;
  Stopwatch clock;
  Described rows = describe_records(row_records, options, out.left_out);
  Described columns;
  if (!symmetric) columns = describe_records(column_records, options, out.left_out);
  out.describe_ms = clock.elapsed_ms();
  const Described& cols = symmetric ? rows : columns;
  if (rows.inputs.empty() || cols.inputs.empty() || (symmetric && rows.inputs.size() < 2)) {
    throw InputError("too few molecules could be read and described to make a matrix (" +
                     std::to_string(out.left_out.size()) +
                     " left out; the first: " + out.left_out.front() + ")");
  }

  clock.restart();
  const std::size_t n = rows.inputs.size(), m = cols.inputs.size();
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = symmetric ? i : 0; j < m; ++j) pairs.emplace_back(i, j);
  out.score = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m));
  if (options.transforms) out.transforms.assign(n * m, Eigen::Matrix4d::Identity());
  std::atomic<std::size_t> done{0};
  std::mutex progress;
  tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
    const auto [i, j] = pairs[k];
    const matching::MatchResult result = matching::match_surfaces(
        rows.inputs[i].descriptors, cols.inputs[j].descriptors, options.inputs.match);
    if (!result.alignments.empty()) {
      const matching::Alignment& top = result.alignments.front();
      const auto r = static_cast<Eigen::Index>(i), c = static_cast<Eigen::Index>(j);
      out.score(r, c) = top.overlay.score;
      if (symmetric) out.score(c, r) = top.overlay.score;
      if (options.transforms) {
        out.transforms[i * m + j] = top.transform;
        if (symmetric) {
          Eigen::Matrix4d inverse = Eigen::Matrix4d::Identity();
          inverse.topLeftCorner<3, 3>() = top.transform.topLeftCorner<3, 3>().transpose();
          inverse.topRightCorner<3, 1>() =
              -inverse.topLeftCorner<3, 3>() * top.transform.topRightCorner<3, 1>();
          out.transforms[j * m + i] = inverse;
        }
      }
    }
    const std::size_t finished = ++done;
    if (options.progress) {
      const std::lock_guard<std::mutex> lock(progress);
      options.progress(finished, pairs.size());
    }
  });
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
