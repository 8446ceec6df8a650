// Tethered points on the adaptive step (scene/scene.hpp, sim/tether_stability.hpp): constants that
// follow the step by the seed's rule, and the guard that keeps fixed constants inside their bound.
#include "../common/errors.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/tether_stability.hpp"

#include <gtest/gtest.h>

using namespace rbfib;
using namespace rbfib::scene;

namespace {

// A 4 x 12 x 4 um channel at h = 0.4 um with a 16 x 16 sheet at y = 1 um (n_A = 16 um^-2): the
// fixed constants' bound is 271 ns there (docs/derivations/tether_stability).
const std::string sheet_scene = R"(
name: sheet
domain:
  size: [4 um, 12 um, 4 um]
  periodic: [x, z]
  walls:
    y: {lower: [0 mm/s, 0 mm/s, 0 mm/s], upper: [0 mm/s, 0 mm/s, 0 mm/s]}
fluid: {density: 1 g/cm^3, viscosity: 1 cP}
grid: {cells: [10, 30, 10]}
time:
  integrator: backward_forward_euler
  dt: 100 ns
  end: 1 us
  adaptive: {dt_min: 50 ns, max_level: 4}
ib: {kernel: bspline3}
tethered_points:
  - name: endothelium
    plane: {y: 1 um, points: [16, 16]}
    TETHERS
output: {diagnostics_every: 1}
)";

std::string with(const std::string& tethers) {
  std::string s = sheet_scene;
  return s.replace(s.find("TETHERS"), 7, tethers);
}

std::string field_of(const std::string& yaml) {
  return rbfib::testing::field_of([&] { build(parse_scene(yaml, "sheet")); });
}

}  // namespace

TEST(Tethers, ConstantsFollowTheStep) {
  const Scene s = parse_scene(with("follow_step: {gain: 0.5}"), "sheet");
  ASSERT_EQ(s.point_sets.size(), 1u);
  EXPECT_EQ(s.point_sets[0].follow_gain, 0.5);
  const sim::TetherSheet sheet = tether_sheet(s, s.point_sets[0]);
  EXPECT_NEAR(sheet.points_per_area, 16 / (units::um * units::um), 1e-6);
  EXPECT_NEAR(sheet.plane, 1 * units::um, 1e-15);
  sim::ImmersedBoundary ib = build(s);
  for (int n = 0; n < 20; ++n) {
    const double dt = ib.dt();
    ib.step();
    const sim::TetherConstants c = sim::tether_constants_for_step(sheet, dt, 0.5);
    EXPECT_EQ(ib.points(0).k, c.k) << "step " << n << " at dt = " << dt;  // the step's own constants
    EXPECT_EQ(ib.points(0).eta, c.eta);
  }
  // Written back exactly.
  const Scene again = parse_scene(to_yaml(s), "again");
  EXPECT_EQ(again.point_sets[0].follow_gain, 0.5);
  EXPECT_EQ(again.point_sets[0].k, 0);
}

TEST(Tethers, FixedConstantsGuardTheLadder) {
  // The seed's constants: 100 ns is inside their 271 ns bound, 400 ns (a rung of the ladder) is not.
  EXPECT_EQ(field_of(with("k: 2.5 dyn/cm\n    eta: 2.5e-7 dyn s/cm")), "");
  std::string above = with("k: 2.5 dyn/cm\n    eta: 2.5e-7 dyn s/cm");
  above.replace(above.find("dt: 100 ns"), 10, "dt: 400 ns");
  EXPECT_EQ(field_of(above), "fluid.dt");
  const std::string message = rbfib::testing::message_of<InputError>([&] { build(parse_scene(above, "sheet")); });
  EXPECT_NE(message.find("guard"), std::string::npos) << message;
  // The ladder never climbs past the guard: 200 ns is its last rung below 271 ns.
  sim::ImmersedBoundary ib = build(parse_scene(with("k: 2.5 dyn/cm\n    eta: 2.5e-7 dyn s/cm"), "sheet"));
  double largest = 0;
  for (int n = 0; n < 200; ++n) largest = std::max(largest, ib.step().dt);
  EXPECT_NEAR(largest, 200 * units::ns, 1e-18);
}

TEST(Tethers, BadRulesAreNamed) {
  EXPECT_EQ(field_of(with("follow_step: {gain: 1.5}")), "tethered_points[0].follow_step.gain");
  EXPECT_EQ(field_of(with("follow_step: {gain: 0.5}\n    k: 2.5 dyn/cm")), "tethered_points[0].k");
  std::string midpoint = with("follow_step: {gain: 0.5}");
  midpoint.replace(midpoint.find("backward_forward_euler"), 22, "peskin_two_stage\n  coupling: midpoint");
  EXPECT_EQ(field_of(midpoint), "tethered_points[0].follow_step");
  std::string periodic = with("follow_step: {gain: 0.5}");
  periodic.replace(periodic.find("periodic: [x, z]"), 16, "periodic: [x, y, z]");
  periodic.erase(periodic.find("  walls:"), periodic.find("fluid:") - periodic.find("  walls:"));
  EXPECT_NE(field_of(periodic), "");
}
