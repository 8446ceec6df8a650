// Contact tests: the winding number of a triangulated closed surface is 1 inside and 0 outside
// (to rounding), and the closest pair of two point sets is found with its distance.
#include "rbfib/surface/contact.hpp"
#include "rbfib/surface/point_sets.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::surface {
namespace {

TEST(Contact, WindingNumberIsOneInsideAndZeroOutside) {
  const SphereSites z = bauer_spiral(200);
  const std::vector<Triangle> tris = sphere_triangulation(z);
  // An ellipsoid 2 x 1 x 0.5 over the sphere's triangulation (the map keeps the orientation).
  const index_t n = z.size();
  std::vector<double> X(std::size_t(3 * n));
  for (index_t i = 0; i < n; ++i) {
    double x[3];
    unit_sphere_point(z.lambda[i], z.theta[i], x);
    X[std::size_t(i)] = 2 * x[0], X[std::size_t(n + i)] = x[1], X[std::size_t(2 * n + i)] = 0.5 * x[2];
  }
  EXPECT_NEAR(winding_number(X, n, tris, {0, 0, 0}), 1.0, 1e-12);
  EXPECT_NEAR(winding_number(X, n, tris, {1.5, 0.2, 0.1}), 1.0, 1e-12);
  EXPECT_NEAR(winding_number(X, n, tris, {2.5, 0, 0}), 0.0, 1e-12);
  EXPECT_NEAR(winding_number(X, n, tris, {0, 0, 0.6}), 0.0, 1e-12);
  const Closest c = closest_points(X, n, X, n, {4.5, 0, 0});
  EXPECT_NEAR(c.distance, 0.5, 0.05);  // the tips at x = 2 and x = -2 + 4.5, up to the sites' spacing
  EXPECT_GT(X[std::size_t(c.a)], 1.9);
}

}  // namespace
}  // namespace rbfib::surface
