#include "surfcomp/screening/shape_screen.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/matching/surface_fit.hpp"
#include "surfcomp/mesh/length_unit.hpp"
#include "surfcomp/molsurf/load_surface.hpp"
#include "surfcomp/screening/hit_files.hpp"

#include <Eigen/LU>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <utility>

namespace surfcomp::screening {
namespace {

/// A part lies within its whole, so that its extent cannot exceed the whole's; noise of a few
/// per cent of the whole's size on each end of the part's widest span leaves this margin.
constexpr double kExtentMargin = 1.15;

/// %.9g of a value: a mesh's coordinates may be of any size.
std::string general(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value == 0.0 ? 0.0 : value);
  return text;
}

/// The length unit a mesh entry's curvature was fitted at (library_build: automatic).
double entry_unit(const mesh::Surface& surface) {
  return mesh::general_mesh_unit({&surface}, mesh::LengthScale::automatic, 0.0, surface.source())
      .value;
}

/// At most the largest distance between two of the surface's vertices: its bounding box's
/// diagonal.
double extent_above(const mesh::Surface& surface) {
  const Eigen::MatrixX3d v = surface.positions();
  return (v.colwise().maxCoeff() - v.colwise().minCoeff()).norm();
}

/// At least the largest distance between two of the surface's vertices: the farthest vertex
/// from the farthest vertex from the first, and so on twice.
double extent_below(const mesh::Surface& surface) {
  const Eigen::MatrixX3d v = surface.positions();
  if (v.rows() == 0) return 0.0;
  Eigen::Index from = 0;
  double longest = 0.0;
  for (int sweep = 0; sweep < 3; ++sweep) {
    Eigen::Index far = 0;
    const double distance =
        std::sqrt((v.rowwise() - v.row(from)).rowwise().squaredNorm().maxCoeff(&far));
    longest = std::max(longest, distance);
    from = far;
  }
  return longest;
}

/// The match of the query with one entry, as a hit; `distance` is the coverage's tolerance in
/// the inputs' coordinates. A match that throws surfcomp::Error leaves the exception in
/// `failure`.
ShapeHit match_entry(const mesh::Surface& query, double query_extent, const Library& library,
                     std::size_t e, double distance, const ShapeScreenOptions& options,
                     std::exception_ptr* failure) {
  ShapeHit hit;
  hit.entry = e;
  const LibraryEntry entry = library.entry(e);
  matching::MatchInput reference;
  reference.surface =
      harmonic::io::decode_hsi(entry.surface, entry.info.source + " (library entry)").surface;
  const double entry_extent = extent_above(*reference.surface);
  if (query_extent > kExtentMargin * entry_extent) {
    hit.note = "not matched: the query's extent (at least " + general(query_extent) +
               ") is beyond the entry's (at most " + general(entry_extent) + ")";
    return hit;
  }
  // Its curvature was fitted at its own unit, which a pair takes when the entry is the larger.
  reference.curvature_unit = entry_unit(*reference.surface);
  matching::MatchInput probe;
  probe.surface = query;
  try {
    // The poses whose coverage is measured are refined in double precision, not left where
    // the single-precision refinement stopped (MatchOptions::fine_top).
    matching::MatchInputOptions inputs = options.inputs;
    if (inputs.match.fine_top > 0) {
      inputs.match.fine_top = std::max(
          inputs.match.fine_top, static_cast<int>(std::min<std::size_t>(options.poses, 1000)));
    }
    const matching::InputMatch found = matching::match_inputs(reference, probe, inputs);
    hit.unit = found.unit;
    const matching::SurfaceFit fit(found.reference.descriptors.surface,
                                   found.probe.descriptors.surface);
    std::size_t measured = 0;
    for (const matching::Alignment& alignment : found.result.alignments) {
      if (alignment.repeat_of != 0) continue;
      const matching::CoverageScore coverage =
          fit.coverage(matching::RigidTransform::from_matrix(alignment.transform), distance);
      if (measured == 0 || coverage.probe > hit.score) {
        hit.score = coverage.probe;
        hit.entry_coverage = coverage.reference;
        hit.overlay = alignment.overlay.score;
        hit.transform = alignment.transform.inverse();
      }
      if (++measured == options.poses) break;
    }
  } catch (const Error& error) {
    hit = ShapeHit{};
    hit.entry = e;
    hit.note = std::string("not matched: ") + error.what();
    *failure = std::current_exception();
  }
  return hit;
}

}  // namespace

bool is_mesh_library(const Library& library) {
  return library.size() > 0 && library.entry(0).molecule.format == io::RecordFormat::mesh;
}

double shape_query_unit(const mesh::Surface& query, const ShapeScreenOptions& options) {
  return mesh::general_mesh_unit({&query}, options.inputs.input.scale, options.inputs.input.unit,
                                 query.source())
      .value;
}

std::vector<ShapeHit> screen_shapes(const mesh::Surface& query, const Library& library,
                                    const ShapeScreenOptions& options) {
  if (options.poses < 1) throw OptionError("shape screen: poses must be at least 1");
  const double tolerance = options.inputs.match.coverage_distance;
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw OptionError("shape screen: coverage_distance must be finite and > 0");
  molsurf::check_vertex_limit(query, options.inputs.input);
  if (!is_mesh_library(library)) {
    throw InputError(library.path().string() +
                     ": not a library of meshes (library build MESH...); a mesh query is "
                     "screened against meshes");
  }
  const double distance = tolerance * shape_query_unit(query, options);
  // The pairs' coverage is measured here, at the query's tolerance; the pairs run side by side,
  // so that a log or a progress line of one description would interleave with the others'.
  ShapeScreenOptions pair = options;
  pair.inputs.match.coverage_distance = 0.0;
  pair.inputs.log = nullptr;
  pair.inputs.descriptors.progress = nullptr;
  const double query_extent = extent_below(query);
  std::vector<ShapeHit> hits(library.size());
  std::vector<std::exception_ptr> failures(library.size());
  std::atomic<std::int64_t> done{0};
  const auto total = static_cast<std::int64_t>(hits.size());
  tbb::parallel_for(std::size_t{0}, hits.size(), [&](std::size_t e) {
    hits[e] = match_entry(query, query_extent, library, e, distance, pair, &failures[e]);
    if (options.progress) options.progress(++done, total);
  });
  // A query (or an option) that no entry can be matched with is the query's fault, not the
  // entries': the first failure says why.
  const auto matched =
      std::count_if(hits.begin(), hits.end(), [](const ShapeHit& hit) { return hit.note.empty(); });
  const auto failed = std::find_if(failures.begin(), failures.end(),
                                   [](const std::exception_ptr& p) { return p != nullptr; });
  if (matched == 0 && failed != failures.end()) std::rethrow_exception(*failed);
  std::stable_sort(hits.begin(), hits.end(), [](const ShapeHit& a, const ShapeHit& b) {
    if (a.score != b.score) return a.score > b.score;
    if (a.overlay != b.overlay) return a.overlay > b.overlay;
    return a.entry < b.entry;
  });
  if (options.top > 0 && hits.size() > options.top) hits.resize(options.top);
  return hits;
}

void write_shape_hits_csv(std::ostream& out, const Library& library,
                          const std::vector<ShapeHit>& hits) {
  out << "rank,entry,name,source,score,entry_coverage,overlay,unit";
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out << ",t" << r << c;
  }
  out << ",note\n";
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const ShapeHit& hit = hits[i];
    const LibraryEntryInfo info = library.info(hit.entry);
    out << i + 1 << ',' << hit.entry + 1 << ',' << csv_field(info.name) << ','
        << csv_field(info.source) << ',' << general(hit.score) << ',' << general(hit.entry_coverage)
        << ',' << general(hit.overlay) << ',' << general(hit.unit);
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) out << ',' << general(hit.transform(r, c));
    }
    out << ',' << csv_field(hit.note) << '\n';
  }
}

}  // namespace surfcomp::screening
