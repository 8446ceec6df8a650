#include "common/capillary.hpp"

#include "rbfib/core/error.hpp"

#include <cmath>

namespace rbfib::capillary {

std::unique_ptr<Run> Runner::go(const Model& m, const chapter3::EvaluationSet* eval, const std::string& label) {
  const std::string path = opt_.out_dir + "/run_" + label +
                           (label.find("_eta") == std::string::npos ? "_eta" + to_text(m.eta) : "") + ".h5";
  auto run = std::make_unique<Run>(m, eval, opt_.keeps_runs() ? path : std::string(), std::max(0.0, sitting_.remaining()));
  if (run->continued()) study::log(opt_, label + ": resumed from " + path + " at step " + to_text(run->step()));
  run->advance();
  study::log(opt_, label + ": step " + to_text(run->step()) + " of " + to_text(m.steps) + ", " +
                       to_text(run->seconds_per_step()) + " s per step" +
                       (run->failure().empty() ? std::string() : ", STOPPED: " + run->failure()));
  return run;
}

void record(study::Json& results, const std::string& id, const Run& run) {
  study::RunProgress p;
  p.finished = run.done();
  p.t = run.step() * run.model().dt;
  p.t_end = run.model().steps * run.model().dt;
  p.steps = run.step();
  p.seconds_per_step = run.seconds_per_step();
  p.stopped = run.failure();
  study::record_run(results, id, p);
}

void write_parameters(study::Json& P, const Model& base) {
  P["units"] = "tables in um, s, pN (1 pN/um = 1e-3 dyn/cm, 1 pN um = 1e-11 erg); computed in CGS";
  P["box_um"] = "[-12, 12]^3, periodic; steady Stokes (alpha = 0), exact inverse of the MAC operators";
  P["eta"] = base.eta;
  P["h_um"] = base.h() / um;
  P["mu_cP"] = base.mu * 100;
  P["background_force_pN_per_um3"] = base.f_in * 1e-5;  // 1 dyn/cm^3 = 1e-5 pN/um^3
  P["capillary"] = "tethered nodes on r = 5 um, x in [-8, 8] um, k_teth = 2.45 pN/um per node (eq. 93), node "
                   "spacing h/2; eqs. (94)-(95) for the constant velocity";
  P["dt_s"] = base.dt;
  P["t_end_s"] = base.dt * base.steps;
  P["kernel"] = "peskin4";
}

EmptyFlow empty_capillary(Runner& runner, study::Json& results, Model m, Region region, const std::string& id) {
  m.with_cell = false;
  m.region = region;
  m.steps = 100;  // the flow is steady within a few steps (column u_max_change_last_half)
  m.record_every = 10;
  m.view_every = m.steps;
  const std::string label = std::string("empty_") + to_string(region) + "_eta" + to_text(m.eta);
  const std::unique_ptr<Run> run = runner.go(m, nullptr, label);
  record(results, id.empty() ? label : id, *run);
  EmptyFlow e;
  // the peak of the last step, and of the step at half the run
  for (const Sample& q : run->series())
    if (std::isfinite(q.u_max)) {
      if (q.t <= 0.5 * m.dt * m.steps + 1e-12) e.u_half = q.u_max;
      e.u_max = q.u_max;
      e.u_zero_mean = q.u_max - q.uc[0];
    }
  if (!run->done() || !run->failure().empty()) e.u_max = e.u_zero_mean = NAN;
  e.profile = run->profile_x(0.0);
  double best = 1e300;
  for (const auto& zu : e.profile)
    if (std::abs(zu[0]) < best) {
      best = std::abs(zu[0]);
      e.u_axis = zu[1];
    }
  if (!run->series().empty()) e.cap_disp = run->series().back().cap_disp;
  e.seconds = run->seconds();
  e.h = m.h();
  e.nodes = double(run->capillary().size());
  study::log(runner.options(), label + ": u_max " + to_text(e.u_max / um) + " um/s with the wall at rest, " +
                                   to_text(e.u_zero_mean / um) + " um/s in the zero-mean frame (paper 750)");
  return e;
}

}  // namespace rbfib::capillary
