// The fuzzy chemical filter's pieces (method §5.2):
// autoscaled surface properties, five fuzzy sets per property and a similarity of two
// membership vectors.
#pragma once

#include "surfcomp/harmonic/surface_descriptors.hpp"

#include <array>
#include <string>
#include <vector>

namespace surfcomp::matching {

/// Memberships of a value in the five fuzzy sets high-, -, neutral, +, high+ (method §5.2).
using FuzzyMemberships = std::array<double, 5>;

/// The memberships of an autoscaled value z (a z-score, dimensionless) in five triangular fuzzy
/// sets centred at -2, -1, 0, 1, 2 with half-width 1 [choice, method §5.2]; the outer two are
/// shoulders (high- is 1 for z <= -2, high+ is 1 for z >= 2). At most two sets are non-zero
/// and the memberships always sum to 1 (a partition of unity): z = 0.5 gives
/// (0, 0, 0.5, 0.5, 0). Throws InputError when z is NaN (infinities take the shoulders).
FuzzyMemberships fuzzy_memberships(double z);

/// The similarity of two membership vectors: sum_k min(m_k, n_k) / sum_k max(m_k, n_k) (a
/// fuzzy Jaccard index [choice, method §5.2]) in [0, 1]: 1 for equal vectors, 0 when no set holds
/// both, symmetric. Throws InputError when both vectors are all zero (the ratio is undefined).
double fuzzy_similarity(const FuzzyMemberships& m, const FuzzyMemberships& n);

/// fuzzy_similarity of the memberships of two autoscaled values; e.g. 0 vs 0.5 gives 0.5 / 1.5
/// = 1/3, values two or more apart give 0. NaN when either value is NaN.
double fuzzy_similarity(double z_a, double z_b);

/// The autoscaled value of each critical point's property `property` ("esp" or "lp"): its
/// disc average (CriticalPoint::esp or ::lp) minus the mean of the vertex property of that
/// name over all vertices of descriptors.surface, divided by the property's population
/// standard deviation over those vertices (method §5.2: autoscaled properties, so that the most
/// positive regions of two molecules match whatever their net charges). One value per
/// critical point, in descriptors.critical_points order. All NaN when the surface has no such
/// property (then the fuzzy filter does not filter on it); all 0 when the property is constant
/// over the surface (standard deviation <= 1e-12 max(1, |mean|)). Throws InputError for a property
/// other than esp or lp.
std::vector<double> autoscaled_point_values(const harmonic::SurfaceDescriptors& descriptors,
                                            const std::string& property);

}  // namespace surfcomp::matching
