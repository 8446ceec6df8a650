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

TEST(Contact, ThePeriodicClosestDistanceUsesTheNearestImage) {
  // Two points 9 apart along x in a box 10 long, periodic in x only: 1 apart through the boundary;
  // along y (walls) the distance is the plain one.
  const PeriodicBox box{{10, 10, 10}, {true, false, true}};
  const std::array<double, 3> s = nearest_image_shift({0.5, 1, 1}, {9.5, 1, 1}, box);
  EXPECT_EQ(s[0], -10.0);
  EXPECT_EQ(s[1], 0.0);
  EXPECT_EQ(s[2], 0.0);
  EXPECT_EQ(nearest_image_shift({1, 0.5, 1}, {1, 9.5, 1}, box)[1], 0.0);  // y is not periodic
  const std::vector<double> A{0.5, 1, 1}, B{9.5, 1, 1};  // one point each, X[d n + i]
  EXPECT_NEAR(closest_points(A, 1, B, 1, nearest_image_shift({0.5, 1, 1}, {9.5, 1, 1}, box)).distance, 1.0, 1e-14);
}

}  // namespace
}  // namespace rbfib::surface
