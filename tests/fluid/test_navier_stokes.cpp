// Unit tests of the Navier-Stokes integrators: exactness on steady Couette flow with a moving wall,
// measured orders on small grids (space: 2D Taylor-Green vortex; time: Couette start-up), the
// divergence after a forced step, and refusal of bad scenes and report of failed solves by name.
#include "rbfib/fluid/exact_solutions.hpp"
#include "rbfib/fluid/navier_stokes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib {
namespace {

using MB = MacBoundary;

VectorField sample_velocity(const NavierStokesSolver& ns, const std::function<double(int, double, double, double)>& f) {
  VectorField u;
  for (int a = 0; a < ns.grid().dims; ++a)
    u[a] = sample(ns.operators().component_box(a), [&](double x, double y, double z) { return f(a, x, y, z); });
  return u;
}

double max_error(const VectorField& u, const VectorField& v, int dims) {
  double e = 0;
  for (int a = 0; a < dims; ++a) {
    dvec d = u[a];
    blas::axpy(-1.0, v[a], d);
    e = std::max(e, blas::norm_inf(d));
  }
  return e;
}

MacGrid channel(int ny) { return make_mac_grid(3, {4, ny, 4}, {1.0, 1.0, 1.0}, {MB::periodic, MB::dirichlet, MB::periodic}); }

TEST(NavierStokes, SteadyCouetteIsExactForBothIntegrators) {
  // u = U y (linear) with the top wall at U: a steady solution the discretization must keep exactly
  // (ghosts and the corrected Laplacian are exact on linears; advection of a shear is zero).
  for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage}) {
    NavierStokesOptions o;
    o.integrator = ti;
    o.dt = 0.01;
    NavierStokesSolver ns(channel(10), FluidParameters{1.0, 0.3}, o,
                          [](int a, int d, int side, double, double, double, double) { return a == 0 && d == 1 && side ? 2.0 : 0.0; });
    FluidState s = ns.zero_state();
    s.u = sample_velocity(ns, [](int a, double, double y, double) { return a == 0 ? 2.0 * y : 0.0; });
    const VectorField u0 = s.u;
    for (int n = 0; n < 10; ++n) ns.step(s);
    // rounding: 10 steps of solves to 1e-11 relative residual on O(1) data
    EXPECT_LT(max_error(s.u, u0, 3), 1e-10) << to_string(ti);
  }
}

double couette_run(TimeIntegrator ti, double dt, int ny, VectorField* out) {
  const double nu = 0.5, U = 1.0;
  exact::Couette c{1.0, U, nu};
  NavierStokesOptions o;
  o.integrator = ti;
  o.dt = dt;
  NavierStokesSolver ns(channel(ny), FluidParameters{1.0, nu}, o,
                        [U](int a, int d, int side, double, double, double, double) { return a == 0 && d == 1 && side ? U : 0.0; });
  FluidState s = ns.zero_state(0.02);
  s.u = sample_velocity(ns, [&](int a, double x, double y, double z) { return c.velocity(a, 0.02, x, y, z); });
  const int steps = int(std::lround(0.08 / dt));
  for (int n = 0; n < steps; ++n) ns.step(s);
  const VectorField e = sample_velocity(ns, [&](int a, double x, double y, double z) { return c.velocity(a, s.t, x, y, z); });
  if (out) *out = s.u;
  return max_error(s.u, e, 3);
}

TEST(NavierStokes, TemporalOrdersOnCouetteStartUp) {
  // differences of runs with dt, dt/2, dt/4 on one grid: the spatial error cancels.
  for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage}) {
    VectorField u1, u2, u3;
    couette_run(ti, 0.02, 16, &u1);
    couette_run(ti, 0.01, 16, &u2);
    couette_run(ti, 0.005, 16, &u3);
    const double order = std::log2(max_error(u1, u2, 3) / max_error(u2, u3, 3));
    const double expected = ti == TimeIntegrator::backward_forward_euler ? 1.0 : 2.0;
    // O(dt) remainder of the difference quotient at these steps: a few percent of the order
    EXPECT_NEAR(order, expected, 0.15) << to_string(ti);
  }
}

TEST(NavierStokes, SpatialOrderOnTaylorGreen2D) {
  // 2D periodic Taylor-Green vortex with Peskin's scheme, dt ~ h: error O(h^2).
  exact::TaylorGreen tg{1.0, 1.0, 0.05, 1.0};
  double err[2];
  for (int k = 0; k < 2; ++k) {
    const int n = 16 << k;
    MacGrid g = make_mac_grid(2, {n, n, 1}, {1.0, 1.0, 1.0}, {MB::periodic, MB::periodic, MB::periodic});
    NavierStokesOptions o;
    o.integrator = TimeIntegrator::peskin_two_stage;
    o.dt = 0.04 / n;
    NavierStokesSolver ns(g, FluidParameters{1.0, 0.05}, o);
    FluidState s = ns.zero_state();
    s.u = sample_velocity(ns, [&](int a, double x, double y, double z) { return tg.velocity(a, 0.0, x, y, z); });
    s.p = sample(ns.operators().scalar_box(), [&](double x, double y, double z) { return tg.pressure(0.0, x, y, z); });
    for (int m = 0; m < n / 4; ++m) ns.step(s);  // to t = 0.01
    err[k] = max_error(s.u, sample_velocity(ns, [&](int a, double x, double y, double z) { return tg.velocity(a, s.t, x, y, z); }), 2);
  }
  // the O(h^4) remainder on 16 cells per wavelength is ~5% of the error: order within 0.2 of 2
  EXPECT_NEAR(std::log2(err[0] / err[1]), 2.0, 0.2);
}

TEST(NavierStokes, ForcedStepLeavesDivergenceFreeVelocity) {
  MacGrid g = make_mac_grid(3, {8, 8, 8}, {1, 1, 1}, {MB::periodic, MB::dirichlet, MB::neumann});
  for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage}) {
    NavierStokesOptions o;
    o.integrator = ti;
    o.dt = 0.01;
    NavierStokesSolver ns(g, FluidParameters{1.0, 0.1}, o,
                          [](int a, int d, int side, double t, double x, double, double z) {
                            return d == 1 && a != 1 ? (side ? 1.0 : -0.5) * std::cos(6.283185307179586 * x + t) + 0.1 * z : 0.0;
                          });
    FluidState s = ns.zero_state();
    VectorField f = sample_velocity(ns, [](int a, double x, double y, double z) {
      return std::exp(-20 * ((x - 0.5) * (x - 0.5) + (y - 0.4) * (y - 0.4) + (z - 0.6) * (z - 0.6))) * (a == 0 ? 5.0 : 2.0);
    });
    for (int n = 0; n < 3; ++n) {
      const StepStats st = ns.step(s, &f);
      double umax = 0;
      for (int a = 0; a < 3; ++a) umax = std::max(umax, blas::norm_inf(s.u[a]));
      // PCG to 1e-11 relative residual on 512 cells: |D u| h / |u| < 1e-11 sqrt(512) with room.
      EXPECT_LT(st.max_divergence * g.h(0) / umax, 1e-10) << to_string(ti) << " step " << n;
      EXPECT_GT(st.poisson_iterations[0], 0);
    }
  }
}

std::string field_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.field();
  }
  return "";
}

TEST(NavierStokes, BadScenesNameTheField) {
  NavierStokesOptions o;
  o.dt = 1e-3;
  const MacGrid g = channel(8);
  EXPECT_EQ(field_of([&] { NavierStokesSolver(g, FluidParameters{1.0, 0.1}, NavierStokesOptions{}); }), "fluid.dt");
  EXPECT_EQ(field_of([&] { NavierStokesSolver(g, FluidParameters{1.0, -0.1}, o); }), "fluid.viscosity");
  EXPECT_EQ(field_of([&] { NavierStokesSolver(g, FluidParameters{0.0, 0.1}, o); }), "fluid.density");
  MacGrid small = g;
  small.cells[0] = 2;
  EXPECT_EQ(field_of([&] { NavierStokesSolver(small, FluidParameters{1.0, 0.1}, o); }), "grid.x.cells");
  MacGrid mixed = g;
  mixed.lower[2] = MB::dirichlet;
  EXPECT_EQ(field_of([&] { NavierStokesSolver(mixed, FluidParameters{1.0, 0.1}, o); }), "grid.z.upper");
  NavierStokesOptions deep = o;
  deep.solvers = FluidSolvers::multigrid;
  deep.poisson.levels = 5;
  EXPECT_EQ(field_of([&] { NavierStokesSolver(g, FluidParameters{1.0, 0.1}, deep); }), "poisson.levels");
}

TEST(NavierStokes, FourierAndMultigridPathsGiveTheSameSteps) {
  // On a channel (x, z periodic, walls in y) the automatic choice is the direct Fourier solver;
  // five forced steps with a moving wall agree with the multigrid path (PCG to 1e-13) to 1e-10,
  // for both integrators. Walls across z force the multigrid path, and asking for Fourier there
  // is a named error.
  const MacGrid g = make_mac_grid(3, {8, 12, 8}, {1.0, 1.2, 1.0}, {MB::periodic, MB::dirichlet, MB::periodic});
  auto wall = [](int a, int d, int side, double t, double x, double, double) {
    return a == 0 && d == 1 && side ? 1.0 + 0.3 * std::sin(6.283185307179586 * x + 10 * t) : 0.0;
  };
  for (TimeIntegrator ti : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage}) {
    NavierStokesOptions o;
    o.integrator = ti;
    o.dt = 0.01;
    NavierStokesOptions m = o;
    m.solvers = FluidSolvers::multigrid;
    m.helmholtz.solver.rtol = 1e-13;
    m.poisson.solver.rtol = 1e-13;
    NavierStokesSolver direct(g, FluidParameters{1.0, 0.1}, o, wall), iterative(g, FluidParameters{1.0, 0.1}, m, wall);
    ASSERT_TRUE(direct.fourier());
    ASSERT_FALSE(iterative.fourier());
    FluidState a = direct.zero_state(), b = iterative.zero_state();
    VectorField f = sample_velocity(direct, [](int c, double x, double y, double z) {
      return std::exp(-20 * ((x - 0.5) * (x - 0.5) + (y - 0.4) * (y - 0.4) + (z - 0.6) * (z - 0.6))) * (c == 0 ? 5.0 : 2.0);
    });
    for (int n = 0; n < 5; ++n) {
      const StepStats sa = direct.step(a, &f);
      iterative.step(b, &f);
      EXPECT_EQ(sa.poisson_iterations[0], 0);
      EXPECT_LT(sa.max_divergence, 1e-9);
    }
    for (int c = 0; c < 3; ++c) {
      dvec d = a.u[c];
      blas::axpy(-1.0, b.u[c], d);
      EXPECT_LT(blas::norm_inf(d), 1e-10 * blas::norm_inf(b.u[c])) << to_string(ti) << " u" << c;
    }
  }
  NavierStokesOptions o;
  o.dt = 0.01;
  const MacGrid walled = make_mac_grid(3, {8, 8, 8}, {1, 1, 1}, {MB::periodic, MB::dirichlet, MB::dirichlet});
  EXPECT_FALSE(NavierStokesSolver(walled, FluidParameters{1.0, 0.1}, o).fourier());
  o.solvers = FluidSolvers::fourier;
  EXPECT_EQ(field_of([&] { NavierStokesSolver(walled, FluidParameters{1.0, 0.1}, o); }), "fluid.solvers");
}

TEST(NavierStokes, ChangingTheStepEqualsASolverBuiltForIt) {
  // Steps at dt, then 2 dt, then dt again (the adaptive step's moves) equal, bit for bit, the
  // same steps by solvers built for each size, on both paths (the multigrid one with its
  // iterative solves from the same guesses); a bad dt names the field.
  const MacGrid g = make_mac_grid(3, {8, 12, 8}, {1.0, 1.2, 1.0}, {MB::periodic, MB::dirichlet, MB::periodic});
  auto wall = [](int a, int d, int side, double, double, double, double) { return a == 0 && d == 1 && side ? 1.0 : 0.0; };
  for (FluidSolvers path : {FluidSolvers::fourier, FluidSolvers::multigrid}) {
    NavierStokesOptions o;
    o.integrator = TimeIntegrator::peskin_two_stage;
    o.solvers = path;
    o.dt = 0.01;
    NavierStokesOptions o2 = o;
    o2.dt = 0.02;
    NavierStokesSolver one(g, FluidParameters{1.0, 0.1}, o, wall), small(g, FluidParameters{1.0, 0.1}, o, wall),
        large(g, FluidParameters{1.0, 0.1}, o2, wall);
    FluidState a = one.zero_state(), b = one.zero_state();
    const double sizes[4] = {0.01, 0.02, 0.02, 0.01};
    for (double dt : sizes) {
      one.set_dt(dt);
      EXPECT_EQ(one.options().dt, dt);
      one.step(a);
      (dt == 0.01 ? small : large).step(b);
    }
    EXPECT_EQ(a.t, b.t);
    for (int c = 0; c < 3; ++c) {
      dvec d = a.u[c];
      blas::axpy(-1.0, b.u[c], d);
      EXPECT_EQ(blas::norm_inf(d), 0.0) << to_string(path) << " u" << c;
    }
    EXPECT_EQ(field_of([&] { one.set_dt(-1.0); }), "fluid.dt");
  }
}

TEST(NavierStokes, FailedSolveStopsTheStepWithItsName) {
  NavierStokesOptions o;
  o.dt = 0.05;
  o.solvers = FluidSolvers::multigrid;
  o.helmholtz.solver.max_iterations = 1;
  NavierStokesSolver ns(channel(16), FluidParameters{1.0, 1.0}, o,
                        [](int a, int d, int side, double, double, double, double) { return a == 0 && d == 1 && side ? 1.0 : 0.0; });
  FluidState s = ns.zero_state();
  try {
    ns.step(s);
    FAIL() << "the iteration limit was not reported";
  } catch (const NumericalError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("helmholtz u0: did not converge in 1 iterations"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace rbfib
