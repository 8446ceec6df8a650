#pragma once
// chapter4_cells' timing of the coupled step (both parts) and Part 2, the whole-blood-size step
// (Sec. 5.2): its scene, its split, and the force calls' dense products against a DGEMM ceiling.
#include "common/study.hpp"
#include "rbfib/cells/batch.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <string>
#include <vector>

namespace rbfib::cells_study {

using study::Json;

/// Per-component medians of the step's timings over `steps` steps (after one warm-up step), and
/// the largest relative volume change of any cell of the first batch over all of them.
struct StepSplit {
  double interpolation = 0, forces = 0, spreading = 0, fluid = 0;
  double total() const { return interpolation + forces + spreading + fluid; }
  double volume_change = 0;
  std::string describe() const {
    return "step " + to_text(total() * 1e3) + " ms (interpolation " + to_text(interpolation * 1e3) + ", forces " + to_text(forces * 1e3) +
           ", spreading " + to_text(spreading * 1e3) + ", fluid " + to_text(fluid * 1e3) + " ms); volume change " + to_text(volume_change);
  }
};

StepSplit time_steps(sim::ImmersedBoundary& ib, int steps);

/// Part 2's setup, echoed (the scene it is built from is kept beside the results).
void whole_blood_parameters(Json& P, index_t rbc_nd, index_t rbc_ns);

/// Part 2's scene: two rows of four red cells at y = 6 um, concavities facing z, the rows staggered
/// by 2 um; platelets lying flat (1 um thick) 0.3 um above the endothelium, between the rows (under
/// a red cell at x = 12 um the rim, 2.1 um above the wall, would cut the platelet).
scene::Scene whole_blood_scene(index_t rbc_nd, index_t rbc_ns);

/// Part 2, the whole-blood-size step: its split, and the dense products of the force calls
/// against the better of two DGEMM ceilings (the one of the run's start, and one measured just
/// before: this shared machine's speed drifts over a run). Returns the volume change.
double whole_blood_step(const study::Options& opt, Json& results, sim::ImmersedBoundary& ib, int steps, index_t dgemm_n, int repeats,
                        double ceiling);

}  // namespace rbfib::cells_study
