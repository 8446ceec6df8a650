// The run loop (run/run.hpp): a run split over sittings equals one taken at once, bit for bit,
// series included; a finished or stopped run is a checkpoint marked so and is not stepped again;
// cadences by steps and by simulated time fire where they should; series survive the checkpoint.
#include "rbfib/run/run.hpp"

#include "rbfib/core/units.hpp"
#include "rbfib/io/checkpoint.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace rbfib::run {
namespace {

// A small periodic box with one relaxing sphere: a few ms of CPU per step.
std::string sphere_scene(const std::string& dt = "0.4 us", const std::string& end = "4 us", const std::string& stretch = "[1, 0.909090909, 1.1]") {
  return R"(
domain: {size: [12 um, 12 um, 12 um], periodic: [x, y, z]}
fluid: {density: 1 g/cm^3, viscosity: 0.1 cP}
grid: {h: 1 um}
time: {integrator: backward_forward_euler, dt: )" + dt + ", end: " + end + R"(}
ib: {kernel: bspline3}
cell_types:
  - {name: sphere, preset: skalak_sphere, radius: 3 um, data_sites: 144, sample_sites: 144}
cells:
  - {type: sphere, center: [6 um, 6 um, 6 um], stretch: )" + stretch + R"(}
)";
}

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("rbfib_test_run_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

/// Hooks that record (t, kinetic energy) every sample in series "energy".
Hooks energy_hooks() {
  Hooks h;
  h.sample = [](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, SeriesSet& s) {
    Series& e = s["energy"];
    e.columns = {"t_s", "kinetic_energy_erg"};
    e.rows.push_back({ib.time(), r ? r->kinetic_energy : 0.0});
  };
  return h;
}

/// Options for a two-step run of sphere_scene("0.4 us", "0.8 us") kept in a fresh temp file.
Options two_steps_kept_in(const std::string& name) {
  Options o;
  o.t_end = 0.8 * units::us;
  o.checkpoint = temp_path(name);
  std::filesystem::remove(o.checkpoint);
  return o;
}

TEST(RunLoop, TwoSittingsEqualOneRunBitForBitWithTheirSeries) {
  const std::string text = sphere_scene();
  Options o;
  o.t_end = 4 * units::us;
  o.sample_every = {2, 0, 0};
  run::Run whole(text, "sphere", o, energy_hooks());
  const Progress pw = whole.evolve();
  EXPECT_EQ(pw.status, RunStatus::finished);
  EXPECT_EQ(pw.clock.step, 10);

  o.checkpoint = temp_path("two_sittings.h5");
  std::filesystem::remove(o.checkpoint);
  o.until = 1.6 * units::us;
  {
    run::Run first(text, "sphere", o, energy_hooks());
    EXPECT_FALSE(first.continued());
    const Progress p = first.evolve();
    EXPECT_EQ(p.status, RunStatus::running);
    EXPECT_EQ(p.clock.step, 4);
  }
  o.until = INFINITY;
  run::Run second(text, "sphere", o, energy_hooks());
  ASSERT_TRUE(second.continued());
  EXPECT_EQ(second.ib().step_count(), 4);
  const Progress p = second.evolve();
  EXPECT_EQ(p.status, RunStatus::finished);
  EXPECT_EQ(p.steps_timed, 10);  // the wall time and steps of both sittings
  const host_vector<double> a = whole.ib().batch(0).state().storage(), b = second.ib().batch(0).state().storage();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << k;
  // Samples at t = 0 and after steps 2, 4, ..., 10, none twice.
  const Series& sw = whole.series("energy");
  const Series& s2 = second.series("energy");
  ASSERT_EQ(sw.rows.size(), 6u);
  ASSERT_EQ(s2.rows.size(), sw.rows.size());
  for (std::size_t r = 0; r < sw.rows.size(); ++r) EXPECT_EQ(sw.rows[r], s2.rows[r]) << r;
  EXPECT_EQ(s2.columns, (std::vector<std::string>{"t_s", "kinetic_energy_erg"}));
}

TEST(RunLoop, AFinishedRunIsACheckpointMarkedFinishedAndIsNotSteppedAgain) {
  const std::string text = sphere_scene("0.4 us", "0.8 us");
  Options o = two_steps_kept_in("finished.h5");
  run::Run(text, "sphere", o, energy_hooks()).evolve();
  EXPECT_EQ(io::read_checkpoint(o.checkpoint).record.status, RunStatus::finished);
  run::Run again(text, "sphere", o, energy_hooks());
  ASSERT_TRUE(again.continued());
  const Progress p = again.evolve();
  EXPECT_EQ(p.status, RunStatus::finished);
  EXPECT_EQ(p.sitting_steps, 0);
  EXPECT_EQ(p.clock.step, 2);
  // Another scene text is another run: the checkpoint is not used.
  run::Run other(sphere_scene("0.2 us", "0.8 us"), "sphere", o, energy_hooks());
  EXPECT_FALSE(other.continued());
}

TEST(RunLoop, ANumericalStopKeepsTheLastGoodStateItsMessageAndItsCause) {
  // Stretched by 2 with a 1 ms step: eq. 5.4 refuses the first step.
  const std::string text = sphere_scene("1 ms", "4 ms", "[2, 1, 0.5]");
  Options o;
  o.t_end = 4e-3;
  o.checkpoint = temp_path("stopped.h5");
  std::filesystem::remove(o.checkpoint);
  run::Run run(text, "sphere", o, energy_hooks());
  const dvec before = run.ib().batch(0).state().storage();
  const Progress p = run.evolve();
  EXPECT_EQ(p.status, RunStatus::stopped);
  ASSERT_TRUE(p.stop_cause.has_value());
  EXPECT_EQ(*p.stop_cause, Cause::stopping_condition);
  EXPECT_NE(p.stop_message.find("eq. 5.4"), std::string::npos) << p.stop_message;
  const io::Checkpoint k = io::read_checkpoint(o.checkpoint);
  EXPECT_EQ(k.record.status, RunStatus::stopped);
  EXPECT_EQ(k.record.stop_cause, Cause::stopping_condition);
  EXPECT_EQ(k.state.clock.step, 0);
  const host_vector<double> a = before, b = k.state.batches.at(0);
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << i;
  run::Run again(text, "sphere", o, energy_hooks());
  EXPECT_EQ(again.evolve().status, RunStatus::stopped);
  EXPECT_EQ(again.progress().sitting_steps, 0);
}

TEST(RunLoop, AStopFoundByAHookSaysAfterWhichStep) {
  // A measurement of the new state that finds it broken stops the run with the step and the time.
  Options o;
  o.t_end = 4 * units::us;
  Hooks h;
  h.after_step = [](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r, SeriesSet&) {
    if (r && ib.step_count() == 3) throw NumericalError(Cause::inverted_cell, "cell 0 turned inside out");
  };
  run::Run run(sphere_scene(), "sphere", o, h);
  const Progress p = run.evolve();
  EXPECT_EQ(p.status, RunStatus::stopped);
  EXPECT_EQ(*p.stop_cause, Cause::inverted_cell);
  EXPECT_EQ(p.clock.step, 3);
  EXPECT_NE(p.stop_message.find("after step 3 at t = "), std::string::npos) << p.stop_message;
  EXPECT_NE(p.stop_message.find("turned inside out"), std::string::npos) << p.stop_message;
}

TEST(RunLoop, CadencesBySimulatedTimeFireAtItsMultiples) {
  const std::string text = sphere_scene("0.4 us", "4 us");
  Options o;
  o.t_end = 4 * units::us;
  o.sample_every = {0, 1.2 * units::us, 0};  // after the steps reaching 1.2, 2.4, 3.6 us, and the end
  run::Run run(text, "sphere", o, energy_hooks());
  run.evolve();
  const Series& s = run.series("energy");
  ASSERT_EQ(s.rows.size(), 5u);
  const double expected[5] = {0, 1.2e-6, 2.4e-6, 3.6e-6, 4.0e-6};
  for (int r = 0; r < 5; ++r) EXPECT_NEAR(s.rows[std::size_t(r)][0], expected[r], 1e-15) << r;
}

TEST(RunLoop, ASittingLimitOfZeroTakesNoStepAndKeepsACheckpoint) {
  const std::string text = sphere_scene();
  Options o;
  o.t_end = 4 * units::us;
  o.sitting = 0;
  o.checkpoint = temp_path("sitting.h5");
  std::filesystem::remove(o.checkpoint);
  const Progress p = run::Run(text, "sphere", o, energy_hooks()).evolve();
  EXPECT_EQ(p.status, RunStatus::running);
  EXPECT_EQ(p.clock.step, 0);
  EXPECT_TRUE(std::filesystem::exists(o.checkpoint));
  EXPECT_EQ(io::read_checkpoint(o.checkpoint).state.clock.step, 0);
}

TEST(RunLoop, SeriesOfAnyRowWidthSurviveTheCheckpoint) {
  const std::string text = sphere_scene("0.4 us", "0.4 us");
  Options o;
  o.t_end = 0.4 * units::us;
  o.checkpoint = temp_path("series.h5");
  std::filesystem::remove(o.checkpoint);
  Hooks h;
  h.sample = [](const sim::ImmersedBoundary& ib, const sim::IbStepReport*, SeriesSet& s) {
    s["ragged"].rows.push_back(std::vector<double>(std::size_t(ib.step_count() + 1), ib.time()));
    s["empty"];
  };
  run::Run(text, "sphere", o, h).evolve();
  const io::Checkpoint k = io::read_checkpoint(o.checkpoint);
  ASSERT_EQ(k.record.series.count("ragged"), 1u);
  const Series& r = k.record.series.at("ragged");
  ASSERT_EQ(r.rows.size(), 2u);
  EXPECT_EQ(r.rows[0].size(), 1u);
  EXPECT_EQ(r.rows[1].size(), 2u);
  EXPECT_EQ(r.rows[1][1], k.state.fluid.t);
  EXPECT_TRUE(r.columns.empty());
  ASSERT_EQ(k.record.series.count("empty"), 1u);
  EXPECT_TRUE(k.record.series.at("empty").rows.empty());
}

TEST(RunLoop, AnEndedRunKeptWithoutItsFluidAnswersAsBeforeAndItsFluidReadsNaN) {
  const std::string text = sphere_scene("0.4 us", "0.8 us");
  Options o = two_steps_kept_in("slim.h5");
  o.ended_keeps_fluid = false;
  // A sitting that ends before the run does keeps the fluid: the run continues from it.
  o.until = 0.4 * units::us;
  run::Run(text, "sphere", o, energy_hooks()).evolve();
  EXPECT_TRUE(io::read_checkpoint_header(o.checkpoint).fluid_kept);
  EXPECT_THROW(io::slim_checkpoint(o.checkpoint), InputError);
  o.until = INFINITY;
  run::Run first(text, "sphere", o, energy_hooks());
  ASSERT_TRUE(first.continued());
  EXPECT_EQ(first.evolve().status, RunStatus::finished);
  const io::CheckpointHeader h = io::read_checkpoint_header(o.checkpoint);
  EXPECT_EQ(h.scene_yaml, text);
  EXPECT_EQ(h.record.status, RunStatus::finished);
  EXPECT_FALSE(h.fluid_kept);
  EXPECT_EQ(h.clock.step, 2);
  EXPECT_EQ(h.clock.t, first.ib().time());
  EXPECT_TRUE(h.record.series.empty());  // the header reads no series
  run::Run again(text, "sphere", o, energy_hooks());
  ASSERT_TRUE(again.continued());
  EXPECT_FALSE(again.fluid_kept());
  const Progress p = again.evolve();
  EXPECT_EQ(p.status, RunStatus::finished);
  EXPECT_EQ(p.sitting_steps, 0);
  EXPECT_EQ(again.series("energy").rows, first.series("energy").rows);
  const host_vector<double> a = first.ib().batch(0).state().storage(), b = again.ib().batch(0).state().storage();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << k;
  const host_vector<double> u = again.ib().fluid_state().u[0];
  ASSERT_FALSE(u.empty());
  for (double v : u) ASSERT_TRUE(std::isnan(v));
  again.checkpoint();  // written again: still without its fluid, never with the NaN in its place
  EXPECT_FALSE(io::read_checkpoint_header(o.checkpoint).fluid_kept);
}

TEST(RunLoop, SlimmingAFinishedRunsCheckpointKeepsAllButItsFluid) {
  const std::string text = sphere_scene("0.4 us", "0.8 us");
  Options o = two_steps_kept_in("to_slim.h5");
  run::Run(text, "sphere", o, energy_hooks()).evolve();
  const io::Checkpoint whole = io::read_checkpoint(o.checkpoint);
  ASSERT_TRUE(whole.fluid_kept);
  const auto before = std::filesystem::file_size(o.checkpoint);
  EXPECT_TRUE(io::slim_checkpoint(o.checkpoint));
  EXPECT_FALSE(io::slim_checkpoint(o.checkpoint));  // nothing left to take out
  EXPECT_LT(std::filesystem::file_size(o.checkpoint), before);
  const io::Checkpoint slim = io::read_checkpoint(o.checkpoint);
  EXPECT_FALSE(slim.fluid_kept);
  EXPECT_TRUE(slim.state.fluid.u[0].empty());
  EXPECT_EQ(slim.state.fluid.t, whole.state.fluid.t);
  EXPECT_EQ(slim.state.clock.step, whole.state.clock.step);
  EXPECT_EQ(slim.scene_yaml, whole.scene_yaml);
  EXPECT_EQ(slim.record.status, whole.record.status);
  EXPECT_EQ(slim.record.wall_seconds, whole.record.wall_seconds);
  EXPECT_EQ(slim.record.series.at("energy").rows, whole.record.series.at("energy").rows);
  const host_vector<double> a = whole.state.batches.at(0), b = slim.state.batches.at(0);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << k;
}

TEST(RunLoop, HoursToGoFollowThisSittingsRateWhenItTookSteps) {
  Progress p;
  p.clock.t = 1e-3, p.clock.step = 1000;  // mean step 1 us: 1,000 steps to t_end
  p.t_end = 2e-3;
  p.wall_seconds = 1000, p.steps_timed = 1000;  // 1 s per step over the sittings
  EXPECT_NEAR(p.hours_to_go(), 1000 * 1.0 / 3600, 1e-12);
  p.sitting_seconds = 60, p.sitting_steps = 20;  // 3 s per step on the machine the run is on now
  EXPECT_DOUBLE_EQ(p.seconds_per_step(), 1.0);
  EXPECT_DOUBLE_EQ(p.seconds_per_step_here(), 3.0);
  EXPECT_NEAR(p.hours_to_go(), 1000 * 3.0 / 3600, 1e-12);
  EXPECT_NE(p.describe().find("0.833 h to go"), std::string::npos) << p.describe();
  p.status = RunStatus::finished;
  EXPECT_EQ(p.hours_to_go(), 0);
}

}  // namespace
}  // namespace rbfib::run
