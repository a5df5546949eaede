// A ligand's description as the pocket sees it (docs/method.md#15-complementarity): the same
// surface looked at from outside it, facing it. Where the ligand bulges the pocket must hollow,
// where its ESP is positive the pocket's must be negative, and a patch seen from the facing
// side is the mirror of the patch seen from its own. Matching a pocket's description against
// this complement with the similarity machinery (matching::match_surfaces) pairs the ligand's
// peaks with the pocket's valleys, compares each image with the mirror of the other and finds
// the rigid motions that put the ligand into the pocket.
#pragma once

#include "surfcomp/harmonic/shape_image.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"

namespace surfcomp::docking {

/// `image` seen from the other side of its patch: the disk reflected across its u axis (the
/// value at polar angle theta is the original's at -theta: sector s becomes sector
/// (sectors - s) mod sectors, with its validity, face and barycentric coordinates) and the
/// values negated (a shape index or a curvature changes sign with the normal).
harmonic::ShapeImage mirrored_image(const harmonic::ShapeImage& image);

/// The complement of a description: every critical point's type swapped (a peak becomes a
/// valley), its curvatures and shape index negated (cc1, cc2 -> -cc2, -cc1), its normal reversed
/// and its ESP negated (LP kept: like faces like); every map reflected (v -> -v) and every image
/// mirrored (mirrored_image); the surface's "esp" property negated. Positions, patches and atoms
/// are unchanged, so that a transform found for the complement moves the original.
harmonic::SurfaceDescriptors complement(harmonic::SurfaceDescriptors descriptors);

}  // namespace surfcomp::docking
