#pragma once
// Checkpoints of a scene's run in HDF5: the scene's YAML text, everything the coupled step
// carries over (sim::ImmersedBoundary::Carried) and what the run loop keeps beside it (its named
// sample series, whether it has finished or stopped, its wall time over all sittings). Restoring
// one into the step built from the same scene continues the run bit for bit.
//
// Layout (one file; every array a 1D dataset of doubles, in the library's layouts):
//   /scene                the YAML text (bytes)
//   /fluid/u0, u1, u2     the MAC velocity components (cm/s), /fluid/p (dyn/cm^2),
//   /fluid/phi0, phi1     the lagged projection data (cm^2/s); attribute t (s)
//   /batches/0, 1, ...    each cell batch's data-site state, n_d x 6N column-major: X then U
//   /points/0, 1, ...     each tethered point set's positions, 3n
//   /shells/0, 1, ...     each LDSM shell's vertices, 3n (absent in older files: none)
//   /series/<name>/values every row of the series, one after the other; .../widths each row's
//                         length; attribute columns (the columns' names, one per line; may be empty)
//   attributes of /: format ("rbfib checkpoint 2"), steps, dt (s), level, allowing, cap, status
//   ("running", "finished" or "stopped"), stop_message, stop_cause, wall_seconds, steps_timed, label
// Format 1 (no series, no run attributes) is read as a running run without series.
// A run that has ended (finished or stopped) never steps again; its checkpoint may keep no fluid
// arrays (/fluid with its attribute t only): its result is its series, its cells and points and
// its clock, about a fiftieth of the file at the grids of Chapter 5 (write_checkpoint's
// keep_fluid, slim_checkpoint). A running run's checkpoint always keeps them.
// Written atomically: to PATH.tmp, flushed and fsynced, then renamed over PATH (and the
// directory fsynced), so a kill at any moment leaves the previous checkpoint whole.
#include "rbfib/core/error.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <map>
#include <string>
#include <vector>

namespace rbfib::io {

/// A named series of samples kept with a run: rows of numbers (by convention the first is the
/// time in s), optionally with the columns' names (with their units).
struct Series {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

enum class RunStatus { running, finished, stopped };
const char* to_string(RunStatus s);

/// What the run loop keeps beside the coupled step's state.
struct RunRecord {
  RunStatus status = RunStatus::running;
  std::string stop_message;          ///< the numerical stop's message (status stopped)
  Cause stop_cause = Cause::solver;  ///< and its cause
  double wall_seconds = 0;           ///< wall time of the steps taken, over all sittings (s)
  long steps_timed = 0;              ///< the steps those seconds took
  std::string label;                 ///< free text kept with the run (e.g. the code version that began it)
  std::map<std::string, Series> series;
};

/// Writes the run's state; on a split fluid a collective call (the whole state is gathered) whose
/// process 0 writes the file, the same file one process writes. keep_fluid false (allowed only
/// for a run that has ended: InputError otherwise) leaves out the fluid's arrays.
void write_checkpoint(const std::string& path, const std::string& scene_yaml, const sim::ImmersedBoundary& ib,
                      const RunRecord& record = {}, bool keep_fluid = true);

struct Checkpoint {
  std::string scene_yaml;
  sim::ImmersedBoundary::Carried state;  ///< without fluid arrays when !fluid_kept
  RunRecord record;
  bool fluid_kept = true;  ///< false: an ended run's checkpoint written without the fluid's arrays
};

/// Reads a checkpoint; throws InputError naming the file and what is missing or malformed.
Checkpoint read_checkpoint(const std::string& path);

/// What a checkpoint says of its run without its arrays or series (cheap on a large file): the
/// scene text, the clock (t, step, dt, level) and the record's status, stop, wall time and label.
struct CheckpointHeader {
  std::string scene_yaml;
  sim::Clock clock;
  RunRecord record;  ///< series not read: empty
  bool fluid_kept = true;
};
CheckpointHeader read_checkpoint_header(const std::string& path);

/// Rewrites an ended run's checkpoint without its fluid's arrays (atomically; nothing to do when
/// it has none); InputError for a running run's, whose fluid is what it continues from. Returns
/// whether the file was rewritten.
bool slim_checkpoint(const std::string& path);

/// The state a scene starts from (scene.start.checkpoint): the checkpoint's state, the cell type
/// of each of its batches and its grid (from the scene text it keeps).
scene::StartingState read_starting_state(const scene::Scene& scene);

/// Builds a scene's coupled step (scene::build), from its start when it has one; on a split fluid
/// (`parts`, dist/) each process builds its part.
sim::ImmersedBoundary build_scene(const scene::Scene& scene, std::shared_ptr<const FluidDecomposition> parts = nullptr);

}  // namespace rbfib::io
