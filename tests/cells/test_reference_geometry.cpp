// Measures of a reference shape (cells/reference_geometry.hpp): the Evans-Fung area by Simpson's
// rule against an independent quadrature of |X_l x X_t| and against its own refinement, and the
// support function against the shape's known extents, rotated and not.
#include "rbfib/cells/reference_geometry.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/units.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::cells {
namespace {

const double R0 = 3.91 * units::um;

TEST(ReferenceGeometry, EvansFungAreaConvergesToTheSurfaceArea) {
  const double A = evans_fung_area(R0);
  EXPECT_NEAR(A / (units::um * units::um), 134.19, 0.01);  // the value of Evans and Fung's shape
  EXPECT_NEAR(evans_fung_area(R0, 2000), A, 1e-10 * A);   // Simpson: converged long before 20,000
  // Independent: the midpoint rule on |X_l x X_t| by central differences of the shape's map (the
  // integrand is smooth and periodic in l; in t it is smooth on (-pi/2, pi/2), error O(h^2)).
  const ReferenceShape shape = evans_fung_red_cell(R0);
  const int nt = 2000;
  const double ht = pi / nt, e = 1e-6;
  double area = 0;
  for (int j = 0; j < nt; ++j) {
    const double t = -pi / 2 + (j + 0.5) * ht;
    double xl[2][3], xt[2][3];
    shape.position(-e, t, xl[0]), shape.position(e, t, xl[1]), shape.position(0, t - e, xt[0]), shape.position(0, t + e, xt[1]);
    double a[3], b[3];
    for (int d = 0; d < 3; ++d) a[d] = (xl[1][d] - xl[0][d]) / (2 * e), b[d] = (xt[1][d] - xt[0][d]) / (2 * e);
    const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    area += 2 * pi * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) * ht;  // axisymmetric: the same at every l
  }
  EXPECT_NEAR(area, A, 1e-5 * A);
}

TEST(ReferenceGeometry, SupportIsTheHullsExtent) {
  const ReferenceShape shape = evans_fung_red_cell(R0);
  const Mat3 I = rotation_matrix({0, 0, 1}, 0);
  EXPECT_NEAR(support(shape, I, {1, 0, 0}), R0, 1e-12 * R0);  // the rim, on the grid
  // Along the axis: half the thickness, max over t of R0 zeta(cos^2 t) sin t by a fine 1D search.
  double half = 0;
  for (int j = 0; j <= 200000; ++j) {
    const double t = pi / 2 * j / 200000, r = std::cos(t) * std::cos(t);
    half = std::max(half, R0 * (0.105 + r - 0.56 * r * r) * std::sin(t));
  }
  EXPECT_NEAR(support(shape, I, {0, 0, 1}), half, 1e-4 * units::um);
  EXPECT_NEAR(half / units::um, 1.28, 0.01);  // thickness 2.57 um
  // Rotated by R, the support along u is the unrotated one along R^T u: a quarter turn about e1
  // puts the axis along -e2.
  EXPECT_NEAR(support(shape, rotation_matrix({1, 0, 0}, pi / 2), {0, -1, 0}), half, 1e-4 * units::um);
  EXPECT_NEAR(support(shape, rotation_matrix({1, 0, 0}, pi / 2), {1, 0, 0}), R0, 1e-12 * R0);
}

}  // namespace
}  // namespace rbfib::cells
