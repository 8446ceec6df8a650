#pragma once
// The run loop: one scene stepped from its start (or its checkpoint) to its end over as many
// sittings as it takes. The `rbfib` command and the studies run scenes through it.
//
// A run is its scene's YAML text plus a checkpoint (io/checkpoint.hpp) holding the coupled step's
// state, the run's named sample series and whether it has finished or stopped. Started again with
// the same scene text, a run continues from its checkpoint bit for bit (same OpenMP team), with
// its series as they were when the checkpoint was written: there are no rows to trim. A finished
// run is a checkpoint marked finished; a run stopped by a numerical failure (eq. 5.4 with a fixed
// step, a non-finite value, a degenerate site, an inverted cell, a failed solve) keeps its last
// good state and the stop's message and cause, and is not stepped again.
//
// Cadences (checkpoints, samples, snapshots, progress lines) count steps, simulated time and wall
// time; a sitting limit (wall seconds) ends this sitting with a checkpoint; `until` ends it at a
// simulated time before the run's end. The end is a time, not a step count, so that the adaptive
// step (sim::AdaptiveStep) ends where a fixed one does: the loop steps while t < t_end (to a
// relative 1e-12).
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <string>

namespace rbfib::run {

using io::RunStatus;
using io::Series;

/// When something is due: every `steps` steps, every `time` of simulated time (s), every `wall`
/// seconds of wall time; a zero measure never fires. Due when any of them is.
struct Cadence {
  long steps = 0;
  double time = 0;  ///< s (simulated)
  double wall = 0;  ///< s (wall clock)
  bool never() const { return steps <= 0 && time <= 0 && wall <= 0; }
};

struct Options {
  double t_end = 0;             ///< the run's end (s, simulated): reaching it finishes the run
  double until = INFINITY;      ///< end this sitting at this simulated time (s), the run unfinished
  double sitting = INFINITY;    ///< wall seconds this sitting may step before it checkpoints and returns
  std::string checkpoint;       ///< the checkpoint's path; empty: none is read or written
  Cadence checkpoint_every{0, 0, 300};  ///< besides the sitting's end, the finish and a stop
  Cadence sample_every{1, 0, 0};        ///< samples: after these steps (and at the start and the end)
  Cadence snapshot_every;               ///< snapshots (Hooks::snapshot): after these steps
  Cadence progress_every{0, 0, 30};     ///< progress lines (Hooks::progress)
  std::string label;                    ///< kept in the checkpoint of a fresh run (e.g. the code version)
  /// Whether the checkpoint of a run that has ended (finished or stopped) keeps the fluid's arrays.
  /// false: its series, cells, points and clock only (io/checkpoint.hpp), for runs whose result
  /// those are (a study's finished runs, kept small); the `rbfib` command keeps the whole state.
  bool ended_keeps_fluid = true;
  /// With the adaptive step, the last step is shortened to land on t_end (runs compared at their
  /// end); otherwise it may pass it by part of a rung. Never on `until`: a run continued from a
  /// sitting's end is the same as one taken at once.
  bool land_on_end = false;
  /// A split fluid (dist/): each process steps its part of a scene; the cadences and the sitting's
  /// end are agreed by all, process 0 writes the checkpoint. Null: one process.
  std::shared_ptr<const FluidDecomposition> parts;
};

/// Where a run stands, for progress lines and reports.
struct Progress {
  RunStatus status = RunStatus::running;
  sim::Clock clock;            ///< t, dt, the step count from t = 0 and the ladder's level now
  double t_end = 0;            ///< s
  double wall_seconds = 0;     ///< wall time of the steps taken, all sittings (s)
  long steps_timed = 0;        ///< the steps those seconds took
  double sitting_seconds = 0;  ///< wall time of this sitting's steps (s)
  long sitting_steps = 0;      ///< steps taken in this sitting
  std::string stop_message;    ///< the stop's message (status stopped)
  std::optional<Cause> stop_cause;
  bool ended() const { return status != RunStatus::running; }
  double seconds_per_step() const { return steps_timed > 0 ? wall_seconds / double(steps_timed) : NAN; }
  /// This sitting's time per step when it took steps, else seconds_per_step(): the rate of the
  /// machine and load the run is on now (sittings on shared machines differ by several times).
  double seconds_per_step_here() const {
    return sitting_steps > 0 && sitting_seconds > 0 ? sitting_seconds / double(sitting_steps) : seconds_per_step();
  }
  /// Hours to the end at the mean step so far and seconds_per_step_here() (0 once ended; NaN unknown).
  double hours_to_go() const;
  /// "t = 1.2 of 5 ms (24%), step 1200, 3.1 steps/s, mean dt 1 us, 0.4 h to go", in the units
  /// that suit the run's end.
  std::string describe() const;
};

/// A run's data series, by name (the checkpoint keeps them).
using SeriesSet = std::map<std::string, Series>;

struct Hooks {
  /// Called once after the scene is built, at t = 0, before a checkpoint is restored (to read the
  /// starting state whether or not the run continues).
  std::function<void(const sim::ImmersedBoundary&)> built;
  /// Appends this moment's samples to the series; `report` is null at the run's start.
  std::function<void(const sim::ImmersedBoundary&, const sim::IbStepReport* report, SeriesSet&)> sample;
  /// Called after every step (after its sample, if one was due) and once at the start of a fresh
  /// run (report null); may add to the series (a sample at a moment of its own choosing).
  std::function<void(const sim::ImmersedBoundary&, const sim::IbStepReport* report, SeriesSet&)> after_step;
  /// Writes a snapshot (io::SnapshotWriter) at the start of a fresh run and at its cadence.
  std::function<void(const sim::ImmersedBoundary&)> snapshot;
  /// Receives progress at its cadence and once when the sitting ends.
  std::function<void(const Progress&)> progress;
  /// Called after each checkpoint is written (e.g. to rewrite a table from the series).
  std::function<void(const SeriesSet&)> checkpointed;
};

class Run {
 public:
  /// Builds the scene `text` (its origin names it in messages) and, when options.checkpoint names
  /// an existing checkpoint of the same text, restores it with its series and status. A
  /// checkpoint of another scene text is left for evolve() to replace. A scene with a start
  /// (scene::Start) begins from its starting state (io::build_scene).
  Run(const std::string& text, const std::string& origin, Options options, Hooks hooks);
  /// The same for a scene already read (its text: scene.source).
  Run(scene::Scene scene, Options options, Hooks hooks);
  /// A coupled step built by the caller (a setup no scene file describes, e.g. Chapter 3's
  /// periodic Stokes runs), with `source`, the text that describes it, in the scene's place: the
  /// checkpoint restores only into a run of the same text.
  Run(std::string source, sim::ImmersedBoundary ib, Options options, Hooks hooks);

  /// Steps until the run's end, the sitting's end, `until` or a numerical stop; returns where it
  /// stands. A run already ended returns at once. max_steps >= 0 also ends the call after that
  /// many steps, without a checkpoint of its own (cadences still write theirs): for callers that
  /// step several runs in turn.
  Progress evolve(long max_steps = -1);

  sim::ImmersedBoundary& ib() { return ib_; }
  const sim::ImmersedBoundary& ib() const { return ib_; }
  /// The scene (InputError for a run built without one).
  const scene::Scene& scene() const;
  const std::string& source() const { return source_; }
  const SeriesSet& series() const { return record_.series; }
  /// The series to add to between sittings (the next checkpoint keeps what is added).
  SeriesSet& series() { return record_.series; }
  const Series& series(const std::string& name) const;
  bool continued() const { return continued_; }  ///< restored from its checkpoint
  /// false: restored from an ended run's checkpoint that kept no fluid; the fluid then holds NaN
  /// (a measure of it cannot pass for a result).
  bool fluid_kept() const { return fluid_kept_; }
  const std::string& label() const { return record_.label; }  ///< the label of the sitting that began it
  Progress progress() const;
  /// Writes the checkpoint now (no-op without one).
  void checkpoint();

 private:
  void start();
  void sample(const sim::IbStepReport* report);
  std::optional<scene::Scene> scene_;
  std::string source_;  // what the checkpoint must match (a scene's text)
  Options options_;
  Hooks hooks_;
  sim::ImmersedBoundary ib_;
  io::RunRecord record_;
  bool continued_ = false;
  bool fluid_kept_ = true;
  double sitting_seconds_ = 0;
  long sitting_steps_ = 0;
};

}  // namespace rbfib::run
