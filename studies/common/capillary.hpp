#pragma once
// The Chapter 3 capillary studies' bookkeeping (chapter3_capillary, chapter3_capillary_flow): runs
// of the model of rbfib/models/capillary.hpp kept over sittings, recorded in the results, and the
// empty capillary both studies measure.
#include "common/study.hpp"
#include "rbfib/models/capillary.hpp"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace rbfib::capillary {

/// Runs (or resumes, or reads back) the runs of a study: checkpoints DIR/run_<label>[_eta<eta>].h5
/// when the scale keeps runs, within one sitting's wall time.
class Runner {
 public:
  explicit Runner(const study::Options& opt) : opt_(opt), sitting_(opt) {}
  std::unique_ptr<Run> go(const Model& m, const chapter3::EvaluationSet* eval, const std::string& label);
  double elapsed() const { return sitting_.elapsed(); }
  const study::Options& options() const { return opt_; }

 private:
  const study::Options& opt_;
  const study::Sitting sitting_;
};

/// results["runs"][id] for one run (harness/FORMAT.md).
void record(study::Json& results, const std::string& id, const Run& run);

/// The study's grid: eta = 64 at full scale, 48 at quick.
inline int study_eta(const study::Options& opt) { return opt.scale == study::Scale::full ? 64 : 48; }

/// The parameters both studies share (fluid, background force, capillary, time step).
void write_parameters(study::Json& P, const Model& base);

/// The empty capillary (100 steps, steady within a few) with the background force in `region`:
/// its peak x-velocity in the capillary's frame (u_c added) and in the solver's zero-mean frame,
/// at half the run, on the axis at x = 0, and the profile along z there; recorded as run `id`
/// (empty: its label, empty_<region>_eta<eta>).
struct EmptyFlow {
  double u_max = NAN, u_zero_mean = NAN, u_half = NAN, u_axis = NAN, cap_disp = NAN, seconds = 0, h = NAN;
  double nodes = 0;
  std::vector<std::array<double, 2>> profile;  ///< (z, u_x) (cm, cm/s)
};
EmptyFlow empty_capillary(Runner& runner, study::Json& results, Model m, Region region, const std::string& id);

}  // namespace rbfib::capillary
