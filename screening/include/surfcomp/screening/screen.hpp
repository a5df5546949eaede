// One query against a library, in three stages (docs/screening.md). The query is a molecule
// against a library of molecules, or a binding site against a pocket library (sites: the
// overlays then compare pocket linings, as MatchMode::binding_sites does):
//  1. a fast score of every entry: the whole-surface overlay score of the entry's stored packed
//     sample at the four principal-axes superpositions onto the query's, without refinement, the
//     best of the four kept (matching::PackedQuery, single precision, SIMD);
//  2. each molecule's `refine` best conformers by that score get the overlay refined
//     (SurfaceOverlay::refine) from each of their principal-axes superpositions, the best kept;
//     a molecule counts by its best conformer, refined scores above fast ones;
//  3. the full match (matching::match_surfaces, as `surfcomp match` runs it) of the query with
//     the best conformer of the `candidates` best molecules, its surface and descriptors
//     rebuilt from the stored molecule.
// Stages 1 and 2 stream through the library a block of molecules at a time, every query scored
// in the same read, and keep of each query only its best molecules (a bounded list) and, for a
// fused ranking of several queries, a bounded list of the best by fused score: the memory held
// does not grow with the library (Library::release drops the pages read and the shards passed).
// Every entry is scored independently into its own slot (TBB): the hits do not depend on the thread
// count, and a caller may split the molecules over processes (score_molecules on a range).
#pragma once

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/match.hpp"
#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/matching/packed_overlay.hpp"
#include "surfcomp/matching/site.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "surfcomp/screening/exchange.hpp"
#include "surfcomp/screening/library.hpp"

#include <Eigen/Core>

#include <array>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace surfcomp::screening {

/// How a molecule's scores against several queries make one score: their maximum, or their mean.
enum class Fusion { max, mean };
/// The names of the fusion rules, indexed by Fusion (as --fusion spells them).
inline constexpr std::array<const char*, 2> fusion_names = {"max", "mean"};

/// What ranks a molecule query's hits: `on`, the overlay score, which weighs ESP, LP and
/// heteroatoms beside shape; `off`, the shape Tanimoto of their pose; `automatic`, the score
/// for a query that carries an ionic group (carries_ionic_group; a .hsi query, which has no
/// formal charges, always) and the mean of the score and the shape Tanimoto
/// (neutral_query_shape_weight) for any other. Either way every stage overlays with chemistry
/// and picks the candidates of stage 3 by the overlay score, so the poses and the molecules
/// given the full match do not change. Site queries keep their own score.
enum class QueryChemistry { automatic, on, off };
/// The names of the chemistry rules, indexed by QueryChemistry (as --chemistry spells them).
inline constexpr std::array<const char*, 3> query_chemistry_names = {"auto", "on", "off"};
/// The weight of the shape Tanimoto beside the overlay score in the value that ranks the hits of
/// a query without an ionic group under QueryChemistry::automatic (docs/decisions.md, "Screen
/// chemistry by query": chosen leave-one-target-out over the DUD and MUV targets).
inline constexpr double neutral_query_shape_weight = 0.5;

struct ScreenOptions {
  /// Default 5. The conformers of each molecule, best fast score first, whose overlay stage 2
  /// refines. 0: no refinement.
  std::size_t refine = 5;
  /// Default 0 (all). Stage 2 refines only this many of an entry's principal-axes starts, those
  /// with the best scores (ties to the earlier start); the others keep their start scores.
  std::size_t refine_starts = 0;
  /// Default 50. The molecules, best score after stage 2 first, whose best conformer gets the
  /// full match (stage 3). 0: no full match.
  std::size_t candidates = 50;
  /// Default 100. Hits returned, best first; 0: every molecule of the library.
  std::size_t top = 100;
  /// Default Fusion::max. How the scores of several queries make one ranking (fuse_scores).
  Fusion fusion = Fusion::max;
  /// Default QueryChemistry::automatic: a molecule query without an ionic group ranks by the
  /// mean of its score and shape.
  QueryChemistry chemistry = QueryChemistry::automatic;
  /// The full match of stage 3, whose overlay options (sigma, spacing, chemistry and atom
  /// weights, refinement steps) stages 1 and 2 score and refine with too; default as
  /// `surfcomp match`.
  matching::MatchOptions match;
  /// How a candidate's stored molecule is read and its surface rebuilt in stage 3; default as
  /// `surfcomp match` (its descriptors are built with the query's DescriptorOptions).
  io::MoleculeReadOptions read;
  molsurf::MolecularSurfaceOptions surface;
  /// A pocket screen: how a candidate site's surface is built in stage 3, its surface margin
  /// raised to molsurf::site_surface_margin of the query's patch radius; default as `match`.
  molsurf::BindingSiteOptions site;
  /// Default none. Called as entries are scored, (stage 1, 2 or 3, done, total), from the worker
  /// threads (it must be thread-safe), and once with done == total at the end of each stage.
  std::function<void(int stage, std::int64_t done, std::int64_t total)> progress;
};

/// A screen as a user asks for it: the screen's stages, and how the query is read, described
/// and where its binding site is (none: a molecule query).
struct QueryScreenOptions {
  ScreenOptions screen;
  /// How the query is read (its record) and described; its site options are screen.site's
  /// (screen_query_options).
  matching::MatchInputOptions query;
  std::string site_ligand;                        ///< a site query: its ligand residue
  std::vector<molsurf::SiteSphere> site_spheres;  ///< a site query: its spheres (A)
  int site_pocket = 0;  ///< a site query: its structure's pocket N (0: none)
};

/// The user's options of a screen, each defined once: --top --refine --refine-starts
/// --candidates --record --site-ligand --site-sphere --site-pocket --site-radius --site-margin,
/// the pocket detection's options (molsurf::pocket_option_table) and --threads.
const options::Table<QueryScreenOptions>& screen_option_table();

/// Whether `options` ask for a binding-site query (a site ligand, spheres or a pocket).
bool is_site_query(const QueryScreenOptions& options);

/// `query` with the site `options` ask for, and the options it is read and described with
/// (matching::prepare_input): its record, the site's sphere radius and margin, the threads.
matching::MatchInput screen_query_input(matching::MatchInput query,
                                        const QueryScreenOptions& options);
matching::MatchInputOptions screen_query_options(const QueryScreenOptions& options);

/// The query, described once: its descriptors (stage 3) and its overlay samples (stages 1, 2), one
/// of each kind an entry's sample can be (matching::SampleKind), so that an entry is always
/// compared with a sample the query made the same way.
struct ScreenQuery {
  harmonic::SurfaceDescriptors descriptors;
  /// sample_surface(descriptors.surface, overlay spacing); of the pocket lining for a site
  matching::SurfaceSample sample;
  matching::AtomSample atoms;  ///< sample_atoms(descriptors.atoms); none for a site
  /// sample_molecule of the query's molecule (the screening surface straight from the atoms,
  /// which library entries of molecules hold); `sample` when the query has no molecule with
  /// charges (a .hsi file) or is a site.
  matching::SurfaceSample atom_sample;
  /// A binding-site query: its spheres and critical_points_in_site of its descriptors. Empty
  /// for a molecule.
  std::vector<molsurf::SiteSphere> site;
  std::vector<bool> site_points;
  /// A site on a structure: its lining residues' composition (matching::lining_composition).
  std::optional<matching::LiningComposition> lining;
  /// The two samples packed and indexed once for stages 1 and 2 (matching::PackedQuery):
  /// `packed` for `sample`, atom_packed for atom_sample.
  std::shared_ptr<const matching::PackedQuery> packed, atom_packed;
  /// The weight of the shape term in the value that ranks this query's hits, the overlay score
  /// weighing 1 - shape_weight (query_shape_weight): 0 ranks by the score, 1 by shape alone.
  double shape_weight = 0.0;
};

/// The shape weight (ScreenQuery::shape_weight) of a query under `chemistry`: 0 for a
/// binding site (`whole_molecule` false) and under `on`, 1 under `off`; under `automatic`,
/// neutral_query_shape_weight for a molecule without an ionic group and 0 for one with, or for a
/// query without `molecule` (a .hsi file).
double query_shape_weight(QueryChemistry chemistry, bool whole_molecule, const Molecule* molecule);

/// The query of a screen from its descriptors (describe_surface of its molecule's surface, or
/// a .hsi file) and, for a molecule, the molecule itself (its screening sample,
/// matching::sample_molecule with options.surface); with `site` spheres, a binding-site query
/// (descriptors from matching::describe_site) whose sample is its pocket lining
/// (matching::pocket_lining, options.match.site.overlay_radius), and with its structure as
/// `molecule` the composition of its lining residues. shape_weight is query_shape_weight's.
/// Throws InputError when its surface (or lining) has no vertex, or no ESP or LP
/// (matching::require_match_properties: entries are compared on them).
ScreenQuery make_screen_query(harmonic::SurfaceDescriptors descriptors,
                              const ScreenOptions& options = {},
                              std::vector<molsurf::SiteSphere> site = {},
                              const Molecule* molecule = nullptr);

/// Several queries are fused on one scale: when their shape weights differ, all of them rank by
/// their score (shape_weight 0). Callers of screen_queries (and of
/// score_molecules with several queries) call this on the queries first.
void agree_on_chemistry(std::vector<ScreenQuery>& queries);

/// Heavy atoms, and amino-acid residues in one chain, from which a whole-molecule query is a
/// macromolecule (macromolecule_query_warning).
inline constexpr std::size_t macromolecule_heavy_atoms = 1000;
inline constexpr std::size_t macromolecule_chain_residues = 30;

/// What to say of a whole-molecule query that is a macromolecule: more than
/// macromolecule_heavy_atoms heavy atoms, or a chain of at least macromolecule_chain_residues
/// standard amino-acid residues. Its whole surface is then compared with the library's
/// molecules, which a user rarely wants (a binding site is the usual query): the text names
/// `source` and what makes the query a macromolecule. Empty for any other query.
std::string macromolecule_query_warning(const Molecule& query, const std::string& source);

/// Throws InputError naming the library and its first entry unless that entry is a binding site
/// when `site_query` (a pocket library) and a molecule otherwise, and naming the library when it
/// holds meshes (screen_shapes screens those): a check before any work, as a library is built
/// of one kind. score_molecules checks the library so and every entry as it reads it.
void check_library_kind(const Library& library, bool site_query);

/// A score of one entry against the query.
struct HitScore {
  /// The overlay score (OverlayScore::score); for a site's full match (stage 3) the site score
  /// (matching::site_score) of that overlay and the two linings' residues.
  double score = 0.0;
  double shape = 0.0;  ///< its terms
  double chem = 0.0;
  double atoms = 0.0;
  /// Moves the entry's coordinates into the query's frame (homogeneous, row-major in CSV).
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
};

/// Stage 1 of one entry (see the file comment), from its packed sample.
HitScore fast_score(const ScreenQuery& query, const matching::PackedSampleView& entry,
                    const ScreenOptions& options = {});
/// Stage 1 of one decoded entry (its packed sample, packed now when it has none).
HitScore fast_score(const ScreenQuery& query, const LibraryEntry& entry,
                    const ScreenOptions& options = {});

/// Stage 2 of one entry (see the file comment), from its packed sample: the best of its starts'
/// scores and their refinements (matching::PackedQuery::refine).
HitScore refined_score(const ScreenQuery& query, const matching::PackedSampleView& entry,
                       const ScreenOptions& options = {});
/// Stage 2 of one decoded entry (its packed sample, packed now when it has none).
HitScore refined_score(const ScreenQuery& query, const LibraryEntry& entry,
                       const ScreenOptions& options = {});

/// One row of a screen's result: a molecule, by its best conformer.
struct Hit {
  std::size_t entry = 0;  ///< 0-based library index of the molecule's best conformer
  int stage = 1;          ///< the stage whose score `score` is: 3 for the candidates
  HitScore score;
  double fast_score = 0.0;  ///< its stage-1 score
};

/// A library's molecules are runs of consecutive entries sharing name, source and record (a build
/// writes a record's conformers together). The first entry at or after `entry` that begins a
/// molecule, or library.size(): `entry` itself when it is 0, library.size() or of another
/// molecule than entry - 1. Reads the index records of the entries it passes.
std::size_t molecule_start_at(const Library& library, std::size_t entry);

/// One row of a fused ranking of several queries.
struct FusedHit {
  std::size_t entry = 0;  ///< the molecule's best conformer against its best query
  std::size_t query = 0;  ///< 0-based: the query that scores the molecule highest (ties: first)
  double score = 0.0;     ///< the fused score
  std::vector<double> scores;  ///< the molecule's score against each query
};

/// A screen's rows and its time.
struct ScreenResult {
  std::vector<Hit> hits;
  double stage1_seconds = 0.0;  ///< wall-clock time of the fast scores
  double stage2_seconds = 0.0;  ///< wall-clock time of the refinements
  double stage3_seconds = 0.0;  ///< wall-clock time of the full matches
};

/// The whole screen in this process: score_molecules over every molecule, the first
/// options.candidates of the best through full_score (in parallel), rank_hits.
ScreenResult screen(const ScreenQuery& query, const Library& library,
                    const ScreenOptions& options = {});

/// A screen of several queries in one read of the library.
struct MultiScreenResult {
  std::vector<std::vector<Hit>> hits;  ///< per query: the rows screen() gives it alone
  std::vector<FusedHit> fused;         ///< their fused ranking (options.fusion, options.top)
  double stage1_seconds = 0.0;         ///< wall-clock times of the stages, as in ScreenResult
  double stage2_seconds = 0.0;
  double stage3_seconds = 0.0;
};

/// screen() of every query at once: the library read once for stages 1 and 2, each query's
/// rows the same as its own screen's, and their fused ranking (the molecules by their scores
/// fused by options.fusion, the queries' stage-3 scores where they have one). Throws InputError
/// when an entry is not of the queries' kind (check_library_kind) or the queries are of two
/// kinds (agree_on_chemistry), FormatError for a damaged entry.
MultiScreenResult screen_queries(const std::vector<const ScreenQuery*>& queries,
                                 const Library& library, const ScreenOptions& options = {});

/// screen_queries split over the processes of `exchange`, each called with the same queries,
/// library and options: each process runs stages 1 and 2 on its slice of whole molecules
/// (about library.size() / processes entries), process 0 gathers each query's best molecules
/// (and, for several queries, those their fused ranking may need) and picks the candidates,
/// whose full matches are dealt out round-robin and gathered. Process 0 gets the same rows as
/// one process would, bit for bit (scores travel as doubles); the others get no rows. Stage
/// times are process 0's, its stages 1 and 2 with the gathers. Throws as screen_queries and
/// what the exchange throws.
MultiScreenResult screen_queries(const std::vector<const ScreenQuery*>& queries,
                                 const Library& library, const ScreenOptions& options,
                                 Exchange& exchange);

/// The fused ranking as CSV: a header row, then one row per molecule with the columns rank,
/// entry (1-based), name, source, record, conformer, score (fused), query (1-based, the best
/// query) and score_1..score_Q, each query's score.
void write_fused_csv(std::ostream& out, const Library& library, const std::vector<FusedHit>& fused);

/// The hits as CSV: a header row, then one row per hit with the columns rank, entry (1-based),
/// name, source, record, conformer, score, stage, shape, chem, atoms, fast_score and the 16
/// numbers t00..t33 of the transform, row-major. Names and sources are quoted when they hold a
/// comma or a quote.
void write_hits_csv(std::ostream& out, const Library& library, const std::vector<Hit>& hits);

}  // namespace surfcomp::screening
