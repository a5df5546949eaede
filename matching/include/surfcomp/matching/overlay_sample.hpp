// The points the whole-surface overlay (overlay.hpp) compares: a surface sampled as
// area-weighted points, and a molecule's heteroatoms.
//
// The vertices are pooled in cubic cells of edge `spacing`, each cell giving one point (the
// area-weighted mean position, unit normal, ESP and LP of its vertices) whose weight is the
// cell's vertex area (A^2). Why this sampling and its default spacing:
// docs/decisions.md#overlay-sampling-and-width.
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace surfcomp::matching {

/// Area-weighted points of a surface (see the file comment). Columns of the matrices and
/// entries of the vectors belong to one point.
struct SurfaceSample {
  Eigen::Matrix3Xd points;   ///< A
  Eigen::Matrix3Xd normals;  ///< unit, outward
  Eigen::VectorXd weights;   ///< A^2; they sum to the area of the sampled vertices
  Eigen::VectorXd esp;       ///< the surface's "esp" property, 0 where it has none
  Eigen::VectorXd lp;        ///< the surface's "lp" property, 0 where it has none

  std::size_t size() const { return static_cast<std::size_t>(points.cols()); }
};

/// The heteroatoms (heavy atoms other than carbon) of a molecule, for the atom term.
struct AtomSample {
  Eigen::Matrix3Xd points;            ///< A
  std::vector<std::string> elements;  ///< one per column of points

  std::size_t size() const { return elements.size(); }
};

/// The heteroatoms among `atoms` (hydrogens and carbons dropped), in their order.
AtomSample sample_atoms(const std::vector<harmonic::SurfaceAtom>& atoms);

/// The sample of `surface`'s vertices whose flag in `vertex_mask` is set (all when null), pooled
/// in cells of `spacing` A; cells are ordered by their integer coordinates (deterministic).
/// Vertex normals are the surface's, or are computed when it has none. Throws InputError when
/// the mask has the wrong size; OptionError when spacing <= 0 or is not finite.
SurfaceSample sample_surface(const mesh::Surface& surface, double spacing,
                             const std::vector<bool>* vertex_mask = nullptr);

/// Default 0.5 A: the grid on which sample_molecule finds its surface points
/// (molsurf::SesPointOptions::grid_spacing).
inline constexpr double screening_grid_spacing = 0.5;

/// The screening sample of a molecule, built straight from its atoms: the points where its SES
/// crosses a grid of `grid_spacing` (molsurf::ses_points, probe `surface.ses.probe_radius`) pooled
/// in cells of `spacing` A as sample_surface pools vertices, with the ESP and LP (`surface.esp`,
/// `surface.lp`) computed at each pooled point. It stands in for sample_surface of the full
/// surface where only the overlay needs it (a screen's first two stages), at a fraction of the
/// cost: docs/decisions.md#screening-surface. Throws InputError for a molecule that
/// validate_molecule refuses or a grid over surface.ses.max_grid_cells; OptionError when spacing
/// is not finite and > 0.
SurfaceSample sample_molecule(const Molecule& molecule, double spacing,
                              const molsurf::MolecularSurfaceOptions& surface = {},
                              double grid_spacing = screening_grid_spacing);

}  // namespace surfcomp::matching
