// Unit tests of the verification runner: steady Couette flow (an exact solution the discretization
// keeps exactly) gives errors at rounding, and the relative difference is measured against its
// second argument.
#include "rbfib/fluid/verification.hpp"

#include <gtest/gtest.h>

namespace rbfib {
namespace {

TEST(Verification, SteadyCouetteRunsAtRoundingForBothIntegrators) {
  ExactProblem p;
  p.name = "steady couette";
  p.grid = make_mac_grid(3, {4, 10, 4}, {1.0, 1.0, 1.0}, {MacBoundary::periodic, MacBoundary::dirichlet, MacBoundary::periodic});
  p.fluid = FluidParameters{1.0, 0.3};
  p.velocity = [](int a, double, double, double y, double) { return a == 0 ? 2.0 * y : 0.0; };
  p.boundary = [](int a, int d, int side, double, double, double, double) { return a == 0 && d == 1 && side ? 2.0 : 0.0; };
  p.t0 = 0.0;
  p.t1 = 0.1;
  for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage}) {
    const ExactRun r = run_exact(p, ti, 0.01);
    EXPECT_EQ(r.steps, 10);
    // rounding: 10 steps of solves to 1e-11 relative residual on O(1) data
    EXPECT_LT(r.err_inf, 1e-10) << to_string(ti);
    EXPECT_LT(r.err_l2, 1e-10) << to_string(ti);
    EXPECT_LT(r.max_div_rel, 1e-10) << to_string(ti);
    EXPECT_GT(r.seconds, 0.0) << to_string(ti);
  }
}

TEST(Verification, RelativeDifferenceIsScaledByTheReference) {
  VectorField u, v;
  for (int a = 0; a < 3; ++a) {
    u[a] = dvec(4, 1.0);
    v[a] = dvec(4, a == 2 ? 4.0 : 2.0);
  }
  EXPECT_DOUBLE_EQ(relative_difference(u, v, 3), 3.0 / 4.0);  // max |u - v| = 3, max |v| = 4
  EXPECT_DOUBLE_EQ(relative_difference(u, v, 2), 1.0 / 2.0);
}

}  // namespace
}  // namespace rbfib
