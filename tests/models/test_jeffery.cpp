// Jeffery's orbit of a rigid spheroid in shear (models/jeffery.hpp) against its period and plane.
#include "rbfib/models/jeffery.hpp"

#include "rbfib/cells/measure.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::models {
namespace {

TEST(Jeffery, OrbitKeepsItsPlaneAndPeriod) {
  // Shear along z, gradient y: an axis in the y-z plane stays there and returns after
  // T = 2 pi (r + 1/r) / gdot; at a quarter period it has turned by more than zero.
  const double r = 0.33, gdot = 1000, T = 2 * pi * (r + 1 / r) / gdot;
  const Vec3 p0{0, std::sin(0.57), std::cos(0.57)};
  const std::vector<Vec3> p = jeffery_axis(p0, r, gdot, 2, 1, {T / 4, T / 2, T});
  for (const Vec3& q : p) EXPECT_NEAR(q[0], 0, 1e-12);
  EXPECT_GT(cells::angle_between_axes(p[0], p0), 0.1);
  EXPECT_NEAR(cells::angle_between_axes(p[2], p0), 0, 1e-6);
  // Half a period turns the axis by pi: the same axis.
  EXPECT_NEAR(cells::angle_between_axes(p[1], p0), 0, 1e-6);
  EXPECT_THROW(jeffery_axis(p0, r, gdot, 1, 1, {T}), InputError);
}

}  // namespace
}  // namespace rbfib::models
