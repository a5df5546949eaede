// A screen of a library of meshes by shape alone: a mesh (a partial scan, say) matched with each
// entry as `surfcomp match ENTRY QUERY` matches them, the entries ranked by how much of the query
// lies on them under the pose found. The overlay's Tanimoto of whole surfaces cannot rank a part
// against wholes (a 30 % crop scores low on its own source); the coverage of the query can, once
// its tolerance is the query's own: measured in each pair's unit (the larger mesh's), a mesh far
// larger than the query would cover it whatever its shape. Why: docs/decisions.md#shape-retrieval.
#pragma once

#include "surfcomp/matching/match_inputs.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/screening/library.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace surfcomp::screening {

/// How a mesh query is screened.
struct ShapeScreenOptions {
  /// How the query and each entry are described and matched, as `surfcomp match` would (its
  /// input.scale and input.unit set each pair's length unit, the larger mesh's under auto);
  /// match.coverage_distance is the coverage's tolerance in the query's own unit.
  matching::MatchInputOptions inputs;
  /// Default 3. The distinct poses of a pair, best first, whose coverage is measured; the best
  /// coverage counts. >= 1.
  std::size_t poses = 3;
  /// Default 100. Hits returned, best first; 0: every entry.
  std::size_t top = 100;
  /// Default none. Called as entries are matched (done, total), from the worker threads (it
  /// must be thread-safe).
  std::function<void(std::int64_t, std::int64_t)> progress;
};

/// One entry's match with the query.
struct ShapeHit {
  std::size_t entry = 0;  ///< 0-based library index
  /// The fraction of the query's area within the tolerance of the entry under the pose (the
  /// best of the poses measured): what ranks the hits. 0 when the pair has no alignment.
  double score = 0.0;
  double entry_coverage = 0.0;  ///< the fraction of the entry's area within it of the query
  double overlay = 0.0;         ///< that pose's overlay score (shape Tanimoto)
  double unit = 0.0;  ///< the pair's length unit, in the inputs' coordinates; 0: not matched
  /// Moves the entry's coordinates into the query's frame.
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
  /// Why the pair was not matched (score 0): the query is wider than the entry, which cannot
  /// hold it as a part, or the match threw (no critical point, say); empty when it was.
  std::string note;
};

/// True when `library` holds meshes (library build of mesh files): its first entry is one.
bool is_mesh_library(const Library& library);

/// The query's own length unit (matching::MatchInputOptions::input's scale and unit), in which
/// the coverage's tolerance counts. Throws as mesh::general_mesh_unit.
double shape_query_unit(const mesh::Surface& query, const ShapeScreenOptions& options);

/// Matches `query` (a mesh, in its coordinates; described as a general mesh unless it carries
/// ESP and LP) with every entry of `library`, in parallel, and gives the options.top best hits:
/// by score, then overlay, then entry (the order does not depend on the threads). An entry
/// narrower than the query (its bounding box's diagonal below 1/1.15 of the query's widest
/// span, which a part of it cannot have) is not matched, nor one whose match throws
/// surfcomp::Error (no critical point, say): each scores 0 with the reason, unless no entry was
/// matched at all, when the first such error is thrown (the query's or the options' fault).
/// options.inputs' log and description progress are not called (the pairs run side by side).
/// Throws InputError naming the library when it does not hold meshes, and the query when it
/// has more vertices than options.inputs.input allows; OptionError for options outside their
/// domain; what reading an entry throws.
std::vector<ShapeHit> screen_shapes(const mesh::Surface& query, const Library& library,
                                    const ShapeScreenOptions& options = {});

/// The hits as CSV: rank,entry,name,source,score,entry_coverage,overlay,unit,t00..t33 (the
/// transform, row-major),note.
void write_shape_hits_csv(std::ostream& out, const Library& library,
                          const std::vector<ShapeHit>& hits);

}  // namespace surfcomp::screening
