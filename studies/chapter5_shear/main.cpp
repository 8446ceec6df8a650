// Reproduces seed Sec. 5.1.2, Fig. 5.2: the full red-cell model of Sec. 2.2 (Skalak, bending,
// membrane dissipation) tumbles at low shear and tank-treads at high shear. One red cell in the
// 16 um box between walls in y moving at -+u_b along z (400 um/s: shear 50/s; 8 mm/s: 1000/s),
// periodic in x and z, plasma of rho = 1 g/cm^3 and mu = 1 cP (the seed's public code; Sec. 2.1
// prints 0.1 cP, kept as a variant at 1000/s), the flow initially the steady shear
// u = gdot (y - 8 um) e_z; the cell at the centre, lying flat and rotated 1 rad about x, the
// vorticity axis, so that it moves in the y-z shear plane; B3 kernel, backward-forward Euler, the
// seed's coupling (a)-(g).
//   full:  h = 0.4 um, n_d = 625, n_s = 2,500, the seed's adaptive step (dt = 2^k x 50 ns up to
//          800 ns by eq. 5.4, sim::AdaptiveStep; the seed's runs used 0.1 us), windows long enough for
//          Fig. 5.2's periods: 0.5 s at 50/s (strain 25), 70 ms at 1000/s, 1 cP (strain 70);
//   quick: h = 0.8 um, n_d = 400, n_s = 1,600, windows of a strain of 0.5-8: rates, not periods.
// Seen as in Fig. 5.2, flow to the right (z) and y up; angles are counterclockwise from the flow
// direction, and the shear turns things clockwise, so rotation rates are -d(angle)/dt / gdot.
// Measured from the data sites every few steps: the short axis p(t) beside Jeffery's orbit of a
// rigid oblate spheroid of the cell's own aspect ratio; the inclination and Taylor deformation
// D = (L - B)/(L + B) of the y-z profile; the angle of a tracked material point (the data site on
// the rim in the shear plane, Fig. 5.2's black dot) and the strain of its full revolution from the
// figure's first panel (gdot t = 0 in (a), 19 in (b)), Fig. 5.2's period; ||f||_inf. Rates are
// least-squares slopes over the second half of each run. A dt scan at 1000/s, 1 cP finds the
// largest stable step beside eq. 5.4's bound and the data sites' difference between dt and dt/2
// at 1 ms. At full scale each run keeps a checkpoint and continues from it when started again.
//
// Run:   build/studies/study_chapter5_shear --scale quick --out runs/chapter5_shear
#include "common/cell_shape.hpp"
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "rbfib/cells/measure.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;
using st::row;
using st::Vec3;

namespace {

const double us = units::us, ms = units::ms, cP = units::cP, deg = 180 / pi;

struct Setup {
  int cells = 0;  // grid cells per 16 um
  int n_data = 0, n_sample = 0;
  bool full = false;
};

/// A sample (a row of the run's series): t, the volume at the last step's force positions (0 before
/// a step), the inclination and Taylor deformation of the y-z profile (Fig. 5.2's view: z right, y up),
/// ||f||_inf of the last step, the shape (common/cell_shape.hpp: centre, axes, extents), the tracked
/// data site (cm), the last step's dt (s; 0 before a step).
enum Column : std::size_t { kT, kVolume, kInclination, kTaylor, kForce, kCenter, kAxes = 8, kExtent = 17, kMaterial = 20, kDt = 23 };

std::vector<double> sample(const sim::ImmersedBoundary& ib, long material, const sim::IbStepReport* rep) {
  const std::vector<double> X = ib.batch(0).positions_host();
  const long n = ib.batch(0).type().n_data();
  const st::CellShape s = st::cell_shape(X, n, 1, 0);
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

struct Case {
  std::string id;  // the run's name in results["runs"] and the suffix of its values
  double rate, mu, dt, t_end;  // dt: the fixed step, or with the ladder its lowest rung dt_min
  double first_panel;  // Fig. 5.2's first panel (gdot t)
  int ladder = 0;      // > 0: the seed's adaptive step, dt = 2^k dt for k = 0..ladder by eq. 5.4
};

/// The scene of one run (docs/scenes.md), kept beside the results, where `rbfib run` reruns it.
scene::Scene shear_scene(const Setup& s, const Case& c) {
  const double L = 16 * units::um, ub = c.rate * L / 2;
  scene::Scene sc;
  sc.name = "chapter5_shear";
  sc.grid.length = {L, L, L};
  sc.grid.cells = {s.cells, s.cells, s.cells};
  sc.grid.lower[1] = sc.grid.upper[1] = MacBoundary::dirichlet;  // walls across y moving at -+u_b along z
  sc.walls[1][0].velocity = {0, 0, -ub};
  sc.walls[1][1].velocity = {0, 0, ub};
  sc.initial_shear = true;
  sc.fluid = {1, c.mu};  // g/cm^3, P
  sc.fluid_options.integrator = TimeIntegrator::backward_forward_euler;
  sc.fluid_options.dt = c.dt;
  sc.t_end = c.t_end;
  if (c.ladder > 0) sc.ib.adaptive = {true, c.dt, c.ladder, 16};
  sc.ib.kernel = ib::Kernel::bspline3;
  sc.types = {scene::cell_type("red cell", "red_cell", s.n_data, s.n_sample)};
  sc.cells = {{"red cell", {{L / 2, L / 2, L / 2}, {1, 0, 0}, 1 - pi / 2}}};  // lying flat (short axis y), then 1 rad about x
  return sc;
}

struct Run {
  Case c;
  st::SceneRun run;              // its samples and series, steps, eq. 5.4's stop
  std::vector<double> snapshot;  // the data sites at t_snapshot (empty when not asked or not reached)
  st::RunProgress progress() const {  // the time reached: steps of the fixed dt (samples are sparser), or the last sample's
    return c.ladder > 0 ? run.progress(c.t_end) : st::RunProgress{run.finished, double(run.steps) * c.dt, c.t_end, run.steps, run.seconds_per_step(), run.stopped};
  }
};

/// Runs one case to its end (or until a numerical failure stops it) with about `samples` samples.
/// Fig. 5.2's outlines (series "outline_<k>": [t], then [z, y] of each data site about the centre)
/// at the start, 1/3, 2/3 and the end, and the data sites at t_snapshot (if > 0; series
/// "snapshot"), are kept with the run as they are taken, so that a continued run has them all.
/// Moments are counted in ticks of c.dt (with the ladder every step is a whole number of them):
/// each is taken at the first step that reaches it.
Run shear_run(const Setup& s, const Case& c, int samples, const st::Options& opt, const std::string& prefix, double max_seconds,
              double t_snapshot) {
  char mu_text[32];
  std::snprintf(mu_text, sizeof mu_text, "%g", c.mu / cP);
  const std::string tag = prefix + "rate" + to_text(std::lround(c.rate)) + "_mu" + mu_text + "cP_dt" + to_text(std::lround(c.dt / units::ns)) + "ns";
  const long total = std::lround(c.t_end / c.dt), snapshot_tick = t_snapshot > 0 ? std::lround(t_snapshot / c.dt) : -1;
  const run::Cadence every = c.ladder > 0 ? run::Cadence{0, c.t_end / samples} : run::Cadence{std::max(1L, std::lround(c.t_end / c.dt / samples))};
  long material = 0;
  st::SceneRunHooks hooks;
  hooks.at_start = [&](const sim::ImmersedBoundary& ib) {  // the rim site farthest along the profile's long axis e_x x p
    const std::vector<double> X = ib.batch(0).positions_host();
    const st::CellShape s0 = st::cell_shape(X, ib.batch(0).type().n_data(), 1, 0);
    material = cells::farthest_along(X, ib.batch(0).type().n_data(), s0.center, {0, -s0.axes[0][2], s0.axes[0][1]});
  };
  hooks.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport* rep) {
    return sample(ib, material, rep);
  };
  hooks.record = [&](const sim::ImmersedBoundary& ib, run::SeriesSet& series) {
    const long tick = std::lround(ib.time() / c.dt), n = ib.batch(0).type().n_data();
    if (snapshot_tick >= 0 && tick >= snapshot_tick && !series.count("snapshot")) series["snapshot"].rows = {{ib.time()}, ib.batch(0).positions_host()};
    for (int k = 0; k < 4; ++k)
      if (tick >= total * k / 3 && !series.count("outline_" + std::to_string(k))) {
        const std::vector<double> X = ib.batch(0).positions_host();
        const Vec3 c = st::cell_shape(X, n, 1, 0).center;
        run::Series& o = series["outline_" + std::to_string(k)];
        o.rows = {{ib.time()}};
        for (long i = 0; i < n; ++i) o.rows.push_back({X[std::size_t(2 * n + i)] - c[2], X[std::size_t(n + i)] - c[1]});
      }
  };
  const std::string text = scene::to_yaml(shear_scene(s, c), "chapter5_shear: one red cell in shear " + to_text(c.rate) + "/s (Sec. 5.1.2, Fig. 5.2)");
  Run r{c, st::run_scene(text, tag, every, s.full, opt, hooks, max_seconds), {}};
  const auto it = r.run.series.find("snapshot");
  if (it != r.run.series.end() && it->second.rows.size() == 2) r.snapshot = it->second.rows[1];
  return r;
}

struct Analysis {
  double aspect = 0;  // thickness / diameter at t = 0 (Jeffery's r)
  // Angles in the view of Fig. 5.2 (counterclockwise from e_z), unwrapped, per sample (rad): the
  // short axis, Jeffery's short axis from the same start, the profile's long axis, the material point.
  std::vector<double> t, strain, axis, jeffery, inclination, material, taylor, force;
  double body_rate = 0, jeffery_rate = 0, material_rate = 0;  // -d(angle)/dt / gdot over the second half
  double volume_change = NAN;     // largest |V - V0| / V0, V0 at the first step (NaN before two steps)
  double force_growth = NAN;      // max ||f|| over the last quarter / max over the second quarter
  double jeffery_period = 0;      // Jeffery's full period 2 pi (r + 1/r) as a strain
  double material_turn = 0;       // how far the material point turned over the window (rad, clockwise positive)
  double period = NAN;            // strain of one full revolution of the material point from the first panel
  double inclination_mean = NAN;  // mean long-axis inclination after the first panel, in (-pi/2, pi/2]
};

Analysis analyse(const Run& r, double first_panel) {
  Analysis a;
  const std::vector<double>& s0 = r.run.samples.front();
  a.aspect = s0[kExtent] / (0.5 * (s0[kExtent + 1] + s0[kExtent + 2]));
  a.jeffery_period = 2 * pi * (a.aspect + 1 / a.aspect);
  std::vector<double> axis, incl, mat, jef;
  double v0 = 0, worst = 0;
  int volumes = 0;
  for (const std::vector<double>& s : r.run.samples) {
    a.t.push_back(s[kT]);
    a.strain.push_back(r.c.rate * s[kT]);
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
  a.axis = st::unwrap(axis, pi);
  a.inclination = st::unwrap(incl, pi);
  a.material = st::unwrap(mat, 2 * pi);
  for (const Vec3& p : st::jeffery_axis({s0[kAxes], s0[kAxes + 1], s0[kAxes + 2]}, a.aspect, r.c.rate, 2, 1, a.t)) jef.push_back(std::atan2(p[1], p[2]));
  a.jeffery = st::unwrap(jef, pi);
  const std::size_t n = a.t.size(), h = n / 2;
  auto rate = [&](const std::vector<double>& v) {
    return -st::slope(std::vector<double>(a.t.begin() + long(h), a.t.end()), std::vector<double>(v.begin() + long(h), v.end())) / r.c.rate;
  };
  a.body_rate = rate(a.axis);
  a.jeffery_rate = rate(a.jeffery);
  a.material_rate = rate(a.material);
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

struct Tables {
  Json orientation = st::table({"rate_1_s", "mu_cP", "t_ms", "strain", "axis_deg", "jeffery_axis_deg", "inclination_deg", "material_deg",
                                "taylor_D", "force_density"},
                               {"1/s", "cP", "ms", "", "deg", "deg", "deg", "deg", "", "dyn/cm^3"});
  Json summary = st::table({"rate_1_s", "mu_cP", "capillary", "dt_us", "dt_top_us", "dt_mean_us", "t_end_ms", "steps", "seconds_per_step", "aspect_ratio",
                            "body_rate_over_gdot", "jeffery_rate_over_gdot", "body_over_jeffery", "material_rate_over_gdot", "material_turn_deg",
                            "first_panel_strain", "period_strain", "period_rate_over_gdot", "jeffery_period_strain", "inclination_end_deg",
                            "inclination_mean_deg", "taylor_D_end", "volume_change_rel", "force_growth", "stopped_ms"},
                           {"1/s", "cP", "", "us", "us", "us", "ms", "", "s", "", "", "", "", "", "deg", "", "", "", "", "deg", "deg", "", "", "", "ms"});
  Json outlines = st::table({"rate_1_s", "mu_cP", "t_ms", "z_um", "y_um"}, {"1/s", "cP", "ms", "um", "um"});
};

/// The parameters, echoed in the results.
void describe(Json& P, const Setup& s, const std::vector<Case>& cases) {
  P["box_um"] = "16 x 16 x 16, periodic x and z, walls in y moving at -+u_b along z";
  P["fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's code; water); 1000/s also at mu = 0.1 cP (printed in Sec. 2.1)";
  P["h_um"] = 16.0 / s.cells;
  P["data_sites"] = s.n_data;
  P["sample_sites"] = s.n_sample;
  P["kernel_integrator_coupling"] = "B3 kernel, backward-forward Euler, the seed's coupling (a)-(g)";
  P["initial_orientation"] = "lying flat (short axis y), rotated 1 rad about x (the vorticity axis), at the box centre";
  Json::Array runs_text;
  for (const Case& c : cases)
    runs_text.push_back(Json(c.id + ": " + to_text(c.rate) + "/s at " + to_text(std::round(c.mu / cP * 10) / 10) + " cP, dt = " +
                             (c.ladder > 0 ? "2^k x " + to_text(c.dt / us) + " us (k = 0.." + to_text(c.ladder) + ", eq. 5.4)" : to_text(c.dt / us) + " us") +
                             " to " + to_text(c.t_end / ms) + " ms (strain " + to_text(c.rate * c.t_end) + ")"));
  P["runs"] = runs_text;
}

/// One case's rows (its angles, summary and outlines as in Fig. 5.2) and values.
void tabulate(Json& results, Tables& T, const Run& r, const st::Options& opt) {
  const Case& c = r.c;
  const Analysis a = analyse(r, c.first_panel);
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
  st::log(opt, c.id + ": body rate " + to_text(a.body_rate) + " gdot (Jeffery " + to_text(a.jeffery_rate) + "), material rate " +
                   to_text(a.material_rate) + " gdot, period " + to_text(a.period) + " (strain), D " + to_text(a.taylor.back()));
  const std::pair<const char*, double> values[] = {
      {"body_rate_", a.body_rate}, {"body_over_jeffery_", a.body_rate / a.jeffery_rate}, {"material_rate_", a.material_rate},
      {"material_minus_body_", a.material_rate - a.body_rate}, {"period_strain_", a.period},
      {"period_rate_", 2 * pi / a.period},  // omega / gdot, rad per unit strain
      {"jeffery_period_strain_", a.jeffery_period}, {"inclination_mean_deg_", a.inclination_mean * deg}, {"volume_change_", a.volume_change},
      {"force_growth_", a.force_growth}, {"completed_", r.run.stopped.empty() ? 1.0 : 0.0}};
  for (const auto& [name, value] : values) results["values"][name + c.id] = value;
}

/// The dt scan at 1000/s, 1 cP; members: the steps above the run's to 3 ms, the run itself (at
/// `own`), half its step to 1 ms. Stable: the window finished (eq. 5.4 did not stop it) and
/// ||f||_inf did not double between its second and last quarters (an instability grows
/// exponentially). Differences at 1 ms between successive steps dt and dt/2: first order in dt.
void dt_scan(Json& results, const std::vector<Run>& members, std::size_t own, double h, double run_dt, double t_diff) {
  st::RunProgress all{true, 0, 0, 0, NAN, ""};  // the members other than the run itself, together
  double seconds = 0;
  long steps_timed = 0;
  for (std::size_t k = 0; k < members.size(); ++k)
    if (k != own) {
      const st::RunProgress p = members[k].progress();
      all.finished = all.finished && p.finished;
      all.t += p.t, all.t_end += p.t_end, all.steps += p.steps;
      seconds += members[k].run.seconds, steps_timed += members[k].run.steps_timed;
    }
  if (steps_timed > 0) all.seconds_per_step = seconds / double(steps_timed);
  st::record_run(results, "dt_scan", all);
  const double rho = 1;  // g/cm^3
  Json scan = st::table({"dt_us", "t_end_ms", "stable", "stopped_us", "force_growth", "seconds_per_step", "dt_bound_us"}, {"us", "ms", "", "us", "", "s", "us"});
  Json diffs = st::table({"dt_us", "X_diff_um", "seconds"}, {"us", "um", "s"});
  double largest = 0;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const Run& r = members[k];
    const Analysis a = analyse(r, 0);
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

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_shear", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_shear",
                                                   "Sec. 5.1.2, Fig. 5.2: a red cell tumbling at 50/s and tank-treading at 1000/s");
    const bool full = opt.scale == st::Scale::full;
    const Setup s = full ? Setup{40, 625, 2500, true} : Setup{20, 400, 1600, false};
    // ---- 1. Parameters ---------------------------------------------------------------------------
    // Both rates at 1 cP, the viscosity of the seed's public code and of water, which Sec. 2.1 says
    // plasma behaves like; 1000/s again at the 0.1 cP printed in Sec. 2.1 (capillary number 0.16,
    // where this cell tumbles). Full windows hold one period: a tumble at 50/s (Jeffery, r = 0.33)
    // takes a strain of 21 (0.42 s), Fig. 5.2(b)'s revolution 19 to 47; 70 ms leaves room for a
    // period up to a strain of 51. Quick windows measure rates; at quick scale 1000/s at 1 cP needs
    // a quarter of the others' step (see the dt scan). Full scale runs the longest, 50/s, last.
    // Full scale climbs the seed's ladder, 50 ns to 800 ns by eq. 5.4 (the dt scan finds 0.8 us
    // stable); quick scale takes the largest stable fixed step.
    const std::vector<Case> cases = full ? std::vector<Case>{{"1000_1cP", 1000, 1 * cP, 0.05 * us, 70 * ms, 19, 4},
                                                             {"1000_0p1cP", 1000, 0.1 * cP, 0.05 * us, 30 * ms, 19, 4},
                                                             {"50_1cP", 50, 1 * cP, 0.05 * us, 500 * ms, 0, 4}}
                                         : std::vector<Case>{{"50_1cP", 50, 1 * cP, 3.2 * us, 10 * ms, 0},
                                                             {"1000_1cP", 1000, 1 * cP, 0.8 * us, 6 * ms, 19},
                                                             {"1000_0p1cP", 1000, 0.1 * cP, 3.2 * us, 8 * ms, 19}};
    const Case& scanned = *std::find_if(cases.begin(), cases.end(), [](const Case& c) { return c.id == "1000_1cP"; });
    // The dt scan: steps above the run's to 3 ms, past the force peak near a strain of 2.5; the run
    // itself when its step is fixed; half the smallest step to 1 ms, the reference for the last
    // difference.
    const std::vector<double> scan_steps = full ? std::vector<double>{3.2, 1.6, 0.8, 0.4, 0.2} : std::vector<double>{6.4, 3.2, 1.6};
    const double t_scan = 3 * ms, t_diff = 1 * ms;
    Json results = st::make_results(opt);
    describe(results["parameters"], s, cases);

    // ---- 2. The runs: the dt scan's short runs first (at full scale in the first sitting), then the
    // cases in their order, each to its end or the sitting's (one finished run is worth more than
    // three that progressed) ------------------------------------------------------------------------
    const st::Sitting sitting(opt);
    std::size_t jobs_left = scan_steps.size() + 2;  // the scan's runs share the sitting with the first case
    std::vector<Run> members;
    for (double d : scan_steps)
      members.push_back(shear_run(s, {"", scanned.rate, scanned.mu, d * us, t_scan, 0}, 40, opt, "scan_", sitting.remaining() / double(jobs_left--), t_diff));
    const bool own = scanned.ladder == 0;  // the run is the scan's member at its own step
    const double dt_ref = (own ? scanned.dt : scan_steps.back() * us) / 2;
    const Run reference = shear_run(s, {"", scanned.rate, scanned.mu, dt_ref, t_diff, 0}, 40, opt, "scan_",
                                    sitting.remaining() / double(jobs_left--), t_diff);
    Tables T;
    for (const Case& c : cases) {
      const Run r = shear_run(s, c, 400, opt, "", sitting.remaining(), own && c.id == scanned.id ? t_diff : 0);
      st::record_run(results, c.id, r.progress());
      tabulate(results, T, r, opt);
      if (own && c.id == scanned.id) members.push_back(r);  // the dt scan's member at the run's own step
    }
    members.push_back(reference);
    results["tables"]["orientation"] = T.orientation;
    results["tables"]["summary"] = T.summary;
    results["tables"]["outlines"] = T.outlines;

    // ---- 3. The dt scan: the largest stable step, and the error of larger steps ------------------
    // Stable: the largest step the run takes (the ladder's top rung) against the scan's largest stable one.
    dt_scan(results, members, own ? scan_steps.size() : members.size(), 16 * units::um / s.cells, scanned.dt * double(1 << scanned.ladder), t_diff);
    st::write_results(opt, results);
    return 0;
  });
}
