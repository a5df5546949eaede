// Matches two general triangle meshes by shape alone, as a mesh researcher would: reads REF and
// PROBE (.off .obj .ply; e.g. a mesh and a partial scan of it), takes a common length unit from
// them, describes both (critical points, geodesic patches, harmonic maps, shape images), matches
// PROBE onto REF, polishes the best pose by ICP and prints it, in the meshes' own coordinates,
// with its coverage: how much of the part lies on the whole.
// usage: match_two_meshes REF PROBE [--repair]
#include "surfcomp/core/error.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/match_inputs.hpp"

#include <cstdio>
#include <cstring>
#include <exception>

using namespace surfcomp;

namespace {

void summarise(const matching::PreparedInput& side) {
  const harmonic::DescriptorCounts counts = harmonic::count_descriptors(side.descriptors);
  std::printf("%s: %zu vertices, %zu peaks, %zu valleys, %zu shape images\n", side.name.c_str(),
              side.descriptors.surface.n_vertices(), counts.peaks, counts.valleys, counts.imaged);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4 || (argc == 4 && std::strcmp(argv[3], "--repair") != 0)) {
    std::fprintf(stderr, "usage: %s REF PROBE [--repair]   (meshes: .off .obj .ply)\n", argv[0]);
    return 1;
  }
  try {
    matching::MatchInput reference, probe;
    reference.path = argv[1];
    probe.path = argv[2];
    matching::MatchInputOptions options;  // --scale auto: the unit comes from the meshes
    options.input.repair = argc == 4;     // CGAL's repair of non-manifold, duplicate, stray parts
    options.match.icp_top = 1;            // the best pose polished by point-to-plane ICP
    const matching::InputMatch m = matching::match_inputs(reference, probe, options);
    for (const std::string& note : m.notes) std::printf("note: %s\n", note.c_str());
    summarise(m.reference);
    summarise(m.probe);
    std::printf("length unit %.6g (%s), shape only: %s\n", m.unit, m.unit_from.c_str(),
                m.shape_only ? "yes" : "no");
    if (m.result.alignments.empty()) {
      std::fprintf(stderr, "match_two_meshes: no alignment of %s onto %s found\n", argv[2],
                   argv[1]);
      return 1;
    }
    const matching::Alignment& top = m.result.alignments.front();
    std::printf("top transform (moves PROBE into REF's frame):\n");
    for (int row = 0; row < 4; ++row) {
      std::printf("  %12.6g %12.6g %12.6g %12.6g\n", top.transform(row, 0), top.transform(row, 1),
                  top.transform(row, 2), top.transform(row, 3));
    }
    std::printf("overlay score %.4f from %zu critical-point pairs\n", top.overlay.score,
                top.cp_pairs.size());
    std::printf("coverage %.3f (of REF %.3f, of PROBE %.3f within %.3g of the other)\n",
                top.coverage.score, top.coverage.reference, top.coverage.probe,
                options.match.coverage_distance * m.unit);
    return 0;
  } catch (const Error& e) {  // surfcomp's errors name the file and the problem
    std::fprintf(stderr, "match_two_meshes: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "match_two_meshes: internal error: %s\n", e.what());
    return 1;
  }
}
