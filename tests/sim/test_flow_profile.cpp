// The x-z averaged velocity profile across a channel (sim/flow_profile.hpp).
#include "rbfib/sim/flow_profile.hpp"

#include "rbfib/core/units.hpp"
#include "rbfib/scene/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace rbfib;

TEST(FlowProfile, SteadyShearAlongTheWallsDirectionIsLinearAcrossTheChannel) {
  // The top wall at (3, 0, 4) mm/s, the flow started as the steady shear: u = (y / Ly) U.
  const scene::Scene sc = scene::parse_scene(R"(
domain:
  size: [8 um, 6 um, 8 um]
  periodic: [x, z]
  walls:
    y: {lower: [0 mm/s, 0 mm/s, 0 mm/s], upper: [3 mm/s, 0 mm/s, 4 mm/s]}
  initial_flow: shear
fluid: {density: 1 g/cm^3, viscosity: 1 cP}
grid: {cells: [8, 6, 8]}
time: {integrator: backward_forward_euler, dt: 0.1 us, end: 0.1 us}
ib: {kernel: bspline3}
)", "test");
  const sim::ImmersedBoundary ib = scene::build(sc);
  const std::vector<double> u = sim::velocity_profile(ib, {0.6, 0, 0.8});  // along the wall's motion
  ASSERT_EQ(u.size(), 6u);
  for (std::size_t j = 0; j < u.size(); ++j) EXPECT_NEAR(u[j], 0.5 * (double(j) + 0.5) / 6, 1e-12) << j;  // |U| = 0.5 cm/s
  const std::vector<double> w = sim::velocity_profile(ib, {0.8, 0, -0.6});  // across it: none
  for (double x : w) EXPECT_NEAR(x, 0, 1e-12);
}
