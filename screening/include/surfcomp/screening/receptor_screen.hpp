// Structure-based screening (`surfcomp screen --receptor`): a library's molecules ranked by how
// well they fit a receptor's site (docs/method.md#15-complementarity), in two stages as the
// ligand screen ranks them:
//  1. every conformer gets a fast dock: a short Monte Carlo search of the site (fast_chains x
//     fast_steps local optimisations of the complementarity score) with its stored surface
//     sample, and a molecule counts by its best conformer;
//  2. the `candidates` best molecules' best conformers get the full dock (docking::dock: their
//     surfaces built and described, the complementary match and the full search) into the one
//     prepared site, and rank by its best pose's score above every other molecule.
#pragma once

#include "surfcomp/core/option_table.hpp"
#include "surfcomp/docking/dock.hpp"
#include "surfcomp/screening/library.hpp"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::screening {

/// What ranks the molecules of a receptor screen.
enum class ReceptorRanking {
  mean,   ///< the complementarity score, a mean over the ligand's surface
  total,  ///< that score times the ligand's surface area (A^2): a sum over its surface
};

/// The names of ReceptorRanking's values, as --rank-by spells them.
inline constexpr std::array<const char*, 2> receptor_ranking_names = {"mean", "total"};

struct ReceptorScreenOptions {
  /// The receptor's site (site_ligand, site_spheres, site_pocket), the score and the full dock of
  /// stage 2 (its search, poses, threads); `conformers` is refused (a library holds them).
  docking::DockOptions dock;
  /// Default 8. Stage 1's Monte Carlo chains per conformer. >= 1.
  int fast_chains = 8;
  /// Default 10. Stage 1's moves per chain. >= 0.
  int fast_steps = 10;
  /// Default 20. The molecules, best stage-1 score first, whose best conformer gets the full dock.
  /// >= 0.
  int candidates = 20;
  /// Default 0: every molecule. The rows kept, best first.
  std::int64_t top = 0;
  /// Default mean. What ranks the conformers and molecules (poses that intersect the receptor
  /// after the others, whichever).
  ReceptorRanking ranking = ReceptorRanking::mean;
  /// Told (stage 1 or 2, done, total) as the work goes; may be empty.
  std::function<void(int stage, std::int64_t done, std::int64_t total)> progress;
};

/// The user's options: the dock's (docking::dock_option_table, without conformers,
/// conformer-seed, poses, local-only, score-only, and the options of a ligand file or a mesh:
/// record, ligand, molecule, repair, scale, unit) and --fast-chains, --fast-steps, --candidates,
/// --top, --rank-by.
const options::Table<ReceptorScreenOptions>& receptor_screen_option_table();

/// Throws OptionError naming the first option outside its domain.
void validate(const ReceptorScreenOptions& options);

/// One row: a molecule, by its best conformer.
struct ReceptorHit {
  std::size_t entry = 0;                ///< 0-based library entry of the molecule's best conformer
  int stage = 1;                        ///< 2: `score` is the full dock's; 1: the fast dock's
  docking::ComplementarityScore score;  ///< of the stage's best pose
  double fast_score = 0.0;              ///< its conformer's stage-1 score
  /// A^2: the area of the ligand's surface the score is a mean over (stage 1: the stored
  /// sample's; stage 2: the built surface's).
  double area = 0.0;
  /// Moves the entry's molecule into the receptor's frame (the stage's best pose).
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
};

struct ReceptorScreenResult {
  std::vector<ReceptorHit> hits;   ///< one per molecule: stage 2's by score, then stage 1's
  std::vector<std::string> notes;  ///< what a reader may want to know, one line each
  std::vector<std::pair<std::string, double>> timing_ms;  ///< per step, in order
};

/// Ranks `library`'s molecules (a library of molecules: check_library_kind) by their fit into
/// `receptor`'s site, in the two stages above. A molecule whose full dock is refused (larger than
/// the site: DockOptions::max_ligand_to_site) keeps its stage-1 row and a note names it. The rows
/// do not depend on the threads. Throws as docking::prepare_dock_site for the receptor,
/// OptionError for options outside their domain, InputError for a library of sites or meshes,
/// FormatError for a damaged entry.
ReceptorScreenResult receptor_screen(const matching::MatchInput& receptor, const Library& library,
                                     const ReceptorScreenOptions& options = {});

/// `hits` as CSV: rank,entry (1-based),name,source,record,conformer,score,stage,contact,clash,esp,
/// lp,deepest,area,fast_score,t00..t33 (the transform moving the entry into the receptor's
/// frame).
void write_receptor_hits_csv(std::ostream& out, const Library& library,
                             const std::vector<ReceptorHit>& hits);

}  // namespace surfcomp::screening
