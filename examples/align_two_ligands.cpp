// Aligns two ligands by their molecular surfaces: reads two molecule files, builds each one's
// solvent-excluded surface with ESP, LP and curvature, describes it (critical points, patches,
// harmonic shape images), matches PROBE onto REF and prints the top alignment.
// usage: align_two_ligands REF PROBE   (.sdf .mol .mol2 .pdb .pqr)
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/match.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include <cstdio>
#include <exception>

using namespace surfcomp;

namespace {

// Reads a molecule and describes its surface, printing a one-line summary.
harmonic::SurfaceDescriptors describe(const char* path) {
  const Molecule molecule = io::read_molecule(path);
  harmonic::SurfaceDescriptors described =
      harmonic::describe_surface(molsurf::build_molecular_surface(molecule), molecule);
  const harmonic::DescriptorCounts counts = harmonic::count_descriptors(described);
  std::printf("%s: %zu vertices, %zu peaks, %zu valleys, %zu images\n", path,
              described.surface.n_vertices(), counts.peaks, counts.valleys, counts.imaged);
  return described;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s REF PROBE   (molecule files: .sdf .mol .mol2 .pdb .pqr)\n",
                 argv[0]);
    return 1;
  }
  try {
    const harmonic::SurfaceDescriptors reference = describe(argv[1]);
    const harmonic::SurfaceDescriptors probe = describe(argv[2]);
    const matching::MatchResult result = matching::match_surfaces(reference, probe);
    if (result.alignments.empty()) {
      std::fprintf(stderr, "align_two_ligands: no alignment of %s onto %s found\n", argv[2],
                   argv[1]);
      return 1;
    }
    const matching::Alignment& top = result.alignments.front();
    std::printf("top transform (moves PROBE into REF's frame):\n");
    for (int row = 0; row < 4; ++row) {
      std::printf("  %10.6f %10.6f %10.6f %10.6f\n", top.transform(row, 0), top.transform(row, 1),
                  top.transform(row, 2), top.transform(row, 3));
    }
    std::printf("overlay score %.4f (shape %.4f, chem %.4f, atoms %.4f)\n", top.overlay.score,
                top.overlay.shape, top.overlay.chem, top.overlay.atoms);
    std::printf("rank-1 source: %s\n",
                top.source == matching::AlignmentSource::cliques ? "cliques" : "principal_axes");
    return 0;
  } catch (const Error& e) {  // surfcomp's errors name the file, the value and what was expected
    std::fprintf(stderr, "align_two_ligands: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "align_two_ligands: internal error: %s\n", e.what());
    return 1;
  }
}
