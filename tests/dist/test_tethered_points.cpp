// Tethered point sets on several ranks, each rank the points whose anchor lies in its planes
// (ImmersedBoundary::add(TetheredPoints)). In the channel of channel.hpp (walls in y,
// u_z = W sin(pi y / L_y), W = 20 cm/s, 100 steps of 0.2 us) two sheets of springs
// (k = 0.5 dyn/cm, eta = 1e-8 dyn s/cm per point): one on the plane y = 4 um across the whole box,
// 16 x 28 points 1 um apart, which every rank holds a band of; one on the plane z = 10.25 um, 8 x 8
// points, which one rank holds whole while the others hold none of it. The flow drags the points
// about 1 um along z against their springs. Rank 0 steps the same sets on one process; the
// whole-run state gathered from the ranks (ImmersedBoundary::carried) is compared with it at steps
// 50 and 100, and the ranks' state at step 50, restored on one process and on as many ranks,
// continues as the uninterrupted run does.
//
// Tolerance: the runs differ in the order of sums only (as test_cell_owners.cpp): measured 5.0e-15
// of the largest displacement (0.87 um) on 1 to 4 ranks and after either restart, 2.0e-15 to
// 2.3e-15 of the largest fluid velocity (AMD EPYC); bounded at 1e-10 of the largest
// displacement, which a point lost or doubled between ranks (its force spread twice or not at
// all) or stepped on a stale ghost plane exceeds by orders.
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/dist/slab_fluid.hpp"
#include "rbfib/dist/slab_interaction.hpp"
#include "rbfib/sim/ib_step.hpp"
#include "channel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace rbfib::dist {
namespace {

const double um = units::um;

/// Points on a lattice of a plane normal to `normal` at `at`: n[0] x n[1] points 1 um apart,
/// starting at 0.5 um, along the other two axes in order.
sim::TetheredPoints sheet(const std::string& name, int normal, double at, std::array<int, 2> n) {
  const int a = normal == 0 ? 1 : 0, b = normal == 2 ? 1 : 2, m = n[0] * n[1];
  std::vector<double> X(std::size_t(3 * m));
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j) {
      const int k = i + n[0] * j;
      X[std::size_t(normal * m + k)] = at;
      X[std::size_t(a * m + k)] = (i + 0.5) * um;
      X[std::size_t(b * m + k)] = (j + 0.5) * um;
    }
  sim::TetheredPoints p;
  p.name = name;
  p.X = dvec(X.begin(), X.end());
  p.anchors = p.X;
  p.k = 0.5;
  p.eta = 1e-8;
  return p;
}

/// The two sheets in the channel and its starting flow, on one process (parts null) or this rank's slab.
sim::ImmersedBoundary two_sheets(const Channel& setup, std::shared_ptr<const FluidDecomposition> parts) {
  sim::ImmersedBoundary s = setup.empty(parts);
  s.add(sheet("floor", 1, 4 * um, {16, 28}));
  s.add(sheet("across", 2, 10.25 * um, {8, 8}));
  start_flow(s, parts.get(), setup.grid);
  return s;
}

/// The largest difference of two whole states' point positions over both sets.
double point_difference(const sim::ImmersedBoundary::Carried& a, const sim::ImmersedBoundary::Carried& b) {
  double worst = 0;
  for (std::size_t p = 0; p < 2; ++p) {
    EXPECT_EQ(a.points[p].size(), b.points[p].size());
    const std::vector<double> x(a.points[p].begin(), a.points[p].end()), y(b.points[p].begin(), b.points[p].end());
    for (std::size_t q = 0; q < std::min(x.size(), y.size()); ++q) worst = std::max(worst, std::abs(x[q] - y[q]));
    for (double v : x) worst = std::isfinite(v) ? worst : INFINITY;  // a point no rank sent
  }
  return worst;
}

TEST(TetheredPoints, SetsSplitByAnchorStepAsOnOneProcessAndRestartOnAnyNumber) {
  const Comm world;
  const Channel setup;
  const int ghosts = SlabInteraction::ghosts_needed(2 * um, setup.grid.h(2), setup.ib.kernel);
  auto parts = std::make_shared<const SlabFluid>(setup.grid, world, ghosts);
  sim::ImmersedBoundary many = two_sheets(setup, parts);
  // Every point on exactly one rank; the plane across z on one rank only.
  EXPECT_EQ(world.sum(index_t(many.points(0).X.size() / 3)), 16 * 28);
  EXPECT_EQ(world.sum(index_t(many.points(1).X.size() / 3)), 64);
  EXPECT_EQ(world.sum(index_t(many.points(1).X.empty() ? 0 : 1)), 1);
  if (world.size() > 1) {
    EXPECT_LT(many.points(0).X.size(), std::size_t(3 * 16 * 28)) << "the floor is not split";
  }

  std::unique_ptr<sim::ImmersedBoundary> one;
  if (world.rank() == 0) one = std::make_unique<sim::ImmersedBoundary>(two_sheets(setup, nullptr));
  const sim::ImmersedBoundary::Carried start = many.carried();
  for (int n = 0; n < 50; ++n) {
    many.step();
    if (one) one->step();
  }
  const sim::ImmersedBoundary::Carried at50 = many.carried();
  for (int n = 0; n < 50; ++n) {
    many.step();
    if (one) one->step();
  }
  const sim::ImmersedBoundary::Carried at100 = many.carried();
  sim::ImmersedBoundary again = two_sheets(setup, parts);
  again.restore(at50);
  for (int n = 0; n < 50; ++n) again.step();
  const sim::ImmersedBoundary::Carried again100 = again.carried();
  if (one) {
    const sim::ImmersedBoundary::Carried one100 = one->carried();
    const double moved = point_difference(one100, start);
    EXPECT_GT(moved, 0.5 * um);
    EXPECT_LT(moved, 2 * um);
    EXPECT_LE(point_difference(at100, one100), 1e-10 * moved) << world.size() << " ranks, step 100";
    EXPECT_LE(point_difference(again100, one100), 1e-10 * moved) << "restarted on " << world.size() << " ranks";
    sim::ImmersedBoundary single = two_sheets(setup, nullptr);
    single.restore(at50);
    for (int n = 0; n < 50; ++n) single.step();
    EXPECT_LE(point_difference(single.carried(), one100), 1e-10 * moved) << "restarted on one process";
    double du = 0, umax = 0;
    for (int a = 0; a < 3; ++a)
      for (std::size_t q = 0; q < one100.fluid.u[a].size(); ++q) {
        du = std::max(du, std::abs(double(at100.fluid.u[a][q]) - double(one100.fluid.u[a][q])));
        umax = std::max(umax, std::abs(double(one100.fluid.u[a][q])));
      }
    EXPECT_LE(du, 1e-10 * umax);
  }
}

TEST(TetheredPoints, ACheckpointOfAnotherSetSizeIsNamed) {
  const Comm world;
  const Channel setup;
  auto parts = std::make_shared<const SlabFluid>(setup.grid, world, SlabInteraction::ghosts_needed(2 * um, setup.grid.h(2), setup.ib.kernel));
  sim::ImmersedBoundary many = two_sheets(setup, parts);
  sim::ImmersedBoundary::Carried c = many.carried();
  c.points[1].resize(c.points[1].size() - 3);
  EXPECT_THROW(many.restore(c), InputError);
}

}  // namespace
}  // namespace rbfib::dist
