// The coupled step (sim/ib_step.hpp) on a split fluid against the same step on one process: four
// Skalak spheres (R = 3 um) in a channel (walls in y) with a flow that shears them along x and
// carries them along z, one of them straddling the periodic seam z = 0. Each rank owns the cells
// whose centroid lies in its planes and steps them in its own batch; 30 steps of the seed's
// coupling on however many ranks the test runs with (n_z = 28: 28, 14 + 14, 10 + 10 + 8,
// 7 x 4 planes, 7 of halo).
//
// Every cell's data sites move as on one process, and the step's reports (eq. 5.4's force
// density, the energies, the largest velocity) are the whole box's. The runs differ only in
// the order of sums (FFT plans, the halo sum, the cells' batched products over other column
// counts): measured 3.9e-14 of the largest displacement (0.11 um) on 1 to 4 ranks alike, a unit or
// two in the last place of the coordinates (about 10 um); bounded here at 1e-10, which a cell
// stepped on a stale ghost plane or a force lost at a seam exceeds by orders.
#include "../common/small_cells.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/dist/slab_interaction.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace rbfib::dist {
namespace {

using MB = MacBoundary;
const double um = units::um;

using rbfib::testing::small_sphere;

std::vector<cells::Placement> four_cells() {
  std::vector<cells::Placement> p(4);
  const double c[4][3] = {{4, 7.5, 0.8}, {12, 8.5, 8}, {6, 8, 15}, {10, 7.8, 22}};  // um; cell 0 straddles z = 0
  for (int k = 0; k < 4; ++k) p[k].center = {c[k][0] * um, c[k][1] * um, c[k][2] * um};
  p[1].stretch = {1.1, 0.95, 1.0};  // a stretched cell: forces from the first step
  return p;
}

// The starting flow: u_x = U sin(pi y / L_y) (a shear across the channel), u_z = W sin(2 pi x / L_x);
// both divergence-free and zero on the walls.
void start_flow(sim::ImmersedBoundary& ib) {
  const MacOperators& ops = ib.fluid().operators();
  const double U = 2.0, W = 1.0, Ly = 16 * um, Lx = 16 * um;  // cm/s
  ib.fluid_state().u[0] = sample(ops.component_box(0), [=](double, double y, double) { return U * std::sin(M_PI * y / Ly); });
  ib.fluid_state().u[2] = sample(ops.component_box(2), [=](double x, double, double) { return W * std::sin(2 * M_PI * x / Lx); });
}

TEST(DistributedIbStep, CellsMoveAsOnOneProcess) {
  const Comm world;
  const MacGrid grid = make_mac_grid(3, {16, 16, 28}, {16 * um, 16 * um, 28 * um}, {MB::periodic, MB::dirichlet, MB::periodic});
  const FluidParameters fluid{1.0, units::cP};
  NavierStokesOptions options;
  options.dt = 0.2 * units::us;
  sim::IbOptions ibo;
  ibo.kernel = ib::Kernel::bspline3;
  const int ghosts = SlabInteraction::ghosts_needed(3.5 * um, grid.h(2), ibo.kernel);
  ASSERT_EQ(ghosts, 7);
  auto parts = std::make_shared<const SlabFluid>(grid, world, ghosts);

  sim::ImmersedBoundary one(std::make_unique<NavierStokesStep>(grid, fluid, options, BoundaryVelocity{}), ibo);
  sim::ImmersedBoundary many(std::make_unique<NavierStokesStep>(grid, fluid, options, BoundaryVelocity{}, parts), ibo);
  const std::vector<cells::Placement> all = four_cells();
  one.add(cells::Batch(small_sphere(), all));
  std::vector<int> mine;  // the cells whose centroid lies in this rank's planes
  std::vector<cells::Placement> placed;
  for (int k = 0; k < 4; ++k) {
    const int plane = int(std::floor(all[k].center[2] / grid.h(2)));
    if (plane >= parts->slabs().first() && plane < parts->slabs().first() + parts->slabs().planes()) {
      mine.push_back(k);
      placed.push_back(all[k]);
    }
  }
  EXPECT_EQ(world.sum(index_t(mine.size())), 4);
  if (!placed.empty()) many.add(cells::Batch(small_sphere(), placed));
  start_flow(one);
  start_flow(many);
  const std::vector<double> X0 = one.batch(0).positions_host();

  sim::IbStepReport r_one, r_many;
  for (int n = 0; n < 30; ++n) {
    r_one = one.step();
    r_many = many.step();
  }
  // Each owned cell's data sites against the same cell on one process.
  const index_t nd = small_sphere()->n_data();
  const std::vector<double> X1 = one.batch(0).positions_host();
  double moved = 0.0, worst = 0.0;
  for (std::size_t q = 0; q < X1.size(); ++q) moved = std::max(moved, std::abs(X1[q] - X0[q]));
  if (!mine.empty()) {
    const std::vector<double> Xm = many.batch(0).positions_host();
    const index_t m = index_t(mine.size());
    for (index_t j = 0; j < m; ++j)
      for (int a = 0; a < 3; ++a)
        for (index_t i = 0; i < nd; ++i) {
          double d = Xm[(a * m + j) * nd + i] - X1[(a * 4 + mine[j]) * nd + i];
          if (a == 2) d -= grid.length[2] * std::round(d / grid.length[2]);  // the same point, another image
          worst = std::max(worst, std::abs(d));
        }
  }
  EXPECT_GT(moved, 0.05 * um);
  EXPECT_LE(world.max(worst), 1e-10 * moved) << world.size() << " ranks";
  auto near = [](double a, double b) { return std::abs(a - b) <= 1e-10 * std::abs(b); };
  EXPECT_PRED2(near, r_many.max_force_density, r_one.max_force_density);
  EXPECT_PRED2(near, r_many.elastic_energy, r_one.elastic_energy);
  EXPECT_PRED2(near, r_many.kinetic_energy, r_one.kinetic_energy);
  EXPECT_PRED2(near, r_many.max_velocity, r_one.max_velocity);
  EXPECT_GT(r_one.elastic_energy, 0.0);
}

TEST(DistributedIbStep, ACellBeyondTheHaloStopsEveryRankWithOneMessageAndKeepsTheState) {
  const Comm world;
  if (world.size() == 1) GTEST_SKIP() << "one rank: the slab is the whole period";
  const MacGrid grid = make_mac_grid(3, {16, 16, 28}, {16 * um, 16 * um, 28 * um}, {MB::periodic, MB::dirichlet, MB::periodic});
  NavierStokesOptions options;
  options.dt = 0.2 * units::us;
  auto parts = std::make_shared<const SlabFluid>(grid, world, 4);  // too few planes for R = 3 um
  sim::ImmersedBoundary many(std::make_unique<NavierStokesStep>(grid, FluidParameters{1.0, units::cP}, options,
                                                                BoundaryVelocity{}, parts),
                             sim::IbOptions{});
  if (world.rank() == 0) {
    cells::Placement p;  // centroid in rank 0's top plane: the cell reaches 3 um above it
    p.center = {8 * um, 8 * um, (parts->slabs().planes() - 0.5) * grid.h(2)};
    many.add(cells::Batch(small_sphere(), {p}));
  }
  try {
    many.step();
    ADD_FAILURE() << "a cell beyond the halo was stepped";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("more ghost planes are needed"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("the state before this step is kept"), std::string::npos) << e.what();
  }
  EXPECT_EQ(many.step_count(), 0);
  EXPECT_EQ(many.time(), 0.0);
}

}  // namespace
}  // namespace rbfib::dist
