// Reproduces seed Sec. 5.1.2, Fig. 5.2: the full red-cell model of Sec. 2.2 (Skalak, bending,
// membrane dissipation) tumbles at low shear and tank-treads at high shear. One red cell in the
// 16 um box between walls in y moving at -+u_b along z (400 um/s: shear 50/s; 8 mm/s: 1000/s),
// periodic in x and z, plasma (rho = 1 g/cm^3, mu = 0.1 cP), the flow initially the steady shear
// u = gdot (y - 8 um) e_z; the cell at the centre, lying flat (disc parallel to the walls) and
// rotated 1 rad about x, the vorticity axis, so that it moves in the y-z shear plane (the seed
// does not name the flow direction; its whole-blood and collision drivers shear along z); B3
// kernel, backward-forward Euler, the seed's coupling (a)-(g).
//   full:  h = 0.4 um, n_d = 625, n_s = 2,500, dt = 0.1 us (the seed's);
//   quick: h = 0.8 um, n_d = 400, n_s = 1,600, dt = 3.2 us (stable there: see the dt scan).
// Seen as in Fig. 5.2, flow to the right (z) and y up; angles are counterclockwise from the flow
// direction, and the shear turns things clockwise, so rotation rates are -d(angle)/dt / gdot.
// Measured from the data sites (material points) every few steps (common/cell_shape.hpp): the
// angle of the short axis p(t) beside Jeffery's orbit of a rigid oblate spheroid of the cell's
// own aspect ratio started from the same p; the inclination of the long axis of the y-z profile;
// the angle about the centre of a tracked material point (the data site on the rim in the shear
// plane, Fig. 5.2's black dot); the Taylor deformation D = (L - B)/(L + B) of the profile; the
// largest spread force density (growth of it flags an instability). Rates are least-squares
// slopes over the second half of each run.
// A dt scan at 1000/s finds the largest stable step beside eq. 5.4's bound and measures the data
// sites' difference from the smallest step (speed against error). At full scale each run writes a
// checkpoint and its samples every few minutes and continues from them when started again.
//
// Run:   build/studies/study_chapter5_shear --scale quick --out runs/chapter5_shear
#include "common/cell_shape.hpp"
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;
using st::Vec3;

namespace {
constexpr double pi = 3.14159265358979323846;

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
  st::SceneRun run;             // steps, wall time, eq. 5.4's bound, a stop, the final data sites
  std::vector<Sample> samples;  // run.samples, read back
  struct Outline {
    double t = 0;
    std::vector<double> z, y;  // data sites relative to the centre (cm), the view of Fig. 5.2
  };
  std::vector<Outline> outlines;  // at the start, 1/3, 2/3 and the end of the window
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

/// Runs one scene to t_end (or until a NumericalError stops it), sampling every `every` steps.
Run shear_run(const Setup& s, double rate, double mu, double dt, double t_end, int every, const st::Options& opt, bool resumable,
              const std::string& prefix = "", double max_seconds = INFINITY) {
  char mu_text[32];
  std::snprintf(mu_text, sizeof mu_text, "%g", mu / units::cP);
  const std::string tag = prefix + "rate" + to_text(std::lround(rate)) + "_mu" + mu_text + "cP_dt" + to_text(std::lround(dt / units::ns)) + "ns";
  Run r;
  r.rate = rate;
  r.mu = mu;
  r.dt = dt;
  r.t_end = t_end;
  const long total = std::lround(t_end / dt);
  long material = 0;
  // Outlines (Fig. 5.2) at the start, 1/3, 2/3 and the end, kept in files as they are taken so
  // that a continued run has them all.
  auto outline_file = [&](int k) { return opt.out_dir + "/outline_" + tag + "_" + std::to_string(k) + ".txt"; };
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
  hooks.after_step = [&](const sim::ImmersedBoundary& ib) {
    const long step = ib.step_count();
    if (step == 0)  // a fresh start: no outline of an earlier run may remain
      for (int k = 1; k < 4; ++k) std::filesystem::remove(outline_file(k));
    for (int k = 0; k < 4; ++k)
      if (step == total * k / 3) {
        const std::vector<double> X = ib.batch(0).positions_host();
        const long n = ib.batch(0).type().n_data();
        const st::CellShape sh = st::cell_shape(X, n, 1, 0);
        std::ofstream f(outline_file(k));
        f.precision(17);
        f << ib.time() << '\n';
        for (long i = 0; i < n; ++i) f << X[std::size_t(2 * n + i)] - sh.center[2] << ' ' << X[std::size_t(n + i)] - sh.center[1] << '\n';
      }
  };
  r.run = st::run_scene(scene_text(s, rate, mu, dt, t_end), tag, every, resumable, opt, hooks, max_seconds);
  for (const std::vector<double>& row : r.run.samples) r.samples.push_back(from_row(row));
  for (int k = 0; k < 4; ++k) {
    std::ifstream f(outline_file(k));
    Run::Outline o;
    if (!(f >> o.t)) continue;
    for (double z, y; f >> z >> y;) o.z.push_back(z), o.y.push_back(y);
    r.outlines.push_back(std::move(o));
  }
  return r;
}

struct Analysis {
  double aspect = 0;  // thickness / diameter at t = 0 (Jeffery's r)
  // Angles in the view of Fig. 5.2 (counterclockwise from e_z), unwrapped, per sample (rad): the
  // short axis, Jeffery's short axis from the same start, the profile's long axis, the material point.
  std::vector<double> t, axis, jeffery, inclination, material, taylor, force;
  double body_rate = 0, jeffery_rate = 0, material_rate = 0;  // -d(angle)/dt / gdot over the second half
  double volume_change = 0;  // largest |V - V0| / V0, V0 at the first step
  double force_growth = 0;   // max ||f|| over the last quarter / max over the second quarter
};

double axis_view_angle(const Vec3& p) { return view_angle(p[2], p[1]); }

Analysis analyse(const Run& r) {
  Analysis a;
  const st::CellShape& s0 = r.samples.front().shape;
  a.aspect = s0.extent[0] / (0.5 * (s0.extent[1] + s0.extent[2]));
  std::vector<double> axis, incl, mat;
  double v0 = 0;
  for (const Sample& s : r.samples) {
    a.t.push_back(s.t);
    axis.push_back(axis_view_angle(s.shape.axes[0]));
    incl.push_back(s.inclination);
    mat.push_back(view_angle(s.material[2] - s.shape.center[2], s.material[1] - s.shape.center[1]));
    a.taylor.push_back(s.taylor);
    a.force.push_back(s.force_density);
    if (s.volume > 0 && v0 == 0) v0 = s.volume;  // the first step's (the start has none)
    if (s.volume > 0) a.volume_change = std::max(a.volume_change, std::abs(s.volume - v0) / v0);
  }
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
  const double q2 = *std::max_element(a.force.begin() + long(n / 4), a.force.begin() + long(h) + 1);
  const double q4 = *std::max_element(a.force.begin() + long(3 * n / 4), a.force.end());
  a.force_growth = q4 / q2;
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
    // The runs: the dissertation's plasma (0.1 cP, Sec. 2.1) at both rates, and 1000/s again at
    // the 1 cP of the seed's public code and of water, which Sec. 2.1 says plasma behaves like.
    // Windows: a tank-treading period at 1000/s is about 2 pi / (0.22 gdot) = 29 ms; a tumble at
    // 50/s (Jeffery, r = 0.33) about 0.42 s, out of reach at the seed's step here, so both scales
    // measure rotation rates over a window. At quick scale 1 cP needs a quarter of the step: its forces
    // are ten times larger; eq. 5.4 stops dt = 3.2 us within 20 steps and 1.6 us after 2.5 ms.
    const double us = units::us, ms = units::ms, cP = units::cP;
    struct Case {
      double rate, mu, dt, t_end;
    };
    // (Full scale runs 1 cP first: tank-treading is what the quick window cannot settle.)
    const std::vector<Case> cases = full ? std::vector<Case>{{1000, 1 * cP, 0.1 * us, 30 * ms}, {1000, 0.1 * cP, 0.1 * us, 30 * ms},
                                                             {50, 0.1 * cP, 0.1 * us, 40 * ms}}
                                         : std::vector<Case>{{50, 0.1 * cP, 3.2 * us, 10 * ms}, {1000, 0.1 * cP, 3.2 * us, 8 * ms},
                                                             {1000, 1 * cP, 0.8 * us, 6 * ms}};
    const double dt = cases[1].dt;  // the step of the dt scan's scene (1000/s, 0.1 cP, both scales)
    const int samples = 400;        // per run

    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "16 x 16 x 16, periodic x and z, walls in y moving at -+u_b along z";
    P["fluid"] = "rho = 1 g/cm^3, mu = 0.1 cP (Sec. 2.1); 1000/s also at mu = 1 cP (the seed's code)";
    P["h_um"] = 16.0 / s.cells;
    P["data_sites"] = s.n_data;
    P["sample_sites"] = s.n_sample;
    P["kernel_integrator_coupling"] = "B3 kernel, backward-forward Euler, the seed's coupling (a)-(g)";
    P["initial_orientation"] = "lying flat (short axis y), rotated 1 rad about x (the vorticity axis), at the box centre";
    Json::Array runs_text;
    for (const Case& c : cases)
      runs_text.push_back(Json(to_text(c.rate) + "/s at " + to_text(std::round(c.mu / cP * 10) / 10) + " cP: dt = " + to_text(c.dt / us) +
                               " us to " + to_text(c.t_end / ms) + " ms"));
    P["runs"] = runs_text;

    // ---- 1. The two shear rates ---------------------------------------------------------------
    const double deg = 180 / pi;
    Json ts = st::table({"rate_1_s", "mu_cP", "t_ms", "strain", "axis_deg", "jeffery_axis_deg", "inclination_deg", "material_deg", "taylor_D",
                         "force_density"},
                        {"1/s", "cP", "ms", "", "deg", "deg", "deg", "deg", "", "dyn/cm^3"});
    Json sum = st::table({"rate_1_s", "mu_cP", "capillary", "dt_us", "t_end_ms", "steps", "seconds_per_step", "aspect_ratio", "body_rate_over_gdot",
                          "jeffery_rate_over_gdot", "body_over_jeffery", "material_rate_over_gdot", "inclination_end_deg", "taylor_D_end",
                          "volume_change_rel", "force_growth", "stopped_ms"},
                         {"1/s", "cP", "", "us", "ms", "", "s", "", "", "", "", "", "deg", "", "", "", "ms"});
    Json outl = st::table({"rate_1_s", "mu_cP", "t_ms", "z_um", "y_um"}, {"1/s", "cP", "ms", "um", "um"});
    const st::Sitting sitting;  // full scale: a sitting's wall time, shared by the runs still to come
    for (std::size_t c = 0; c < cases.size(); ++c) {
      const auto& [rate, mu, step, t_end] = cases[c];
      const Run r = shear_run(s, rate, mu, step, t_end, std::max(1, int(std::lround(t_end / step / samples))), opt, full, "",
                              sitting.remaining() / double(cases.size() - c));
      const Analysis a = analyse(r);
      const std::size_t stride = std::max<std::size_t>(1, a.t.size() / 200);
      for (std::size_t i = 0; i < a.t.size(); i += stride)
        ts["rows"].push(Json::Array{Json(rate), Json(mu / cP), Json(a.t[i] / units::ms), Json(rate * a.t[i]), Json(a.axis[i] * deg), Json(a.jeffery[i] * deg),
                                    Json(a.inclination[i] * deg), Json(a.material[i] * deg), Json(a.taylor[i]), Json(a.force[i])});
      // Capillary number mu gdot R / E_s with the Skalak shear modulus (Sec. 2.2) and R = 3.91 um.
      const double capillary = mu * rate * cells::seed::red_cell_radius / cells::seed::red_cell_E;
      sum["rows"].push(Json::Array{Json(rate), Json(mu / cP), Json(capillary), Json(step / us), Json(r.samples.back().t / units::ms), Json(double(r.run.steps)),
                                   Json(r.run.seconds_per_step()), Json(a.aspect), Json(a.body_rate),
                                   Json(a.jeffery_rate), Json(a.body_rate / a.jeffery_rate), Json(a.material_rate),
                                   Json(a.inclination.back() * deg), Json(a.taylor.back()), Json(a.volume_change), Json(a.force_growth),
                                   r.run.stopped.empty() ? Json() : Json(r.samples.back().t / units::ms)});
      // Outlines as in Fig. 5.2: the data sites in the y-z view, relative to the centre.
      for (const Run::Outline& o : r.outlines)
        for (std::size_t i = 0; i < o.z.size(); ++i)
          outl["rows"].push(Json::Array{Json(rate), Json(mu / cP), Json(std::round(o.t / ms * 1e3) / 1e3), Json(o.z[i] / units::um), Json(o.y[i] / units::um)});
      st::log(opt, "shear " + to_text(rate) + "/s, mu = " + to_text(mu / cP) + " cP: aspect " + to_text(a.aspect) + ", body rate " + to_text(a.body_rate) + " gdot (Jeffery " +
                       to_text(a.jeffery_rate) + "), material rate " + to_text(a.material_rate) + " gdot, inclination " +
                       to_text(a.inclination.back() * deg) + " deg, D " + to_text(a.taylor.back()) + ", volume change " +
                       to_text(a.volume_change) + ", force growth " + to_text(a.force_growth));
      const std::string k = to_text(std::lround(rate)) + (mu > 0.5 * cP ? "_1cP" : "");
      results["values"]["body_rate_" + k] = a.body_rate;
      results["values"]["body_over_jeffery_" + k] = a.body_rate / a.jeffery_rate;
      results["values"]["material_rate_" + k] = a.material_rate;
      results["values"]["material_minus_body_" + k] = a.material_rate - a.body_rate;
      results["values"]["volume_change_" + k] = a.volume_change;
      results["values"]["force_growth_" + k] = a.force_growth;
      results["values"]["completed_" + k] = r.run.stopped.empty() ? 1.0 : 0.0;
      results["values"]["finished_" + k] = r.run.finished ? 1.0 : 0.0;  // reached its end (or was stopped)
    }
    results["tables"]["orientation"] = ts;
    results["tables"]["summary"] = sum;
    results["tables"]["outlines"] = outl;

    // ---- 2. The dt scan at 1000/s: the largest stable step, and the error of larger steps ------
    Json scan = st::table({"dt_us", "stable", "stopped_us", "force_growth", "seconds_per_step", "seconds", "dt_bound_us"},
                          {"us", "", "us", "", "s", "s", "us"});
    Json diffs = st::table({"dt_us", "X_diff_um", "seconds"}, {"us", "um", "s"});
    const double t_scan = 1 * units::ms;
    std::vector<Run> runs;
    for (double d : full ? std::vector<double>{3.2, 1.6, 0.8, 0.4, 0.2, 0.1} : std::vector<double>{6.4, 3.2, 1.6, 0.8})
      runs.push_back(shear_run(s, 1000, 0.1 * units::cP, d * units::us, t_scan, std::max(1, int(std::lround(t_scan / (d * units::us) / 40))), opt, false, "scan_"));
    double largest = 0;
    // Stable: the window finished (eq. 5.4 did not stop it) and ||f||_inf did not double between
    // its second and last quarters (an instability grows exponentially; the cell's own transient
    // at 1000/s settles within a strain of about one).
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const Run& r = runs[k];
      const double growth = analyse(r).force_growth;
      const bool stable = r.run.stopped.empty() && growth < 2;
      if (stable) largest = std::max(largest, r.dt);
      scan["rows"].push(Json::Array{Json(r.dt / units::us), Json(stable ? 1.0 : 0.0), r.run.stopped.empty() ? Json() : Json(r.run.steps * r.dt / units::us),
                                    Json(growth), Json(r.run.seconds_per_step()), Json(r.run.seconds), Json(r.run.min_bound / units::us)});
      // Differences between successive steps dt and dt/2 (both finished): first order in dt.
      if (k + 1 < runs.size() && r.run.stopped.empty() && runs[k + 1].run.stopped.empty())
        diffs["rows"].push(Json::Array{Json(r.dt / units::us),
                                       Json(rms_difference_um(r.run.final_positions.at(0), runs[k + 1].run.final_positions.at(0))),
                                       Json(r.run.seconds)});
    }
    results["tables"]["dt_scan"] = scan;
    results["tables"]["dt_differences"] = diffs;
    results["values"]["largest_stable_dt_us"] = largest / units::us;
    results["values"]["largest_stable_dt_over_run_dt"] = largest / dt;
    st::write_results(opt, results);
    return 0;
  });
}
