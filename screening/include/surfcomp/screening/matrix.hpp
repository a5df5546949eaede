// All against all: each molecule of a set read and described once, then every pair compared,
// into a similarity matrix of overlay scores (docs/method.md §12.1), coarse to fine as a screen
// ranks (screen.hpp): every pair's overlay at the principal-axes superpositions of the two
// surfaces' samples (a screen's stage 1), each molecule's best neighbours' overlays refined from
// them (stage 2), then each molecule's best few given the full match (`surfcomp match`, a screen's
// stage 3), whose top alignment's score replaces it; or every pair given the full match. Each
// cell keeps the best overlay found for it, and says at which stage. In parallel (TBB), the same
// whatever the thread count.
#pragma once

#include "surfcomp/core/option_table.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/screening/exchange.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace surfcomp::screening {

struct MatrixOptions {
  /// How the molecules are read, surfaced, described and matched; default as `surfcomp match`.
  matching::MatchInputOptions inputs;
  /// Default 10^7. A matrix of more pairs than this is refused before any work. The matrix
  /// takes 9 bytes a cell (both triangles, and `stage`), 137 with the transforms; each molecule's
  /// description and packed index about 5 MB more (a drug-sized ligand), about 30 KB with
  /// `neighbours`. The limit applies with `neighbours` too: it bounds the work. >= 1.
  std::int64_t max_pairs = 10'000'000;
  /// Default 0 (docs/decisions.md, "Matrix coarse to fine"). The columns of each row, best
  /// stage-1 score first (the diagonal excepted), whose overlay is refined; 0: every pair's.
  std::size_t refined_overlays = 0;
  /// Default 2 (docs/decisions.md, "Matrix coarse to fine"). The columns of each row, best
  /// score after stage 2 first (the diagonal excepted), given the full match. 0: none.
  std::size_t full_matches = 2;
  /// Default false. Every pair given the full match, the refined overlays skipped (docs/
  /// benchmarks.md, "All-against-all matrix", gives both costs).
  bool exact = false;
  /// Default 0: the whole matrix (SimilarityMatrix::score). K > 0: each row's K best columns
  /// alone (SimilarityMatrix::neighbours), the same as the whole matrix's; memory then grows with
  /// the molecules, not with the pairs: a molecule's packed sample (about 30 KB), the indexes of
  /// 32 rows a process, and per row 2 (K + full_matches) + refined_overlays cells of about 150
  /// bytes (with their transforms) and its refined and fully matched cells. A row whose best may
  /// have been let go (full matches lowered the cells kept; rare) is computed again on process
  /// 0, a row's stage-1 work. Not with `exact`.
  std::size_t neighbours = 0;
  /// Default false. Keep each pair's top transform (SimilarityMatrix::transforms, and
  /// Neighbour::transform).
  bool transforms = false;
  /// Default none. Told (pairs done, pairs) as the pairs are matched, for a progress line.
  std::function<void(std::size_t, std::size_t)> progress;
};

/// The user's options of a matrix: the surface, description and match options of a pair match
/// without its sites, --full-matches, --exact, --max-pairs and --threads.
const options::Table<MatrixOptions>& matrix_option_table();

/// One molecule of a set: a record of a molecule file.
struct MatrixMember {
  std::string name;              ///< its record's name (io::MoleculeRecord::name)
  std::filesystem::path source;  ///< its file
  std::size_t record = 1;        ///< its 1-based position in the file
};

/// A row's neighbour (MatrixOptions::neighbours): a column and its cell.
struct Neighbour {
  std::size_t column = 0;  ///< its index in SimilarityMatrix::columns
  double score = 0.0;      ///< as SimilarityMatrix::score
  std::uint8_t stage = 0;  ///< as SimilarityMatrix::stage
  /// With MatrixOptions::transforms, as SimilarityMatrix::transforms (else the identity).
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
};

struct SimilarityMatrix {
  /// The molecules compared: the rows, and the columns (the same set for all against all),
  /// in file order, without those left out.
  std::vector<MatrixMember> rows, columns;
  /// True when rows and columns are one set: the pairs i < j are compared once (row i as REF)
  /// and the matrix is symmetric, the diagonal the self-overlays (the self-matches with
  /// MatrixOptions::exact).
  bool symmetric = false;
  /// rows x columns. score(i, j): the overlay score of columns[j] aligned onto rows[i], the best
  /// found at the stage `stage` gives (0 when none found an alignment; NaN when the full match
  /// failed, see `warnings`). Empty with MatrixOptions::neighbours.
  Eigen::MatrixXd score;
  /// rows x columns: the stage that gave score(i, j): 1, the best principal-axes superposition
  /// (single precision); 2, its refinement (MatrixOptions::refined_overlays); 3, the full match's
  /// top alignment (MatrixOptions::full_matches, exact); 0, none (exact, without an alignment).
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic> stage;
  /// With MatrixOptions::neighbours K, per row its K best columns, best first (ties to the lower
  /// column, NaN last; all against all, not the diagonal): the row of `score` the whole matrix
  /// would have, cut to its K best.
  std::vector<std::vector<Neighbour>> neighbours;
  /// With MatrixOptions::transforms, row-major (i * columns + j): the 4x4 rigid transform that
  /// moves columns[j] onto rows[i] (identity without an alignment).
  std::vector<Eigen::Matrix4d> transforms;
  /// The records left out, one line each: the file, the record and why (a file without a
  /// record: the file).
  std::vector<std::string> left_out;
  /// What the matching cut, one line each: a pair that could not be matched (a limit such as
  /// max_graph_nodes; its score is NaN), and how many pairs' clique searches stopped at their
  /// budget (alignments may be missing).
  std::vector<std::string> warnings;
  double describe_ms = 0.0;  ///< reading, surfaces and descriptions
  double match_ms = 0.0;     ///< the pairs: their refined overlays and full matches
};

/// Every record of the molecule files `set` (SDF, MOL2, PDB, mmCIF, PQR; each file's records
/// in order) read and described once as prepare_input describes a molecule, then compared all
/// against all (`against` empty) or each of `set` (rows) against each of `against` (columns):
/// every pair by a screen's stage 1 (fast_score), each row's options.refined_overlays best by its
/// stage 2 (refined_score, every start; all against all, the diagonal too), then each row's
/// options.full_matches best by the full match (match_surfaces, as for two prepared molecules),
/// or with options.exact every pair by the full match. All against all, a pair is
/// compared once (the lower index as the reference) and its mirrored cell gets the inverse
/// transform. A record that cannot be read or described
/// is left out and named in SimilarityMatrix::left_out; a pair that cannot be matched is named
/// in SimilarityMatrix::warnings. Throws, before any work, OptionError for options outside
/// their domain or that do not apply to a file (check_match_input), InputError for a file that
/// is not a molecule file (a mesh, a SMILES list: no coordinates), an empty set, a set of one
/// without `against`, or more pairs than options.max_pairs; after reading, InputError when
/// fewer than two molecules (or none on a side) are left; OptionError for an option no record
/// can be read with.
SimilarityMatrix similarity_matrix(const std::vector<std::filesystem::path>& set,
                                   const std::vector<std::filesystem::path>& against = {},
                                   const MatrixOptions& options = {});

/// The same over the processes of `exchange` (an MPI job), every one given the same arguments:
/// each reads and describes every molecule, then computes its share of each stage's pairs (rows
/// in turn for the first, every processes()-th pair of the others); process 0 gathers the cells
/// and chooses the next stage's pairs. The matrix (score, stage, transforms, warnings) is
/// process 0's alone, and the same as one process's; the others get the molecules and times.
SimilarityMatrix similarity_matrix(const std::vector<std::filesystem::path>& set,
                                   const std::vector<std::filesystem::path>& against,
                                   const MatrixOptions& options, Exchange& exchange);

/// The neighbours (MatrixOptions::neighbours) as CSV: a header
/// "row,name,rank,column,neighbour,score,stage", then a line per row and neighbour, best first:
/// the row's 1-based index and name, the neighbour's rank (1 the best), index and name, its
/// score to 4 decimals ("nan" for a pair not matched) and stage; names quoted as
/// write_matrix_csv quotes them.
void write_neighbours_csv(std::ostream& out, const SimilarityMatrix& matrix);

/// The matrix as CSV: a header "name" then the columns' names, one line per row (its name,
/// then its scores to 4 decimals, "nan" for a pair not matched); names quoted when they hold a
/// comma or a quote.
void write_matrix_csv(std::ostream& out, const SimilarityMatrix& matrix);

}  // namespace surfcomp::screening
