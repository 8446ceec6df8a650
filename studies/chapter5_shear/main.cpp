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
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "measures.hpp"
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
using namespace rbfib::shear;

namespace {

const double us = units::us, ms = units::ms, cP = units::cP;

struct Setup {
  int cells = 0;  // grid cells per 16 um
  int n_data = 0, n_sample = 0;
  bool full = false;
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
    const cells::CellShape s0 = cells::cell_shape(X, ib.batch(0).type().n_data(), 1, 0);
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
        const Vec3 c = cells::cell_shape(X, n, 1, 0).center;
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
