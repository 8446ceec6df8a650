#include "common/scene_run.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace rbfib::study {

RunProgress SceneRun::progress(double t_end) const {
  const double here = sitting_steps > 0 && sitting_seconds > 0 ? sitting_seconds / double(sitting_steps) : NAN;
  return {finished, samples.empty() ? 0.0 : samples.back().at(0), t_end, steps, seconds_per_step(), stopped, here};
}

namespace {
/// Where the resumable run under `tag` keeps its checkpoint.
std::string checkpoint_path(const Options& opt, const std::string& tag) { return opt.out_dir + "/checkpoint_" + tag + ".h5"; }
}  // namespace

bool scene_run_ended(const std::string& text, const std::string& tag, const Options& opt) {
  const std::string path = checkpoint_path(opt, tag);
  if (!std::filesystem::exists(path)) return false;
  const io::CheckpointHeader c = io::read_checkpoint_header(path);
  return c.scene_yaml == text && c.record.status != io::RunStatus::running;
}

SceneRun run_scene(const std::string& text, const std::string& tag, run::Cadence every, bool resumable, const Options& opt,
                   const SceneRunHooks& hooks, double max_seconds, bool land_on_end) {
  std::ofstream(opt.out_dir + "/scene_" + tag + ".yaml") << text;
  scene::Scene sc = scene::parse_scene(text, "scene_" + tag + ".yaml");
  run::Options o;
  o.t_end = sc.t_end;
  o.land_on_end = land_on_end;
  o.sitting = resumable ? std::max(0.0, max_seconds) : INFINITY;  // a spent sitting takes no step
  if (resumable) o.checkpoint = checkpoint_path(opt, tag);
  o.ended_keeps_fluid = false;  // what is taken from an ended run: its series and its cells and points
  o.sample_every = every;
  run::Hooks h;
  h.built = hooks.at_start;
  if (hooks.after_step || hooks.record)
    h.after_step = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport*, run::SeriesSet& series) {
      if (hooks.after_step) hooks.after_step(ib);
      if (hooks.record) hooks.record(ib, series);
    };
  h.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport* report, run::SeriesSet& series) {
    series["samples"].rows.push_back(hooks.sample(ib, report));
  };
  h.progress = [&](const run::Progress& p) { log(opt, tag + ": " + p.describe()); };
  run::Run run(std::move(sc), o, h);
  if (run.continued()) log(opt, tag + ": continuing from " + o.checkpoint + " at t = " + to_text(run.ib().time() / units::ms) + " ms");
  const run::Progress p = run.evolve();
  SceneRun r;
  r.samples = run.series("samples").rows;
  r.series = run.series();
  r.steps = p.clock.step;
  r.steps_timed = p.steps_timed;
  r.seconds = p.wall_seconds;
  r.sitting_steps = p.sitting_steps;
  r.sitting_seconds = p.sitting_seconds;
  r.stopped = p.stop_message;
  r.stop_cause = p.stop_cause;
  r.finished = p.ended();
  const sim::ImmersedBoundary& ib = run.ib();
  for (index_t b = 0; b < ib.batches(); ++b) r.final_positions.push_back(ib.batch(b).positions_host());
  for (index_t p = 0; p < ib.point_sets(); ++p) r.final_points.push_back(ib.points(p).X);
  return r;
}

double divergence_um(const SceneRun& a, const SceneRun& b) {
  double m = 0;
  for (std::size_t k = 0; k < a.final_positions.size(); ++k) {
    const std::vector<double>& X = a.final_positions[k];
    const std::vector<double>& Y = b.final_positions.at(k);
    const std::size_t n = X.size() / 3;  // component-major, 3 n for one batch's N cells together
    for (std::size_t i = 0; i < n; ++i) {
      double d2 = 0;
      for (std::size_t d = 0; d < 3; ++d) d2 += (X[d * n + i] - Y[d * n + i]) * (X[d * n + i] - Y[d * n + i]);
      m = std::max(m, std::sqrt(d2));
    }
  }
  return m / units::um;
}

}  // namespace rbfib::study
