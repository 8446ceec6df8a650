// Reproduces the platelet baseline of seed Sec. 5.2 (before Sec. 5.2.1): two platelets over a
// flat endothelium, no red cells, shear 1000/s. The 16 x 12 x 16 um box of Sec. 5.2, periodic in x
// and z, walls in y, the top one moving at 12 mm/s along z, the flow started as the steady shear;
// the endothelium as tethered points on the plane y = 1 um (eq. 2.10, k = 2.5 dyn/cm, eta = 2.5e-7
// dyn s/cm per point, Sec. 2.2); two platelets (neo-Hookean + bending about the reference
// curvature, Sec. 2.2) lying flat, 0.3 um and 0.5 um above it (gaps between surfaces: the platelet
// is 1 um thick); B3 kernel, backward-forward Euler; plasma of 1 cP (the seed's code; at the 0.1 cP
// of Sec. 2.1 this endothelium is unstable at 50 ns, reference/chapter4_cells.yaml).
// Four walls: the seed's tethers at its fixed step, the grid's own wall, the endothelium's plane
// held exactly by a solve, and tethers whose k and eta follow the step by the seed's rule (the
// checks' run); all but the first on the seed's ladder. The seed's tethers hold the step at 50 ns
// (61 hours to 100 ms here), so they, the grid wall and the held wall run over an A/B window
// (table wall_ab) and the rule's run goes to the end.
//   full:  h = 0.2 um, 900 / 900 sites, 16,000 endothelium points, dt = 50 ns (the seed's; the
//          ladder's lowest rung), to 100 ms (a wobble at the seed's 10/s), the A/B window 2 ms,
//          continued from checkpoints;
//   quick: h = 0.4 um, 400 / 400 sites, 64 x 64 endothelium points (the same spacing in h), dt =
//          100 ns (the springs' explicit limit here is about 160 ns: 200 ns blows up in 3 steps),
//          every run to 0.3 ms: the onset of the motion, not a period.
// Measured per platelet every few steps: the gap (the lowest data site above the endothelium's
// plane), the tilt of its short axis from the wall normal in the shear plane (the sense of the
// shear positive; edge-on, the edge pointing at the wall, within 45 degrees of 90), the centre's
// height; the endothelium's largest displacement from its anchors; volumes. Rates beside Jeffery's
// rigid spheroid in unbounded shear (a wall slows a particle's rotation); at full scale the wobble
// frequency (from the crossings of the tilt's mean after 5 ms), the tumble frequency in full orbits
// per second (1 / (2 x the mean interval between flips): a flip is half of Jeffery's orbit) and the
// mean contiguous edge-on interval, beside the seed's 10/s, 30/s and 3-4 ms (NaN when the window
// holds no wobble, fewer than two flips, or no complete edge-on interval).
//
// Run:   build/studies/study_chapter5_platelets --scale quick --out runs/chapter5_platelets
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "measures.hpp"
#include "rbfib/cells/measure.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/tether_motion.hpp"

#include <cmath>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;
using st::row;
using namespace rbfib::platelets;

namespace {

/// The wall under the platelets: the seed's endothelium of tethered points on the plane y = 1 um
/// (eq. 2.10 with the seed's k and eta), or the grid's own no-slip wall (the seed: "for modeling a
/// healthy blood vessel, a flat wall suffices"). The grid wall lies at y = 0 and the top wall moves
/// at 12 mm/s x 12/11, so that the platelets see the same gaps and the same shear as over the
/// endothelium, which holds the fluid at rest across the 11 um below the top wall (1091/s). Or the
/// endothelium whose k and eta follow the step by the seed's own rule at gain 0.5
/// (sim/tether_stability.hpp), so that the ladder climbs. Or, beyond the seed, the endothelium's
/// plane held exactly by a solve (sim/held_wall.hpp), its markers 2h apart, on the ladder.
enum class Wall { tethers, grid, rule, held };

struct Setup {
  int cells_x = 0, cells_y = 0;  // grid cells along x (and z) and y
  int sites = 0;                 // data = sample sites per platelet
  int endothelium = 0;           // points per side of the lattice
  double dt = 0, t_end = 0;      // s (dt: the fixed step, or with the ladder its lowest rung)
  double t_ab = 0;               // s, the window of the seed's tethers at its fixed step (the A/B)
};

double wall_plane(Wall w) { return w == Wall::grid ? 0.0 : 1 * units::um; }

/// The two platelets over the flat wall (Sec. 5.2) as a scene, the flow started as the shear; with
/// the grid wall or the rule the step climbs the seed's ladder (2^k dt, k = 0..4, by eq. 5.4).
scene::Scene platelets_scene(const Setup& s, Wall w, double t_end) {
  scene::Scene sc;
  sc.name = "chapter5_platelets";
  sc.grid = make_mac_grid(3, {s.cells_x, s.cells_y, s.cells_x}, {16 * units::um, 12 * units::um, 16 * units::um},
                          {MacBoundary::periodic, MacBoundary::dirichlet, MacBoundary::periodic});
  sc.walls[1][1].velocity = {0, 0, w == Wall::grid ? 12 * units::mm * 12 / 11 : 12 * units::mm};
  sc.initial_shear = true;
  sc.fluid = {1, 1 * units::cP};  // g/cm^3, P
  sc.fluid_options.integrator = TimeIntegrator::backward_forward_euler;
  sc.fluid_options.dt = s.dt;
  sc.t_end = t_end;
  if (w != Wall::tethers) sc.ib.adaptive = {true, s.dt, 4, 16, INFINITY};
  sc.ib.kernel = ib::Kernel::bspline3;
  sc.types.push_back(scene::cell_type("platelet", "platelet", s.sites, s.sites));
  for (int c = 0; c < 2; ++c) {  // lying flat, the short axis along y; the centre 0.5 um above the gap
    const double xz = (4 + 8 * c) * units::um;
    sc.cells.push_back({"platelet", {{xz, wall_plane(w) + (gaps_um[c] + 0.5) * units::um, xz}, {1, 0, 0}, 90 * (pi / 180)}});
  }
  if (w == Wall::held)
    sc.held_walls.push_back({"endothelium", {false, 1, wall_plane(w), {s.cells_x / 2, s.cells_x / 2}}});
  else if (w != Wall::grid)
    sc.point_sets.push_back({"endothelium", {false, 1, wall_plane(w), {s.endothelium, s.endothelium}}, w == Wall::tethers ? 2.5 : 0,
                             w == Wall::tethers ? 2.5e-7 : 0, w == Wall::rule ? 0.5 : 0});
  return sc;
}

/// One sample: t, then per platelet (centre 3, short axis 3, gap, volume), then the endothelium's
/// largest displacement from its anchors and the RMS slip at them (sim/tether_motion.hpp).
std::vector<double> sample(const sim::ImmersedBoundary& ib, double wall_y) {
  const cells::Batch& b = ib.batch(0);
  const std::vector<double> X = b.positions_host();
  const long n = b.type().n_data();
  std::vector<double> row{ib.time()};
  for (long c = 0; c < 2; ++c) {
    const cells::CellShape s = cells::cell_shape(X, n, 2, c);
    double lowest = INFINITY;
    for (long i = 0; i < n; ++i) lowest = std::min(lowest, X[std::size_t((2 + c) * n + i)]);  // y of cell c: column d N + c = 2 + c
    row.insert(row.end(), s.center.begin(), s.center.end());
    row.insert(row.end(), s.axes[0].begin(), s.axes[0].end());
    row.push_back(lowest - wall_y);
    // NaN until a force call has measured it (a state just restored from a checkpoint).
    row.push_back(ib.diagnostics(0).volume.empty() ? NAN : ib.diagnostics(0).volume[std::size_t(c)]);
  }
  const sim::TetherMotion motion = ib.point_sets() > 0 ? sim::tether_motion(ib, 0) : sim::TetherMotion{};  // none over the grid wall
  row.insert(row.end(), {motion.max_displacement, motion.slip_rms});
  return row;
}

/// One wall's run and its tables. Every run's values carry its `key`; the checks' run's values are
/// also written without it.
struct WallRun {
  Wall wall;
  std::string suffix, key, label;  // of its run's id and tables; of its values; its row of wall_treatments
  double share = 1;                // its part of what is left of the sitting: 1 / share
  bool checks;                     // the run every check measures
  double t_end;                    // s
  Json series, summary;
  // At the A/B window's end (NaN before the run has reached it): each platelet's tilt (rad) and
  // gap (cm), the wall's largest displacement up to then (cm).
  double tilt_ab[2] = {NAN, NAN}, gap_ab[2] = {NAN, NAN}, displacement_ab = NAN;
  double setup_seconds = 0;  // the held wall's mobilities, built in this sitting (s)
};

/// Linear interpolation of y(t) at `at` (NaN outside the samples).
double value_at(const std::vector<double>& t, const std::vector<double>& y, double at) {
  for (std::size_t i = 1; i < t.size(); ++i)
    if (t[i] >= at * (1 - 1e-9)) return y[i - 1] + (y[i] - y[i - 1]) * std::clamp((at - t[i - 1]) / (t[i] - t[i - 1]), 0.0, 1.0);
  return NAN;
}

/// The scene of one wall's run, as YAML.
std::string scene_text(const WallRun& w, const Setup& s) {
  return scene::to_yaml(platelets_scene(s, w.wall, w.t_end), w.wall == Wall::grid   ? "chapter5_platelets: two platelets over the grid's flat wall (Sec. 5.2)"
                                                             : w.wall == Wall::held ? "chapter5_platelets: two platelets over a held flat wall"
                                                                                    : "chapter5_platelets: two platelets over a flat endothelium (Sec. 5.2)");
}

/// Runs (or continues) one wall's scene; adds its rows to the tables and its values.
void run_wall(WallRun& w, const Setup& s, const st::Sitting& sitting, const st::Options& opt, Json& results, Json& walls, Json& cost) {
  const double us = units::us, ms = units::ms, gdot = 1000;
  const bool seed = w.wall == Wall::tethers;
  const std::string id = "platelets" + w.suffix;
  st::SceneRunHooks hooks;
  hooks.sample = [&w](const sim::ImmersedBoundary& ib, const sim::IbStepReport*) { return sample(ib, wall_plane(w.wall)); };
  hooks.after_step = [&w](const sim::ImmersedBoundary& ib) {
    if (ib.held_walls() > 0) w.setup_seconds = ib.held_wall(0).seconds_building();
  };
  const std::string text = scene_text(w, s);
  const run::Cadence every = seed ? run::Cadence{std::max(1L, std::lround(w.t_end / s.dt) / 400)} : run::Cadence{0, w.t_end / 400};
  const st::SceneRun run = st::run_scene(text, id, every, opt.keeps_runs(), opt, hooks, sitting.remaining() / w.share);
  std::vector<double> t;
  double displacement = 0;  // the largest over the run; the slip at its end (at t = 0 it is the initial shear's, gdot x 1 um)
  for (const auto& r : run.samples) t.push_back(r[0]), displacement = std::max(displacement, r[r.size() - 2]);
  const double slip = run.samples.back().back();
  Json& V = results["values"];
  Json ignored;
  Platelet p[2];
  for (int c = 0; c < 2; ++c) {
    p[c] = analyse(run.samples, t, c, gdot, w.series);
    report(p[c], c, t.back() - t.front(), w.summary, w.checks ? V : ignored, opt);
    w.tilt_ab[c] = value_at(t, p[c].tilt, s.t_ab);
    w.gap_ab[c] = value_at(t, p[c].gap, s.t_ab);
  }
  if (t.back() >= s.t_ab * (1 - 1e-9)) {
    w.displacement_ab = 0;
    for (const auto& r : run.samples)
      if (r[0] <= s.t_ab * (1 + 1e-9)) w.displacement_ab = std::max(w.displacement_ab, r[r.size() - 2]);
  }
  for (const std::string& k : w.checks ? std::vector<std::string>{w.key, ""} : std::vector<std::string>{w.key}) {
    V["endothelium_displacement_um" + k] = displacement / units::um;
    V["completed" + k] = run.stopped.empty() ? 1.0 : 0.0;
  }
  st::record_run(results, id, run.progress(w.t_end));
  // The cost: time per step and the time to the seed's 100 ms at the mean step so far.
  // The time per step without the held wall's one-off mobilities (built once per rung).
  const double t_now = t.back(), mean_dt = run.steps > 0 ? t_now / double(run.steps) : s.dt;
  const double sps = run.steps_timed > 0 ? (run.seconds - w.setup_seconds) / double(run.steps_timed) : NAN;
  const double steps_100 = std::round(100 * ms / mean_dt);
  cost["rows"].push(row({id, 16.0 / s.cells_x, mean_dt / us, double(run.steps), run.seconds, w.setup_seconds, sps, steps_100, steps_100 * sps / 3600,
                         (w.t_end - t_now) / mean_dt * sps / 3600}));
  walls["rows"].push(row({w.label, t_now / ms, mean_dt / us, s.dt * (seed ? 1 : 16) / us, double(run.steps), sps, steps_100 * sps / 3600,
                          displacement / units::um, slip / units::um, p[0].min_gap / units::um, p[1].min_gap / units::um, p[0].tilt.back() * 180 / pi,
                          p[1].tilt.back() * 180 / pi, p[0].tilt_rate / p[0].jeffery_rate, p[1].tilt_rate / p[1].jeffery_rate}));
  for (int c = 0; c < 2; ++c) {  // the checks' run writes these without its key too (report)
    const std::string k = (c == 0 ? "_near" : "_far") + w.key;
    V["min_gap_um" + k] = p[c].min_gap / units::um;
    V["rate_over_jeffery" + k] = p[c].tilt_rate / p[c].jeffery_rate;
    V["volume_change" + k] = p[c].volume_change;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_platelets", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_platelets",
                                                   "Sec. 5.2: two platelets over a flat endothelium in shear 1000/s, wobbling and tumbling");
    const bool full = opt.scale == st::Scale::full;
    const double us = units::us, ms = units::ms;
    const Setup s = full ? Setup{80, 60, 900, 128, 50 * units::ns, 100 * ms, 2 * ms} : Setup{40, 30, 400, 64, 100 * units::ns, 0.3 * ms, 0.3 * ms};
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "16 x 12 x 16, periodic x and z, walls in y, the top one at 12 mm/s along z (shear 1000/s)";
    P["fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's code; Sec. 2.1 says 0.1 cP)";
    P["h_um"] = 16.0 / s.cells_x;
    P["platelet_sites"] = s.sites;
    P["endothelium"] = to_text(s.endothelium) + " x " + to_text(s.endothelium) + " tethered points at y = 1 um, k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm";
    P["gaps_um"] = Json::Array{Json(gaps_um[0]), Json(gaps_um[1])};
    P["walls"] = "run platelets_tether_rule (the checks' run, to t_end): the endothelium with k and eta following the step (the seed's rule "
                 "at gain 0.5); run platelets (to t_ab_ms): the seed's endothelium at its fixed step; run platelets_grid_wall (to t_ab_ms): no "
                 "endothelium, the grid's no-slip wall at y = 0 with the platelets at the same gaps above it and the top wall at 12 mm/s x 12/11 "
                 "(the same shear above the wall, 1091/s); run platelets_held_wall (to t_ab_ms): the endothelium's plane held exactly by a "
                 "solve, " + to_text(s.cells_x / 2) + " x " + to_text(s.cells_x / 2) + " markers 2h apart; all but the seed's tethers on the "
                 "seed's ladder dt = 2^k x " + to_text(s.dt / us) + " us, k = 0..4, by eq. 5.4";
    P["dt_us"] = s.dt / us;
    P["t_end_ms"] = s.t_end / ms;
    P["t_ab_ms"] = s.t_ab / ms;
    P["kernel_integrator_coupling"] = "B3 kernel, backward-forward Euler, the seed's coupling (a)-(g)";

    // The seed's endothelium at its fixed step and the grid's wall over the A/B window, the tethers
    // following the step (the checks' run) to the end; side by side in the tables wall_treatments
    // and wall_ab.
    const Json series = st::table({"gap_um", "t_ms", "strain", "tilt_deg", "jeffery_tilt_deg", "gap_now_um", "height_um"}, {"um", "ms", "", "deg", "deg", "um", "um"});
    const Json summary = st::table({"gap_um", "min_gap_um", "tilt_end_deg", "tilt_rate_over_gdot", "jeffery_rate_over_gdot", "rate_over_jeffery", "flips",
                                    "flip_frequency_1_s", "edge_on_ms", "tumble_frequency_1_s", "edge_on_ms_per_tumble", "wobble_frequency_1_s", "volume_change_rel"},
                                   {"um", "um", "deg", "", "", "", "", "1/s", "ms", "1/s", "ms", "1/s", ""});
    Json walls = st::table({"wall", "t_ms", "dt_mean_us", "dt_top_us", "steps", "seconds_per_step", "hours_to_100ms", "wall_displacement_um",
                            "slip_rms_end_um_s", "min_gap_um_near", "min_gap_um_far", "tilt_end_deg_near", "tilt_end_deg_far",
                            "rate_over_jeffery_near", "rate_over_jeffery_far"},
                           {"", "ms", "us", "us", "", "s", "h", "um", "um/s", "um", "um", "deg", "deg", "", ""});
    Json cost = st::table({"wall", "h_um", "dt_us", "steps", "seconds", "setup_seconds", "seconds_per_step", "steps_to_100ms", "hours_to_100ms", "hours_to_go"},
                          {"", "um", "us", "", "s", "s", "s", "", "h", "h"});
    WallRun runs[4] = {{Wall::tethers, "", "_tethers", "tethers (k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm)", 1, false, s.t_ab, series, summary},
                       {Wall::grid, "_grid_wall", "_grid_wall", "grid wall", 1, false, s.t_ab, series, summary},
                       {Wall::held, "_held_wall", "_held_wall", "held wall (markers 2h apart, solved)", 1, false, s.t_ab, series, summary},
                       {Wall::rule, "_tether_rule", "_tether_rule", "tethers following the step (gain 0.5)", 1, true, s.t_end, series, summary}};
    // A sitting is shared equally among the runs that have not ended, taken in turn: each gets what
    // is left over the number still to go (a run kept ended takes no time).
    if (opt.keeps_runs()) {
      int to_go = 0;
      for (int i = 3; i >= 0; --i) {
        if (!st::scene_run_ended(scene_text(runs[i], s), "platelets" + runs[i].suffix, opt)) ++to_go;
        runs[i].share = std::max(1, to_go);
      }
    }
    const st::Sitting sitting(opt);
    for (WallRun& w : runs) run_wall(w, s, sitting, opt, results, walls, cost);
    // The A/B at the window's end: each wall against the seed's tethers at their fixed step.
    Json ab = st::table({"wall", "t_ms", "tilt_deg_near", "tilt_deg_far", "tilt_minus_seed_deg_near", "tilt_minus_seed_deg_far", "gap_um_near",
                         "gap_um_far", "gap_minus_seed_um_near", "gap_minus_seed_um_far", "wall_displacement_um"},
                        {"", "ms", "deg", "deg", "deg", "deg", "um", "um", "um", "um", "um"});
    const WallRun& seed = runs[0];
    for (const WallRun& w : runs) {
      const double deg = 180 / pi, um = units::um;
      ab["rows"].push(row({w.label, s.t_ab / ms, st::number(w.tilt_ab[0] * deg), st::number(w.tilt_ab[1] * deg),
                           st::number((w.tilt_ab[0] - seed.tilt_ab[0]) * deg), st::number((w.tilt_ab[1] - seed.tilt_ab[1]) * deg),
                           st::number(w.gap_ab[0] / um), st::number(w.gap_ab[1] / um), st::number((w.gap_ab[0] - seed.gap_ab[0]) / um),
                           st::number((w.gap_ab[1] - seed.gap_ab[1]) / um), st::number(w.displacement_ab / um)}));
    }
    results["tables"]["wall_ab"] = ab;
    for (const WallRun& w : runs) {
      results["tables"]["platelets" + w.suffix] = w.series;
      results["tables"]["summary" + w.suffix] = w.summary;
    }
    results["tables"]["wall_treatments"] = walls;
    results["tables"]["cost"] = cost;
    st::write_results(opt, results);
    return 0;
  });
}
