#pragma once
// Runs one scene for a study through the library's run loop (run/run.hpp): built from its YAML
// text (kept beside the results, where `rbfib run` reruns it), stepped to the scene's end time,
// sampled every few steps, progress logged every 30 s; a numerical failure (eq. 5.4, a degenerate
// cell) ends the run early and is reported, not thrown. Resumable runs (full scale) keep
// DIR/checkpoint_<tag>.h5 with their samples inside, written every five minutes of wall time, at
// the sitting's end and at the run's end, and continue from it when started again with the same
// scene text; a run stopped by a numerical failure keeps its last good state and the stop, and is
// not stepped again.
#include "common/study.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rbfib::study {

struct SceneRunHooks {
  /// Called once after the scene is built, at t = 0 (before a checkpoint is restored).
  std::function<void(const sim::ImmersedBoundary&)> at_start;
  /// One row of numbers describing the state; `report` is null for the row at the start.
  std::function<std::vector<double>(const sim::ImmersedBoundary&, const sim::IbStepReport* report)> sample;
  /// Called after every step (and once at the start of a fresh run).
  std::function<void(const sim::ImmersedBoundary&)> after_step;
  /// Called after every step (and once at the start of a fresh run) with the run's series, to keep
  /// a moment of the run (an outline, a snapshot) in the checkpoint beside the samples.
  std::function<void(const sim::ImmersedBoundary&, run::SeriesSet&)> record;
};

struct SceneRun {
  std::vector<std::vector<double>> samples;  ///< rows from hooks.sample, the first at t = 0
  run::SeriesSet series;                     ///< every series of the run (samples and those hooks.record keeps)
  std::vector<std::vector<double>> final_positions;  ///< each batch's data sites at the end (cm)
  std::vector<dvec> final_points;                    ///< each tethered point set's positions at the end (cm)
  long steps = 0;        ///< steps from t = 0 to the end (or to the failure)
  long steps_timed = 0;  ///< steps timed, over all sittings
  double seconds = 0;    ///< their wall time (s)
  long sitting_steps = 0;        ///< steps taken in this sitting
  double sitting_seconds = 0;    ///< their wall time (s)
  std::string stopped;   ///< the NumericalError's message when the run ended early
  std::optional<Cause> stop_cause;  ///< and its cause
  bool finished = false; ///< reached the scene's end (or stopped); false: the wall-time budget ran out
  double seconds_per_step() const { return steps_timed > 0 ? seconds / double(steps_timed) : NAN; }
  /// How far the run is toward t_end, for record_run (the time is the last sample's).
  RunProgress progress(double t_end) const;
};

/// Runs the scene `text` (its end time is the run's), sampling at the cadence `every` (steps, or
/// simulated time for a run whose step changes) and at the end;
/// writes DIR/scene_<tag>.yaml. A resumable run given `max_seconds` of wall time (a sitting) saves
/// its checkpoint when they are spent and returns unfinished (continued at the next start).
/// `land_on_end`: with the adaptive step, the last step lands on the scene's end (run::Options).
SceneRun run_scene(const std::string& text, const std::string& tag, run::Cadence every, bool resumable, const Options& opt,
                   const SceneRunHooks& hooks, double max_seconds = INFINITY, bool land_on_end = false);

/// The largest distance (um) between the data sites of two runs' cells at their ends (the same
/// scene's cells, compared site by site): how far one run's result lies from another's.
double divergence_um(const SceneRun& a, const SceneRun& b);

/// Whether the resumable run of `text` under `tag` has ended (finished or stopped) in a checkpoint
/// this sitting would continue from: for sharing a sitting among the runs still to go.
bool scene_run_ended(const std::string& text, const std::string& tag, const Options& opt);

}  // namespace rbfib::study
