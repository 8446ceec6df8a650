// The stability criterion of the adaptive step (sim/ib_step.hpp) and the membranes' explicit
// stability bound it caps the ladder with (sim/membrane_stability.hpp,
// docs/derivations/membrane_stability).
#include "../common/errors.hpp"
#include "../common/small_cells.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/sim/ib_step.hpp"
#include "rbfib/sim/membrane_stability.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace rbfib;
using namespace rbfib::sim;
using units::um;
using MB = MacBoundary;

namespace {

/// The closed form of the derivation (closed_form.py) at the seed's whole-blood grid: red cells'
/// tangential area-stretch waves set it, 3.56 us at the limit (gain 1) and 1.64 us at gain 1/2, the
/// same for 400 data sites as for 2,500 (the kernel, not the sites, sets the worst mode).
TEST(MembraneStability, RedCellBoundsOfTheDerivation) {
  const auto rbc = cells::red_cell(400, 1600);
  const MembraneStiffness m = membrane_stiffness(*rbc);
  EXPECT_NEAR(m.mu_s, 2.5e-3, 1e-12);
  EXPECT_NEAR(m.K, 2.5e-3 + 2 * 0.25, 1e-12);
  const double h = 0.2 * um, mu = 1 * units::cP;
  EXPECT_NEAR(membrane_dt_limit(m, h, 1.0, mu, ib::Kernel::bspline3, 1.0) / units::us, 3.56, 0.02);
  EXPECT_NEAR(membrane_dt_limit(m, h, 1.0, mu, ib::Kernel::bspline3, 0.5) / units::us, 1.64, 0.02);
  EXPECT_EQ(membrane_limiting_family(m, h, 1.0, mu, ib::Kernel::bspline3, 0.5), "tangential along k");
  // Twice the grid spacing, about twice the bound (lambda ~ 1/h); a tenth of the viscosity: the membrane's
  // explicit dissipation (d = 1.42 > 1/2) leaves only the fluid's inertia to bound the step.
  // (the fluid's inertia, rho h^2 / mu, grows as h^2: 3.7 us at h = 0.4 um, a little over twice)
  EXPECT_NEAR(membrane_dt_limit(m, 2 * h, 1.0, mu, ib::Kernel::bspline3, 0.5) / units::us, 3.7, 0.05);
  EXPECT_LT(membrane_dt_limit(m, h, 1.0, 0.1 * mu, ib::Kernel::bspline3, 1.0), 0.6 * units::us);
}

/// Platelets (neo-Hookean, mu_s = 0.1, K = 1 dyn/cm) at h = 0.2 um: 0.76 us at gain 1/2.
TEST(MembraneStability, PlateletBoundOfTheDerivation) {
  const auto plt = cells::platelet(400, 400);
  const MembraneStiffness m = membrane_stiffness(*plt);
  EXPECT_NEAR(m.mu_s, 0.1, 1e-12);
  EXPECT_NEAR(m.K, 1.0, 1e-12);
  const double dt = membrane_dt_limit(m, 0.2 * um, 1.0, 1 * units::cP, ib::Kernel::bspline3, 0.5);
  EXPECT_GT(dt / units::us, 0.70);
  EXPECT_LT(dt / units::us, 0.85);
}

TEST(MembraneStability, BadInputIsNamed) {
  const MembraneStiffness m = membrane_stiffness(*cells::red_cell(400, 1600));
  const std::string e = rbfib::testing::message_of<InputError>([&] { membrane_dt_limit(m, 0.0, 1.0, 0.01, ib::Kernel::bspline3, 0.5); });
  EXPECT_NE(e.find("membrane stability"), std::string::npos) << e;
}

/// The sphere of the adaptive-step tests, stretched, relaxing in a periodic box of 0.1 cP (where
/// its explicit dissipation and stiffness make large steps unstable), on the stability criterion
/// with no cap from the membranes' bound: the growth guard alone holds the ladder.
ImmersedBoundary guarded_box(double guard_growth) {
  NavierStokesOptions o;
  o.dt = 0.05 * units::us * 4;
  IbOptions io;
  io.adaptive = AdaptiveStep{true, 0.05 * units::us, 10, 4};
  io.adaptive.criterion = StepCriterion::stability;
  io.adaptive.membrane_gain = INFINITY;
  io.adaptive.guard_growth = guard_growth;
  const MacGrid g = make_mac_grid(3, {16, 16, 16}, {16 * um, 16 * um, 16 * um}, {MB::periodic, MB::periodic, MB::periodic});
  ImmersedBoundary ib(g, FluidParameters{1.0, 0.1 * units::cP}, o, {}, io);
  cells::Placement p;
  p.center = {8 * um, 8 * um, 8 * um};
  p.stretch = {1.0, 1 / 1.1, 1.1};
  ib.add(cells::Batch(rbfib::testing::small_sphere(), {p}));
  return ib;
}

/// Without the guard the ladder climbs into the coupling's instability and the run is stopped
/// (eq. 5.4 at dt_min, or a non-finite force); with it, a growing sign-flipping part is refused
/// before it matters, the ladder is capped under the refused rung, and the run goes on.
TEST(StepStability, TheGrowthGuardHoldsTheLadderBelowTheInstability) {
  {
    ImmersedBoundary ib = guarded_box(INFINITY);  // a growth no step reaches: the guard never fires
    bool stopped = false;
    try {
      for (int n = 0; n < 400; ++n) ib.step();
    } catch (const NumericalError&) {
      stopped = true;
    }
    ASSERT_TRUE(stopped) << "the unguarded ladder reached dt = " << ib.dt() << " s without an instability: the test shows nothing";
  }
  ImmersedBoundary ib = guarded_box(1.05);
  int by_guard = 0;
  double refused_dt = INFINITY, largest_after = 0;
  for (int n = 0; n < 400; ++n) {
    const double dt = ib.dt();
    const IbStepReport r = ib.step();
    ASSERT_TRUE(std::isfinite(r.max_velocity)) << "step " << n;
    if (r.refused_by_guard > 0) {
      ++by_guard;
      refused_dt = std::min(refused_dt, dt);
    } else if (by_guard > 0) {
      largest_after = std::max(largest_after, r.dt);
    }
  }
  EXPECT_GT(by_guard, 0);
  EXPECT_LT(largest_after, refused_dt) << "the ladder climbed back to a refused rung";
  EXPECT_GE(ib.clock().cap, 0);
  EXPECT_TRUE(blas::all_finite(ib.batch(0).state().storage()));
}

/// A run's end inside a rung: that step alone is shortened to land on it, the ladder keeps its level.
TEST(StepStability, AStepLandsOnTheRunsEndAndTheLadderKeepsItsRung) {
  ImmersedBoundary ib = guarded_box(1.05);
  ib.step();
  const double rung = ib.dt(), t = ib.time();
  const sim::Clock before = ib.clock();
  const IbStepReport r = ib.step(rung / 3);
  EXPECT_EQ(r.dt, rung / 3);
  EXPECT_NEAR(ib.time(), t + rung / 3, 1e-15 * t);
  EXPECT_EQ(ib.dt(), rung);
  EXPECT_EQ(ib.clock().level, before.level);
  // A limit beyond the rung changes nothing.
  EXPECT_EQ(ib.step(10 * rung).dt, rung);
}

}  // namespace
