// A scene that starts from another run's checkpoint (scene::Start, io::build_scene): the fluid, clock,
// tethered points and kept cells come from the checkpoint bit for bit, the scene's own cells are
// added where it places them, and the contact check sees the kept cells where they are, not where
// the first scene placed them. Mismatches are InputErrors naming the field.
#include "../common/errors.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/scene/scene.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

namespace rbfib::io {
namespace {

// Two spheres in a periodic box with a sheet of tethered points below them.
const std::string first_scene = R"(
domain: {size: [16 um, 16 um, 16 um], periodic: [x, y, z]}
fluid: {density: 1 g/cm^3, viscosity: 0.1 cP}
grid: {h: 1 um}
time: {integrator: backward_forward_euler, dt: 0.4 us, end: 4 us}
ib: {kernel: bspline3, body_force: [2e4 dyn/cm^3, 0 dyn/cm^3, 0 dyn/cm^3]}
cell_types:
  - {name: sphere, preset: skalak_sphere, radius: 2 um, data_sites: 144, sample_sites: 144}
cells:
  - {type: sphere, center: [4 um, 8 um, 8 um], stretch: [1, 0.909090909, 1.1]}
  - {type: sphere, center: [12 um, 8 um, 8 um]}
tethered_points:
  - {name: sheet, plane: {y: 2 um, points: [8, 8]}, k: 1e-3 dyn/cm, eta: 1e-7 dyn s/cm}
)";

// The second scene: the spheres kept from the first run's checkpoint, a small sphere of another
// type added at `center`.
std::string second_scene(const std::string& checkpoint, const std::string& center, const std::string& keep = "[sphere]") {
  return R"(
domain: {size: [16 um, 16 um, 16 um], periodic: [x, y, z]}
fluid: {density: 1 g/cm^3, viscosity: 0.1 cP}
grid: {h: 1 um}
time: {integrator: backward_forward_euler, dt: 0.4 us, end: 8 us}
ib: {kernel: bspline3}
start: {checkpoint: )" + checkpoint + ", keep: " + keep + R"(}
cell_types:
  - {name: sphere, preset: skalak_sphere, radius: 2 um, data_sites: 144, sample_sites: 144}
  - {name: small, preset: skalak_sphere, radius: 1 um, data_sites: 64, sample_sites: 64}
cells:
  - {type: small, center: )" + center + R"(}
tethered_points:
  - {name: sheet, plane: {y: 2 um, points: [8, 8]}, k: 1e-3 dyn/cm, eta: 1e-7 dyn s/cm}
)";
}

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("rbfib_test_start_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

TEST(Start, KeptCellsFluidClockAndPointsComeFromTheCheckpointBitForBit) {
  const scene::Scene a = scene::parse_scene(first_scene, "first");
  sim::ImmersedBoundary first = build_scene(a);
  for (int n = 0; n < 5; ++n) first.step();  // the body force moves the fluid, the spheres and the sheet
  const std::string file = temp_path("first.h5");
  write_checkpoint(file, a.source, first);
  const sim::ImmersedBoundary::Carried was = first.carried();

  const scene::Scene b = scene::parse_scene(second_scene(file, "[8 um, 12 um, 8 um]"), "second");
  sim::ImmersedBoundary second = build_scene(b);
  const sim::ImmersedBoundary::Carried now = second.carried();
  EXPECT_EQ(now.clock.step, 5);
  EXPECT_EQ(now.clock.t, was.clock.t);
  ASSERT_EQ(now.batches.size(), 2u);  // the kept spheres, then the added type
  EXPECT_TRUE(now.batches[0] == was.batches[0]);
  EXPECT_EQ(second.batch(0).size(), 2);
  EXPECT_EQ(second.batch(1).size(), 1);
  for (int a3 = 0; a3 < 3; ++a3) EXPECT_TRUE(now.fluid.u[a3] == was.fluid.u[a3]);
  ASSERT_EQ(now.points.size(), 1u);
  EXPECT_TRUE(now.points[0] == was.points[0]);
  // The added sphere sits where the scene places it.
  const std::vector<double> X = second.batch(1).positions_host();
  double cy = 0;
  for (index_t i = 0; i < 64; ++i) cy += X[std::size_t(64 + i)] / 64;
  EXPECT_NEAR(cy, 12 * units::um, 1e-3 * units::um);
  second.step();
  EXPECT_EQ(second.step_count(), 6);
}

TEST(Start, TheContactCheckSeesTheKeptCellsWhereTheyAre) {
  const scene::Scene a = scene::parse_scene(first_scene, "first");
  sim::ImmersedBoundary first = build_scene(a);
  // Move the second sphere by 4 um in z by hand: where it is now, not where the first scene
  // placed it, is what the added cell must not overlap.
  sim::ImmersedBoundary::Carried c = first.carried();
  host_vector<double> state = c.batches[0];
  const index_t n = 144, N = 2;
  for (index_t i = 0; i < n; ++i) state[std::size_t((2 * N + 1) * n + i)] += 4 * units::um;  // column d N + c, d = z, c = 1
  c.batches[0] = dvec(state.begin(), state.end());
  first.restore(c);
  const std::string file = temp_path("moved.h5");
  write_checkpoint(file, a.source, first);
  // At the first scene's placement of that sphere the small one is clear of it now...
  EXPECT_EQ(testing::message_of<InputError>([&] { build_scene(scene::parse_scene(second_scene(file, "[12 um, 8 um, 8 um]"), "clear")); }), "");
  // ... and where it has moved to, it overlaps.
  const std::string overlap =
      testing::message_of<InputError>([&] { build_scene(scene::parse_scene(second_scene(file, "[12 um, 8 um, 12 um]"), "overlap")); });
  EXPECT_NE(overlap.find("start: sphere 1"), std::string::npos) << overlap;
}

TEST(Start, MismatchesAreNamed) {
  const scene::Scene a = scene::parse_scene(first_scene, "first");
  sim::ImmersedBoundary first = build_scene(a);
  const std::string file = temp_path("mismatch.h5");
  write_checkpoint(file, a.source, first);
  // A kept type may not also be placed by the scene.
  std::string both = second_scene(file, "[8 um, 12 um, 8 um]");
  both.replace(both.find("type: small"), 11, "type: sphere");
  EXPECT_NE(testing::message_of<InputError>([&] { scene::parse_scene(both, "both"); }).find("cells[0].type"), std::string::npos);
  // An unknown type in keep.
  EXPECT_NE(testing::message_of<InputError>([&] { scene::parse_scene(second_scene(file, "[8 um, 12 um, 8 um]", "[blob]"), "x"); })
                .find("start.keep[0]"),
            std::string::npos);
  // A type the checkpoint has no cells of.
  EXPECT_NE(testing::message_of<InputError>([&] { build_scene(scene::parse_scene(second_scene(file, "[8 um, 12 um, 8 um]", "[small]"), "x")); })
                .find("start.keep"),
            std::string::npos);
  // Another grid.
  std::string grid = second_scene(file, "[8 um, 12 um, 8 um]");
  grid.replace(grid.find("h: 1 um"), 7, "h: 2 um");
  EXPECT_NE(testing::message_of<InputError>([&] { build_scene(scene::parse_scene(grid, "grid")); }).find("start.checkpoint"), std::string::npos);
  // A missing file.
  EXPECT_NE(testing::message_of<InputError>([&] { build_scene(scene::parse_scene(second_scene(file + ".none", "[8 um, 12 um, 8 um]"), "x")); }),
            "");
  // An ended run's checkpoint written without its fluid.
  const std::string slim = temp_path("mismatch_slim.h5");
  RunRecord ended;
  ended.status = RunStatus::finished;
  write_checkpoint(slim, a.source, first, ended, false);
  EXPECT_NE(testing::message_of<InputError>([&] { build_scene(scene::parse_scene(second_scene(slim, "[8 um, 12 um, 8 um]"), "x")); })
                .find("keeps no fluid"),
            std::string::npos);
  // ... which a running run's may not be.
  EXPECT_THROW(write_checkpoint(slim, a.source, first, RunRecord{}, false), InputError);
  // to_yaml writes the start back.
  const scene::Scene b = scene::parse_scene(second_scene(file, "[8 um, 12 um, 8 um]"), "second");
  const scene::Scene again = scene::parse_scene(scene::to_yaml(b), "again");
  EXPECT_EQ(again.start.checkpoint, file);
  EXPECT_EQ(again.start.keep, std::vector<std::string>{"sphere"});
}

}  // namespace
}  // namespace rbfib::io
