// Unit tests of the periodic cubic-spline restriction: the spline reproduces trigonometric data to
// fourth order at the midpoints, and the restriction of a MAC component picks coincident faces
// exactly and interpolates centres to fourth order.
#include "rbfib/grid/periodic_spline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace rbfib {
namespace {

const double two_pi = 6.283185307179586;

double midpoint_error(int n) {
  const double h = 1.0 / n;
  std::vector<double> y(n);
  for (int i = 0; i < n; ++i) y[i] = std::sin(two_pi * i * h) + 0.5 * std::cos(2 * two_pi * i * h);
  const std::vector<double> mid = periodic_spline_midpoints(y, h);
  double e = 0;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) * h;
    e = std::max(e, std::abs(mid[i] - (std::sin(two_pi * x) + 0.5 * std::cos(2 * two_pi * x))));
  }
  return e;
}

TEST(PeriodicSpline, MidpointsOfSmoothPeriodicDataToFourthOrder) {
  const double e16 = midpoint_error(16), e32 = midpoint_error(32);
  EXPECT_LT(e16, 1e-3);
  // a cubic spline interpolant is O(h^4): the ratio of errors at h and h/2 is near 16
  EXPECT_NEAR(std::log2(e16 / e32), 4.0, 0.2);
}

TEST(PeriodicSpline, ConstantsAndLinesThroughTheSeamAreKept) {
  const std::vector<double> mid = periodic_spline_midpoints(std::vector<double>(8, 3.0), 0.125);
  for (double v : mid) EXPECT_NEAR(v, 3.0, 1e-14);
}

TEST(PeriodicSpline, RestrictionTakesFacesAndInterpolatesCentres) {
  // component a = 0 on an 8^3 grid of [0, 1)^3, fine face p at x = p h here, centres (j + 1/2) h in y, z.
  const int nf = 8;
  const double hf = 1.0 / nf;
  auto f = [](double x, double y, double z) { return std::sin(two_pi * x) + std::cos(two_pi * y) * std::sin(two_pi * z); };
  std::vector<double> fine(nf * nf * nf);
  for (int k = 0; k < nf; ++k)
    for (int j = 0; j < nf; ++j)
      for (int i = 0; i < nf; ++i) fine[i + nf * (j + nf * k)] = f(i * hf, (j + 0.5) * hf, (k + 0.5) * hf);
  const std::vector<double> coarse = restrict_mac_component(fine, nf, hf, 0);
  const int nc = nf / 2;
  ASSERT_EQ(coarse.size(), std::size_t(nc * nc * nc));
  const double hc = 2 * hf;
  double e = 0;
  for (int k = 0; k < nc; ++k)
    for (int j = 0; j < nc; ++j)
      for (int i = 0; i < nc; ++i) {
        // coarse face i is fine face 2 i + 1; coarse centres lie midway between fine centres
        const double want = f((2 * i + 1) * hf, (j + 0.5) * hc, (k + 0.5) * hc);
        e = std::max(e, std::abs(coarse[i + nc * (j + nc * k)] - want));
      }
  // 8 fine points per wavelength: the spline's O(h^4) error is a few 1e-3 of the unit amplitude
  EXPECT_LT(e, 2e-2);
}

}  // namespace
}  // namespace rbfib
