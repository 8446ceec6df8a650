// Reproduces seed Sec. 5.1.2, Fig. 5.2: the full red-cell model of Sec. 2.2 (Skalak, bending,
// membrane dissipation) tumbles at low shear and tank-treads at high shear. One red cell in the
// 16 um box between walls in y moving at -+u_b along z (400 um/s: shear 50/s; 8 mm/s: 1000/s),
// periodic in x and z, plasma of rho = 1 g/cm^3 and mu = 1 cP (the seed's public code; Sec. 2.1
// prints 0.1 cP, kept as a variant at 1000/s), the flow initially the steady shear
// u = gdot (y - 8 um) e_z; the cell at the centre, lying flat (disc parallel to the walls) and
// rotated 1 rad about x, the vorticity axis, so that it moves in the y-z shear plane (the seed
// does not name the flow direction; its whole-blood and collision drivers shear along z); B3
// kernel, backward-forward Euler, the seed's coupling (a)-(g).
//   full:  h = 0.4 um, n_d = 625, n_s = 2,500, dt = 0.1 us (the seed's), windows long enough for
//          Fig. 5.2's periods: 0.5 s at 50/s (strain 25), 70 ms at 1000/s, 1 cP (strain 70);
//   quick: h = 0.8 um, n_d = 400, n_s = 1,600, windows of a strain of 0.5-8: rates, not periods.
// Seen as in Fig. 5.2, flow to the right (z) and y up; angles are counterclockwise from the flow
// direction, and the shear turns things clockwise, so rotation rates are -d(angle)/dt / gdot.
// Measured from the data sites (material points) every few steps (common/cell_shape.hpp): the
// angle of the short axis p(t) beside Jeffery's orbit of a rigid oblate spheroid of the cell's
// own aspect ratio started from the same p; the inclination of the long axis of the y-z profile;
// the angle about the centre of a tracked material point (the data site on the rim in the shear
// plane, Fig. 5.2's black dot); the Taylor deformation D = (L - B)/(L + B) of the profile; the
// largest spread force density (growth of it flags an instability). Rates are least-squares
// slopes over the second half of each run. Fig. 5.2's own measure is a period: the strain the
// black dot takes for one full revolution, from the figure's first panel (gdot t = 0 in (a), 19
// in (b)); it is measured so (NaN when the window ends first).
// A dt scan at 1000/s, 1 cP finds the largest stable step beside eq. 5.4's bound and measures the
// data sites' difference between dt and dt/2 at 1 ms (speed against error). At full scale each run
// writes a checkpoint and its samples every few minutes and continues from them when started again.
//
// Run:   build/studies/study_chapter5_shear --scale quick --out runs/chapter5_shear
#include "common/cell_shape.hpp"
#include "rbfib/core/constants.hpp"
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;
using st::Vec3;

namespace {

struct Setup {
  int cells = 0;  // grid cells per 16 um
  int n_data = 0, n_sample = 0;
  bool full = false;
};

struct Sample {
  double t = 0;
  st::CellShape shape;
  Vec3 material{};          // the tracked data site (cm)
  double inclination = 0;   // long axis of the y-z profile, counterclockwise from e_z (rad, in (-pi/2, pi/2])
  double taylor = 0;        // (L - B)/(L + B) of the y-z profile
  double volume = 0;        // enclosed volume at the last step's force positions (cm^3; 0 before a step)
  double force_density = 0; // ||f||_inf of the last step (dyn/cm^3)
};

struct Run {
  double rate = 0, mu = 0, dt = 0, t_end = 0;
  st::SceneRun run;             // steps, eq. 5.4's stop, the final data sites
  std::vector<Sample> samples;  // run.samples, read back
  struct Outline {
    double t = 0;
    std::vector<double> z, y;  // data sites relative to the centre (cm), the view of Fig. 5.2
  };
  std::vector<Outline> outlines;  // at the start, 1/3, 2/3 and the end of the window
  std::vector<double> snapshot;   // the data sites at t_snapshot (empty when not asked or not reached)
  double seconds = 0;             // wall time of the steps taken, over all sittings (s)
  long steps_timed = 0;           // those steps
  double seconds_per_step() const { return steps_timed > 0 ? seconds / double(steps_timed) : NAN; }
  st::RunProgress progress() const {  // the time reached: steps of the fixed dt (samples are sparser)
    return {run.finished, double(run.steps) * dt, t_end, run.steps, seconds_per_step(), run.stopped};
  }
};

/// The scene of one run, in CGS to 17 digits so that it reads back exactly (docs/scenes.md); kept
/// beside the results, where `rbfib run` reruns it.
std::string scene_text(const Setup& s, double rate, double mu, double dt, double t_end) {
  const double L = 16 * units::um, ub = rate * L / 2, flat = 1 - pi / 2;  // lie flat (short axis y), then 1 rad
  const std::string len = to_text(L) + " cm", c = to_text(L / 2) + " cm";
  return "# chapter5_shear: one red cell in shear " + to_text(rate) + "/s (Sec. 5.1.2, Fig. 5.2)\n"
         "name: chapter5_shear\n"
         "domain:\n  size: [" + len + ", " + len + ", " + len + "]\n  periodic: [x, z]\n"
         "  walls:\n    y: {lower: [0 cm/s, 0 cm/s, " + to_text(-ub) + " cm/s], upper: [0 cm/s, 0 cm/s, " + to_text(ub) + " cm/s]}\n"
         "  initial_flow: shear\n"
         "fluid: {density: 1 g/cm^3, viscosity: " + to_text(mu) + " P}\n"
         "grid: {cells: [" + to_text(s.cells) + ", " + to_text(s.cells) + ", " + to_text(s.cells) + "]}\n"
         "time: {integrator: backward_forward_euler, dt: " + to_text(dt) + " s, end: " + to_text(t_end) + " s}\n"
         "ib: {kernel: bspline3}\n"
         "cell_types:\n  - {name: red cell, preset: red_cell, data_sites: " + to_text(s.n_data) + ", sample_sites: " + to_text(s.n_sample) + "}\n"
         "cells:\n  - {type: red cell, center: [" + c + ", " + c + ", " + c + "], axis: [1, 0, 0], angle: " + to_text(flat) + " rad}\n";
}

/// Counterclockwise angle from the flow direction in the view of Fig. 5.2 (z right, y up), rad.
double view_angle(double z, double y) { return std::atan2(y, z); }

Sample sample(const sim::ImmersedBoundary& ib, long material, double force_density) {
  const cells::Batch& b = ib.batch(0);
  const std::vector<double> X = b.positions_host();
  const long n = b.type().n_data();
  Sample s;
  s.t = ib.time();
  s.shape = st::cell_shape(X, n, 1, 0);
  for (int d = 0; d < 3; ++d) s.material[d] = X[std::size_t(d * n + material)];
  // The y-z profile: the major axis of its second moments, and its extents along and across it.
  auto z = [&](long i) { return X[std::size_t(2 * n + i)] - s.shape.center[2]; };
  auto y = [&](long i) { return X[std::size_t(n + i)] - s.shape.center[1]; };
  double mzz = 0, mzy = 0, myy = 0;
  for (long i = 0; i < n; ++i) mzz += z(i) * z(i), mzy += z(i) * y(i), myy += y(i) * y(i);
  s.inclination = 0.5 * std::atan2(2 * mzy, mzz - myy);
  const double c = std::cos(s.inclination), sn = std::sin(s.inclination);
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (long i = 0; i < n; ++i) {
    const double q[2] = {c * z(i) + sn * y(i), -sn * z(i) + c * y(i)};
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  }
  const double L = hi[0] - lo[0], B = hi[1] - lo[1];
  s.taylor = (L - B) / (L + B);
  s.volume = ib.diagnostics(0).volume.empty() ? 0 : ib.diagnostics(0).volume[0];
  s.force_density = force_density;
  return s;
}

/// A sample as a row of numbers (common/scene_run.hpp keeps them on disk at full scale) and back.
std::vector<double> to_row(const Sample& s) {
  std::vector<double> r{s.t, s.volume, s.inclination, s.taylor, s.force_density};
  r.insert(r.end(), s.shape.center.begin(), s.shape.center.end());
  for (const Vec3& a : s.shape.axes) r.insert(r.end(), a.begin(), a.end());
  r.insert(r.end(), s.shape.extent.begin(), s.shape.extent.end());
  r.insert(r.end(), s.material.begin(), s.material.end());
  return r;
}

Sample from_row(const std::vector<double>& r) {
  require(r.size() == 23, "chapter5_shear sample row", r.size(), "expected 23 numbers");
  Sample s;
  s.t = r[0], s.volume = r[1], s.inclination = r[2], s.taylor = r[3], s.force_density = r[4];
  auto take = [&](std::size_t at, Vec3& v) { std::copy(r.begin() + long(at), r.begin() + long(at) + 3, v.begin()); };
  take(5, s.shape.center);
  for (int a = 0; a < 3; ++a) take(8 + 3 * std::size_t(a), s.shape.axes[a]);
  take(17, s.shape.extent);
  take(20, s.material);
  return s;
}

/// Runs one scene to t_end (or until a NumericalError stops it), sampling every `every` steps;
/// keeps the data sites at t_snapshot (if > 0).
Run shear_run(const Setup& s, double rate, double mu, double dt, double t_end, int every, const st::Options& opt, bool resumable,
              const std::string& prefix = "", double max_seconds = INFINITY, double t_snapshot = 0) {
  char mu_text[32];
  std::snprintf(mu_text, sizeof mu_text, "%g", mu / units::cP);
  const std::string tag = prefix + "rate" + to_text(std::lround(rate)) + "_mu" + mu_text + "cP_dt" + to_text(std::lround(dt / units::ns)) + "ns";
  Run r;
  r.rate = rate;
  r.mu = mu;
  r.dt = dt;
  r.t_end = t_end;
  const long total = std::lround(t_end / dt), snapshot_step = t_snapshot > 0 ? std::lround(t_snapshot / dt) : -1;
  long material = 0;
  // Outlines (Fig. 5.2) at the start, 1/3, 2/3 and the end, and the snapshot, kept as series of
  // the run (in its checkpoint) as they are taken, so that a continued run has them all:
  // "outline_<k>" rows [t] then [z, y] per data site; "snapshot" rows [t] then the data sites.
  st::SceneRunHooks hooks;
  hooks.at_start = [&](const sim::ImmersedBoundary& ib) {
    // The tracked material point: the data site on the rim in the shear plane, farthest along
    // the profile's long axis (e_x x p, p the short axis) at t = 0.
    const std::vector<double> X = ib.batch(0).positions_host();
    const long n = ib.batch(0).type().n_data();
    const st::CellShape s0 = st::cell_shape(X, n, 1, 0);
    const Vec3& p = s0.axes[0];
    double best = -1e300;
    for (long i = 0; i < n; ++i) {
      const double q = (X[std::size_t(2 * n + i)] - s0.center[2]) * p[1] - (X[std::size_t(n + i)] - s0.center[1]) * p[2];
      if (q > best) best = q, material = i;
    }
  };
  hooks.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport* rep) {
    return to_row(sample(ib, material, rep ? rep->max_force_density : 0));
  };
  hooks.record = [&](const sim::ImmersedBoundary& ib, run::SeriesSet& series) {
    const long step = ib.step_count();
    if (step == snapshot_step) {
      run::Series& snap = series["snapshot"];
      snap.rows = {{ib.time()}, ib.batch(0).positions_host()};
    }
    for (int k = 0; k < 4; ++k)
      if (step == total * k / 3) {
        const std::vector<double> X = ib.batch(0).positions_host();
        const long n = ib.batch(0).type().n_data();
        const st::CellShape sh = st::cell_shape(X, n, 1, 0);
        run::Series& o = series["outline_" + std::to_string(k)];
        o.rows = {{ib.time()}};
        for (long i = 0; i < n; ++i) o.rows.push_back({X[std::size_t(2 * n + i)] - sh.center[2], X[std::size_t(n + i)] - sh.center[1]});
      }
  };
  r.run = st::run_scene(scene_text(s, rate, mu, dt, t_end), tag, every, resumable, opt, hooks, max_seconds);
  for (const std::vector<double>& row : r.run.samples) r.samples.push_back(from_row(row));
  for (int k = 0; k < 4; ++k) {
    const auto it = r.run.series.find("outline_" + std::to_string(k));
    if (it == r.run.series.end() || it->second.rows.empty()) continue;
    Run::Outline o;
    o.t = it->second.rows[0].at(0);
    for (std::size_t i = 1; i < it->second.rows.size(); ++i) o.z.push_back(it->second.rows[i].at(0)), o.y.push_back(it->second.rows[i].at(1));
    r.outlines.push_back(std::move(o));
  }
  if (const auto it = r.run.series.find("snapshot"); it != r.run.series.end() && it->second.rows.size() == 2 && snapshot_step >= 0 &&
                                                     r.run.steps >= snapshot_step)
    r.snapshot = it->second.rows[1];
  r.seconds = r.run.seconds;  // over all sittings: the checkpoint keeps them
  r.steps_timed = r.run.steps_timed;
  return r;
}

struct Analysis {
  double aspect = 0;  // thickness / diameter at t = 0 (Jeffery's r)
  // Angles in the view of Fig. 5.2 (counterclockwise from e_z), unwrapped, per sample (rad): the
  // short axis, Jeffery's short axis from the same start, the profile's long axis, the material point.
  std::vector<double> t, strain, axis, jeffery, inclination, material, taylor, force;
  double body_rate = 0, jeffery_rate = 0, material_rate = 0;  // -d(angle)/dt / gdot over the second half
  double volume_change = NAN;  // largest |V - V0| / V0, V0 at the first step (NaN before two steps)
  double force_growth = NAN;   // max ||f|| over the last quarter / max over the second quarter
  double jeffery_period = 0;   // Jeffery's full period 2 pi (r + 1/r) as a strain
  double material_turn = 0;    // how far the material point turned over the window (rad, clockwise positive)
  double period = NAN;         // strain of one full revolution of the material point from the first panel
  double inclination_mean = NAN;  // mean long-axis inclination after the first panel, in (-pi/2, pi/2]
};

double axis_view_angle(const Vec3& p) { return view_angle(p[2], p[1]); }

/// The strain from s0 until the material point has made one full clockwise revolution (its
/// unwrapped angle has fallen by 2 pi), linearly between samples; NaN when s0 lies outside the
/// window or the window ends first. For a periodic motion this is its period from any phase.
double revolution_strain(const std::vector<double>& s, const std::vector<double>& angle, double s0) {
  if (s.size() < 2 || s0 < s.front() || s0 > s.back()) return NAN;
  std::size_t i0 = 0;
  while (s[i0] < s0) ++i0;
  const double a0 = i0 == 0 ? angle[0] : angle[i0 - 1] + (angle[i0] - angle[i0 - 1]) * (s0 - s[i0 - 1]) / (s[i0] - s[i0 - 1]);
  const double target = a0 - 2 * pi;
  for (std::size_t i = i0 + 1; i < s.size(); ++i)
    if (angle[i] <= target) return s[i - 1] + (s[i] - s[i - 1]) * (angle[i - 1] - target) / (angle[i - 1] - angle[i]) - s0;
  return NAN;
}

/// An axis angle reduced to (-pi/2, pi/2].
double axis_angle_reduced(double a) { return a - pi * std::ceil(a / pi - 0.5); }

Analysis analyse(const Run& r, double first_panel) {
  Analysis a;
  const st::CellShape& s0 = r.samples.front().shape;
  a.aspect = s0.extent[0] / (0.5 * (s0.extent[1] + s0.extent[2]));
  a.jeffery_period = 2 * pi * (a.aspect + 1 / a.aspect);
  std::vector<double> axis, incl, mat;
  double v0 = 0, worst = 0;
  int volumes = 0;
  for (const Sample& s : r.samples) {
    a.t.push_back(s.t);
    a.strain.push_back(r.rate * s.t);
    axis.push_back(axis_view_angle(s.shape.axes[0]));
    incl.push_back(s.inclination);
    mat.push_back(view_angle(s.material[2] - s.shape.center[2], s.material[1] - s.shape.center[1]));
    a.taylor.push_back(s.taylor);
    a.force.push_back(s.force_density);
    if (s.volume > 0) {  // measured after a step (the start has none)
      if (volumes++ == 0) v0 = s.volume;
      worst = std::max(worst, std::abs(s.volume - v0) / v0);
    }
  }
  if (volumes >= 2) a.volume_change = worst;
  a.axis = st::unwrap(axis, pi);
  a.inclination = st::unwrap(incl, pi);
  a.material = st::unwrap(mat, 2 * pi);
  std::vector<double> jef;
  for (const Vec3& p : st::jeffery_axis(s0.axes[0], a.aspect, r.rate, 2, 1, a.t)) jef.push_back(axis_view_angle(p));
  a.jeffery = st::unwrap(jef, pi);
  const std::size_t n = a.t.size(), h = n / 2;
  auto rate = [&](const std::vector<double>& v) {
    return -st::slope(std::vector<double>(a.t.begin() + long(h), a.t.end()), std::vector<double>(v.begin() + long(h), v.end())) / r.rate;
  };
  a.body_rate = rate(a.axis);
  a.jeffery_rate = rate(a.jeffery);
  a.material_rate = rate(a.material);
  a.material_turn = a.material.front() - a.material.back();
  a.period = revolution_strain(a.strain, a.material, first_panel);
  double sum = 0;
  int count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (a.strain[i] >= first_panel) sum += a.inclination[i], ++count;
  if (count > 0) a.inclination_mean = axis_angle_reduced(sum / count);
  if (n >= 4) {
    const double q2 = *std::max_element(a.force.begin() + long(n / 4), a.force.begin() + long(h) + 1);
    const double q4 = *std::max_element(a.force.begin() + long(3 * n / 4), a.force.end());
    a.force_growth = q4 / q2;
  }
  return a;
}

double rms_difference_um(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s / double(a.size())) / units::um;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_shear", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_shear",
                                                   "Sec. 5.1.2, Fig. 5.2: a red cell tumbling at 50/s and tank-treading at 1000/s");
    const bool full = opt.scale == st::Scale::full;
    const Setup s = full ? Setup{40, 625, 2500, true} : Setup{20, 400, 1600, false};
    const double us = units::us, ms = units::ms, cP = units::cP;
    // The runs: both rates at 1 cP, the viscosity of the seed's public code and of water, which
    // Sec. 2.1 says plasma behaves like; 1000/s again at the 0.1 cP printed in Sec. 2.1 (a variant:
    // capillary number 0.16, where this cell tumbles). The period of Fig. 5.2 is measured from the
    // figure's first panel, gdot t = 0 in (a) and 19 in (b). Full windows hold one period: a tumble
    // at 50/s (Jeffery, r = 0.33) takes a strain of 21 (0.42 s), Fig. 5.2(b)'s revolution 19 to 47;
    // 70 ms leaves room for a period up to a strain of 51. Quick windows measure rates. At quick
    // scale 1000/s at 1 cP needs a quarter of the others' step (see the dt scan).
    struct Case {
      std::string id;      // the run's name in results["runs"] and the suffix of its values
      double rate, mu, dt, t_end;
      double first_panel;  // Fig. 5.2's first panel (gdot t)
    };
    // (Full scale runs the longest, 50/s, last: it takes what the sittings leave to it.)
    const std::vector<Case> cases =
        full ? std::vector<Case>{{"1000_1cP", 1000, 1 * cP, 0.1 * us, 70 * ms, 19},
                                 {"1000_0p1cP", 1000, 0.1 * cP, 0.1 * us, 30 * ms, 19},
                                 {"50_1cP", 50, 1 * cP, 0.1 * us, 500 * ms, 0}}
             : std::vector<Case>{{"50_1cP", 50, 1 * cP, 3.2 * us, 10 * ms, 0},
                                 {"1000_1cP", 1000, 1 * cP, 0.8 * us, 6 * ms, 19},
                                 {"1000_0p1cP", 1000, 0.1 * cP, 3.2 * us, 8 * ms, 19}};
    const Case& scanned = *std::find_if(cases.begin(), cases.end(), [](const Case& c) { return c.id == "1000_1cP"; });
    // The dt scan (section 2): steps above the run's to 3 ms, past the force peak near a strain of
    // 2.5; the run itself; half its step to 1 ms, the reference for the last difference.
    const std::vector<double> scan_steps = full ? std::vector<double>{3.2, 1.6, 0.8, 0.4, 0.2} : std::vector<double>{6.4, 3.2, 1.6};
    const double t_scan = 3 * ms, t_diff = 1 * ms;
    const int samples = 400;  // per run

    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "16 x 16 x 16, periodic x and z, walls in y moving at -+u_b along z";
    P["fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's code; water); 1000/s also at mu = 0.1 cP (printed in Sec. 2.1)";
    P["h_um"] = 16.0 / s.cells;
    P["data_sites"] = s.n_data;
    P["sample_sites"] = s.n_sample;
    P["kernel_integrator_coupling"] = "B3 kernel, backward-forward Euler, the seed's coupling (a)-(g)";
    P["initial_orientation"] = "lying flat (short axis y), rotated 1 rad about x (the vorticity axis), at the box centre";
    Json::Array runs_text;
    for (const Case& c : cases)
      runs_text.push_back(Json(c.id + ": " + to_text(c.rate) + "/s at " + to_text(std::round(c.mu / cP * 10) / 10) + " cP, dt = " + to_text(c.dt / us) +
                               " us to " + to_text(c.t_end / ms) + " ms (strain " + to_text(c.rate * c.t_end) + ")"));
    P["runs"] = runs_text;

    // ---- 1. The runs ----------------------------------------------------------------------------
    const double deg = 180 / pi;
    Json ts = st::table({"rate_1_s", "mu_cP", "t_ms", "strain", "axis_deg", "jeffery_axis_deg", "inclination_deg", "material_deg", "taylor_D",
                         "force_density"},
                        {"1/s", "cP", "ms", "", "deg", "deg", "deg", "deg", "", "dyn/cm^3"});
    Json sum = st::table({"rate_1_s", "mu_cP", "capillary", "dt_us", "t_end_ms", "steps", "seconds_per_step", "aspect_ratio", "body_rate_over_gdot",
                          "jeffery_rate_over_gdot", "body_over_jeffery", "material_rate_over_gdot", "material_turn_deg", "first_panel_strain",
                          "period_strain", "period_rate_over_gdot", "jeffery_period_strain", "inclination_end_deg", "inclination_mean_deg",
                          "taylor_D_end", "volume_change_rel", "force_growth", "stopped_ms"},
                         {"1/s", "cP", "", "us", "ms", "", "s", "", "", "", "", "", "deg", "", "", "", "", "deg", "deg", "", "", "", "ms"});
    Json outl = st::table({"rate_1_s", "mu_cP", "t_ms", "z_um", "y_um"}, {"1/s", "cP", "ms", "um", "um"});
    // The dt scan's short runs first (section 2): at full scale they are done in the first sitting
    // and the runs share what is left of each.
    const st::Sitting sitting(opt);  // full scale: a sitting's wall time, shared by the runs still to come
    std::size_t jobs_left = scan_steps.size() + 1 + cases.size();
    std::vector<Run> members;
    for (double d : scan_steps)
      members.push_back(shear_run(s, scanned.rate, scanned.mu, d * us, t_scan, std::max(1, int(std::lround(t_scan / (d * us) / 40))), opt, full, "scan_",
                                  sitting.remaining() / double(jobs_left--), t_diff));
    const Run reference = shear_run(s, scanned.rate, scanned.mu, scanned.dt / 2, t_diff, std::max(1, int(std::lround(t_diff / (scanned.dt / 2) / 40))), opt,
                                    full, "scan_", sitting.remaining() / double(jobs_left--), t_diff);
    for (const Case& c : cases) {
      const Run r = shear_run(s, c.rate, c.mu, c.dt, c.t_end, std::max(1, int(std::lround(c.t_end / c.dt / samples))), opt, full, "",
                              sitting.remaining() / double(jobs_left--), c.id == scanned.id ? t_diff : 0);
      st::record_run(results, c.id, r.progress());
      const Analysis a = analyse(r, c.first_panel);
      const std::size_t stride = std::max<std::size_t>(1, a.t.size() / 200);
      for (std::size_t i = 0; i < a.t.size(); i += stride)
        ts["rows"].push(Json::Array{Json(c.rate), Json(c.mu / cP), Json(a.t[i] / ms), Json(a.strain[i]), Json(a.axis[i] * deg), Json(a.jeffery[i] * deg),
                                    Json(a.inclination[i] * deg), Json(a.material[i] * deg), Json(a.taylor[i]), Json(a.force[i])});
      // Capillary number mu gdot R / E_s with the Skalak shear modulus (Sec. 2.2) and R = 3.91 um.
      const double capillary = c.mu * c.rate * cells::seed::red_cell_radius / cells::seed::red_cell_E;
      sum["rows"].push(Json::Array{Json(c.rate), Json(c.mu / cP), Json(capillary), Json(c.dt / us), Json(r.samples.back().t / ms), Json(double(r.run.steps)),
                                   Json(r.seconds_per_step()), Json(a.aspect), Json(a.body_rate), Json(a.jeffery_rate), Json(a.body_rate / a.jeffery_rate),
                                   Json(a.material_rate), Json(a.material_turn * deg), Json(c.first_panel), Json(a.period), Json(2 * pi / a.period),
                                   Json(a.jeffery_period), Json(a.inclination.back() * deg), Json(a.inclination_mean * deg), Json(a.taylor.back()),
                                   Json(a.volume_change), Json(a.force_growth), r.run.stopped.empty() ? Json() : Json(r.samples.back().t / ms)});
      // Outlines as in Fig. 5.2: the data sites in the y-z view, relative to the centre.
      for (const Run::Outline& o : r.outlines)
        for (std::size_t i = 0; i < o.z.size(); ++i)
          outl["rows"].push(Json::Array{Json(c.rate), Json(c.mu / cP), Json(std::round(o.t / ms * 1e3) / 1e3), Json(o.z[i] / units::um), Json(o.y[i] / units::um)});
      st::log(opt, c.id + ": aspect " + to_text(a.aspect) + ", body rate " + to_text(a.body_rate) + " gdot (Jeffery " + to_text(a.jeffery_rate) +
                       "), material rate " + to_text(a.material_rate) + " gdot, material turn " + to_text(a.material_turn * deg) +
                       " deg, period " + to_text(a.period) + " (strain, from " + to_text(c.first_panel) + "; Jeffery " + to_text(a.jeffery_period) +
                       "), inclination " + to_text(a.inclination.back() * deg) + " deg, D " + to_text(a.taylor.back()) + ", volume change " +
                       to_text(a.volume_change) + ", force growth " + to_text(a.force_growth));
      Json& V = results["values"];
      V["body_rate_" + c.id] = a.body_rate;
      V["body_over_jeffery_" + c.id] = a.body_rate / a.jeffery_rate;
      V["material_rate_" + c.id] = a.material_rate;
      V["material_minus_body_" + c.id] = a.material_rate - a.body_rate;
      V["period_strain_" + c.id] = a.period;
      V["period_rate_" + c.id] = 2 * pi / a.period;  // omega / gdot, rad per unit strain
      V["jeffery_period_strain_" + c.id] = a.jeffery_period;
      V["inclination_mean_deg_" + c.id] = a.inclination_mean * deg;
      V["volume_change_" + c.id] = a.volume_change;
      V["force_growth_" + c.id] = a.force_growth;
      V["completed_" + c.id] = r.run.stopped.empty() ? 1.0 : 0.0;
      if (c.id == scanned.id) members.push_back(r);  // the dt scan's member at the run's own step
    }
    members.push_back(reference);
    results["tables"]["orientation"] = ts;
    results["tables"]["summary"] = sum;
    results["tables"]["outlines"] = outl;

    // ---- 2. The dt scan at 1000/s, 1 cP: the largest stable step, and the error of larger steps --
    // Stable: the window finished (eq. 5.4 did not stop it) and ||f||_inf did not double between
    // its second and last quarters (an instability grows exponentially).
    // Members: the steps above the run's to 3 ms, the run itself, half its step to 1 ms.
    st::RunProgress scan_progress{true, 0, 0, 0, NAN, ""};  // the members other than the run itself, together
    double scan_seconds = 0;
    long scan_steps_timed = 0;
    for (std::size_t k = 0; k < members.size(); ++k)
      if (k != scan_steps.size()) {
        const st::RunProgress p = members[k].progress();
        scan_progress.finished = scan_progress.finished && p.finished;
        scan_progress.t += p.t, scan_progress.t_end += p.t_end, scan_progress.steps += p.steps;
        scan_seconds += members[k].seconds, scan_steps_timed += members[k].steps_timed;
      }
    if (scan_steps_timed > 0) scan_progress.seconds_per_step = scan_seconds / double(scan_steps_timed);
    st::record_run(results, "dt_scan", scan_progress);
    const double h = 16 * units::um / s.cells, rho = 1;  // g/cm^3
    Json scan = st::table({"dt_us", "t_end_ms", "stable", "stopped_us", "force_growth", "seconds_per_step", "dt_bound_us"},
                          {"us", "ms", "", "us", "", "s", "us"});
    Json diffs = st::table({"dt_us", "X_diff_um", "seconds"}, {"us", "um", "s"});
    double largest = 0;
    for (std::size_t k = 0; k < members.size(); ++k) {
      const Run& r = members[k];
      const Analysis a = analyse(r, 0);
      const bool stable = r.run.finished && r.run.stopped.empty() && a.force_growth < 2;
      if (stable) largest = std::max(largest, r.dt);
      // Eq. 5.4's bound (1/4) sqrt(h rho / ||f||_inf) at the largest sampled force density.
      const double f_max = *std::max_element(a.force.begin(), a.force.end());
      scan["rows"].push(Json::Array{Json(r.dt / us), Json(r.t_end / ms), Json(stable ? 1.0 : 0.0),
                                    r.run.stopped.empty() ? Json() : Json(r.run.steps * r.dt / us), Json(a.force_growth), Json(r.seconds_per_step()),
                                    Json(0.25 * std::sqrt(h * rho / f_max) / us)});
      // Differences at 1 ms between successive steps dt and dt/2 (both reached it): first order in
      // dt; against the wall time of the step dt to 1 ms.
      if (k + 1 < members.size() && !r.snapshot.empty() && !members[k + 1].snapshot.empty())
        diffs["rows"].push(Json::Array{Json(r.dt / us), Json(rms_difference_um(r.snapshot, members[k + 1].snapshot)),
                                       Json(r.seconds_per_step() * double(std::lround(t_diff / r.dt)))});
    }
    results["tables"]["dt_scan"] = scan;
    results["tables"]["dt_differences"] = diffs;
    results["values"]["largest_stable_dt_us"] = largest / us;
    results["values"]["largest_stable_dt_over_run_dt"] = largest / scanned.dt;
    st::write_results(opt, results);
    return 0;
  });
}
