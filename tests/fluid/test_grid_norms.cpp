// Grid norms of an error: a constant error c has grid 2-norm c sqrt(measure of the unknowns' cells)
// and max norm c; a single spike e has max norm e and 2-norm e sqrt(h_x h_y).
#include "rbfib/fluid/grid_norms.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib {
namespace {

Box box_2d() {
  Box b;
  b.dims = 2;
  b.axes[0] = Axis{8, 1.0, 0.5, BoundaryCondition::dirichlet(), BoundaryCondition::dirichlet(), 0.0};
  b.axes[1] = Axis{4, 2.0, 0.5, BoundaryCondition::periodic(), BoundaryCondition::periodic(), 0.0};
  return b;
}

TEST(GridErrorNorms, ConstantErrorAndSpike) {
  const Box b = box_2d();
  const dvec zero(b.size(), 0.0), c(b.size(), 0.25);
  const GridNorms n = grid_error_norms(b, c, zero);
  EXPECT_NEAR(n.l2, 0.25 * std::sqrt(b.size() * b.axes[0].h() * b.axes[1].h()), 1e-15);
  EXPECT_EQ(n.linf, 0.25);
  host_vector<double> s(b.size(), 0.0);
  s[5] = -3.0;
  const GridNorms m = grid_error_norms(b, zero, dvec(s));
  EXPECT_EQ(m.linf, 3.0);
  EXPECT_NEAR(m.l2, 3.0 * std::sqrt(b.axes[0].h() * b.axes[1].h()), 1e-15);
}

}  // namespace
}  // namespace rbfib
