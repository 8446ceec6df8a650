// Cells moving between ranks and checkpoints that do not depend on the number of ranks
// (sim/cell_owners.hpp). Four Skalak spheres (R = 3 um) in a channel (walls in y) are carried
// along z by u_z = W sin(pi y / L_y), W = 20 cm/s: about 2.8 um in 100 steps of 0.2 us (the cells lag the flow), so that
// their centroids (z = 6, 13, 19, 26 um at the start) cross the slab boundaries of 2, 3 and 4
// ranks (z = 7, 10, 14, 20, 21 um) and the periodic seam. Rank 0 steps the same cells on one
// process; the whole-run state gathered from the ranks (ImmersedBoundary::carried, the state a
// checkpoint keeps) is compared with it at steps 50 and 100. Restarts: the ranks' state at step 50
// restored on one process, and on as many ranks as wrote it, continues to step 100 as the
// uninterrupted run does.
//
// Tolerance: as the four-cell test beside it (test_ib_step.cpp), the runs differ in the order of
// sums only: measured 3.1e-15 to 3.9e-15 of the largest displacement (2.8 um) at steps 50 and
// 100 and after either restart, and 1.9e-15 to 5.4e-15 of the largest fluid velocity, on 1 to 4
// ranks (AMD EPYC); bounded at 1e-10, which a cell
// stepped on a stale ghost plane, a force lost at a seam or a cell lost in transit exceeds by
// orders (a lost or duplicated cell changes the whole state's size).
#include "../common/small_cells.hpp"
#include "channel.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/dist/slab_fluid.hpp"
#include "rbfib/dist/slab_interaction.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace rbfib::dist {
namespace {

using rbfib::testing::small_sphere;
const double um = units::um;

/// The step on one process (parts null) or on this rank's slab; every rank adds all four cells.
sim::ImmersedBoundary four_cells(const Channel& setup, std::shared_ptr<const FluidDecomposition> parts) {
  sim::ImmersedBoundary s = setup.empty(parts);
  std::vector<cells::Placement> p(4);
  const double z[4] = {6, 13, 19, 26};
  for (int k = 0; k < 4; ++k) p[k].center = {8 * um, 8 * um, z[k] * um};
  p[1].stretch = {1.1, 0.95, 1.0};  // a stretched cell: forces from the first step
  s.add(cells::Batch(small_sphere(), p));
  return s;
}

/// The largest difference of two whole states' cell positions (z compared modulo the period).
double position_difference(const sim::ImmersedBoundary::Carried& a, const sim::ImmersedBoundary::Carried& b, index_t nd, double Lz) {
  EXPECT_EQ(a.batches[0].size(), b.batches[0].size());
  const std::vector<double> x(a.batches[0].begin(), a.batches[0].end()), y(b.batches[0].begin(), b.batches[0].end());
  const index_t N = index_t(x.size()) / (6 * nd);
  double worst = 0;
  for (index_t q = 0; q < 3 * N * nd; ++q) {
    double d = x[q] - y[q];
    if (q / (N * nd) == 2) d -= Lz * std::round(d / Lz);
    worst = std::max(worst, std::abs(d));
  }
  return worst;
}

TEST(CellOwners, CellsCrossingRanksMoveAsOnOneProcessAndCheckpointsRestartOnAnyNumber) {
  const Comm world;
  const Channel setup;
  const int ghosts = SlabInteraction::ghosts_needed(3.5 * um, setup.grid.h(2), setup.ib.kernel);
  auto parts = std::make_shared<const SlabFluid>(setup.grid, world, ghosts);
  const index_t nd = small_sphere()->n_data();
  const double Lz = setup.grid.length[2];

  sim::ImmersedBoundary many = four_cells(setup, parts);
  start_flow(many, parts.get(), setup.grid);
  EXPECT_EQ(world.sum(index_t(many.batch(0).size())), 4);
  std::vector<index_t> first_owned = many.cell_ids(0);

  std::unique_ptr<sim::ImmersedBoundary> one;  // rank 0: the same cells on one process
  if (world.rank() == 0) {
    one = std::make_unique<sim::ImmersedBoundary>(four_cells(setup, nullptr));
    start_flow(*one, nullptr, setup.grid);
  }
  const sim::ImmersedBoundary::Carried start = many.carried();
  for (int n = 0; n < 50; ++n) {
    many.step();
    if (one) one->step();
  }
  const sim::ImmersedBoundary::Carried at50 = many.carried();
  double moved = 0, worst50 = 0;
  sim::ImmersedBoundary::Carried one50;
  if (one) {
    one50 = one->carried();
    moved = position_difference(one50, start, nd, Lz);
    worst50 = position_difference(at50, one50, nd, Lz);
  }
  for (int n = 0; n < 50; ++n) {
    many.step();
    if (one) one->step();
  }
  const sim::ImmersedBoundary::Carried at100 = many.carried();
  EXPECT_EQ(world.sum(index_t(many.batch(0).size())), 4) << "a cell lost or duplicated in transit";
  // The cells crossed: on more than one rank some cell is owned elsewhere than at the start.
  const int changed = world.sum(index_t(many.cell_ids(0) != first_owned ? 1 : 0));
  if (world.size() > 1) {
    EXPECT_GT(changed, 0) << "no cell changed owner: the test does not test migration";
  }

  // Restarts from the ranks' step-50 state: on as many ranks, and (rank 0) on one process.
  sim::ImmersedBoundary again = four_cells(setup, parts);
  again.restore(at50);
  for (int n = 0; n < 50; ++n) again.step();
  const sim::ImmersedBoundary::Carried again100 = again.carried();
  if (one) {
    const sim::ImmersedBoundary::Carried one100 = one->carried();
    const double moved100 = position_difference(one100, start, nd, Lz);
    EXPECT_GT(moved, 0.5 * um);
    EXPECT_GT(moved100, 2.0 * um);
    EXPECT_LE(worst50, 1e-10 * moved100) << world.size() << " ranks, step 50";
    EXPECT_LE(position_difference(at100, one100, nd, Lz), 1e-10 * moved100) << world.size() << " ranks, step 100";
    EXPECT_LE(position_difference(again100, one100, nd, Lz), 1e-10 * moved100) << "restarted on " << world.size() << " ranks";
    sim::ImmersedBoundary single = four_cells(setup, nullptr);
    single.restore(at50);
    for (int n = 0; n < 50; ++n) single.step();
    EXPECT_LE(position_difference(single.carried(), one100, nd, Lz), 1e-10 * moved100) << "restarted on one process";
    // The fluid gathered from the ranks is the one process's.
    double du = 0, umax = 0;
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(at100.fluid.u[a].size(), one100.fluid.u[a].size());
      for (std::size_t q = 0; q < one100.fluid.u[a].size(); ++q) {
        du = std::max(du, std::abs(double(at100.fluid.u[a][q]) - double(one100.fluid.u[a][q])));
        umax = std::max(umax, std::abs(double(one100.fluid.u[a][q])));
      }
    }
    EXPECT_LE(du, 1e-10 * umax);
    EXPECT_EQ(at100.clock.step, 100);
  }
}

}  // namespace
}  // namespace rbfib::dist
