// The surface stage of the pipeline: molecule -> SES with per-vertex ESP, LP and curvature,
// or a surface read elsewhere -> the same properties (method §1).
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/mesh/curvature.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/potentials.hpp"
#include "surfcomp/molsurf/ses.hpp"

namespace surfcomp::molsurf {

struct MolecularSurfaceOptions {
  SesOptions ses;  ///< probe 1.4 A, about 2.5 vertices per A^2
  EspOptions esp;  ///< eps = 1, Coulomb
  LpOptions lp;    ///< Fauchere kernel exp(-d)
  /// Curvature fitted over a 2 A neighbourhood rather than CurvatureOptions' 2-ring default: a
  /// fixed size in A makes the shape index, and so the harmonic shape images, independent of
  /// the vertex density (docs/decisions.md#curvature-neighbourhood).
  mesh::CurvatureOptions curvature = [] {
    mesh::CurvatureOptions options;
    options.radius = 2.0;
    return options;
  }();
};

/// The atoms of a molecule as balls, in its order.
struct AtomBalls {
  Eigen::MatrixX3d centers;  ///< #A by 3, A
  Eigen::VectorXd radii;     ///< #A, A
};

/// The centres and radii of `molecule`'s atoms (no check: validate_molecule does that).
AtomBalls atom_balls(const Molecule& molecule);

/// Builds the solvent-excluded surface of `molecule` (atom positions and radii) and assigns the
/// vertex properties esp (kcal/(mol*e)), lp, cc1, cc2 (1/A), shape_index and curvedness.
/// Preconditions: validate_molecule(molecule) passes (checked; throws InputError otherwise).
/// The result is closed, 2-manifold and outward-oriented (checked; TopologyError otherwise).
mesh::Surface build_molecular_surface(const Molecule& molecule,
                                      const MolecularSurfaceOptions& options = {});

/// Adds curvature properties (cc1, cc2, shape_index, curvedness) to a surface made elsewhere
/// and, when `molecule` is given, esp and lp at its vertices. Normals are computed if absent.
/// Properties the surface already has under other names are kept.
void assign_surface_properties(mesh::Surface& surface, const Molecule* molecule,
                               const MolecularSurfaceOptions& options = {});

}  // namespace surfcomp::molsurf
