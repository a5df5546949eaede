// A ligand placed into a receptor's pocket by its surface (docs/method.md#15-complementarity):
// the pocket's description matched against the complement of the ligand's (complement.hpp) by
// the similarity machinery (association graph, cliques, rigid fits, merging, consensus) and a
// Monte Carlo search of the site (search.hpp) give poses, optimised on the complementarity
// score (complementarity.hpp) and ranked by it.
#pragma once

#include "surfcomp/core/conformers.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/docking/complementarity.hpp"
#include "surfcomp/docking/search.hpp"
#include "surfcomp/matching/match_inputs.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::docking {

/// How dock reads, describes, matches and refines.
struct DockOptions {
  /// How both sides are read and described, the receptor's site (site, pockets) and the
  /// association graph's filters (match.graph); the rest of `match` is set by dock.
  matching::MatchInputOptions inputs;
  /// The receptor's site, as a user gives it: a ligand residue to take out (the crystal's
  /// site), spheres, or pocket N of molsurf::detect_pockets; none of the three: pocket 1.
  std::string site_ligand;
  std::vector<molsurf::SiteSphere> site_spheres;
  int site_pocket = 0;
  ComplementarityOptions complementarity;  ///< the score poses are refined and ranked on
  /// Default 0: the ligand's own coordinates are docked. N >= 1: N conformers of its record
  /// (generate_conformers from the bonds alone, ETKDG seeded by conformer_seed; hydrogens as the
  /// ligand file has them) are docked instead, each matched and searched (its search seeded
  /// apart), and the distinct best poses over all of them kept. The ligand is then a file's SDF
  /// or MOL2 record. In [0, 1000].
  int conformers = 0;
  /// Default 42. ETKDG's seed for `conformers`. >= 0.
  int conformer_seed = ConformerOptions{}.seed;
  /// Default 9. The most poses reported, best first. >= 1.
  int poses = 9;
  /// Default 40. The first clique poses (consensus order) refined on the score. >= 1.
  int refine_top = 40;
  /// Besides the clique poses, the Monte Carlo search of the site (search_site).
  SearchOptions search;
  /// Default 1 A. Two refined poses whose ligand heavy atoms lie within this RMSD of each other
  /// are one pose (the better is kept). Finite, >= 0.
  double distinct_rmsd = 1.0;
  /// Default 3. A ligand whose volume exceeds this many times the free volume of the site is
  /// refused before any matching. Finite, > 0.
  double max_ligand_to_site = 3.0;
  /// Default false. The ligand's own pose alone, optimised on the score to its nearest local
  /// maximum (refine_pose) and reported as the one pose: no clique match and no search. Asks
  /// how the score judges a known pose, a crystal ligand's, after a small move. Not with
  /// conformers or score_only.
  bool local_only = false;
  /// Default false. The ligand's own pose alone, scored as it is and reported as the one pose.
  /// Not with conformers or local_only.
  bool score_only = false;
};

/// The user's options of a dock, with their ranges: the surface and description options, the
/// site's, the graph's filters, the score's terms and the pose counts.
const options::Table<DockOptions>& dock_option_table();

/// Throws OptionError naming the first of the dock's own options outside its domain.
void validate(const DockOptions& options);

/// One placement of the ligand in the receptor.
struct DockPose {
  int rank = 0;  ///< 1-based, best first
  /// Moves the ligand's coordinates into the receptor's frame.
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
  ComplementarityScore score;  ///< of the refined pose
  /// The consensus rank (1-based) of the clique alignment it was refined from; 0 for a pose of
  /// the Monte Carlo search (DockOptions::search).
  int start = 0;
  /// (receptor critical point, ligand critical point) of that alignment.
  std::vector<std::pair<int, int>> cp_pairs;
  /// True when a ligand surface point lies deeper inside the receptor than twice the clash
  /// tolerance: such poses are ranked after every pose that does not.
  bool intersects = false;
  /// 0: the ligand's own coordinates; k >= 1: DockResult::conformers[k - 1] (moved by transform).
  int conformer = 0;
};

struct DockResult {
  /// The two sides as described: the ligand in its own coordinates, or its first conformer.
  matching::PreparedInput ligand, receptor;
  /// With DockOptions::conformers: the docked conformers as MDL mol blocks, in ETKDG's order,
  /// and as described (the first is also `ligand`); DockPose::conformer k is item k - 1.
  std::vector<std::string> conformers;
  std::vector<matching::PreparedInput> conformer_inputs;
  std::vector<DockPose> poses;              ///< best first
  std::size_t starts = 0;                   ///< clique alignments found (over every conformer)
  std::vector<matching::TraceStage> trace;  ///< the association graph's stages (`ligand`'s)
  double site_volume = 0.0;                 ///< A^3: the site's free volume
  double ligand_volume = 0.0;               ///< A^3: the ligand's surface's volume
  std::vector<std::string> notes;           ///< what a reader may want to know
  std::vector<std::pair<std::string, double>> timing_ms;  ///< per step, in order
};

/// `receptor` with the site of `options` (site_ligand, site_spheres, site_pocket), or pocket 1
/// when neither it nor the options name one.
matching::MatchInput with_dock_site(matching::MatchInput receptor, const DockOptions& options);

/// A receptor's site made ready for docks into it (prepare_dock_site): its site surface built and
/// described, and its score's grid. Docks share one (it is only read).
struct DockSite {
  matching::PreparedInput receptor;            ///< the receptor's site side, as described
  std::shared_ptr<const ReceptorField> field;  ///< the score's grid over the site
  double free_volume = 0.0;                    ///< A^3: the site's free volume
  std::vector<std::pair<std::string, double>> timing_ms;  ///< per step, in order
};

/// The receptor's site of `options` (with_dock_site) prepared for docks: its surface built and
/// described as dock describes it, its grid tabulated. Throws as dock does for the receptor: a
/// structure without protein atoms, a site with no way out, a pocket out of range.
DockSite prepare_dock_site(const matching::MatchInput& receptor, const DockOptions& options);

/// Checks from names and options alone, before any work, that `ligand` can be docked as asked:
/// a molecule without a site (an SDF or MOL2 file with options.conformers). Throws OptionError
/// or InputError.
void check_dock_ligand(const matching::MatchInput& ligand, const DockOptions& options);

/// Checks from names and options alone, before any work, that a dock can be run as asked:
/// the options in their domains, the ligand a molecule without a site, the receptor a
/// structure (with_dock_site gives it its site). Throws OptionError or InputError.
void check_dock_inputs(const matching::MatchInput& ligand, const matching::MatchInput& receptor,
                       const DockOptions& options);

/// Docks `ligand` into `receptor`'s site (with_dock_site). The receptor's site surface and the
/// ligand's surface are built and described with common parameters (matching::prepare_input); the
/// receptor needs protein atoms, and a ligand more than max_ligand_to_site times the site's free
/// volume is refused (InputError). The candidates are the first refine_top alignments of the
/// site's critical points with the ligand's complement (matching::match_surfaces, consensus
/// ranking) and the local optima of the Monte Carlo search (search_site), each optimised on the
/// complementarity score (refine_pose) of the ligand's coarse sample (SearchOptions::
/// sample_spacing) and scored on its fine one (ComplementarityOptions::sample_spacing); the best
/// 4 x poses candidates are optimised further on the fine sample and the distinct poses ranked
/// by it. With options.conformers, each conformer of the ligand is
/// docked so against the one receptor field and the poses of all are ranked together. With
/// options.local_only or score_only, the one pose is the ligand's own, optimised (refine_pose on
/// the fine sample) or as it is, with no match and no search. Throws
/// InputError for a ligand or receptor given as a surface or a description alone (a dock reads
/// their atoms), and for conformers asked of a ligand that is not an SDF or MOL2 file.
DockResult dock(const matching::MatchInput& ligand, const matching::MatchInput& receptor,
                const DockOptions& options = {});

/// `ligand` docked into a prepared site, as dock above does after preparing it. The site, its
/// grid and the score's terms and weights are `site`'s (prepare_dock_site read them from its
/// options); of `options` the ligand's reading and description, the match, the search, the
/// conformers, sample_spacing, poses, local_only, score_only and the distinct and size limits
/// are read. Its timing_ms has
/// the ligand's steps only. Throws InputError for a site that was not prepared (no field).
DockResult dock(const matching::MatchInput& ligand, const DockSite& site,
                const DockOptions& options = {});

}  // namespace surfcomp::docking
