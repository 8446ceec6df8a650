// A wall held exactly by a solve (sim/held_wall.hpp): in a channel sheared by its top wall, a
// plane of markers 2h apart above the bottom wall does not slip (the velocity interpolated at the
// markers after each step is zero to the rounding of the solve, where unheld it would be the
// shear's), the flow below it comes to rest, and at steady state the force the markers exert
// balances the shear stress over them; the mobility is built once per step size. Bad input is named.
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/flow_profile.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::sim {
namespace {

const double um = units::um;
constexpr double U_top = 0.3;  // cm/s (3 mm/s along x)

/// The 8 x 6 x 8 um channel, h = 0.5 um, its top wall at 3 mm/s along x, started as the shear.
ImmersedBoundary channel(double dt_us) {
  const scene::Scene sc = scene::parse_scene(R"(
domain:
  size: [8 um, 6 um, 8 um]
  periodic: [x, z]
  walls:
    y: {lower: [0 mm/s, 0 mm/s, 0 mm/s], upper: [3 mm/s, 0 mm/s, 0 mm/s]}
  initial_flow: shear
fluid: {density: 1 g/cm^3, viscosity: 1 cP}
grid: {cells: [16, 12, 16]}
time: {integrator: backward_forward_euler, dt: )" + std::to_string(dt_us) + R"( us, end: 1 ms}
ib: {kernel: bspline3}
)", "held wall test");
  return scene::build(sc);
}

/// Markers on the plane y = y0 every `spacing` in x and z (8 x 8 um).
HeldWall plane(double y0, double spacing) {
  const int m = int(std::lround(8 * um / spacing)), n = m * m;
  host_vector<double> X(static_cast<std::size_t>(3 * n));
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < m; ++k) {
      const int p = i * m + k;
      X[p] = (i + 0.25) * spacing, X[n + p] = y0, X[2 * n + p] = (k + 0.25) * spacing;
    }
  return HeldWall{"plane", dvec(X.begin(), X.end())};
}

TEST(HeldWall, MarkersDoNotSlipWhereTheShearWouldMoveThem) {
  ImmersedBoundary ib = channel(0.1);
  ib.add(plane(1.5 * um, 1.0 * um));  // 2h apart: 64 markers, 192 unknowns
  for (int s = 0; s < 5; ++s) {
    const IbStepReport r = ib.step();
    EXPECT_GT(r.seconds_held, 0.0);
    // Unheld, the markers would move with the shear: U_top y0 / Ly = 0.075 cm/s.
    EXPECT_LT(blas::norm_inf(ib.held_wall(0).velocity()), 1e-10 * U_top) << "step " << s;
  }
  EXPECT_EQ(ib.held_wall(0).mobilities(), 1u);  // one dt, one mobility
}

TEST(HeldWall, SteadyShearAboveItAndRestBelowIt) {
  // Backward Euler in the viscous term: 10 us steps reach the steady state of the 4.5 um gap
  // (slowest mode decays by 1 / (1 + nu k^2 dt) = 1/5.9 per step) in 30 steps to 1e-20.
  ImmersedBoundary ib = channel(10);
  const double y0 = 1.5 * um, Ly = 6 * um;
  ib.add(plane(y0, 1.0 * um));
  for (int s = 0; s < 30; ++s) ib.step();
  EXPECT_LT(blas::norm_inf(ib.held_wall(0).velocity()), 1e-10 * U_top);
  const std::vector<double> u = velocity_profile(ib, {1, 0, 0});  // x-z means per cell row
  // Below the markers the flow is brought to rest: the rows whose centres lie more than the
  // kernel's half-support (2h = 1 um) below the plane (measured: -0.6% of U_top at y = 0.25 um).
  EXPECT_LT(std::abs(u[0]), 0.02 * U_top) << "row y = 0.25 um";
  // Above, the shear between the plane and the top wall: linear in y through the held plane
  // within the kernel's smearing of where the wall sits (the effective plane within 2h of y0;
  // measured: 0.15 um above the markers, u = 0.2137 U_top here).
  const double lo = U_top * (4.75 * um - (y0 + 1 * um)) / (Ly - (y0 + 1 * um));
  const double hi = U_top * (4.75 * um - (y0 - 1 * um)) / (Ly - (y0 - 1 * um));
  EXPECT_GT(u[9], lo) << "row y = 4.75 um";
  EXPECT_LT(u[9], hi) << "row y = 4.75 um";
  // The markers' force balances the shear stress mu U / (Ly - y0) over the plane's 64 um^2 (the
  // same smearing bounds the gap): its sum is the force on the fluid, against the top wall's drag
  // (measured 4.87e-6 dyn: the stress above, 4.42e-6 at the measured slope, and the small one of
  // the flow below, which the markers also hold).
  const std::vector<double> F(ib.held_wall(0).force().begin(), ib.held_wall(0).force().end());
  double Fx = 0;
  for (std::size_t p = 0; p < F.size() / 3; ++p) Fx += F[p];
  const double mu = 0.01, area = 64 * um * um;
  EXPECT_LT(-Fx, mu * U_top / (Ly - (y0 + 1 * um)) * area);
  EXPECT_GT(-Fx, mu * U_top / (Ly - (y0 - 1 * um)) * area);
}

TEST(HeldWall, BadMarkersAndASecondWallAreNamed) {
  ImmersedBoundary ib = channel(0.1);
  EXPECT_THROW(ib.add(HeldWall{"empty", dvec()}), InputError);
  EXPECT_THROW(ib.add(HeldWall{"ragged", dvec(4, 1e-4)}), InputError);
  ib.add(plane(1.5 * um, 1.0 * um));
  EXPECT_THROW(ib.add(plane(2.5 * um, 1.0 * um)), InputError);
}

}  // namespace
}  // namespace rbfib::sim
