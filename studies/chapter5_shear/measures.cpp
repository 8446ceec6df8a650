#include "measures.hpp"

#include "common/study.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/cells/measure.hpp"
#include "rbfib/core/series.hpp"
#include "rbfib/models/jeffery.hpp"

#include <algorithm>

namespace rbfib::shear {

using study::row;
namespace {
const double us = units::us, ms = units::ms, cP = units::cP;
}  // namespace


std::vector<double> sample(const sim::ImmersedBoundary& ib, long material, const sim::IbStepReport* rep) {
  const std::vector<double> X = ib.batch(0).positions_host();
  const long n = ib.batch(0).type().n_data();
  const cells::CellShape s = cells::cell_shape(X, n, 1, 0);
  const cells::Profile p = cells::profile(X, n, s.center, 2, 1);
  std::vector<double> r{ib.time(), ib.diagnostics(0).volume.empty() ? 0 : ib.diagnostics(0).volume[0], p.inclination, p.taylor(),
                        rep ? rep->max_force_density : 0};
  r.insert(r.end(), s.center.begin(), s.center.end());
  for (const Vec3& a : s.axes) r.insert(r.end(), a.begin(), a.end());
  r.insert(r.end(), s.extent.begin(), s.extent.end());
  for (int d = 0; d < 3; ++d) r.push_back(X[std::size_t(d * n + material)]);
  r.push_back(rep ? rep->dt : 0);
  return r;
}

Analysis analyse(const std::vector<std::vector<double>>& samples, double rate, double first_panel) {
  Analysis a;
  const std::vector<double>& s0 = samples.front();
  a.aspect = s0[kExtent] / (0.5 * (s0[kExtent + 1] + s0[kExtent + 2]));
  a.jeffery_period = 2 * pi * (a.aspect + 1 / a.aspect);
  std::vector<double> axis, incl, mat, jef;
  double v0 = 0, worst = 0;
  int volumes = 0;
  for (const std::vector<double>& s : samples) {
    a.t.push_back(s[kT]);
    a.strain.push_back(rate * s[kT]);
    axis.push_back(std::atan2(s[kAxes + 1], s[kAxes + 2]));
    incl.push_back(s[kInclination]);
    mat.push_back(std::atan2(s[kMaterial + 1] - s[kCenter + 1], s[kMaterial + 2] - s[kCenter + 2]));
    a.taylor.push_back(s[kTaylor]);
    a.force.push_back(s[kForce]);
    if (s[kVolume] > 0) {  // measured after a step (the start has none)
      if (volumes++ == 0) v0 = s[kVolume];
      worst = std::max(worst, std::abs(s[kVolume] - v0) / v0);
    }
  }
  if (volumes >= 2) a.volume_change = worst;
  a.axis = unwrap(axis, pi);
  a.inclination = unwrap(incl, pi);
  a.material = unwrap(mat, 2 * pi);
  for (const Vec3& p : models::jeffery_axis({s0[kAxes], s0[kAxes + 1], s0[kAxes + 2]}, a.aspect, rate, 2, 1, a.t)) jef.push_back(std::atan2(p[1], p[2]));
  a.jeffery = unwrap(jef, pi);
  const std::size_t n = a.t.size(), h = n / 2;
  auto turning = [&](const std::vector<double>& v) {  // -d(angle)/dt / gdot over the second half
    return -study::slope(std::vector<double>(a.t.begin() + long(h), a.t.end()), std::vector<double>(v.begin() + long(h), v.end())) / rate;
  };
  a.body_rate = turning(a.axis);
  a.jeffery_rate = turning(a.jeffery);
  a.material_rate = turning(a.material);
  a.material_turn = a.material.front() - a.material.back();
  a.period = cells::revolution_strain(a.strain, a.material, first_panel);
  double sum = 0;
  int count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (a.strain[i] >= first_panel) sum += a.inclination[i], ++count;
  if (count > 0) a.inclination_mean = sum / count - pi * std::ceil(sum / count / pi - 0.5);  // in (-pi/2, pi/2]
  if (n >= 4) {
    const double q2 = *std::max_element(a.force.begin() + long(n / 4), a.force.begin() + long(h) + 1);
    const double q4 = *std::max_element(a.force.begin() + long(3 * n / 4), a.force.end());
    a.force_growth = q4 / q2;
  }
  return a;
}

void tabulate(Json& results, Tables& T, const Run& r, const study::Options& opt) {
  const Case& c = r.c;
  const Analysis a = analyse(r.run.samples, c.rate, c.first_panel);
  const std::size_t stride = std::max<std::size_t>(1, a.t.size() / 200);
  for (std::size_t i = 0; i < a.t.size(); i += stride)
    T.orientation["rows"].push(row({c.rate, c.mu / cP, a.t[i] / ms, a.strain[i], a.axis[i] * deg, a.jeffery[i] * deg, a.inclination[i] * deg,
                                    a.material[i] * deg, a.taylor[i], a.force[i]}));
  // Capillary number mu gdot R / E_s with the Skalak shear modulus (Sec. 2.2) and R = 3.91 um.
  const double capillary = c.mu * c.rate * cells::seed::red_cell_radius / cells::seed::red_cell_E;
  const double t_reached = r.run.samples.back()[kT], top = c.dt * double(1 << c.ladder);  // dt_us: the step, or the ladder's lowest rung
  T.summary["rows"].push(row({c.rate, c.mu / cP, capillary, c.dt / us, top / us, r.run.steps > 0 ? t_reached / double(r.run.steps) / us : NAN,
                              t_reached / ms, double(r.run.steps), r.run.seconds_per_step(),
                              a.aspect, a.body_rate, a.jeffery_rate, a.body_rate / a.jeffery_rate, a.material_rate, a.material_turn * deg,
                              c.first_panel, a.period, 2 * pi / a.period, a.jeffery_period, a.inclination.back() * deg, a.inclination_mean * deg,
                              a.taylor.back(), a.volume_change, a.force_growth,
                              r.run.stopped.empty() ? Json() : Json(r.run.samples.back()[kT] / ms)}));
  for (int k = 0; k < 4; ++k)
    if (const auto it = r.run.series.find("outline_" + std::to_string(k)); it != r.run.series.end() && !it->second.rows.empty())
      for (std::size_t i = 1; i < it->second.rows.size(); ++i)
        T.outlines["rows"].push(row({c.rate, c.mu / cP, std::round(it->second.rows[0].at(0) / ms * 1e3) / 1e3,
                                     it->second.rows[i].at(0) / units::um, it->second.rows[i].at(1) / units::um}));
  study::log(opt, c.id + ": body rate " + to_text(a.body_rate) + " gdot (Jeffery " + to_text(a.jeffery_rate) + "), material rate " +
                   to_text(a.material_rate) + " gdot, period " + to_text(a.period) + " (strain), D " + to_text(a.taylor.back()));
  const std::pair<const char*, double> values[] = {
      {"body_rate_", a.body_rate}, {"body_over_jeffery_", a.body_rate / a.jeffery_rate}, {"material_rate_", a.material_rate},
      {"material_minus_body_", a.material_rate - a.body_rate}, {"period_strain_", a.period},
      {"period_rate_", 2 * pi / a.period},  // omega / gdot, rad per unit strain
      {"jeffery_period_strain_", a.jeffery_period}, {"inclination_mean_deg_", a.inclination_mean * deg}, {"volume_change_", a.volume_change},
      {"force_growth_", a.force_growth}, {"completed_", r.run.stopped.empty() ? 1.0 : 0.0}};
  for (const auto& [name, value] : values) results["values"][name + c.id] = value;
}

void dt_scan(Json& results, const std::vector<Run>& members, std::size_t own, double h, double run_dt, double t_diff) {
  study::RunProgress all{true, 0, 0, 0, NAN, ""};  // the members other than the run itself, together
  double seconds = 0;
  long steps_timed = 0;
  for (std::size_t k = 0; k < members.size(); ++k)
    if (k != own) {
      const study::RunProgress p = members[k].progress();
      all.finished = all.finished && p.finished;
      all.t += p.t, all.t_end += p.t_end, all.steps += p.steps;
      seconds += members[k].run.seconds, steps_timed += members[k].run.steps_timed;
    }
  if (steps_timed > 0) all.seconds_per_step = seconds / double(steps_timed);
  study::record_run(results, "dt_scan", all);
  const double rho = 1;  // g/cm^3
  Json scan = study::table({"dt_us", "t_end_ms", "stable", "stopped_us", "force_growth", "seconds_per_step", "dt_bound_us"}, {"us", "ms", "", "us", "", "s", "us"});
  Json diffs = study::table({"dt_us", "X_diff_um", "seconds"}, {"us", "um", "s"});
  double largest = 0;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const Run& r = members[k];
    const Analysis a = analyse(r.run.samples, r.c.rate, 0);
    const bool stable = r.run.finished && r.run.stopped.empty() && a.force_growth < 2;
    if (stable) largest = std::max(largest, r.c.dt);
    // Eq. 5.4's bound (1/4) sqrt(h rho / ||f||_inf) at the largest sampled force density.
    const double f_max = *std::max_element(a.force.begin(), a.force.end());
    scan["rows"].push(row({r.c.dt / us, r.c.t_end / ms, stable ? 1.0 : 0.0, r.run.stopped.empty() ? Json() : Json(r.run.steps * r.c.dt / us),
                           a.force_growth, r.run.seconds_per_step(), 0.25 * std::sqrt(h * rho / f_max) / us}));
    if (k + 1 < members.size() && !r.snapshot.empty() && !members[k + 1].snapshot.empty()) {
      double sum = 0;  // the rms difference of the data sites, against the wall time of the step dt to 1 ms
      for (std::size_t i = 0; i < r.snapshot.size(); ++i) sum += (r.snapshot[i] - members[k + 1].snapshot[i]) * (r.snapshot[i] - members[k + 1].snapshot[i]);
      diffs["rows"].push(row({r.c.dt / us, std::sqrt(sum / double(r.snapshot.size())) / units::um, r.run.seconds_per_step() * double(std::lround(t_diff / r.c.dt))}));
    }
  }
  results["tables"]["dt_scan"] = scan;
  results["tables"]["dt_differences"] = diffs;
  results["values"]["largest_stable_dt_us"] = largest / us;
  results["values"]["largest_stable_dt_over_run_dt"] = largest / run_dt;
}

}  // namespace rbfib::shear
