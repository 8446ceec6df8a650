// The fluid steps the coupled step sees (fluid/fluid_step.hpp): the double-buffered Navier-Stokes
// step leaves the state it reads untouched and equals the in-place step bit for bit; unsteady
// periodic Stokes decays a shear wave by the discrete factor 1 / (1 + dt nu lambda) per step;
// steady periodic Stokes is the solver's exact flow of the force; bad input is named.
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/fluid/fluid_step.hpp"
#include "rbfib/linalg/blas.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rbfib {
namespace {

using MB = MacBoundary;

MacGrid periodic_cube(int n, double L) { return make_mac_grid(3, {n, n, n}, {L, L, L}, {MB::periodic, MB::periodic, MB::periodic}); }

/// u_x = sin(2 pi y / L) on the x-faces (divergence free on the MAC grid), u_y = u_z = 0.
VectorField shear_wave(const MacOperators& ops, double L) {
  VectorField u;
  for (int a = 0; a < 3; ++a) u[a] = dvec(static_cast<std::size_t>(ops.component_box(a).size()), 0.0);
  const Box& b = ops.component_box(0);
  std::vector<double> ux(u[0].size());
  for (int k = 0; k < b.n(2); ++k)
    for (int j = 0; j < b.n(1); ++j)
      for (int i = 0; i < b.n(0); ++i) ux[i + index_t(b.n(0)) * (j + index_t(b.n(1)) * k)] = std::sin(2 * pi * b.x(1, j) / L);
  u[0] = dvec(ux.begin(), ux.end());
  return u;
}

TEST(FluidStep, TheDoubleBufferedNavierStokesStepEqualsTheInPlaceOneAndLeavesItsInputAlone) {
  const double L = 1e-3;
  const MacGrid g = make_mac_grid(3, {12, 10, 8}, {L, L, L}, {MB::periodic, MB::dirichlet, MB::periodic});
  NavierStokesOptions o;
  o.integrator = TimeIntegrator::peskin_two_stage;
  o.dt = 1e-5;
  NavierStokesSolver ns(g, FluidParameters{1.0, 0.01}, o);
  FluidState a = ns.zero_state(0.0);
  const MacOperators& ops = ns.operators();
  a.u = shear_wave(ops, L);
  VectorField f;
  for (int c = 0; c < 3; ++c) f[c] = dvec(static_cast<std::size_t>(ops.component_box(c).size()), 1e3 * (c + 1));
  FluidState in_place = a, from = a, to;
  for (int n = 0; n < 3; ++n) {
    ns.step(in_place, &f);
    const FluidState before = from;
    ns.step(from, to, &f);
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(before.u[c] == from.u[c]);
    EXPECT_TRUE(before.p == from.p);
    std::swap(from, to);
  }
  for (int c = 0; c < 3; ++c) EXPECT_TRUE(in_place.u[c] == from.u[c]) << "component " << c;
  EXPECT_TRUE(in_place.p == from.p);
  EXPECT_TRUE(in_place.phi[0] == from.phi[0] && in_place.phi[1] == from.phi[1]);
  EXPECT_EQ(in_place.t, from.t);
  EXPECT_THROW(ns.step(from, from, &f), InputError);
}

TEST(FluidStep, UnsteadyPeriodicStokesDecaysAShearWaveByTheDiscreteFactor) {
  const int n = 16;
  const double L = 16e-4, rho = 1.0, mu = 0.01, dt = 1e-4;
  PeriodicStokesStep step(periodic_cube(n, L), FluidParameters{rho, mu}, dt, false);
  step.state().u = shear_wave(step.operators(), L);
  // The MAC Laplacian's eigenvalue of sin(2 pi y / L): -(2 - 2 cos(2 pi h / L)) / h^2.
  const double h = L / n, lambda = (2 - 2 * std::cos(2 * pi * h / L)) / (h * h);
  const double factor = 1 / (1 + dt * mu * lambda / rho);
  const double a0 = blas::norm_inf(step.state().u[0]);
  for (int k = 0; k < 4; ++k) {
    step.step(nullptr);
    step.accept();
  }
  EXPECT_NEAR(blas::norm_inf(step.state().u[0]) / a0, std::pow(factor, 4), 1e-12);
  EXPECT_LT(blas::norm_inf(step.state().u[1]), 1e-13);
  EXPECT_NEAR(step.state().t, 4 * dt, 1e-18);
}

TEST(FluidStep, SteadyPeriodicStokesIsTheSolversFlowAndTheStateWaitsForAccept) {
  const int n = 12;
  const double L = 12e-4;
  PeriodicStokesStep step(periodic_cube(n, L), FluidParameters{1.0, 0.012}, 1e-4, true);
  const MacOperators& ops = step.operators();
  VectorField f = shear_wave(ops, L);
  blas::scale(8e3, f[0]);
  step.step(&f);
  EXPECT_EQ(blas::norm_inf(step.state().u[0]), 0.0);  // not accepted yet
  step.accept();
  VectorField u;
  dvec p;
  PeriodicStokesSolver(periodic_cube(n, L), 0.012, 0.0).solve(f, u, p);
  EXPECT_TRUE(step.state().u[0] == u[0]);
  EXPECT_GT(blas::norm_inf(u[0]), 0.0);
}

TEST(FluidStep, BadInputIsNamed) {
  const MacGrid g = periodic_cube(8, 8e-4);
  auto field_of = [](auto&& make) {
    try {
      make();
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("no error");
  };
  EXPECT_EQ(field_of([&] { PeriodicStokesStep(g, FluidParameters{1.0, 0.01}, 0.0, true); }), "fluid.dt");
  EXPECT_EQ(field_of([&] { PeriodicStokesStep(g, FluidParameters{0.0, 0.01}, 1e-4, true); }), "fluid.density");
  EXPECT_EQ(field_of([&] { PeriodicStokesStep(g, FluidParameters{1.0, -1.0}, 1e-4, true); }), "fluid.viscosity");
  const MacGrid walls = make_mac_grid(3, {8, 8, 8}, {8e-4, 8e-4, 8e-4}, {MB::periodic, MB::dirichlet, MB::periodic});
  EXPECT_EQ(field_of([&] { PeriodicStokesStep(walls, FluidParameters{1.0, 0.01}, 1e-4, true); }), "grid.y.boundary");
  PeriodicStokesStep s(g, FluidParameters{1.0, 0.01}, 1e-4, true);
  EXPECT_EQ(field_of([&] { s.midpoint_velocity(); }), "ib.coupling");
}

}  // namespace
}  // namespace rbfib
