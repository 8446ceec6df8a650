// The radial extent of a surface's points (surface/radial_extent.hpp), Chapter 3's Fig. 4 measure:
// an ellipsoid's semi-axes about its centre, wherever the centre is.
#include "rbfib/surface/radial_extent.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/shapes.hpp"

#include <gtest/gtest.h>

namespace rbfib::surface {
namespace {

TEST(RadialExtent, AnEllipsoidsSemiAxes) {
  SphereSites s;  // the six axis points and a spiral
  s.lambda = {0, 3.141592653589793, 1.5707963267948966, -1.5707963267948966, 0, 0};
  s.theta = {0, 0, 0, 0, 1.5707963267948966, -1.5707963267948966};
  const SphereSites spiral = bauer_spiral(101);
  s.lambda.insert(s.lambda.end(), spiral.lambda.begin(), spiral.lambda.end());
  s.theta.insert(s.theta.end(), spiral.theta.begin(), spiral.theta.end());
  std::vector<double> X = ellipsoid(1.5, 1.0, 0.5).points(s);
  const std::size_t n = X.size() / 3;
  const double c[3] = {2.0, -1.0, 0.25};
  for (int d = 0; d < 3; ++d)
    for (std::size_t i = 0; i < n; ++i) X[d * n + i] += c[d];
  const RadialExtent e = radial_extent(X, c);
  EXPECT_NEAR(e.max, 1.5, 1e-14);
  EXPECT_NEAR(e.min, 0.5, 1e-14);
}

}  // namespace
}  // namespace rbfib::surface
