#pragma once
// Where the wall time of a run's coupled steps goes: the phases of sim::IbStepReport (forces,
// spreading, fluid solve, interpolation, update) kept as a run series, one row per step, and read
// back as sums or per-step medians (a descheduled step inflates a sum, not a median). For runs
// advanced in lockstep and timed over blocks of steps: the spread of the ratio of two runs' times
// over the blocks, the timing noise of that ratio measured in the run itself.
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <vector>

namespace rbfib::run {

/// Wall time of the phases of the steps (s).
struct PhaseTimes {
  double forces = 0, spread = 0, solve = 0, interpolate = 0, update = 0;
  double force_products = 0;  ///< the cells' dense products (part of forces)
  double total() const { return forces + spread + solve + interpolate + update; }
};

/// Appends the phases of one step as a row of `phases` (columns: forces, products, spread, solve,
/// interpolate, update, in s).
void append_phases(io::Series& phases, const sim::IbStepReport& step);

/// The phases summed over the rows of a series written by append_phases.
PhaseTimes phase_sums(const io::Series& phases);

/// The per-step median of each phase over those rows (0 without rows).
PhaseTimes phase_medians(const io::Series& phases);

/// The sample standard deviation over blocks of steps of the ratio a / b of two runs' wall times
/// in each block, from the cumulative times at the blocks' ends (NaN for fewer than two blocks or
/// unequal counts).
double block_ratio_std(const std::vector<double>& a_ends, const std::vector<double>& b_ends);

}  // namespace rbfib::run
