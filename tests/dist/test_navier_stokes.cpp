// The Navier-Stokes solver stepping slabs (dist/slab_fluid.hpp) against the same solver on one
// process: a channel (x, z periodic; no-slip walls in y, the upper one sliding) driven by a body
// force that varies along x and z, 12 steps of each integrator, on however many ranks the test
// runs with (n_z = 12: 12, 6 + 6, 4 + 4 + 4, 3 + 3 + 3 + 3 planes). The velocity and pressure agree
// with the one-process run to rounding on every plane, and the divergence the step reports is
// the whole box's.
//
// Tolerance: the two runs differ only in the order of the FFTs' sums (the same operators, the same
// arithmetic otherwise); measured 5e-16 to 3e-15 of the largest value on 1 to 4 ranks. 1e-13
// leaves a factor of 30 for other FFT plans; a ghost plane read stale or a mode solved twice
// shows as O(1).
#include "rbfib/dist/slab_fluid.hpp"
#include "rbfib/fluid/navier_stokes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace rbfib::dist {
namespace {

using MB = MacBoundary;

double largest_difference(const host_vector<double>& a, const host_vector<double>& b, double* scale) {
  double worst = 0.0;
  for (std::size_t p = 0; p < a.size(); ++p) {
    worst = std::max(worst, std::abs(a[p] - b[p]));
    *scale = std::max(*scale, std::abs(b[p]));
  }
  return worst;
}

TEST(DistributedNavierStokes, StepsAsOneProcessDoes) {
  const Comm world;
  const MacGrid grid = make_mac_grid(3, {8, 8, 12}, {0.8, 0.8, 1.2}, {MB::periodic, MB::dirichlet, MB::periodic});
  const double U = 2.0;  // upper wall sliding along x (cm/s)
  const BoundaryVelocity wall = [U](int a, int d, int side, double, double, double, double) {
    return (a == 0 && d == 1 && side == 1) ? U : 0.0;
  };
  auto force = [](int a, double x, double y, double z) {
    return (a == 0 ? 30.0 : a == 1 ? 10.0 : 20.0) * std::sin(2 * M_PI * x / 0.8 + a) * std::cos(2 * M_PI * z / 1.2) *
           (1.0 + y);
  };
  for (TimeIntegrator integrator : {TimeIntegrator::backward_forward_euler, TimeIntegrator::peskin_two_stage}) {
    NavierStokesOptions options;
    options.integrator = integrator;
    options.dt = 2e-3;
    const FluidParameters fluid{1.0, 0.05};
    auto parts = std::make_shared<const SlabFluid>(grid, world);
    NavierStokesSolver one(grid, fluid, options, wall);
    NavierStokesSolver many(grid, fluid, options, wall, parts);
    ASSERT_TRUE(many.fourier());
    VectorField f_one, f_many;
    for (int a = 0; a < 3; ++a) {
      f_one[a] = sample(one.operators().component_box(a), [&](double x, double y, double z) { return force(a, x, y, z); });
      f_many[a] = sample(many.operators().component_box(a), [&](double x, double y, double z) { return force(a, x, y, z); });
    }
    FluidState s_one = one.zero_state(), s_many = many.zero_state();
    StepStats st_one, st_many;
    for (int n = 0; n < 12; ++n) {
      st_one = one.step(s_one, &f_one);
      st_many = many.step(s_many, &f_many);
    }
    double worst = 0.0, scale = 0.0;
    for (int a = 0; a < 3; ++a) {
      const Box& local = many.operators().component_box(a);
      worst = std::max(worst, largest_difference(parts->gather(local, s_many.u[a]), s_one.u[a], &scale));
    }
    double p_scale = 0.0;
    const double p_worst = largest_difference(parts->gather(many.operators().scalar_box(), s_many.p), s_one.p, &p_scale);
    EXPECT_GT(scale, 0.1 * U) << to_string(integrator);
    EXPECT_LE(worst, 1e-13 * scale) << to_string(integrator) << " on " << world.size() << " ranks";
    EXPECT_LE(p_worst, 1e-13 * p_scale) << to_string(integrator) << " pressure on " << world.size() << " ranks";
    EXPECT_NEAR(st_many.max_divergence, st_one.max_divergence, 1e-9 * (1.0 + st_one.max_divergence));
    EXPECT_DOUBLE_EQ(s_many.t, s_one.t);
  }
}

TEST(DistributedNavierStokes, RefusesTheMultigridPathAndWallsAcrossZ) {
  const Comm world;
  const MacGrid channel = make_mac_grid(3, {8, 8, 8}, {1, 1, 1}, {MB::periodic, MB::dirichlet, MB::periodic});
  NavierStokesOptions options;
  options.dt = 1e-3;
  options.solvers = FluidSolvers::multigrid;
  EXPECT_THROW(NavierStokesSolver(channel, {}, options, {}, std::make_shared<const SlabFluid>(channel, world)), InputError);
  const MacGrid duct = make_mac_grid(3, {8, 8, 8}, {1, 1, 1}, {MB::periodic, MB::dirichlet, MB::dirichlet});
  EXPECT_THROW(SlabFluid(duct, world), InputError);
}

}  // namespace
}  // namespace rbfib::dist
