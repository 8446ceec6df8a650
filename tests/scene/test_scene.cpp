// Scenes: the example files parse to the seed's values in CGS, a scene builds the same coupled
// step as the same setup written in C++ (bit for bit over a few steps), and every kind of bad
// input is an InputError naming the field (its path in the file) and the value.
#include "../common/errors.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/scene/scene.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace rbfib::scene {
namespace {
using io::Checkpoint;
using io::read_checkpoint;
using io::write_checkpoint;

const char* sphere_scene = R"(
name: relaxing_sphere
domain:
  size: [16 um, 16 um, 16 um]
  periodic: [x, y, z]
fluid:
  density: 1 g/cm^3
  viscosity: 0.1 cP
grid:
  h: 1 um
time:
  integrator: backward_forward_euler
  dt: 0.4 us
  end: 40 us
ib:
  kernel: bspline3
cell_types:
  - name: sphere
    preset: skalak_sphere
    radius: 3 um
    data_sites: 144
    sample_sites: 400
cells:
  - type: sphere
    center: [8 um, 8 um, 8 um]
    stretch: [1, 0.909090909, 1.1]
)";

const char* channel_scene = R"(
domain:
  size: [16 um, 12 um, 16 um]
  periodic: [x, z]
  walls:
    y: {lower: [0 mm/s, 0 mm/s, 0 mm/s], upper: [12 mm/s, 0 mm/s, 0 mm/s]}
  initial_flow: shear
fluid: {density: 1 g/cm^3, viscosity: 0.1 cP}
grid: {cells: [16, 12, 16]}
time:
  integrator: peskin_two_stage
  coupling: midpoint
  dt: 100 ns
  end: 1 us
  adaptive: {dt_min: 25 ns, max_level: 3}
ib: {kernel: roma3, body_force: [8e3 dyn/cm^3, 0 dyn/cm^3, 0 dyn/cm^3]}
cell_types:
  - name: plt
    preset: platelet
    data_sites: 144
    sample_sites: 144
    model:
      elastic: [{law: neo_hookean, E: 0.1 dyn/cm, G: 1 dyn/cm}]
      kappa: 2e-11 erg
      H0: reference
cells:
  - {type: plt, center: [4 um, 3 um, 4 um], axis: [1, 0, 0], angle: 90 deg, force: [0 dyn, 1e-9 dyn, 0 dyn]}
tethered_points:
  - name: endothelium
    plane: {y: 1 um, points: [32, 30]}
    k: 2.5 dyn/cm
    eta: 2.5e-7 dyn s/cm
output: {diagnostics_every: 5}
)";

TEST(Scene, TheValuesArriveInCgs) {
  const Scene s = parse_scene(channel_scene, "channel");
  EXPECT_EQ(s.name, "channel");
  EXPECT_NEAR(s.grid.length[1], 12 * units::um, 1e-18);
  EXPECT_EQ(s.grid.cells[1], 12);
  EXPECT_TRUE(s.grid.periodic(0));
  EXPECT_FALSE(s.grid.periodic(1));
  EXPECT_NEAR(s.walls[1][1].at(0)[0], 1.2, 1e-15);  // 12 mm/s
  EXPECT_TRUE(s.initial_shear);
  EXPECT_NEAR(s.fluid.viscosity, 1e-3, 1e-18);
  EXPECT_EQ(s.fluid_options.integrator, TimeIntegrator::peskin_two_stage);
  EXPECT_EQ(s.ib.coupling, sim::Coupling::midpoint);
  EXPECT_NEAR(s.fluid_options.dt, 1e-7, 1e-22);
  EXPECT_TRUE(s.ib.adaptive.enabled);
  EXPECT_EQ(s.ib.adaptive.grow_after, 16);
  EXPECT_EQ(s.ib.kernel, ib::Kernel::roma3);
  EXPECT_NEAR(s.ib.body_force[0], 8e3, 1e-9);
  ASSERT_EQ(s.types.size(), 1u);
  EXPECT_TRUE(s.types[0].spec.model.H0_reference);
  EXPECT_NEAR(s.types[0].spec.model.kappa, 2e-11, 1e-25);
  ASSERT_EQ(s.cells.size(), 1u);
  EXPECT_NEAR(s.cells[0].placement.angle, 1.5707963267948966, 1e-15);
  EXPECT_NEAR(s.cells[0].force[1], 1e-9, 1e-24);
  ASSERT_EQ(s.point_sets.size(), 1u);
  EXPECT_EQ(point_positions(s.point_sets[0].surface, s.grid.length).size(), 3u * 32 * 30);
  EXPECT_EQ(s.diagnostics_every, 5);
  // It builds and steps.
  sim::ImmersedBoundary ib = build(s);
  EXPECT_EQ(ib.batches(), 1);
  for (int n = 0; n < 3; ++n) ib.step();
  EXPECT_GT(ib.time(), 0.0);
}

TEST(Scene, ASceneBuildsTheSameStepAsTheSameSetupInCode) {
  sim::ImmersedBoundary a = build(parse_scene(sphere_scene, "sphere"));
  NavierStokesOptions o;
  o.dt = 0.4 * units::us;
  const MacGrid g = make_mac_grid(3, {16, 16, 16}, {16 * units::um, 16 * units::um, 16 * units::um},
                                  {MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic});
  sim::ImmersedBoundary b(g, FluidParameters{1.0, 0.1 * units::cP}, o, {}, sim::IbOptions{});
  cells::CellTypeSpec spec = cells::skalak_sphere_spec(3 * units::um, 144, 400);
  spec.name = "sphere";
  cells::Placement p;
  p.center = {8 * units::um, 8 * units::um, 8 * units::um};
  p.stretch = {1, 0.909090909, 1.1};
  b.add(cells::Batch(std::make_shared<const cells::CellType>(spec), {p}));
  for (int n = 0; n < 5; ++n) {
    a.step();
    b.step();
  }
  const std::vector<double> xa = a.batch(0).positions_host(), xb = b.batch(0).positions_host();
  ASSERT_EQ(xa.size(), xb.size());
  for (std::size_t k = 0; k < xa.size(); ++k) ASSERT_EQ(xa[k], xb[k]) << k;
}

/// The field named by the InputError of parsing `yaml` ("" if none).
std::string field_of(const std::string& yaml) {
  return rbfib::testing::field_of([&] { build(parse_scene(yaml, "mutant")); });
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

TEST(Scene, EveryBadInputNamesItsField) {
  const std::string ok = channel_scene;
  ASSERT_EQ(field_of(ok), "");
  struct Case {
    const char* from;
    const char* to;
    const char* field;
  };
  const Case cases[] = {
      {"viscosity: 0.1 cP", "viscosity: 0.1 cm", "fluid.viscosity"},          // wrong dimension
      {"viscosity: 0.1 cP", "viscosity: -0.1 cP", "fluid.viscosity"},         // negative
      {"viscosity: 0.1 cP", "viscosity: nan cP", "fluid.viscosity"},          // NaN
      {"viscosity: 0.1 cP", "viscosity: 0.1 parsec", "fluid.viscosity"},      // unknown unit
      {"viscosity: 0.1 cP", "viscosity: 0.1 cP, colour: red", "fluid.colour"},  // unknown key
      {"density: 1 g/cm^3, ", "", "fluid.density"},                           // missing key
      {"dt: 100 ns", "dt: 0 ns", "time.dt"},                                  // zero
      {"dt: 100 ns", "dt: 1e300 s", "time.end"},                              // huge: end shorter than a step
      {"dt: 100 ns", "dt: 60 ns", "time.dt"},                                 // not 2^k dt_min
      {"integrator: peskin_two_stage", "integrator: rk4", "time.integrator"},
      {"integrator: peskin_two_stage", "integrator: backward_forward_euler", "time.coupling"},
      {"kernel: roma3", "kernel: gauss", "ib.kernel"},
      {"cells: [16, 12, 16]", "cells: [16, 3, 16]", "grid.cells"},
      {"grid: {cells: [16, 12, 16]}", "grid: {h: 0.7 um}", "grid.h"},        // does not divide
      {"periodic: [x, z]", "periodic: [x, w]", "domain.periodic[1]"},
      {"upper: [12 mm/s, 0 mm/s, 0 mm/s]", "upper: [12 mm/s, 1 mm/s, 0 mm/s]", "domain.walls.y.upper[1]"},
      {"upper: [12 mm/s, 0 mm/s, 0 mm/s]", "upper: [12 mm/s, 0 mm/s]", "domain.walls.y.upper"},
      {"preset: platelet", "preset: neutrophil", "cell_types[0].preset"},
      {"data_sites: 144\n    sample_sites: 144", "data_sites: 3\n    sample_sites: 144", "cell_types[0].data_sites"},
      {"sample_sites: 144\n", "sample_sites: 144\n    products: half\n", "cell_types[0].products"},
      {"{type: plt,", "{type: rbc,", "cells[0].type"},
      {"center: [4 um, 3 um, 4 um]", "center: [4 um, 13 um, 4 um]", "cells[0].center[1]"},
      {"center: [4 um, 3 um, 4 um]", "center: [4 um, 0.2 um, 4 um]", "cells[0]"},  // through a wall
      {"axis: [1, 0, 0]", "axis: [0, 0, 0]", "cells[0].axis"},
      {"angle: 90 deg", "angle: 90 um", "cells[0].angle"},
      {"force: [0 dyn, 1e-9 dyn, 0 dyn]", "force: [0 dyn, 1e-9 dyn/cm, 0 dyn]", "cells[0].force[1]"},
      {"k: 2.5 dyn/cm", "k: -2.5 dyn/cm", "tethered_points[0].k"},
      {"plane: {y: 1 um, points: [32, 30]}", "plane: {y: 20 um, points: [32, 30]}", "tethered_points[0].plane.y"},
      {"output: {diagnostics_every: 5}", "output: {diagnostics_every: 0}", "output.diagnostics_every"},
      {"output: {diagnostics_every: 5}", "output: {snapshots: 1 us}", "output.snapshots"},
      {"output: {diagnostics_every: 5}", "output: {stability: maybe}", "output.stability"},
      {"end: 1 us", "end: 1 us\n  stopping_condition: never", "time.stopping_condition"},
      {"max_level: 3}", "max_level: 3, criterion: fast}", "time.adaptive.criterion"},
      {"max_level: 3}", "max_level: 3, ratio: 3}", "time.adaptive.ratio"},
      {"max_level: 3}", "max_level: 3, guard_steps: 2}", "time.adaptive.guard_steps"},  // guard without stability
  };
  for (const Case& c : cases) EXPECT_EQ(field_of(replaced(ok, c.from, c.to)), c.field) << c.from << " -> " << c.to;
  // A kernel wider than the grid allows: B3 spans 4 cells, a 4-cell axis needs 3.
  EXPECT_EQ(field_of(replaced(replaced(ok, "cells: [16, 12, 16]", "cells: [16, 4, 16]"), "kernel: roma3", "kernel: bspline3")), "ib.kernel");
  EXPECT_EQ(field_of(replaced(ok, "fluid:", "? [a, b]\n: 1\nfluid:")), "scene");  // a key that is not a name
  EXPECT_EQ(field_of(replaced(ok, "grid: {cells: [16, 12, 16]}", "grid: {cells: [16, 12, 16], h: 1 um}")), "grid.h");
  EXPECT_EQ(field_of("domain: [1, 2"), "mutant");  // not YAML
  EXPECT_EQ(field_of(""), "mutant");               // empty
  const std::string m = testing::message_of<InputError>([&] { parse_scene(replaced(ok, "0.1 cP", "0.1 cm"), "m"); });
  EXPECT_NE(m.find("fluid.viscosity = '0.1 cm': has the dimension length; expected dynamic viscosity"), std::string::npos) << m;
}

TEST(Scene, TheStabilityCriterionAndItsSwitchesAreReadAndWrittenBack) {
  // time.adaptive.criterion: stability with rungs of 2^(1/2); eq. 5.4 off; the step's stability measured.
  std::string text = replaced(channel_scene, "dt: 100 ns", "dt: 50 ns");
  text = replaced(text, "max_level: 3}", "max_level: 6, criterion: stability, ratio: 1.4142135623730951, guard_growth: 1.1}");
  text = replaced(text, "end: 1 us", "end: 1 us\n  stopping_condition: off");
  text = replaced(text, "output: {diagnostics_every: 5}", "output: {diagnostics_every: 5, stability: yes}");
  const Scene s = parse_scene(text, "stability");
  for (const Scene& t : {s, parse_scene(to_yaml(s), "back")}) {
    EXPECT_EQ(t.ib.adaptive.criterion, sim::StepCriterion::stability);
    EXPECT_NEAR(t.ib.adaptive.ratio, std::sqrt(2.0), 1e-15);
    EXPECT_EQ(t.ib.adaptive.grow_after, 4);  // the stability criterion's default
    EXPECT_EQ(t.ib.adaptive.guard_growth, 1.1);
    EXPECT_FALSE(t.ib.stopping_condition);
    EXPECT_TRUE(t.ib.watch_stability);
  }
  // dt = 50 ns = sqrt(2)^2 x 25 ns; 60 ns is no rung
  EXPECT_EQ(field_of(replaced(text, "dt: 50 ns", "dt: 60 ns")), "time.dt");
  // The platelets' membrane bound at gain 1/2 (and the tethers') caps the ladder, above the first step.
  const sim::ImmersedBoundary ib = build(s);
  EXPECT_TRUE(std::isfinite(ib.options().adaptive.dt_max));
  EXPECT_GT(ib.options().adaptive.dt_max, 50e-9);
  EXPECT_LT(ib.options().adaptive.dt_max, 1e-5);
  // The inertial default writes none of it back.
  EXPECT_EQ(to_yaml(parse_scene(channel_scene, "plain")).find("criterion"), std::string::npos);
}

TEST(Scene, SinglePrecisionProductsAreReadWrittenBackAndBuilt) {
  // cell_types[i].products: single: the type's operators are applied in single precision.
  const std::string text = replaced(channel_scene, "sample_sites: 144\n", "sample_sites: 144\n    products: single\n");
  const Scene s = parse_scene(text, "single");
  ASSERT_EQ(s.types.size(), 1u);
  EXPECT_TRUE(s.types[0].spec.single_precision_products);
  EXPECT_FALSE(parse_scene(channel_scene, "double").types[0].spec.single_precision_products);
  EXPECT_TRUE(parse_scene(to_yaml(s), "back").types[0].spec.single_precision_products);
  const sim::ImmersedBoundary ib = build(s);
  EXPECT_TRUE(ib.batch(0).type().operators().single_precision());
}

TEST(Scene, AWallTurnsAsInSection521) {
  // The top wall at 16 mm/s (sin alpha e1 + cos alpha e3), alpha from 0 to pi/4 over 7.2 ms.
  const std::string turning = replaced(channel_scene, "upper: [12 mm/s, 0 mm/s, 0 mm/s]",
                                       "upper: {speed: 16 mm/s, turn: {from: 0 deg, to: 45 deg, over: 7.2 ms}}");
  const Scene s = parse_scene(turning, "turning");
  const WallMotion& top = s.walls[1][1];
  ASSERT_TRUE(top.turning);
  const double c = 1.6;  // cm/s
  auto expect_velocity = [&](double t, double alpha) {
    const auto v = top.at(t);
    EXPECT_NEAR(v[0], c * std::sin(alpha), 1e-14) << t;
    EXPECT_EQ(v[1], 0.0) << t;
    EXPECT_NEAR(v[2], c * std::cos(alpha), 1e-14) << t;
  };
  expect_velocity(0, 0);
  expect_velocity(3.6e-3, pi / 8);
  expect_velocity(7.2e-3, pi / 4);
  expect_velocity(20e-3, pi / 4);
  // The flow starts as the shear of the walls at t = 0: along z, 1.6 cm/s at the top.
  sim::ImmersedBoundary ib = build(s);
  EXPECT_EQ(blas::norm_inf(ib.fluid_state().u[0]), 0.0);
  EXPECT_NEAR(blas::norm_inf(ib.fluid_state().u[2]), c * 11.5 / 12, 1e-12);  // the top cell centres, y = 11.5 um
  EXPECT_EQ(field_of(replaced(turning, "over: 7.2 ms", "over: 7.2 um")), "domain.walls.y.upper.turn.over");
  EXPECT_EQ(field_of(replaced(turning, "speed: 16 mm/s", "pace: 16 mm/s")), "domain.walls.y.upper.speed");
}

TEST(Scene, AHeldWallReadsWritesBackAndBuildsOnAnAffineFluidStep) {
  // held_walls: markers on a plane (sim/held_wall.hpp), written back as read; the fluid must be
  // affine in its force, which Peskin's two-stage scheme is not: named.
  const std::string held = replaced(channel_scene, R"(tethered_points:
  - name: endothelium
    plane: {y: 1 um, points: [32, 30]}
    k: 2.5 dyn/cm
    eta: 2.5e-7 dyn s/cm
)", "held_walls:\n  - {name: wall, plane: {y: 1 um, points: [8, 6]}}\n");
  const Scene s = parse_scene(held, "held");
  ASSERT_EQ(s.held_walls.size(), 1u);
  EXPECT_TRUE(s.point_sets.empty());
  const Scene back = parse_scene(to_yaml(s), "back");
  ASSERT_EQ(back.held_walls.size(), 1u);
  EXPECT_EQ(back.held_walls[0].name, "wall");
  EXPECT_EQ(back.held_walls[0].surface.lattice, (std::array<int, 2>{8, 6}));
  EXPECT_EQ(back.held_walls[0].surface.at, s.held_walls[0].surface.at);
  EXPECT_EQ(field_of(held), "held wall 'wall': fluid");
  const std::string affine = replaced(replaced(held, "integrator: peskin_two_stage", "integrator: backward_forward_euler"), "coupling: midpoint",
                                      "coupling: seed");
  const sim::ImmersedBoundary ib = build(parse_scene(affine, "affine"));
  EXPECT_EQ(ib.held_walls(), 1);
  EXPECT_EQ(ib.point_sets(), 0);
  EXPECT_EQ(ib.held_wall(0).wall().X.size(), 3u * 48u);
  EXPECT_EQ(field_of(replaced(affine, "plane: {y: 1 um, points: [8, 6]}", "plane: {y: 1 um}")), "held_walls[0].plane.points");
}

TEST(Scene, TheEndotheliumOfEquation55LiesOnTheToroidalSpiral) {
  // Sec. 5.2: 16,000 points on the toroidal spiral of Appendix B, flat (y = 1 um) or bumpy
  // (y = 0.75 um + 1 um cos^2(theta - phi) sin^2(phi / 2)), x = 16 um theta / 2 pi, z = 16 um phi / 2 pi.
  const std::string bumpy = replaced(channel_scene, "plane: {y: 1 um, points: [32, 30]}", "spiral: {y: 0.75 um, bump: 1 um, points: 16000}");
  const Scene s = parse_scene(bumpy, "bumpy");
  ASSERT_EQ(s.point_sets.size(), 1u);
  const std::vector<double> X = point_positions(s.point_sets[0].surface, s.grid.length);
  const std::size_t N = 16000;
  ASSERT_EQ(X.size(), 3 * N);
  const double um = 1e-4;
  double y_min = 1, y_max = 0, y_mean = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const double phi = 2 * pi * double(i) / double(N);
    const double theta = std::fmod(127 * phi, 2 * pi);  // ceil(sqrt 16000) = 127 turns
    EXPECT_NEAR(X[i], 16 * um * theta / (2 * pi), 1e-12) << i;
    EXPECT_NEAR(X[2 * N + i], 16 * um * phi / (2 * pi), 1e-12) << i;
    const double y = X[N + i];
    EXPECT_NEAR(y, 0.75 * um + um * std::pow(std::cos(theta - phi) * std::sin(phi / 2), 2), 1e-12) << i;
    y_min = std::min(y_min, y), y_max = std::max(y_max, y), y_mean += y / double(N);
  }
  EXPECT_NEAR(y_min, 0.75 * um, 1e-9);
  EXPECT_NEAR(y_max, 1.75 * um, 1e-3 * um);  // the bumps' prominence, 1 um
  // The mean height is the flat wall's 1 um (the mean of cos^2 sin^2 is 1/4): both shapes leave the
  // same volume above them, as Sec. 5.2 keeps the hematocrit.
  EXPECT_NEAR(y_mean, 1.0 * um, 1e-3 * um);
  // Its normal: (-dy/dx, 1, -dy/dz) normalized, against central differences of the height.
  const EndotheliumSurface e{0.75 * um, um, 16 * um, 16 * um};
  for (const auto& [x, z] : std::vector<std::pair<double, double>>{{3 * um, 5 * um}, {11 * um, 2 * um}, {7.5 * um, 13 * um}}) {
    const double d = 1e-4 * um;
    const double gx = (e.height(x + d, z) - e.height(x - d, z)) / (2 * d), gz = (e.height(x, z + d) - e.height(x, z - d)) / (2 * d);
    const double nn = std::sqrt(1 + gx * gx + gz * gz);
    const auto n = e.normal(x, z);
    EXPECT_NEAR(n[0], -gx / nn, 1e-7);
    EXPECT_NEAR(n[1], 1 / nn, 1e-7);
    EXPECT_NEAR(n[2], -gz / nn, 1e-7);
  }
  EXPECT_EQ(field_of(replaced(bumpy, "bump: 1 um", "bump: 20 um")), "tethered_points[0].spiral.bump");
  EXPECT_EQ(field_of(replaced(bumpy, "points: 16000", "points: 0")), "tethered_points[0].spiral.points");
  EXPECT_EQ(field_of(replaced(bumpy, "spiral: {", "plane: {y: 1 um, points: [4, 4]}\n    spiral: {")), "tethered_points[0]");
}

void expect_same(const dvec& a, const dvec& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  const host_vector<double> x = a, y = b;
  for (std::size_t k = 0; k < x.size(); ++k) ASSERT_EQ(x[k], y[k]) << what << " entry " << k;
}

TEST(Checkpoint, RestartContinuesBitForBit) {
  // The channel scene carries everything a checkpoint must hold: walls, the midpoint coupling
  // with Peskin's scheme, the adaptive step, a cell with a constant force, tethered points.
  // 4 steps, a checkpoint, 4 more steps equal 4 steps, a restart from the file, 4 more steps.
  const std::string dir = ::testing::TempDir() + "rbfib_checkpoint_test";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/checkpoint.h5";
  sim::ImmersedBoundary a = build(parse_scene(channel_scene, "channel"));
  for (int n = 0; n < 4; ++n) a.step();
  write_checkpoint(path, channel_scene, a);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  for (int n = 0; n < 4; ++n) a.step();

  const Checkpoint k = read_checkpoint(path);
  EXPECT_EQ(k.scene_yaml, channel_scene);
  sim::ImmersedBoundary b = build(parse_scene(k.scene_yaml, "channel"));
  b.restore(k.state);
  EXPECT_EQ(b.step_count(), 4);
  for (int n = 0; n < 4; ++n) b.step();
  EXPECT_EQ(a.time(), b.time());
  EXPECT_EQ(a.step_count(), b.step_count());
  EXPECT_EQ(a.dt(), b.dt());
  for (int c = 0; c < 3; ++c) expect_same(a.fluid_state().u[c], b.fluid_state().u[c], "u" + std::to_string(c));
  expect_same(a.fluid_state().p, b.fluid_state().p, "p");
  expect_same(a.batch(0).state().storage(), b.batch(0).state().storage(), "cells");
  expect_same(a.points(0).X, b.points(0).X, "tethered points");

  // A damaged file (truncated) and a file of another setup are named errors.
  {
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream out(dir + "/truncated.h5", std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size() / 2));
  }
  EXPECT_NE(testing::message_of<InputError>([&] { read_checkpoint(dir + "/truncated.h5"); }).find("checkpoint"), std::string::npos);
  sim::ImmersedBoundary other = build(parse_scene(sphere_scene, "sphere"));
  EXPECT_NE(testing::message_of<InputError>([&] { other.restore(k.state); }).find("checkpoint"), std::string::npos);
  std::filesystem::remove_all(dir);
}


std::string with(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(Contacts, OverlappingCellsAreRefusedPeriodicImagesIncluded) {
  const std::string two = std::string(sphere_scene) + "  - {type: sphere, center: [12 um, 8 um, 8 um]}\n";
  // Spheres of radius 3 um (the first stretched by 1.1 along z) 4 um apart: they overlap.
  const std::string overlap = testing::message_of<InputError>([&] { check_contacts(parse_scene(two, "two")); });
  EXPECT_NE(overlap.find("overlap"), std::string::npos) << overlap;
  EXPECT_NE(overlap.find("cells["), std::string::npos) << overlap;
  // Across the periodic boundary: x = 14 um is 3 um from x = 1 um's image at 17 um.
  const std::string wrap = with(with(two, "center: [8 um, 8 um, 8 um]", "center: [1 um, 8 um, 8 um]"), "[12 um, 8 um, 8 um]",
                                "[14 um, 8 um, 8 um]");
  EXPECT_NE(testing::message_of<InputError>([&] { check_contacts(parse_scene(wrap, "wrap")); }).find("overlap"), std::string::npos);
  // 6.6 um apart: distinct (a gap of about 0.6 um), but closer than 2h = 2 um: one line says so.
  const std::string near = with(two, "[12 um, 8 um, 8 um]", "[14.6 um, 8 um, 8 um]");
  std::vector<std::string> lines;
  EXPECT_EQ(testing::message_of<InputError>([&] { lines = check_contacts(parse_scene(near, "near")); }), "");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("cells[0] and cells[1]"), std::string::npos) << lines[0];
  // 8 um apart in a 16 um box: 2 um gaps on both sides, no line.
  const std::string far = with(two, "[12 um, 8 um, 8 um]", "[16 um, 8 um, 8 um]");
  EXPECT_TRUE(check_contacts(parse_scene(with(far, "stretch: [1, 0.909090909, 1.1]", "stretch: [1, 1, 1]"), "far")).empty());
}

TEST(Contacts, ACellAroundTetheredPointsIsRefused) {
  const std::string ok = channel_scene;
  EXPECT_EQ(testing::message_of<InputError>([&] { check_contacts(parse_scene(ok, "ok")); }), "");
  // Lying flat on the endothelium's plane y = 1 um: the plane's points are inside it.
  const std::string around = with(ok, "center: [4 um, 3 um, 4 um]", "center: [4 um, 1.2 um, 4 um]");
  const std::string a = testing::message_of<InputError>([&] { check_contacts(parse_scene(around, "around")); });
  EXPECT_NE(a.find("encloses point"), std::string::npos) << a;
  EXPECT_NE(a.find("tethered_points[0]"), std::string::npos) << a;
}

}  // namespace
}  // namespace rbfib::scene

namespace rbfib::scene {
namespace {

TEST(Scene, DimensionlessGroupsComeFromTheWallsTheFluidAndTheFirstShearModulus) {
  // 12 mm/s over 12 um: 1000/s; viscosity 0.1 cP; the platelet's neo-Hookean E = 0.1 dyn/cm.
  const Scene s = parse_scene(channel_scene, "channel");
  EXPECT_NEAR(shear_rate(s), 1000.0, 1e-9);
  const std::vector<CellTypeGroups> g = dimensionless_groups(s);
  ASSERT_EQ(g.size(), 1u);
  EXPECT_GT(g[0].radius, 0.5 * units::um);
  EXPECT_NEAR(g[0].reynolds, 1.0 * 1000.0 * g[0].radius * g[0].radius / 1e-3, 1e-12);
  EXPECT_EQ(g[0].shear_modulus, 0.1);
  EXPECT_NEAR(g[0].capillary, 1e-3 * 1000.0 * g[0].radius / 0.1, 1e-15);
  EXPECT_NE(g[0].modulus.find("E"), std::string::npos) << g[0].modulus;
}

}  // namespace
}  // namespace rbfib::scene
