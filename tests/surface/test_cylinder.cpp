// Points on a cylinder (surface/cylinder.hpp): on the radius, inside the length, ring counts from
// the spacing, alternate rings staggered; the triangles close each ring and face outward.
#include "rbfib/core/constants.hpp"
#include "rbfib/surface/cylinder.hpp"
#include "rbfib/surface/geometry_kernels.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::surface {
namespace {

TEST(Cylinder, PointsOnTheRadiusInRingsAlongX) {
  const CylinderPoints c = cylinder_points(5.0, -8.0, 8.0, 0.5);
  EXPECT_EQ(c.around, 63);  // round(2 pi 5 / 0.5)
  EXPECT_EQ(c.along, 32);
  const index_t n = c.size();
  ASSERT_EQ(c.X.size(), std::size_t(3 * n));
  for (index_t q = 0; q < n; ++q) {
    EXPECT_NEAR(std::hypot(c.X[n + q], c.X[2 * n + q]), 5.0, 1e-12);
    EXPECT_GT(c.X[q], -8.0);
    EXPECT_LT(c.X[q], 8.0);
  }
  EXPECT_DOUBLE_EQ(c.X[0], -8.0 + 0.25);
  EXPECT_NEAR(std::atan2(c.X[2 * n + c.around], c.X[n + c.around]), pi / 63, 1e-12);  // ring 1 turned
}

TEST(Cylinder, TrianglesCloseTheRingsAndFaceOutward) {
  const CylinderPoints c = cylinder_points(1.0, 0.0, 2.0, 0.25);
  const std::vector<Triangle> T = cylinder_triangles(c);
  ASSERT_EQ(T.size(), std::size_t(2 * c.around * (c.along - 1)));
  const index_t n = c.size();
  for (const Triangle& t : T) {
    double e1[3], e2[3], nn[3];
    for (int k = 0; k < 3; ++k) {
      e1[k] = c.X[k * n + t[1]] - c.X[k * n + t[0]];
      e2[k] = c.X[k * n + t[2]] - c.X[k * n + t[0]];
    }
    cross3(e1, e2, nn);
    const double radial = nn[1] * c.X[n + t[0]] + nn[2] * c.X[2 * n + t[0]];
    EXPECT_GT(radial, 0.0);
  }
}

}  // namespace
}  // namespace rbfib::surface
