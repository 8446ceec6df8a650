// The studies' shape helpers (studies/common/cell_shape.hpp, study.hpp): principal axes and
// extents of points on a known ellipsoid, the 3 x 3 eigenproblem, Jeffery's orbit against its
// period and plane, angle unwrapping and least-squares fits.
#include "common/cell_shape.hpp"
#include "rbfib/core/constants.hpp"
#include "common/study.hpp"
#include "rbfib/core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::study {
namespace {


TEST(CellShape, AxesAndExtentsOfARotatedEllipsoid) {
  // Points on an ellipsoid with semi-axes 3, 2, 1 along x, y, z, rotated by 30 deg about x, at (5, 6, 7).
  const long n = 2000;
  std::vector<double> X(3 * n);
  const double c = std::cos(pi / 6), s = std::sin(pi / 6);
  for (long i = 0; i < n; ++i) {
    const double z = -1 + (2 * i + 1.0) / n, lat = std::asin(z), lon = std::sqrt(pi * n) * lat;  // a Bauer spiral
    const double p[3] = {3 * std::cos(lon) * std::cos(lat), 2 * std::sin(lon) * std::cos(lat), 1 * z};
    X[i] = 5 + p[0];
    X[n + i] = 6 + c * p[1] - s * p[2];
    X[2 * n + i] = 7 + s * p[1] + c * p[2];
  }
  const CellShape sh = cell_shape(X, n, 1, 0);
  EXPECT_NEAR(sh.center[0], 5, 1e-3);
  EXPECT_NEAR(sh.center[1], 6, 1e-3);
  EXPECT_NEAR(sh.center[2], 7, 1e-3);
  // Short axis: the rotated z axis (0, -sin, cos); long axis x.
  EXPECT_NEAR(std::abs(sh.axes[0][1] * -s + sh.axes[0][2] * c), 1, 1e-6);
  EXPECT_NEAR(std::abs(sh.axes[2][0]), 1, 1e-6);
  EXPECT_NEAR(sh.extent[0], 2, 1e-2);
  EXPECT_NEAR(sh.extent[2], 6, 1e-2);
  EXPECT_THROW(cell_shape(X, n, 2, 0), InputError);  // sizes that do not match
}

TEST(CellShape, JefferyOrbitKeepsItsPlaneAndPeriod) {
  // Shear along z, gradient y: an axis in the y-z plane stays there and returns after
  // T = 2 pi (r + 1/r) / gdot; at a quarter period it has turned by more than zero.
  const double r = 0.33, gdot = 1000, T = 2 * pi * (r + 1 / r) / gdot;
  const Vec3 p0{0, std::sin(0.57), std::cos(0.57)};
  const std::vector<Vec3> p = jeffery_axis(p0, r, gdot, 2, 1, {T / 4, T / 2, T});
  for (const Vec3& q : p) EXPECT_NEAR(q[0], 0, 1e-12);
  EXPECT_GT(axis_angle(p[0], p0), 0.1);
  EXPECT_NEAR(axis_angle(p[2], p0), 0, 1e-6);
  // Half a period turns the axis by pi: the same axis.
  EXPECT_NEAR(axis_angle(p[1], p0), 0, 1e-6);
  EXPECT_THROW(jeffery_axis(p0, r, gdot, 1, 1, {T}), InputError);
}

TEST(CellShape, UnwrapAndFits) {
  const std::vector<double> a = unwrap({3.0, -3.0, -0.2}, 2 * pi);
  EXPECT_NEAR(a[1], -3.0 + 2 * pi, 1e-12);
  EXPECT_NEAR(a[2], -0.2 + 2 * pi, 1e-12);
  EXPECT_NEAR(slope({0, 1, 2, 3}, {1, 3, 5, 7}), 2, 1e-12);
  EXPECT_NEAR(power_law_order({10, 20, 40}, {1e-2, 2.5e-3, 6.25e-4}), 2, 1e-12);
  EXPECT_TRUE(std::isnan(slope({1}, {1})));
}

}  // namespace
}  // namespace rbfib::study
