// The evaluation sets of Chapter 3 (surface/evaluation_sets.hpp) and the measures of a triangulated
// surface: an octahedron's volume, area and centroid exactly; a spiral's weights sum to the
// sphere's area, its axis site lies on the x axis for odd n and is the rightmost site for even n;
// the triangulated unit sphere's volume converges to 4 pi / 3 at second order in the spacing.
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/surface/evaluation_sets.hpp"
#include "rbfib/surface/shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace rbfib::surface {
namespace {

TEST(EvaluationSets, AnOctahedronsMeasuresAreExact) {
  SphereSites s;
  s.lambda = {0, pi, pi / 2, -pi / 2, 0, 0};
  s.theta = {0, 0, 0, 0, pi / 2, -pi / 2};
  const std::vector<Triangle> tris = sphere_triangulation(s);
  ASSERT_EQ(tris.size(), 8u);
  std::vector<double> X = ellipsoid(1, 1, 1).points(s);
  const double shift[3] = {0.5, -2.0, 3.0};
  for (int d = 0; d < 3; ++d)
    for (int i = 0; i < 6; ++i) X[d * 6 + i] = 2 * X[d * 6 + i] + shift[d];  // an octahedron of half-diagonal 2
  const PolyhedronMeasures m = polyhedron_measures(tris, X);
  EXPECT_NEAR(m.volume, 4.0 / 3.0 * 8, 1e-12);                // (4/3) r^3
  EXPECT_NEAR(m.area, 8 * std::sqrt(3.0) / 4 * 8, 1e-12);     // 8 equilateral triangles of side 2 sqrt 2
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(m.centroid[d], shift[d], 1e-12);
}

TEST(EvaluationSets, SpiralWeightsAxisSiteAndSecondOrderVolume) {
  double previous = NAN;
  for (index_t n : {401, 1601}) {
    const EvaluationSet e = make_evaluation_set(n);
    EXPECT_NEAR(std::accumulate(e.w.begin(), e.w.end(), 0.0), 4 * pi, 1e-6);
    ASSERT_GE(e.axis_site, 0);
    EXPECT_EQ(e.Z[e.axis_site], 1.0);  // odd n: the site (n + 1) / 2 is (1, 0, 0)
    const double err = std::abs(polyhedron_measures(e.tris, e.Z).volume - 4 * pi / 3);
    if (std::isfinite(previous)) EXPECT_NEAR(std::log(previous / err) / std::log(2.0), 2.0, 0.2);  // h halves
    previous = err;
  }
  const EvaluationSet even = make_evaluation_set(400);
  EXPECT_EQ(even.axis_site, rightmost_site(even.sites));
  for (index_t i = 0; i < even.size(); ++i) EXPECT_LE(even.Z[i], even.Z[even.axis_site]);
  EXPECT_THROW(make_evaluation_set(3), InputError);
}

}  // namespace
}  // namespace rbfib::surface
