// Unit tests of the MAC grid: staggering per component, unknown counts and positions, boundary
// conditions per component, and refusal of bad grids with the field named.
#include "rbfib/grid/mac.hpp"

#include "rbfib/core/error.hpp"

#include <gtest/gtest.h>

namespace rbfib {
namespace {

using MB = MacBoundary;

TEST(MacGrid, StaggeringAndUnknownsPerComponent) {
  MacGrid g = make_mac_grid(3, {8, 6, 5}, {1.6, 1.2, 1.0}, {MB::periodic, MB::dirichlet, MB::neumann});
  // scalar: cell centres, N unknowns per axis
  const Box s = g.scalar();
  EXPECT_EQ(s.n(0), 8);
  EXPECT_EQ(s.n(1), 6);
  EXPECT_EQ(s.n(2), 5);
  EXPECT_DOUBLE_EQ(s.x(1, 0), 0.1);  // h/2
  // u_x: g = 1 along periodic x (N unknowns, at the upper face of each cell), g = 1/2 across
  const Box u = g.component(0);
  EXPECT_EQ(u.n(0), 8);
  EXPECT_DOUBLE_EQ(u.x(0, 0), 0.2);
  EXPECT_DOUBLE_EQ(u.x(1, 0), 0.1);
  EXPECT_EQ(u.axes[1].lower.kind, BoundaryKind::dirichlet);
  EXPECT_EQ(u.axes[2].lower.kind, BoundaryKind::neumann);  // tangential on a slip wall
  // u_y: normal to the walls in y: N - 1 interior faces, the walls are its boundary points
  const Box v = g.component(1);
  EXPECT_EQ(v.n(1), 5);
  EXPECT_DOUBLE_EQ(v.x(1, 0), 0.2);
  EXPECT_DOUBLE_EQ(v.x(1, 4), 1.0);
  EXPECT_EQ(v.axes[1].lower.kind, BoundaryKind::dirichlet);
  // u_z on the slip walls in z: the normal component is Dirichlet (no penetration)
  const Box w = g.component(2);
  EXPECT_EQ(w.n(2), 4);
  EXPECT_EQ(w.axes[2].lower.kind, BoundaryKind::dirichlet);
  EXPECT_EQ(w.axes[1].upper.kind, BoundaryKind::dirichlet);
  // the scalar box is homogeneous Neumann on every wall (eq. 2.9)
  EXPECT_EQ(s.axes[1].lower.kind, BoundaryKind::neumann);
  EXPECT_EQ(s.axes[2].upper.kind, BoundaryKind::neumann);
  EXPECT_TRUE(s.axes[0].periodic());
}

TEST(MacGrid, TwoDimensionalByTheSameConstruction) {
  MacGrid g = make_mac_grid(2, {6, 4, 1}, {1.5, 1.0, 1.0}, {MB::periodic, MB::dirichlet, MB::periodic});
  EXPECT_EQ(g.component(0).size(), 6 * 4);
  EXPECT_EQ(g.component(1).size(), 6 * 3);
  EXPECT_EQ(g.scalar().size(), 24);
  EXPECT_THROW(g.component(2), InputError);
}

std::string field_of(const MacGrid& g) {
  try {
    g.validate();
  } catch (const InputError& e) {
    return e.field();
  }
  return "";
}

TEST(MacGrid, BadGridsNameTheField) {
  MacGrid g = make_mac_grid(3, {8, 8, 8}, {1, 1, 1}, {MB::periodic, MB::dirichlet, MB::periodic});
  MacGrid bad = g;
  bad.cells[1] = 3;
  EXPECT_EQ(field_of(bad), "grid.y.cells");
  bad = g;
  bad.upper[0] = MB::dirichlet;  // periodic below, wall above
  EXPECT_EQ(field_of(bad), "grid.x.upper");
  bad = g;
  bad.length[2] = -1.0;
  EXPECT_EQ(field_of(bad), "grid.z.length");
  bad = g;
  bad.dims = 4;
  EXPECT_EQ(field_of(bad), "grid.dims");
  EXPECT_EQ(field_of(g), "");
}

}  // namespace
}  // namespace rbfib
