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
#include <limits>
#include <map>
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
  /// overlays); with neighbours, its descriptors dropped (see describe_records).
  std::vector<ScreenQuery> queries;
  std::vector<io::MoleculeRecord> records;  ///< with neighbours, each molecule's record
  /// With neighbours, each molecule's packed sample: its index (ScreenQuery::packed, a
  /// megabyte) is built only while a stage compares the molecule as a row (RowIndexes).
  std::vector<matching::PackedSample> samples;
};

/// The screen's options of the refined overlays: the match's overlay options, every start refined.
ScreenOptions screen_options(const MatrixOptions& options) {
  ScreenOptions screen;
  screen.match = options.inputs.match;
  screen.refine_starts = 0;
  return screen;
}

/// A record read and described as prepare_input describes a molecule, quietly: neither the log
/// nor the progress tells molecules apart, and several are described at once.
harmonic::SurfaceDescriptors describe_record(const io::MoleculeRecord& record,
                                             const MatrixOptions& options) {
  matching::MatchInputOptions quiet = options.inputs;
  quiet.log = nullptr;
  quiet.descriptors.progress = nullptr;
  matching::MatchInput input;
  input.molecule = io::read_record_molecule(record, options.inputs.input.read);
  return std::move(matching::prepare_input(input, quiet).descriptors);
}

/// Each record read and described once (in parallel), those that fail left out with a line.
/// With neighbours, only the packed samples are kept (a molecule's descriptors are megabytes,
/// its samples kilobytes): the full matches describe their two molecules again.
Described describe_records(std::vector<io::MoleculeRecord> records, const MatrixOptions& options,
                           std::vector<std::string>& left_out) {
  std::vector<std::optional<ScreenQuery>> prepared(records.size());
  std::vector<matching::PackedSample> samples(options.neighbours > 0 ? records.size() : 0);
  std::vector<std::string> why(records.size());
  const ScreenOptions screen = screen_options(options);
  tbb::parallel_for(std::size_t{0}, records.size(), [&](std::size_t k) {
    try {
      harmonic::SurfaceDescriptors described = describe_record(records[k], options);
      if (options.exact) {  // the full matches alone: no sample to pack
        prepared[k].emplace();
        prepared[k]->descriptors = std::move(described);
      } else {
        prepared[k] = make_screen_query(std::move(described), screen);
        if (options.neighbours > 0) {  // the packed sample alone (Described::samples)
          prepared[k]->descriptors = {};
          prepared[k]->sample = {};
          prepared[k]->atoms = {};
          prepared[k]->atom_sample = {};
          prepared[k]->atom_packed.reset();
          samples[k] = prepared[k]->packed->sample();
          prepared[k]->packed.reset();
        }
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
    if (samples.empty()) continue;
    out.records.push_back(std::move(records[k]));
    out.samples.push_back(std::move(samples[k]));
  }
  return out;
}

/// With neighbours, the indexes of the rows of some pairs, built for a stage and dropped after.
class RowIndexes {
 public:
  RowIndexes(Described& rows, const std::vector<std::pair<std::size_t, std::size_t>>& pairs)
      : rows_(rows) {
    if (rows.samples.empty()) return;  // the whole matrix: every index kept
    for (const auto& pair : pairs)
      if (built_.empty() || built_.back() != pair.first) built_.push_back(pair.first);
    std::sort(built_.begin(), built_.end());
    built_.erase(std::unique(built_.begin(), built_.end()), built_.end());
    tbb::parallel_for(std::size_t{0}, built_.size(), [&](std::size_t k) {
      const std::size_t i = built_[k];
      rows.queries[i].packed = std::make_shared<const matching::PackedQuery>(rows.samples[i]);
    });
  }
  ~RowIndexes() {
    for (const std::size_t i : built_) rows_.queries[i].packed.reset();
  }
  RowIndexes(const RowIndexes&) = delete;
  RowIndexes& operator=(const RowIndexes&) = delete;

 private:
  Described& rows_;
  std::vector<std::size_t> built_;
};

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

/// Whether cell a (in column ja) ranks before cell b (in column jb) in a row: a NaN last, a higher
/// score first, ties to the lower column.
bool ranks_before(std::size_t ja, const Cell& a, std::size_t jb, const Cell& b) {
  if (std::isnan(a.score) != std::isnan(b.score)) return !std::isnan(a.score);
  if (a.score != b.score) return a.score > b.score;
  return ja < jb;
}

/// The mirrored cell of a symmetric matrix: the same score and stage, the inverse transform.
Cell mirrored(const Cell& cell) {
  return {cell.score, cell.stage,
          matching::RigidTransform::from_matrix(cell.transform).inverse().matrix()};
}

/// Each row's `capacity` best cells (ranks_before) of those offered to it, a cell offered again
/// taking its new value, and per row a bound on the cells it does not hold: the best score of
/// those it let go or did not take.
class BestCells {
 public:
  BestCells(std::size_t rows, std::size_t capacity)
      : rows_(rows), floor_(rows, -std::numeric_limits<double>::infinity()), capacity_(capacity) {}

  void offer(std::size_t i, std::size_t j, const Cell& cell) {
    std::vector<std::pair<std::size_t, Cell>>& row = rows_[i];
    for (auto& [column, kept] : row) {
      if (column != j) continue;
      kept = cell;
      return;
    }
    if (row.size() < capacity_) {
      row.emplace_back(j, cell);
      return;
    }
    auto worst = row.begin();
    for (auto it = row.begin(); it != row.end(); ++it)
      if (ranks_before(worst->first, worst->second, it->first, it->second)) worst = it;
    if (ranks_before(j, cell, worst->first, worst->second)) {
      let_go(i, worst->second.score);
      *worst = {j, cell};
    } else {
      let_go(i, cell.score);
    }
  }

  /// Row i's `count` best cells, best first.
  std::vector<std::pair<std::size_t, Cell>> best(std::size_t i, std::size_t count) const {
    std::vector<std::pair<std::size_t, Cell>> row = rows_[i];
    std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) {
      return ranks_before(a.first, a.second, b.first, b.second);
    });
    row.resize(std::min(count, row.size()));
    return row;
  }

  /// Whether row i's `count` best of all its `columns` cells are among those it holds.
  bool holds_best(std::size_t i, std::size_t count, std::size_t columns) const {
    if (floor_[i] == -std::numeric_limits<double>::infinity()) return true;  // none let go
    const std::size_t wanted = std::min(count, columns);
    if (rows_[i].size() < wanted) return false;
    const double last = best(i, wanted).back().second.score;
    return !std::isnan(last) && last > floor_[i];
  }

 private:
  void let_go(std::size_t i, double score) {
    if (!std::isnan(score)) floor_[i] = std::max(floor_[i], score);
  }

  std::vector<std::vector<std::pair<std::size_t, Cell>>> rows_;
  std::vector<double> floor_;
  std::size_t capacity_;
};

/// A count of a stage's pairs done, told to MatrixOptions::progress.
struct Told {
  std::size_t done = 0, total = 0;
  std::mutex lock;
};

/// The pairs of the rows [begin, end) of an n x m matrix that are process's (row - begin mod
/// processes), each row's columns in order (all against all, from the diagonal on, or after it
/// without `diagonal`).
std::vector<Pair> row_share(std::size_t begin, std::size_t end, std::size_t m, bool symmetric,
                            bool diagonal, int process, int processes) {
  std::vector<Pair> pairs;
  for (std::size_t i = begin + static_cast<std::size_t>(process); i < end;
       i += static_cast<std::size_t>(processes)) {
    for (std::size_t j = symmetric ? (diagonal ? i : i + 1) : 0; j < m; ++j)
      pairs.emplace_back(i, j);
  }
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

/// The pairs of a list whose row is process's (row mod processes), in order.
std::vector<Pair> row_owned(const std::vector<Pair>& pairs, int process, int processes) {
  std::vector<Pair> mine;
  for (const Pair& pair : pairs)
    if (pair.first % static_cast<std::size_t>(processes) == static_cast<std::size_t>(process))
      mine.push_back(pair);
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

/// The pairs of a matrix compared stage by stage (the header's coarse to fine), each stage's
/// pairs split over the processes of an exchange, into the whole matrix or each row's best cells
/// (MatrixOptions::neighbours) on process 0.
class Comparison {
 public:
  Comparison(Described& rows, const Described& columns, bool symmetric,
             const MatrixOptions& options, Exchange& exchange, SimilarityMatrix& out)
      : rows_(rows),
        columns_(columns),
        symmetric_(symmetric),
        options_(options),
        exchange_(exchange),
        out_(out),
        n_(rows.queries.size()),
        m_(columns.queries.size()),
        root_(exchange.process() == 0),
        dense_(options.neighbours == 0),
        // Blocks of rows of about 2^20 cells (what a gather holds) and, with neighbours, of 32
        // rows a process (the indexes RowIndexes builds at once, about a megabyte each); a row
        // a process at least.
        block_(std::max<std::size_t>(
            static_cast<std::size_t>(exchange.processes()),
            std::min<std::size_t>(
                (std::size_t{1} << 20) / m_,
                dense_ ? n_ : 32 * static_cast<std::size_t>(exchange.processes())))),
        screen_(screen_options(options)) {
    // The matrix keeps the top score alone: no alignment's coverage is measured.
    full_match_ = options.inputs.match;
    full_match_.coverage_distance = 0.0;
    if (!root_) return;
    if (dense_) {
      out.score =
          Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n_), static_cast<Eigen::Index>(m_));
      out.stage.setZero(static_cast<Eigen::Index>(n_), static_cast<Eigen::Index>(m_));
      if (options.transforms) out.transforms.assign(n_ * m_, Eigen::Matrix4d::Identity());
    } else {
      // Room for the neighbours, the cells the next stages choose and as many again that a
      // full match may move below them.
      best_.emplace(n_, 2 * (options.neighbours + options.full_matches) + options.refined_overlays);
    }
  }

  /// Every stage, then (process 0) the neighbours and the warnings.
  void run() {
    if (!options_.exact) {
      // Every pair, a block of rows at a time, a row at a time to each process; with
      // neighbours, not the diagonal.
      const auto rows_of = [&](std::size_t begin, int process) {
        return row_share(begin, std::min(n_, begin + block_), m_, symmetric_, dense_, process,
                         exchange_.processes());
      };
      Told told;
      for (std::size_t begin = 0; begin < n_; begin += block_)
        told.total += rows_of(begin, exchange_.process()).size();
      for (std::size_t begin = 0; begin < n_; begin += block_) {
        run_stage(
            first_stage(), rows_of(begin, exchange_.process()),
            [&](int process) { return rows_of(begin, process); }, told);
      }
      if (first_stage() == 1)
        run_chosen(2, [&] { return choose(options_.refined_overlays, false, dense_); });
    }
    const std::size_t full_matches =
        run_chosen(3, [&] { return choose(options_.full_matches, options_.exact, false); });
    if (!root_) return;
    if (!dense_) neighbours();
    std::sort(failed_.begin(), failed_.end());  // in pair order, whatever processes and threads
    for (const auto& [i, j, why] : failed_) {
      out_.warnings.push_back(record_name(rows_.members[i]) + " and " +
                              record_name(columns_.members[j]) +
                              ": not matched (its score is nan): " + why);
    }
    if (cuts_ > 0) {
      out_.warnings.push_back(std::to_string(cuts_) + " of " + std::to_string(full_matches) +
                              " full matches: the clique search stopped at its budget (" +
                              options::named("max_clique_work") + ", " +
                              options::named("max_cliques") + "): alignments may be missing");
    }
  }

 private:
  /// Pair (i, j)'s cell at `stage`: 1, the best principal-axes start; 2, refined; 3, the full
  /// match (stage 0 without an alignment: the former stage's cell stays). Counts a clique search
  /// cut in `cuts`.
  Cell compute(std::uint8_t stage, std::size_t i, std::size_t j,
               std::atomic<std::size_t>& cuts) const {
    if (stage <= 2) {
      const matching::PackedSampleView sample =
          dense_ ? columns_.queries[j].packed->sample().view() : columns_.samples[j].view();
      const HitScore hit = stage == 1 ? fast_score(rows_.queries[i], sample, screen_)
                                      : refined_score(rows_.queries[i], sample, screen_);
      return {hit.score, stage, hit.transform};
    }
    const matching::MatchResult result =
        dense_
            ? matching::match_surfaces(rows_.queries[i].descriptors,
                                       columns_.queries[j].descriptors, full_match_)
            : matching::match_surfaces(describe_record(rows_.records[i], options_),
                                       describe_record(columns_.records[j], options_), full_match_);
    if (!result.cliques_complete) ++cuts;
    if (result.alignments.empty()) return {};
    const matching::Alignment& top = result.alignments.front();
    return {top.overlay.score, 3, top.transform};
  }

  /// Every pair's first cell: stage 1, or stage 2 when every pair gets it.
  std::uint8_t first_stage() const { return options_.refined_overlays == 0 ? 2 : 1; }

  /// A cell and, all against all, its mirror: the same score and stage, the inverse transform.
  void set_cell(std::size_t i, std::size_t j, const Cell& cell) {
    if (!dense_) {
      if (chosen_stage_) later_[{i, j}] = cell;
      best_->offer(i, j, cell);
      if (symmetric_ && i != j) best_->offer(j, i, mirrored(cell));
      return;
    }
    const auto r = static_cast<Eigen::Index>(i), c = static_cast<Eigen::Index>(j);
    out_.score(r, c) = cell.score;
    out_.stage(r, c) = cell.stage;
    if (symmetric_) {
      out_.score(c, r) = cell.score;
      out_.stage(c, r) = cell.stage;
    }
    if (!options_.transforms) return;
    out_.transforms[i * m_ + j] = cell.transform;
    if (symmetric_ && i != j) out_.transforms[j * m_ + i] = mirrored(cell).transform;
  }

  /// Each row's `count` best columns (every column with `every`; the diagonal with `diagonal`),
  /// as pairs (row <= column all against all), in order. Process 0's.
  std::vector<Pair> choose(std::size_t count, bool every, bool diagonal) const {
    if (dense_) return best_pairs(out_.score, symmetric_, count, every, diagonal);
    std::set<Pair> pairs;
    for (std::size_t i = 0; i < n_; ++i) {
      for (const auto& [j, cell] : best_->best(i, count))
        pairs.emplace(symmetric_ ? std::min(i, j) : i, symmetric_ ? std::max(i, j) : j);
    }
    return {pairs.begin(), pairs.end()};
  }

  /// One stage's pairs over the processes: this process's, `mine`, computed in parallel, then
  /// every process's cells gathered and set on process 0 (`theirs(r)`: process r's, in order).
  template <class Theirs>
  void run_stage(std::uint8_t stage, const std::vector<Pair>& mine, const Theirs& theirs,
                 Told& told) {
    const std::size_t width = options_.transforms ? 18 : 2;
    const RowIndexes indexes(rows_, stage == 3 ? std::vector<Pair>{} : mine);
    std::vector<double> local(mine.size() * width);
    std::vector<std::string> why(mine.size());
    std::atomic<std::size_t> cut{0};
    tbb::parallel_for(std::size_t{0}, mine.size(), [&](std::size_t k) {
      Cell cell;
      try {
        cell = compute(stage, mine[k].first, mine[k].second, cut);
      } catch (const Error& error) {
        cell = {std::numeric_limits<double>::quiet_NaN(), stage, Eigen::Matrix4d::Identity()};
        why[k] = error.what();
      }
      put_cell(cell, options_.transforms, local.data() + k * width);
      if (!options_.progress) return;
      const std::lock_guard<std::mutex> lock(told.lock);
      options_.progress(++told.done, told.total);
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
    const std::vector<double> cells = exchange_.gather(local);
    const std::vector<double> said = exchange_.gather(notes);
    if (!root_) return;
    std::size_t at = 0, note = 0;
    for (int process = 0; process < exchange_.processes(); ++process) {
      const std::vector<Pair> pairs = theirs(process);
      for (const auto& [i, j] : pairs) {
        const Cell cell = get_cell(cells.data() + at, options_.transforms);
        if (cell.stage != 0) set_cell(i, j, cell);  // 0: no alignment, the cell stays
        at += width;
      }
      cuts_ += static_cast<std::size_t>(said[note++]);
      const auto failures = static_cast<std::size_t>(said[note++]);
      for (std::size_t f = 0; f < failures; ++f) {
        const auto k = static_cast<std::size_t>(said[note++]);
        const auto length = static_cast<std::size_t>(said[note++]);
        std::string text;
        for (std::size_t c = 0; c < length; ++c)
          text += static_cast<char>(static_cast<unsigned char>(said[note++]));
        failed_.emplace_back(pairs[k].first, pairs[k].second, std::move(text));
      }
    }
  }

  /// A stage of the pairs process 0 chooses: the list told to every process. Stage 2 goes a
  /// block of rows at a time, each row's pairs to one process (its index built once); stage 3,
  /// which builds no index, in one go, the pairs dealt in turn (full matches vary in cost).
  /// Returns how many.
  template <class Chosen>
  std::size_t run_chosen(std::uint8_t stage, const Chosen& chosen) {
    const std::vector<Pair> pairs =
        broadcast_pairs(exchange_, root_ ? chosen() : std::vector<Pair>{});
    chosen_stage_ = true;
    const int processes = exchange_.processes();
    const auto mine_of = [&](const std::vector<Pair>& some, int process) {
      return stage == 3 ? share(some, process, processes) : row_owned(some, process, processes);
    };
    std::vector<std::vector<Pair>> blocks;
    for (std::size_t begin = 0; begin < pairs.size();) {  // pairs are in row order
      std::size_t end = stage == 3 ? pairs.size() : begin;
      while (end < pairs.size() && pairs[end].first < pairs[begin].first + block_) ++end;
      blocks.emplace_back(pairs.begin() + static_cast<std::ptrdiff_t>(begin),
                          pairs.begin() + static_cast<std::ptrdiff_t>(end));
      begin = end;
    }
    Told told;
    for (const std::vector<Pair>& some : blocks)
      told.total += mine_of(some, exchange_.process()).size();
    for (const std::vector<Pair>& some : blocks) {
      run_stage(
          stage, mine_of(some, exchange_.process()),
          [&](int process) { return mine_of(some, process); }, told);
    }
    return pairs.size();
  }

  /// Each row's neighbours. A row whose best may have been let go (full matches lowered the
  /// cells held) is computed again from its first cells and the later stages' (rare).
  void neighbours() {
    const std::size_t others = symmetric_ ? m_ - 1 : m_;
    out_.neighbours.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      std::vector<std::pair<std::size_t, Cell>> row;
      if (best_->holds_best(i, options_.neighbours, others)) {
        row = best_->best(i, options_.neighbours);
      } else {
        row = whole_row(i);
        row.resize(std::min(options_.neighbours, row.size()));
      }
      for (const auto& [j, cell] : row)
        out_.neighbours[i].push_back({j, cell.score, cell.stage, cell.transform});
    }
  }

  /// Row i's cells as the whole matrix holds them, best first (not the diagonal): a block of
  /// columns at a time, each pair compared as its first stage compared it (all against all, the
  /// lower index as the reference) unless a later stage's cell is kept.
  std::vector<std::pair<std::size_t, Cell>> whole_row(std::size_t i) const {
    std::vector<std::pair<std::size_t, Cell>> row;
    for (std::size_t begin = 0; begin < m_; begin += block_) {
      std::vector<Pair> pairs;
      for (std::size_t j = begin; j < std::min(m_, begin + block_); ++j)
        if (!symmetric_ || j != i)
          pairs.emplace_back(symmetric_ ? std::min(i, j) : i, symmetric_ ? std::max(i, j) : j);
      const RowIndexes indexes(rows_, pairs);
      std::vector<Cell> cells(pairs.size());
      tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t k) {
        const auto known = later_.find(pairs[k]);
        if (known != later_.end()) {
          cells[k] = known->second;
          return;
        }
        try {
          std::atomic<std::size_t> cuts{0};
          cells[k] = compute(first_stage(), pairs[k].first, pairs[k].second, cuts);
        } catch (const Error&) {  // named when it first failed
          cells[k] = {std::numeric_limits<double>::quiet_NaN(), first_stage(),
                      Eigen::Matrix4d::Identity()};
        }
      });
      for (std::size_t k = 0; k < pairs.size(); ++k) {
        const bool mirror = pairs[k].first != i;
        row.emplace_back(mirror ? pairs[k].first : pairs[k].second,
                         mirror ? mirrored(cells[k]) : cells[k]);
      }
    }
    std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) {
      return ranks_before(a.first, a.second, b.first, b.second);
    });
    return row;
  }

  Described& rows_;
  const Described& columns_;
  bool symmetric_;
  const MatrixOptions& options_;
  Exchange& exchange_;
  SimilarityMatrix& out_;
  std::size_t n_, m_;
  bool root_, dense_;
  std::size_t block_;
  ScreenOptions screen_;
  matching::MatchOptions full_match_;
  std::optional<BestCells> best_;
  /// With neighbours, the cells of the chosen stages (2 and 3; row <= column all against all),
  /// for whole_row.
  std::map<Pair, Cell> later_;
  bool chosen_stage_ = false;
  /// The pairs that failed (row, column, why), and how many pairs' clique searches were cut;
  /// few, so kept apart from the cells.
  std::vector<std::tuple<std::size_t, std::size_t, std::string>> failed_;
  std::size_t cuts_ = 0;
};

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
        {"neighbours", options::Kind::integer,
         "keep each molecule's best neighbours only, not the whole matrix (memory grows with the "
         "molecules, not with the pairs); 0: the whole matrix",
         "", 0, 1e6},
        [](auto& m) -> auto& { return m.neighbours; }));
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
  if (options.exact && options.neighbours > 0) {
    throw OptionError(options::named("exact") + " and " + options::named("neighbours") +
                      " do not go together: every pair's full match is kept as a matrix");
  }
  SimilarityMatrix out;
  std::vector<io::MoleculeRecord> row_records = set_records(set, options, out.left_out);
  std::vector<io::MoleculeRecord> column_records = set_records(against, options, out.left_out);
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
  Described rows = describe_records(std::move(row_records), options, row_failures);
  Described columns;
  if (!symmetric) columns = describe_records(std::move(column_records), options, column_failures);
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
  Comparison(rows, cols, symmetric, options, exchange, out).run();
  out.match_ms = clock.elapsed_ms();
  out.rows = std::move(rows.members);
  out.columns = symmetric ? out.rows : std::move(columns.members);
  return out;
}

namespace {

/// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace

void write_neighbours_csv(std::ostream& out, const SimilarityMatrix& matrix) {
  out << "row,name,rank,column,neighbour,score,stage\n";
  char number[32];
  for (std::size_t i = 0; i < matrix.neighbours.size(); ++i) {
    for (std::size_t k = 0; k < matrix.neighbours[i].size(); ++k) {
      const Neighbour& next = matrix.neighbours[i][k];
      std::snprintf(number, sizeof number, "%.4f", next.score);
      out << i + 1 << ',' << csv_field(matrix.rows[i].name) << ',' << k + 1 << ','
          << next.column + 1 << ',' << csv_field(matrix.columns[next.column].name) << ',' << number
          << ',' << static_cast<int>(next.stage) << '\n';
    }
  }
}

void write_matrix_csv(std::ostream& out, const SimilarityMatrix& matrix) {
  out << "name";
  for (const MatrixMember& column : matrix.columns) out << ',' << csv_field(column.name);
  out << '\n';
  char number[32];
  for (std::size_t i = 0; i < matrix.rows.size(); ++i) {
    out << csv_field(matrix.rows[i].name);
    for (std::size_t j = 0; j < matrix.columns.size(); ++j) {
      std::snprintf(number, sizeof number, ",%.4f",
                    matrix.score(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
      out << number;
    }
    out << '\n';
  }
}

}  // namespace surfcomp::screening
