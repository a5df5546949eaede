// The fuzzy chemical filter's pieces (method §5.2): triangular memberships on autoscaled
// values, their similarity, and the autoscaling of critical point properties.
#include "surfcomp/matching/fuzzy.hpp"
#include "surfcomp/core/error.hpp"

#include "analytic_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace surfcomp {
namespace {

using matching::fuzzy_memberships;
using matching::fuzzy_similarity;

TEST(Fuzzy, MembershipsAreOneHotAtTheCentresAndSumToOne) {
  for (int centre = -2; centre <= 2; ++centre) {
    const auto m = fuzzy_memberships(centre);
    for (int k = 0; k < 5; ++k)
      EXPECT_DOUBLE_EQ(m[static_cast<std::size_t>(k)], k == centre + 2 ? 1.0 : 0.0);
  }
  for (double z = -4.0; z <= 4.0; z += 0.037) {
    const auto m = fuzzy_memberships(z);
    double sum = 0.0;
    int nonzero = 0;
    for (const double v : m) {
      EXPECT_GE(v, 0.0);
      sum += v;
      nonzero += v > 0.0;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << z;
    EXPECT_LE(nonzero, 2) << z;
  }
  const auto half = fuzzy_memberships(0.5);
  EXPECT_DOUBLE_EQ(half[2], 0.5);
  EXPECT_DOUBLE_EQ(half[3], 0.5);
  const auto m = fuzzy_memberships(-1.25);
  EXPECT_DOUBLE_EQ(m[0], 0.25);
  EXPECT_DOUBLE_EQ(m[1], 0.75);
  // Shoulders: everything beyond +-2 is fully "high".
  EXPECT_DOUBLE_EQ(fuzzy_memberships(-7.0)[0], 1.0);
  EXPECT_DOUBLE_EQ(fuzzy_memberships(3.5)[4], 1.0);
  EXPECT_DOUBLE_EQ(fuzzy_memberships(std::numeric_limits<double>::infinity())[4], 1.0);
  EXPECT_THROW(fuzzy_memberships(std::nan("")), InputError);
}

TEST(Fuzzy, SimilarityIsOneForEqualZeroForFarApartSymmetricAndKnownInBetween) {
  for (const double z : {-3.0, -1.3, 0.0, 0.2, 1.7, 5.0})
    EXPECT_DOUBLE_EQ(fuzzy_similarity(z, z), 1.0);
  EXPECT_DOUBLE_EQ(fuzzy_similarity(-2.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(fuzzy_similarity(0.0, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(fuzzy_similarity(-3.0, 3.0), 0.0);
  // 0 -> (0,0,1,0,0), 0.5 -> (0,0,.5,.5,0): min sum 0.5, max sum 1.5.
  EXPECT_DOUBLE_EQ(fuzzy_similarity(0.0, 0.5), 1.0 / 3.0);
  // 0.25 -> (0,0,.75,.25,0), 0.75 -> (0,0,.25,.75,0): min .5, max 1.5.
  EXPECT_DOUBLE_EQ(fuzzy_similarity(0.25, 0.75), 1.0 / 3.0);
  // Beyond the shoulder values are equal: 2.5 and 9 are both "high +".
  EXPECT_DOUBLE_EQ(fuzzy_similarity(2.5, 9.0), 1.0);
  for (double x = -2.5; x <= 2.5; x += 0.31) {
    for (double y = -2.5; y <= 2.5; y += 0.29) {
      const double s = fuzzy_similarity(x, y);
      EXPECT_DOUBLE_EQ(s, fuzzy_similarity(y, x));
      EXPECT_GE(s, 0.0);
      EXPECT_LE(s, 1.0);
    }
  }
  // Within the centres the similarity of d apart is (1 - d) / (1 + d).
  EXPECT_NEAR(fuzzy_similarity(-0.8, -0.6), 0.8 / 1.2, 1e-12);
  EXPECT_TRUE(std::isnan(fuzzy_similarity(std::nan(""), 0.0)));
  EXPECT_THROW(fuzzy_similarity(matching::FuzzyMemberships{}, matching::FuzzyMemberships{}),
               InputError);
}

TEST(Fuzzy, PointValuesAreZScoresAgainstTheirOwnSurface) {
  harmonic::SurfaceDescriptors d;
  d.surface = test::icosphere(3.0, 2);  // 42 vertices
  const auto n = static_cast<Eigen::Index>(d.surface.n_vertices());
  Eigen::VectorXd esp(n);
  for (Eigen::Index i = 0; i < n; ++i) esp[i] = i % 2 == 0 ? 10.0 : 14.0;  // mean 12, sd 2
  d.surface.set_property(mesh::property::esp, esp);
  d.surface.set_property(mesh::property::lp, Eigen::VectorXd::Constant(n, 0.7));
  for (const double value : {12.0, 16.0, 9.0}) {
    harmonic::CriticalPointDescriptor cp;
    cp.point.esp = value;
    cp.point.lp = 5.0;
    d.critical_points.push_back(cp);
  }
  const auto z = matching::autoscaled_point_values(d, mesh::property::esp);
  ASSERT_EQ(z.size(), 3u);
  EXPECT_DOUBLE_EQ(z[0], 0.0);
  EXPECT_DOUBLE_EQ(z[1], 2.0);
  EXPECT_DOUBLE_EQ(z[2], -1.5);
  // Constant property: every z is 0.
  for (const double v : matching::autoscaled_point_values(d, mesh::property::lp)) EXPECT_EQ(v, 0.0);
  d.surface.remove_property(mesh::property::lp);
  for (const double v : matching::autoscaled_point_values(d, mesh::property::lp))
    EXPECT_TRUE(std::isnan(v));
  EXPECT_THROW(matching::autoscaled_point_values(d, "shape_index"), InputError);
}

}  // namespace
}  // namespace surfcomp
