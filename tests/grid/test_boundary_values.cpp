// Boundary data of a known function: Dirichlet faces carry u, Neumann faces the derivative along the
// inward normal (+du/dx at the lower face, -du/dx at the upper), Robin faces alpha u + beta du/dnu;
// periodic axes carry none.
#include "rbfib/grid/boundary_values.hpp"

#include <gtest/gtest.h>

namespace rbfib {
namespace {

Box box_1d(BoundaryCondition lower, BoundaryCondition upper) {
  Box b;
  b.dims = 1;
  b.axes[0] = Axis{4, 2.0, 0.5, lower, upper, 0.0};  // faces at x = 0 and x = 2
  return b;
}

TEST(RobinBoundaryData, DirichletNeumannAndRobinFaces) {
  auto u = [](double x, double, double) { return 1 + 3 * x; };
  auto grad = [](int, double, double, double) { return 3.0; };
  const BoundaryData dn = robin_boundary_data(box_1d(BoundaryCondition::dirichlet(), BoundaryCondition::neumann()), u, grad);
  ASSERT_EQ(dn.face[0][0].size(), 1u);
  EXPECT_DOUBLE_EQ(host_vector<double>(dn.face[0][0])[0], 1.0);   // u(0)
  EXPECT_DOUBLE_EQ(host_vector<double>(dn.face[0][1])[0], -3.0);  // -du/dx at the upper face
  const BoundaryData r = robin_boundary_data(box_1d(BoundaryCondition::robin(2, 0.5), BoundaryCondition::robin(2, 0.5)), u, grad);
  EXPECT_DOUBLE_EQ(host_vector<double>(r.face[0][0])[0], 2 * 1.0 + 0.5 * 3);   // lower: alpha u + beta u'
  EXPECT_DOUBLE_EQ(host_vector<double>(r.face[0][1])[0], 2 * 7.0 - 0.5 * 3);   // upper, u(2) = 7
}

TEST(RobinBoundaryData, PeriodicAxesCarryNone) {
  const BoundaryData p = robin_boundary_data(box_1d(BoundaryCondition::periodic(), BoundaryCondition::periodic()),
                                             [](double, double, double) { return 1.0; },
                                             [](int, double, double, double) { return 0.0; });
  EXPECT_EQ(p.face[0][0].size(), 0u);
}

}  // namespace
}  // namespace rbfib
