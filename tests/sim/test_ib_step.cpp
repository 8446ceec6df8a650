// The coupled immersed-boundary step (Sec. 2.4): a cell at rest stays at rest, a cell in a uniform
// periodic flow is carried with it, the fluid's momentum changes by exactly the impulse of the
// spread force, the same run twice is bitwise identical, and failures (a planted NaN, the stopping
// condition of eq. 5.4) stop the step with a named error and keep the state before it.
#include "../common/errors.hpp"
#include "../common/small_cells.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/mechanics/ldsm.hpp"
#include "rbfib/sim/ib_step.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/shapes.hpp"

#include <gtest/gtest.h>

#include <thrust/reduce.h>

#include <cmath>
#include <cstdio>

namespace rbfib::sim {
namespace {

using MB = MacBoundary;
const double um = units::um;

using rbfib::testing::small_sphere;

/// The 16 um triply periodic box with h = 1 um.
MacGrid box16() { return make_mac_grid(3, {16, 16, 16}, {16 * um, 16 * um, 16 * um}, {MB::periodic, MB::periodic, MB::periodic}); }

/// A 16 um periodic box, h = 1 um, plasma (rho = 1 g/cm^3, mu = 0.1 cP), dt = 0.1 us.
ImmersedBoundary periodic_box(const std::vector<cells::Placement>& cells) {
  const MacGrid g = box16();
  NavierStokesOptions o;
  o.dt = 0.1 * units::us;
  ImmersedBoundary ib(g, FluidParameters{1.0, 0.1 * units::cP}, o, {}, IbOptions{});
  ib.add(cells::Batch(small_sphere(), cells));
  return ib;
}

cells::Placement at(double x, double y, double z) {
  cells::Placement p;
  p.center = {x * um, y * um, z * um};
  return p;
}

double max_abs_diff(const dvec& a, const dvec& b) {
  dvec d = a;
  blas::axpy(-1.0, b, d);
  return blas::norm_inf(d);
}

TEST(IbStep, CellAtRestInFluidAtRestStaysAtRest) {
  ImmersedBoundary ib = periodic_box({at(8, 8, 8)});
  const dvec X0 = ib.batch(0).state().storage();
  for (int n = 0; n < 3; ++n) ib.step();
  // Forces at the reference are rounding (1e-12 of E/R), so displacements are far below 1e-8 um.
  EXPECT_LT(max_abs_diff(ib.batch(0).state().storage(), X0), 1e-12);
  EXPECT_NEAR(ib.time(), 3 * 0.1 * units::us, 1e-20);
}

TEST(IbStep, CellInAUniformPeriodicFlowIsCarriedWithIt) {
  // u = (U, 0, 0) everywhere: interpolation reproduces constants, the cell translates rigidly
  // (no elastic force) and the flow stays uniform, so X^n = X^0 + n dt U e_x.
  ImmersedBoundary ib = periodic_box({at(8, 8, 8)});
  const double U = 0.1;  // cm/s
  thrust::fill(ib.fluid_state().u[0].begin(), ib.fluid_state().u[0].end(), U);
  const std::vector<double> X0 = ib.batch(0).positions_host();
  const int steps = 4;
  for (int n = 0; n < steps; ++n) ib.step();
  const std::vector<double> X = ib.batch(0).positions_host();
  const index_t nd = small_sphere()->n_data();
  const double shift = steps * 0.1 * units::us * U;
  // Each update X^n + dt U rounds at eps |X| (|X| <= 11 um): 4 steps, with room, 16 eps |X|.
  const double tol = 16 * 2.2e-16 * 11 * um;
  for (index_t i = 0; i < nd; ++i) {
    EXPECT_NEAR(X[i] - X0[i], shift, tol);
    EXPECT_NEAR(X[nd + i], X0[nd + i], 1e-15);
    EXPECT_NEAR(X[2 * nd + i], X0[2 * nd + i], 1e-15);
  }
}

TEST(IbStep, MomentumChangesByTheImpulseOfTheSpreadForce) {
  // Periodic box: advection is conservative, the Helmholtz and projection steps keep the mean, so
  // rho sum(u) h^3 after the steps equals sum over steps of dt sum(f) h^3 to rounding; and the net
  // spread force of internal (translation-invariant) forces is the quadrature error, small.
  cells::Placement p = at(8, 8.3, 7.6);
  p.stretch = {1.0, 1 / 1.1, 1.1};
  ImmersedBoundary ib = periodic_box({p});
  const double h3 = std::pow(um, 3), dt = 0.1 * units::us;
  double impulse[3] = {0, 0, 0}, total[3] = {0, 0, 0};
  for (int n = 0; n < 4; ++n) {
    ib.step();
    for (int a = 0; a < 3; ++a) {
      const dvec& f = ib.force_density()[a];
      impulse[a] += dt * thrust::reduce(f.begin(), f.end(), 0.0) * h3;
      total[a] += dt * blas::norm_inf(f) * h3 * double(f.size());
    }
  }
  for (int a = 0; a < 3; ++a) {
    const dvec& u = ib.fluid_state().u[a];
    const double momentum = 1.0 * thrust::reduce(u.begin(), u.end(), 0.0) * h3;
    ASSERT_GT(total[a], 0.0);  // the stretched cell does push on the fluid
    EXPECT_NEAR(momentum, impulse[a], 1e-10 * total[a]) << "component " << a;
    EXPECT_LT(std::abs(impulse[a]), 1e-3 * total[a]) << "component " << a;
  }
}

TEST(IbStep, AStretchedCellLosesElasticEnergyAndKeepsItsVolume) {
  // Stretched by 1.1 in z and compressed by 1.1 in y (Sec. 4.2.2.1). The fluid moves along the
  // force it receives, so the elastic energy falls (its rate is -sum F . U); the flow is
  // divergence free, so the volume stays, to the interpolation error (1e-3 here). (The shape does
  // not simply shrink back in z at first: with G = 100 E the area-compressed poles push outward.)
  cells::Placement p = at(8, 8, 8);
  p.stretch = {1.0, 1 / 1.1, 1.1};
  ImmersedBoundary ib = periodic_box({p});
  cells::CellForces f0, f1;
  cells::compute_forces(ib.batch(0), f0);
  EXPECT_TRUE(ib.diagnostics(0).volume.empty());
  double energy = 0;
  for (int n = 0; n < 20; ++n) energy = ib.step().elastic_energy;
  cells::compute_forces(ib.batch(0), f1);
  EXPECT_LT(f1.energy, 0.99 * f0.energy);
  EXPECT_NEAR(f1.cells.volume[0], f0.cells.volume[0], 1e-3 * f0.cells.volume[0]);
  // The step's own diagnostics (at X* of the last step, dt U from X^{n+1}) agree to that motion.
  const cells::CellDiagnostics& d = ib.diagnostics(0);
  ASSERT_EQ(d.volume.size(), 1u);
  EXPECT_EQ(d.energy[0], energy);
  EXPECT_NEAR(d.volume[0], f1.cells.volume[0], 1e-4 * f1.cells.volume[0]);
  EXPECT_NEAR(d.area[0], f1.cells.area[0], 1e-4 * f1.cells.area[0]);
}

TEST(IbStep, AUniformBodyForceAcceleratesThePeriodicBoxUniformly) {
  // No cells: a body force b in a periodic box gives rho du/dt = b exactly, u = b t / rho, and the
  // report's kinetic energy is rho/2 |u|^2 V.
  const MacGrid g = make_mac_grid(3, {8, 8, 8}, {8 * um, 8 * um, 8 * um}, {MB::periodic, MB::periodic, MB::periodic});
  NavierStokesOptions o;
  o.dt = 0.1 * units::us;
  IbOptions io;
  io.body_force = {8.0e3, 0, 0};  // dyn/cm^3 (the capillary's background force, paper Sec. 4.2)
  ImmersedBoundary ib(g, FluidParameters{1.0, 0.1 * units::cP}, o, {}, io);
  IbStepReport r;
  for (int n = 0; n < 5; ++n) r = ib.step();
  const double u = 8.0e3 * 5 * 0.1 * units::us;
  EXPECT_NEAR(blas::norm_inf(ib.fluid_state().u[0]), u, 1e-12 * u);
  EXPECT_NEAR(r.max_velocity, u, 1e-12 * u);
  EXPECT_NEAR(r.kinetic_energy, 0.5 * u * u * std::pow(8 * um, 3), 1e-10 * 0.5 * u * u * std::pow(8 * um, 3));
}

TEST(IbStep, TetheredPointsArePulledBackToTheirAnchorsAndPushTheFluid) {
  // Eq. 2.10 with the endothelium's constants (k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm, per point):
  // points at their anchors stay; points displaced by 0.2 um in x move back towards the anchors,
  // and the fluid's momentum equals the impulse of the spring forces, sum -k (X* - X') dt.
  const MacGrid g = box16();
  NavierStokesOptions o;
  o.dt = 50 * units::ns;
  ImmersedBoundary ib(g, FluidParameters{1.0, 0.1 * units::cP}, o, {}, IbOptions{});
  const index_t n = 8;
  host_vector<double> anchors(3 * n), X(3 * n);
  for (index_t k = 0; k < n; ++k) {
    const double xyz[3] = {(2.0 + 1.5 * k) * um, (4.0 + 0.7 * k) * um, (9.0 - 0.5 * k) * um};
    for (int d = 0; d < 3; ++d) anchors[d * n + k] = X[d * n + k] = xyz[d];
    X[k] += 0.2 * um;  // displaced in x
  }
  TetheredPoints still{"still", anchors, anchors, 2.5, 2.5e-7, false, {}};
  ib.add(still);
  ib.add(TetheredPoints{"displaced", X, anchors, 2.5, 2.5e-7, false, {}});
  const double h3 = std::pow(um, 3);
  double impulse = 0;
  for (int s = 0; s < 10; ++s) {
    const IbStepReport r = ib.step();
    (void)r;
    const dvec& f = ib.force_density()[0];
    impulse += o.dt * thrust::reduce(f.begin(), f.end(), 0.0) * h3;
  }
  const host_vector<double> Xd = ib.points(1).X;
  for (index_t k = 0; k < n; ++k) {
    EXPECT_LT(Xd[k] - anchors[k], 0.2 * um) << k;  // moved back
    EXPECT_GT(Xd[k] - anchors[k], 0.0) << k;       // not past the anchor in 0.5 us
  }
  const dvec& u = ib.fluid_state().u[0];
  const double momentum = thrust::reduce(u.begin(), u.end(), 0.0) * h3;
  EXPECT_LT(impulse, 0.0);
  EXPECT_NEAR(momentum, impulse, 1e-10 * std::abs(impulse));
  // Bad input is named.
  EXPECT_THROW(ib.add(TetheredPoints{"bad", X, dvec(3, 0.0), 2.5, 0.0, false, {}}), InputError);
  EXPECT_THROW(ib.add(TetheredPoints{"bad", X, anchors, -1.0, 0.0, false, {}}), InputError);
}

TEST(IbStep, TheSameRunTwiceIsBitwiseIdentical) {
  cells::Placement p = at(8, 8, 8);
  p.stretch = {1.05, 1.0, 1 / 1.05};
  ImmersedBoundary a = periodic_box({p}), b = periodic_box({p});
  for (int n = 0; n < 3; ++n) {
    a.step();
    b.step();
  }
  const std::vector<double> xa = a.batch(0).positions_host(), xb = b.batch(0).positions_host();
  for (std::size_t k = 0; k < xa.size(); ++k) ASSERT_EQ(xa[k], xb[k]) << k;
}

TEST(IbStep, APlantedNanStopsTheStepNamingTheCellAndKeepsTheState) {
  ImmersedBoundary ib = periodic_box({at(5, 8, 8), at(11, 8, 8)});
  ib.step();
  const index_t nd = small_sphere()->n_data();
  ib.batch(0).state().storage()[(0 * 2 + 1) * nd + 7] = std::nan("");  // column d N + c: x of cell 1, data site 7
  const dvec before = ib.batch(0).state().storage();
  const dvec u_before = ib.fluid_state().u[0];
  const std::string m = testing::message_of<NumericalError>([&] { ib.step(); });
  ASSERT_FALSE(m.empty()) << "no error";
  EXPECT_NE(m.find("step 1"), std::string::npos) << m;
  EXPECT_NE(m.find("cell 1"), std::string::npos) << m;
  EXPECT_NE(m.find("data site 7"), std::string::npos) << m;
  try {
    ib.step();
    ADD_FAILURE() << "no error on the second try";
  } catch (const NumericalError& e) {
    EXPECT_EQ(e.cause(), Cause::non_finite) << to_string(e.cause());
  }
  EXPECT_EQ(ib.step_count(), 1);
  EXPECT_EQ(max_abs_diff(ib.fluid_state().u[0], u_before), 0.0);
  const host_vector<double> h0 = before, h1 = ib.batch(0).state().storage();
  for (std::size_t k = 0; k < h0.size(); ++k)
    if (!std::isnan(h0[k])) {
      ASSERT_EQ(h0[k], h1[k]) << k;
    }
}

TEST(IbStep, TheStoppingConditionFiresWithItsNumbersAndKeepsTheState) {
  // A sphere stretched by 2 with dt = 1 ms: ||f||_inf far beyond what eq. 5.4 allows.
  const MacGrid g = box16();
  NavierStokesOptions o;
  o.dt = 1e-3;
  ImmersedBoundary ib(g, FluidParameters{1.0, 0.1 * units::cP}, o, {}, IbOptions{});
  cells::Placement p = at(8, 8, 8);
  p.stretch = {2.0, 1.0, 0.5};
  ib.add(cells::Batch(small_sphere(), {p}));
  const dvec before = ib.batch(0).state().storage();
  const std::string m = testing::message_of<NumericalError>([&] { ib.step(); });
  ASSERT_FALSE(m.empty()) << "no error";
  EXPECT_NE(m.find("eq. 5.4"), std::string::npos) << m;
  EXPECT_NE(m.find("||f||_inf = "), std::string::npos) << m;
  EXPECT_NE(m.find("t = 0 s"), std::string::npos) << m;
  // The cause travels with the error, through the step's own wrapping of it.
  try {
    ib.step();
    ADD_FAILURE() << "no error on the second try";
  } catch (const NumericalError& e) {
    EXPECT_EQ(e.cause(), Cause::stopping_condition) << to_string(e.cause());
  }
  EXPECT_EQ(max_abs_diff(ib.batch(0).state().storage(), before), 0.0);
  EXPECT_EQ(ib.time(), 0.0);
}

/// A sphere stretched by 1.1 in z and compressed by 1.1 in y, relaxing with the adaptive step
/// dt = 2^k dt_min, k <= max_level, starting at dt.
ImmersedBoundary adaptive_box(double dt_min, int max_level, double dt) {
  NavierStokesOptions o;
  o.dt = dt;
  IbOptions io;
  io.adaptive = AdaptiveStep{true, dt_min, max_level, 16};
  ImmersedBoundary ib(box16(), FluidParameters{1.0, 0.1 * units::cP}, o, {}, io);
  cells::Placement p = at(8, 8, 8);
  p.stretch = {1.0, 1 / 1.1, 1.1};
  ib.add(cells::Batch(small_sphere(), {p}));
  return ib;
}

TEST(IbStep, TheAdaptiveStepShrinksAtOnceAndGrowsOnlyAfterSixteenStepsThatAllowIt) {
  const double dt_min = 0.05 * units::us;
  const int max_level = 8;
  ImmersedBoundary ib = adaptive_box(dt_min, max_level, std::ldexp(dt_min, max_level));
  std::vector<double> dts, bounds;
  int refused_first = 0, grew = 0;
  double t = 0;
  for (int n = 0; n < 120; ++n) {
    const IbStepReport r = ib.step();
    // A refusal later on is expected too: near the explicit coupling's stability limit the force
    // grows over a few steps at the larger size until eq. 5.4 refuses it and the step shrinks.
    if (n == 0) refused_first = r.refused;
    const double k = std::log2(r.dt / dt_min);
    ASSERT_EQ(k, std::round(k)) << "step " << n << ": dt = " << r.dt << " is not 2^k dt_min";
    ASSERT_LE(r.dt, r.dt_bound) << "step " << n << ": eq. 5.4 violated";
    t += r.dt;
    dts.push_back(r.dt);
    bounds.push_back(r.dt_bound);
  }
  EXPECT_NEAR(ib.time(), t, 1e-12 * t);
  // The first attempt at 2^8 dt_min is refused and retaken at once at the largest level allowed.
  EXPECT_GT(refused_first, 0);
  EXPECT_LT(dts[0], std::ldexp(dt_min, max_level));
  EXPECT_GT(2 * dts[0], bounds[0]) << "the retaken step is not the largest the bound allows";
  // The level never grows by more than one, and only after 16 steps at one size that allowed 2 dt.
  for (size_t n = 1; n < dts.size(); ++n) {
    if (dts[n] <= dts[n - 1]) continue;
    ++grew;
    ASSERT_EQ(dts[n], 2 * dts[n - 1]) << "step " << n;
    ASSERT_GE(n, 16u) << "step " << n;
    for (size_t m = n - 16; m < n; ++m) {
      ASSERT_EQ(dts[m], dts[n - 1]) << "step " << m << " before the growth at step " << n;
      ASSERT_LE(2 * dts[m], bounds[m]) << "step " << m << " did not allow a doubling";
    }
  }
  EXPECT_GT(grew, 0) << "the relaxing cell's force falls; the step should grow";
}

TEST(IbStep, TheAdaptiveStepStopsWhenEvenItsSmallestStepViolatesTheBound) {
  // The sphere stretched by 2 with dt_min = 1 ms: no level can satisfy eq. 5.4.
  NavierStokesOptions o;
  o.dt = 2e-3;
  IbOptions io;
  io.adaptive = AdaptiveStep{true, 1e-3, 3, 16};
  ImmersedBoundary ib(box16(), FluidParameters{1.0, 0.1 * units::cP}, o, {}, io);
  cells::Placement p = at(8, 8, 8);
  p.stretch = {2.0, 1.0, 0.5};
  ib.add(cells::Batch(small_sphere(), {p}));
  const dvec before = ib.batch(0).state().storage();
  const std::string m = testing::message_of<NumericalError>([&] { ib.step(); });
  EXPECT_NE(m.find("eq. 5.4"), std::string::npos) << m;
  EXPECT_NE(m.find("dt_min = 0.001 s"), std::string::npos) << m;
  try {
    ib.step();
    ADD_FAILURE() << "no error on the second try";
  } catch (const NumericalError& e) {
    EXPECT_EQ(e.cause(), Cause::stopping_condition) << to_string(e.cause());
  }
  EXPECT_EQ(max_abs_diff(ib.batch(0).state().storage(), before), 0.0);
  EXPECT_EQ(ib.time(), 0.0);
  // A first dt that is not 2^k dt_min is bad input naming the field.
  const std::string bad = testing::message_of<InputError>([&] { adaptive_box(1e-7, 4, 3e-7); });
  EXPECT_NE(bad.find("fluid.dt"), std::string::npos) << bad;
}

/// Data-site positions of a stretched sphere after T = 2 us with step dt, coupling c.
std::vector<double> relaxed(double dt, TimeIntegrator ti, Coupling c) {
  const MacGrid g = box16();
  NavierStokesOptions o;
  o.dt = dt;
  o.integrator = ti;
  IbOptions io;
  io.coupling = c;
  ImmersedBoundary ib(g, FluidParameters{1.0, 0.1 * units::cP}, o, {}, io);
  cells::Placement p = at(8, 8, 8);
  p.stretch = {1.0, 1 / 1.1, 1.1};
  ib.add(cells::Batch(small_sphere(), {p}));
  const int steps = int(std::lround(2 * units::us / dt));
  for (int n = 0; n < steps; ++n) ib.step();
  return ib.batch(0).positions_host();
}

TEST(IbStep, TemporalOrdersOfTheTwoCouplings) {
  // Differences of the positions between dt and dt/2 (dt = 0.2, 0.1, 0.05 us) fall as dt^p: the
  // seed's coupling interpolates u^{n+1} at X^n, first order (p = 1 +- 0.25, with either fluid
  // scheme); the midpoint coupling with Peskin's scheme is second order (p >= 1.7).
  auto orders = [](TimeIntegrator ti, Coupling c) {
    std::vector<std::vector<double>> X;
    for (double dt : {0.2, 0.1, 0.05, 0.025}) X.push_back(relaxed(dt * units::us, ti, c));
    std::vector<double> d;
    for (std::size_t k = 0; k + 1 < X.size(); ++k) {
      double m = 0;
      for (std::size_t i = 0; i < X[k].size(); ++i) m = std::max(m, std::abs(X[k][i] - X[k + 1][i]));
      d.push_back(m);
    }
    return std::vector<double>{std::log2(d[0] / d[1]), std::log2(d[1] / d[2])};
  };
  const auto seed_bfe = orders(TimeIntegrator::backward_forward_euler, Coupling::seed);
  const auto seed_peskin = orders(TimeIntegrator::peskin_two_stage, Coupling::seed);
  const auto midpoint = orders(TimeIntegrator::peskin_two_stage, Coupling::midpoint);
  EXPECT_NEAR(seed_bfe[1], 1.0, 0.25);
  EXPECT_NEAR(seed_peskin[1], 1.0, 0.25);
  EXPECT_GE(midpoint[1], 1.7);
  std::printf("orders: seed+BFE %.3f %.3f, seed+Peskin %.3f %.3f, midpoint+Peskin %.3f %.3f\n", seed_bfe[0], seed_bfe[1],
              seed_peskin[0], seed_peskin[1], midpoint[0], midpoint[1]);
  // The midpoint coupling needs the midpoint velocity of Peskin's scheme.
  NavierStokesOptions o;
  o.dt = 1e-7;
  IbOptions io;
  io.coupling = Coupling::midpoint;
  const MacGrid g = box16();
  EXPECT_THROW(ImmersedBoundary(g, FluidParameters{1.0, 0.1 * units::cP}, o, {}, io), InputError);
}

// ---- Chapter 3's forward Euler on periodic Stokes -------------------------------------------

/// A stretched unit-radius LDSM shell (300 spiral vertices, neo-Hookean + tension) in [-2, 2]^3,
/// dimensionless as Chapter 3's dynamic test.
LdsmShell stretched_shell() {
  const surface::SphereSites sites = surface::bauer_spiral(300);
  LdsmShell s;
  s.name = "shell";
  s.triangles = surface::sphere_triangulation(sites);
  s.reference = surface::ellipsoid(1, 1, 1).points(sites);
  s.X = surface::ellipsoid(1.2, 1, 1 / 1.2).points(sites);
  s.energies = {mechanics::EnergyDensity::neo_hookean_paper(1, 1), mechanics::EnergyDensity::surface_tension(1)};
  return s;
}

MacGrid chapter3_box(int eta) {
  MacGrid g = make_mac_grid(3, {eta, eta, eta}, {4.0, 4.0, 4.0}, {MB::periodic, MB::periodic, MB::periodic});
  g.origin = {-2, -2, -2};
  return g;
}

ImmersedBoundary forward_euler(const MacGrid& g, double dt, IbOptions o = {}) {
  o.coupling = Coupling::forward_euler;
  o.kernel = ib::Kernel::peskin4;
  o.stopping_condition = false;
  return ImmersedBoundary(std::make_unique<PeriodicStokesStep>(g, FluidParameters{1.0, 1.0}, dt, true), o);
}

TEST(IbStep, ForwardEulerOnSteadyStokesIsChapter3sUpdateBitForBit) {
  // Sec. 3.3 written out by hand (forces at X^k by eq. 66, spread from X^k, the exact Stokes flow,
  // U at X^k, X^{k+1} = X^k + dt U) against the library's step with an LDSM shell.
  const MacGrid g = chapter3_box(16);
  const double dt = 1.0 / 64;
  ImmersedBoundary ib = forward_euler(g, dt);
  const LdsmShell shell = stretched_shell();
  ib.add(shell);
  PeriodicStokesSolver stokes(g, 1.0, 0.0);
  const MacOperators& ops = stokes.operators();
  ib::Interaction I({ops.component_box(0), ops.component_box(1), ops.component_box(2)}, ib::Kernel::peskin4);
  std::vector<double> X = shell.X;
  for (int k = 0; k < 3; ++k) {
    const std::vector<double> F = mechanics::ldsm_forces("shell", shell.triangles, shell.reference, X, shell.energies).F;
    dvec Xd(X.begin(), X.end()), Fd(F.begin(), F.end()), U;
    ib::SortedPoints at;
    I.sort(ptr(Xd), index_t(X.size() / 3), at);
    VectorField f, u;
    dvec p;
    I.spread(at, ptr(Fd), f);
    stokes.solve(f, u, p);
    U.resize(X.size());
    I.interpolate(at, u, ptr(U));
    const std::vector<double> Uh(U.begin(), U.end());
    for (std::size_t i = 0; i < X.size(); ++i) X[i] += dt * Uh[i];
    const IbStepReport r = ib.step();
    EXPECT_EQ(r.dt, dt);
    EXPECT_TRUE(ib.fluid_state().u[0] == u[0]) << "step " << k;
  }
  EXPECT_TRUE(ib.shell(0).shell().X == X);
  EXPECT_NEAR(ib.time(), 3 * dt, 1e-15);
}

TEST(IbStep, AFrameSetReturnsToItsAnchorsOnAverageAndCarriesEveryoneWithIt) {
  // Eqs. 94-95: the frame velocity u_c moves everything so that the mean of X' - X^{n+1} over a
  // ring of tethered nodes vanishes after each step: a ring displaced downstream by 0.1 is put
  // back by u_c of about -0.1 / dt, and a shell away from the ring moves with it by dt (U + u_c).
  const MacGrid g = chapter3_box(16);
  const double dt = 1.0 / 64;
  IbOptions o;
  const index_t n = 16;
  host_vector<double> Z(3 * n);
  for (index_t q = 0; q < n; ++q) {
    Z[q] = -1.0 + 0.1 * (q % 2);
    Z[n + q] = 1.2 * std::cos(2 * pi * q / n);
    Z[2 * n + q] = 1.2 * std::sin(2 * pi * q / n);
  }
  ImmersedBoundary ib = forward_euler(g, dt, o);
  TetheredPoints ring{"ring", Z, Z, 5.0, 0.0, false, {}};
  ring.frame = true;
  ib.add(ring);
  ring.name = "second";
  EXPECT_THROW(ib.add(ring), InputError);  // one frame only
  for (int k = 0; k < 4; ++k) {
    const IbStepReport r = ib.step();
    const host_vector<double> X = ib.points(0).X;
    for (int d = 0; d < 3; ++d) {
      double mean = 0;
      for (index_t q = 0; q < n; ++q) mean += Z[d * n + q] - X[d * n + q];
      EXPECT_NEAR(mean / n, 0.0, 1e-15) << "step " << k << " axis " << d;
    }
    (void)r;
  }
  // A ring displaced downstream is pulled back and the frame moves with it.
  host_vector<double> X = Z;
  for (index_t q = 0; q < n; ++q) X[q] += 0.1;
  ImmersedBoundary moved = forward_euler(g, dt, o);
  TetheredPoints displaced{"ring", X, Z, 5.0, 0.0, false, {}};
  displaced.frame = true;
  moved.add(displaced);
  moved.add(stretched_shell());
  const std::vector<double> S0 = moved.shell(0).shell().X;
  const IbStepReport r = moved.step();
  // u_c = mean(X' - X^) / dt: about -0.1 / dt (the springs' own flow moves X^ by far less).
  EXPECT_NEAR(r.frame_velocity[0], -0.1 / dt, 0.05 * 0.1 / dt);
  const host_vector<double> Xn = moved.points(0).X;
  double mean = 0;
  for (index_t q = 0; q < n; ++q) mean += Z[q] - Xn[q];
  EXPECT_NEAR(mean / n, 0.0, 1e-15);
  // The shell moved by dt (U + u_c): its mean x displacement is dt u_c plus its own small flow.
  const std::vector<double>& S1 = moved.shell(0).shell().X;
  double shift = 0;
  const std::size_t ns = S1.size() / 3;
  for (std::size_t i = 0; i < ns; ++i) shift += S1[i] - S0[i];
  EXPECT_NEAR(shift / ns, dt * r.frame_velocity[0], 0.05 * 0.1);
}

}  // namespace
}  // namespace rbfib::sim
