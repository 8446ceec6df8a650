// Rotation matrices (core/rotation.hpp): Rodrigues' matrix is orthogonal with determinant 1 and
// turns about its axis the right-handed way, products compose angles about one axis, and the axis
// and angle read back from a matrix are the ones it was built from.
#include "rbfib/core/constants.hpp"
#include "rbfib/core/rotation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib {
namespace {

constexpr double kTol = 1e-14;  // a few ulps of the matrix entries (all of order 1)

Vec3 apply(const Mat3& R, const Vec3& x) {
  Vec3 y{0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) y[i] += R[i][j] * x[j];
  return y;
}

TEST(Rotation, RodriguesIsAProperRotationAboutItsAxis) {
  const Vec3 axis{1, -2, 0.5};
  const Mat3 R = rotation_matrix(axis, 0.9);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double rtr = 0;
      for (int k = 0; k < 3; ++k) rtr += R[k][i] * R[k][j];
      EXPECT_NEAR(rtr, i == j ? 1.0 : 0.0, kTol);
    }
  const double det = R[0][0] * (R[1][1] * R[2][2] - R[1][2] * R[2][1]) - R[0][1] * (R[1][0] * R[2][2] - R[1][2] * R[2][0]) +
                     R[0][2] * (R[1][0] * R[2][1] - R[1][1] * R[2][0]);
  EXPECT_NEAR(det, 1.0, kTol);
  const Vec3 fixed = apply(R, axis);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(fixed[d], axis[d], kTol);
  // Right-handed: a quarter turn about e1 takes e3 to -e2, about e2 takes e3 to e1.
  const Vec3 a = apply(rotation_matrix({1, 0, 0}, pi / 2), {0, 0, 1}), b = apply(rotation_matrix({0, 1, 0}, pi / 2), {0, 0, 1});
  EXPECT_NEAR(a[1], -1.0, kTol);
  EXPECT_NEAR(b[0], 1.0, kTol);
}

TEST(Rotation, ProductsComposeAndAxisAngleReadsBack) {
  const Vec3 axis{0.3, 0.4, -1.2};
  const Mat3 AB = product(rotation_matrix(axis, 0.5), rotation_matrix(axis, 0.7)), C = rotation_matrix(axis, 1.2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(AB[i][j], C[i][j], kTol);
  const AxisAngle r = axis_angle(C);
  const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  EXPECT_NEAR(r.angle, 1.2, kTol);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(r.axis[d], axis[d] / n, kTol);
  // A matrix and the one rebuilt from its axis and angle agree.
  const Mat3 D = product(rotation_matrix({1, 0, 0}, pi / 2), rotation_matrix({0, 1, 0}, pi / 4)), E = rotation_matrix(axis_angle(D));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(D[i][j], E[i][j], kTol);
}

}  // namespace
}  // namespace rbfib
