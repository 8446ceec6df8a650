// Measures of placed cells (cells/measure.hpp) on point sets whose answers are known: a cell's
// columns out of a batch, extents across a periodic boundary, the section and silhouette of a
// circle, the inclination, extents and Taylor deformation of a rotated ellipse, the point farthest
// along a direction, and the period of a steadily turning angle.
#include "rbfib/cells/measure.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::cells {
namespace {

constexpr double kTol = 1e-12;  // relative to lengths of order 1 (a few hundred ulps of sums of n terms)

/// n points (n x 3) of an ellipse with semi-axes a (along e_z) and b (along e_y), turned by `angle`
/// from e_z toward e_y, about c, at x = c[0].
std::vector<double> ellipse(index_t n, double a, double b, double angle, const Vec3& c) {
  std::vector<double> X(std::size_t(3 * n));
  for (index_t i = 0; i < n; ++i) {
    const double s = 2 * pi * double(i) / double(n), p = a * std::cos(s), q = b * std::sin(s);
    X[std::size_t(i)] = c[0];
    X[std::size_t(n + i)] = c[1] + std::sin(angle) * p + std::cos(angle) * q;
    X[std::size_t(2 * n + i)] = c[2] + std::cos(angle) * p - std::sin(angle) * q;
  }
  return X;
}

TEST(Measure, CellPointsTakesOneCellsColumns) {
  const index_t n = 3, N = 2;
  std::vector<double> X(std::size_t(3 * N * n));
  for (std::size_t k = 0; k < X.size(); ++k) X[k] = double(k);
  const std::vector<double> P = cell_points(X, n, N, 1);  // columns d N + 1 = 1, 3, 5
  const std::vector<double> expected{3, 4, 5, 9, 10, 11, 15, 16, 17};
  EXPECT_EQ(P, expected);
  EXPECT_THROW(cell_points(X, n, N, 2), InputError);
}

TEST(Measure, ExtentsTakeTheNearestPeriodicImage) {
  // Two points 1 apart across the periodic boundary x = 0 = 10, and 3 apart in y (not periodic).
  const std::vector<double> X{9.5, 0.5, 1, 4, 0, 0};
  const surface::PeriodicBox box{{10, 10, 10}, {true, false, true}};
  const std::vector<double> e = extents(X, 2, {0.2, 2.5, 0}, {{1, 0, 0}, {0, 1, 0}, {std::sqrt(0.5), std::sqrt(0.5), 0}}, box);
  EXPECT_NEAR(e[0], 1, kTol);
  EXPECT_NEAR(e[1], 3, kTol);
  EXPECT_NEAR(e[2], std::sqrt(0.5) * 4, kTol);
  EXPECT_NEAR(extents(X, 2, {0, 0, 0}, {{1, 0, 0}})[0], 9, kTol);  // without periodicity: the far pair
}

TEST(Measure, OutlineOfACircle) {
  // A circle of radius 2 in the plane x = 1, seen along e_x: every point lies in the section
  // (|x - 1| < 0.1) and the silhouette has one point per angular bin, all at radius 2.
  const index_t n = 720;
  const std::vector<double> X = ellipse(n, 2, 2, 0, {1, 3, 5});
  const Outline o = outline(X, n, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {5, 3}, 1, 0.1, 72);
  EXPECT_EQ(o.section.size(), std::size_t(n));
  ASSERT_EQ(o.silhouette.size(), std::size_t(72));
  for (const auto& p : o.silhouette) EXPECT_NEAR(std::hypot(p[0], p[1]), 2, kTol);
  EXPECT_TRUE(outline(X, n, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {5, 3}, 1.5, 0.1).section.empty());  // the plane x = 1.5 misses it
}

TEST(Measure, ProfileOfARotatedEllipse) {
  const index_t n = 3600;  // the extremes s = 0, pi/2 are among the points
  for (const double angle : {0.3, -1.1}) {
    const Vec3 c{0, 1, 2};
    const Profile p = profile(ellipse(n, 3, 1, angle, c), n, c, 2, 1);
    EXPECT_NEAR(p.inclination, angle, kTol);
    EXPECT_NEAR(p.length, 6, 1e-6);  // the extents of n points: the extremes within (2 pi / n)^2
    EXPECT_NEAR(p.breadth, 2, 1e-6);
    EXPECT_NEAR(p.taylor(), 0.5, 1e-6);
  }
}

TEST(Measure, FarthestAlongADirection) {
  const index_t n = 8;
  const std::vector<double> X = ellipse(n, 1, 1, 0, {0, 0, 0});  // point i at angle 2 pi i / n from e_z toward e_y
  EXPECT_EQ(farthest_along(X, n, {0, 0, 0}, {0, 1, 0}), 2);
  EXPECT_EQ(farthest_along(X, n, {0, 0, 0}, {0, 0, -1}), 4);
}

TEST(Measure, RevolutionStrainOfASteadyTurn) {
  // An angle falling by 2 pi every 7 units of strain, sampled every 0.25: the period from any start.
  std::vector<double> s, a;
  for (int i = 0; i <= 100; ++i) s.push_back(0.25 * i), a.push_back(1 - 2 * pi * 0.25 * i / 7);
  EXPECT_NEAR(revolution_strain(s, a, 0), 7, kTol);
  EXPECT_NEAR(revolution_strain(s, a, 3.1), 7, kTol);
  EXPECT_TRUE(std::isnan(revolution_strain(s, a, 20)));   // the samples end first
  EXPECT_TRUE(std::isnan(revolution_strain(s, a, -1)));   // before the samples
}

TEST(CellShape, AxesAndExtentsOfARotatedEllipsoid) {
  // Points on an ellipsoid with semi-axes 3, 2, 1 along x, y, z, rotated by 30 deg about x, at (5, 6, 7).
  const index_t n = 2000;
  std::vector<double> X(3 * n);
  const double c = std::cos(pi / 6), s = std::sin(pi / 6);
  for (index_t i = 0; i < n; ++i) {
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

}  // namespace
}  // namespace rbfib::cells
