// A held wall on several ranks (sim/held_wall.hpp): every rank holds the whole wall, interpolates
// and spreads at the markers in its planes, gathers the velocities at all markers and solves the
// same mobility system. In the channel of channel.hpp (walls in y, u_z = W sin(pi y / L_y),
// W = 20 cm/s, 0.2 us steps): a plane of 8 x 14 markers 2h apart at y = 4 um across the whole box,
// which every rank holds a band of (commensurate: the circulant mobility), and a 3 x 3 patch of
// markers 2h apart at y = 10 um (not a lattice of the plane: the dense mobility). Rank 0 steps the
// same wall on one process; the whole fluid gathered from the ranks (ImmersedBoundary::carried)
// and the wall force after 10 steps are compared with it, and the markers do not slip on any rank.
//
// Tolerance: the runs differ in the order of sums only (the spreading's halo sum, the distributed
// transforms; the gathered velocities feed the same solve): measured on 1 to 4 ranks 6e-15 to
// 2.7e-14 of the largest wall force and 6e-16 to 1.1e-15 of the largest velocity (AMD EPYC);
// bounded at 1e-10 of each, which a marker lost or doubled between ranks (its force spread twice
// or not at all) or a velocity read off the unwidened slab exceeds by orders.
#include "rbfib/core/units.hpp"
#include "rbfib/dist/slab_fluid.hpp"
#include "rbfib/dist/slab_interaction.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/sim/ib_step.hpp"
#include "channel.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace rbfib::dist {
namespace {

const double um = units::um;

/// Markers 2 um apart on the plane y = y0: n[0] along x from x0, n[1] along z from z0.
sim::HeldWall markers(const std::string& name, double y0, std::array<int, 2> n, double x0, double z0, bool dense) {
  const int m = n[0] * n[1];
  std::vector<double> X(std::size_t(3 * m));
  for (int i = 0; i < n[0]; ++i)
    for (int k = 0; k < n[1]; ++k) {
      const int p = i + n[0] * k;
      X[std::size_t(p)] = x0 + 2 * i * um, X[std::size_t(m + p)] = y0, X[std::size_t(2 * m + p)] = z0 + 2 * k * um;
    }
  return sim::HeldWall{name, dvec(X.begin(), X.end()), dense};
}

/// The channel and its starting flow with one wall, on one process (parts null) or this rank's slab.
sim::ImmersedBoundary held(const Channel& setup, std::shared_ptr<const FluidDecomposition> parts, const sim::HeldWall& wall) {
  sim::ImmersedBoundary s = setup.empty(parts);
  s.add(wall);
  start_flow(s, parts.get(), setup.grid);
  return s;
}

void agrees_with_one_process(const sim::HeldWall& wall) {
  const Comm world;
  const Channel setup;
  const int ghosts = SlabInteraction::ghosts_needed(2 * um, setup.grid.h(2), setup.ib.kernel);
  auto parts = std::make_shared<const SlabFluid>(setup.grid, world, ghosts);
  sim::ImmersedBoundary many = held(setup, parts, wall);
  const index_t n = index_t(wall.X.size()) / 3;
  EXPECT_EQ(world.sum(index_t(many.held_wall(0).markers().size())), n) << "every marker on exactly one rank";
  std::unique_ptr<sim::ImmersedBoundary> one;
  if (world.rank() == 0) one = std::make_unique<sim::ImmersedBoundary>(held(setup, nullptr, wall));
  for (int s = 0; s < 10; ++s) {
    many.step();
    if (one) one->step();
    // No slip at this rank's markers: 1e-10 of the flow's W = 20 cm/s (on one process the bound
    // of test_held_wall.cpp, 1e-10 of its shear).
    EXPECT_LT(blas::norm_inf(many.held_wall(0).velocity()), 1e-10 * 20) << wall.name << ", step " << s;
  }
  const sim::ImmersedBoundary::Carried whole = many.carried();
  if (!one) return;
  EXPECT_EQ(many.held_wall(0).circulant(), one->held_wall(0).circulant());
  const std::vector<double> F(many.held_wall(0).force().begin(), many.held_wall(0).force().end());
  const std::vector<double> F1(one->held_wall(0).force().begin(), one->held_wall(0).force().end());
  ASSERT_EQ(F.size(), F1.size());
  double dF = 0, Fmax = 0;
  for (std::size_t q = 0; q < F.size(); ++q) dF = std::max(dF, std::abs(F[q] - F1[q])), Fmax = std::max(Fmax, std::abs(F1[q]));
  EXPECT_GT(Fmax, 0.0);
  EXPECT_LE(dF, 1e-10 * Fmax) << wall.name << " on " << world.size() << " ranks: the wall force";
  const sim::ImmersedBoundary::Carried single = one->carried();
  double du = 0, umax = 0;
  for (int a = 0; a < 3; ++a)
    for (std::size_t q = 0; q < single.fluid.u[a].size(); ++q) {
      du = std::max(du, std::abs(double(whole.fluid.u[a][q]) - double(single.fluid.u[a][q])));
      umax = std::max(umax, std::abs(double(single.fluid.u[a][q])));
    }
  EXPECT_LE(du, 1e-10 * umax) << wall.name << " on " << world.size() << " ranks: the fluid";
}

TEST(HeldWall, APlaneAcrossEveryRankHoldsAsOnOneProcess) { agrees_with_one_process(markers("plane", 4 * um, {8, 14}, 0.5 * um, 0.5 * um, false)); }

TEST(HeldWall, ADensePatchHoldsAsOnOneProcess) { agrees_with_one_process(markers("patch", 10 * um, {3, 3}, 5.5 * um, 11.5 * um, true)); }

}  // namespace
}  // namespace rbfib::dist
