// Internal to the molsurf module (not installed): the component filter of build_ses and
// build_sas, which drops what the grid keeps of features thinner than a voxel (and, unless
// asked for, the cavities) before the grid mesh becomes a Surface.
#pragma once

#include "ses_grid.hpp"

namespace surfcomp::molsurf::detail {

/// The smallest volumes (A^3) a component of the grid mesh must enclose to be kept.
struct ComponentVolumes {
  double outward = 0.0;  ///< an outward component (a body of the molecule)
  double cavity = 0.0;   ///< an inward one (a cavity), when cavities are kept at all
  bool keep_cavities = false;
};

/// The vertex-connected components of `soup` that are kept: outward-facing ones (positive
/// enclosed volume) of at least `limits.outward`, and with `limits.keep_cavities` inward-facing
/// ones (they line cavities) of at least `limits.cavity` in absolute value. The outward
/// component of largest volume is always kept. Vertex and face order are preserved.
TriangleSoup kept_components(const TriangleSoup& soup, const ComponentVolumes& limits);

/// The vertex-connected components of a soup, in two soups by their bounding boxes.
struct ComponentsBySize {
  TriangleSoup small;  ///< the components whose bounding box fits in the cube
  TriangleSoup large;  ///< the others
};

/// The components of `soup` whose bounding box has every side shorter than `side` (A), and the
/// others. Vertex and face order are preserved within each.
ComponentsBySize split_by_extent(const TriangleSoup& soup, double side);

}  // namespace surfcomp::molsurf::detail
