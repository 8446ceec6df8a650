// The tethered capillary (sim/capillary.hpp): the driving force is f_in on the x-faces inside the
// cylinder (and the segment, when bounded), a uniform balance outside, and sums to zero over the
// grid; the capillary's nodes start at their anchors and hold the frame.
#include "rbfib/sim/capillary.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rbfib::sim {
namespace {

MacOperators box(int eta, double L) {
  MacGrid g = make_mac_grid(3, {eta, eta, eta}, {2 * L, 2 * L, 2 * L},
                            {MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic});
  g.origin = {-L, -L, -L};
  return MacOperators(g);
}

void expect_driving_force(const MacOperators& ops, double R, double x0, double x1) {
  const double f_in = 8e3;
  const VectorField f = capillary_driving_force(ops, R, f_in, x0, x1);
  const std::vector<double> fx(f[0].begin(), f[0].end());
  const Box& b = ops.component_box(0);
  double sum = 0;
  int inside = 0;
  for (int kz = 0; kz < b.n(2); ++kz)
    for (int jy = 0; jy < b.n(1); ++jy)
      for (int ix = 0; ix < b.n(0); ++ix) {
        const double x = b.x(0, ix), y = b.x(1, jy), z = b.x(2, kz);
        const double v = fx[ix + std::size_t(b.n(0)) * (jy + std::size_t(b.n(1)) * kz)];
        const bool in = y * y + z * z < R * R && x >= x0 && x <= x1;
        inside += in;
        if (in) EXPECT_EQ(v, f_in);
        else EXPECT_LT(v, 0.0);
        sum += v;
      }
  EXPECT_GT(inside, 0);
  EXPECT_NEAR(sum, 0.0, 1e-12 * f_in * double(fx.size()));
  for (int a : {1, 2})
    for (double v : std::vector<double>(f[a].begin(), f[a].end())) EXPECT_EQ(v, 0.0);
}

TEST(Capillary, DrivingForceInsideTheCylinderBalancedOutside) {
  const MacOperators ops = box(16, 12e-4);
  expect_driving_force(ops, 5e-4, -INFINITY, INFINITY);
  expect_driving_force(ops, 5e-4, -8e-4, 8e-4);
}

TEST(Capillary, NodesStartAtTheirAnchorsAndHoldTheFrame) {
  const surface::CylinderPoints c = surface::cylinder_points(5e-4, -8e-4, 8e-4, 0.5e-4);
  const TetheredPoints p = tethered_capillary("capillary", c, 2.45e-3);
  EXPECT_TRUE(p.frame);
  EXPECT_EQ(p.k, 2.45e-3);
  ASSERT_EQ(p.X.size(), c.X.size());
  for (std::size_t i = 0; i < c.X.size(); ++i) {
    EXPECT_EQ(double(p.X[i]), c.X[i]);
    EXPECT_EQ(double(p.anchors[i]), c.X[i]);
  }
}

}  // namespace
}  // namespace rbfib::sim
