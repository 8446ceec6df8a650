// Reproduces seed Sec. 5.1.3, Fig. 5.3: collision tests. Two red cells (the red_cell preset, Sec.
// 2.2) in the 16 um box with walls at rest in y (periodic in x and z), fluid at rest; Peskin's
// two-stage scheme, the 4-point cosine kernel; centres on the line x = z, y = 8 um, the gap between
// the cells' convex hulls 4h along d = (e1 + e3)/sqrt 2; each cell pushed toward the other by
// F_fict, the seed's 0.1 dyn/cm over the public code's unit of length (10 um): 100 dyn/cm^2 per
// unit reference area (eq. 2.24), 1.3419e-4 dyn per cell (derivation: reference/chapter5_collision.yaml).
// Orientations (Fig. 5.3): a-b concavities facing (both axes along d); c-d edges facing (both axes
// along e2); e-f the edge of cell 2 facing the concavity of cell 1; g-h as c-d with cell 2 turned by
// pi/2 about e1 + e3. mu = 1 cP (the seed's public drivers; Sec. 2.1's 0.1 cP a full-scale variant).
// Quick: h = 0.5 um (n_d = 400, n_s = 1,600: the seed's n h^2), dt = 100 ns, to 60 us. Full: to 10 ms
// or eq. 5.4's stop, h = 0.5 um at 1 and 0.1 cP, then the seed's h = 0.2 um (2,500 / 10,000), on the
// seed's adaptive ladder dt = 2^k x 50 ns up to 800 ns.
// Measured: the minimum distance between the cells' sample sites, the centroids' approach, volumes,
// max |u|, dt over eq. 5.4's bound; outlines seen from above the plane x = z and each cell's depth
// over width (a hemisphere facing the other cell: 1/2) at t = 0, mid-run (full: the figure's time)
// and the end; eq. 5.4's stop; time per step. Each run keeps DIR/<setup>/<orientation>/ (scene.yaml,
// the series as CSV; at full scale and with --resumable a checkpoint, every 1000 steps at h = 0.5 um,
// 200 at h = 0.2 um and at a sitting's end, from which the same command continues).
//
// Run:   build/studies/study_chapter5_collision --scale quick --out runs/chapter5_collision/quick
//        build/studies/study_chapter5_collision --scale full --sitting 3600 --out runs/chapter5_collision/full
#include "common/study.hpp"
#include "measures.hpp"
#include "rbfib/cells/batch.hpp"
#include "rbfib/cells/measure.hpp"
#include "rbfib/cells/reference_geometry.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/run/run.hpp"
#include "rbfib/scene/scene.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;
using st::row;
using namespace rbfib::collision;

namespace {

const double kFict = 0.1 / (1e-3 * units::cm);  // dyn/cm^2: 0.1 dyn/cm over the code's 10 um (header)
const cells::ReferenceShape kCell = cells::evans_fung_red_cell(3.91 * units::um);  // R0 of Sec. 2.2
const double A0 = cells::evans_fung_area(3.91 * units::um);                       // its area (cm^2)

std::string fmt(double v, const char* f = "%.4g") {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::vector<Orientation> orientations() {
  const Pose along_d{{0, 1, 0}, pi / 4};  // e3 -> d
  const Pose along_y{{1, 0, 0}, pi / 2};  // e3 -> -e2
  const Pose turned = axis_angle(product(rotation_matrix(kLine, pi / 2), rotation_matrix(along_y)));  // turned by pi/2 about d
  return {{"a-b", "concavities facing", {along_d, along_d}, 1.5},
          {"c-d", "edges facing", {along_y, along_y}, 1.1},
          {"e-f", "edge facing a concavity", {along_d, along_y}, 1.5},
          {"g-h", "edges facing, one turned by pi/2 about e1 + e3", {along_y, turned}, 1.1}};
}

/// The run's scene (docs/scenes.md). Centres on the line x = z, y = 8 um with the planes supporting
/// the two hulls normal to d 4h apart, the gap centred on the box centre (for these orientations,
/// the gap between the hulls); each cell pushed into the gap by `force` (dyn).
scene::Scene collision_scene(const Orientation& o, const Setup& s, double force) {
  scene::Scene sc;
  sc.name = "collision_" + o.id;
  sc.grid.length = {kBox, kBox, kBox};
  const int n = int(std::lround(kBox / s.h));
  sc.grid.cells = {n, n, n};
  sc.grid.lower[1] = sc.grid.upper[1] = MacBoundary::dirichlet;  // walls at rest across y
  sc.fluid = {1, s.mu};                                           // g/cm^3, P
  sc.fluid_options.integrator = TimeIntegrator::peskin_two_stage;
  sc.fluid_options.dt = s.dt;
  sc.t_end = s.t_end;
  if (s.ladder > 0) sc.ib.adaptive = {true, s.dt, s.ladder, 16};
  sc.ib.kernel = ib::Kernel::cosine4;
  sc.types = {scene::cell_type("red cell", "red_cell", s.n_data, s.n_sample)};
  for (int c = 0; c < 2; ++c) {
    const double sign = c == 0 ? 1 : -1;  // toward the gap
    const double support = cells::support(kCell, rotation_matrix(o.pose[c]), {sign * kLine[0], sign * kLine[1], sign * kLine[2]});
    Vec3 center;
    for (int a = 0; a < 3; ++a) center[a] = kBox / 2 - sign * (2 * s.h + support) * kLine[a];
    sc.cells.push_back({"red cell", {center, o.pose[c].axis, o.pose[c].angle}, {sign * force * kLine[0], 0, sign * force * kLine[2]}});
  }
  return sc;
}

/// One orientation's run at one setup through the run loop, in DIR/<setup>/<orientation>/; a
/// resumable run keeps its checkpoint and steps while the sitting has time.
Outcome run_orientation(const Orientation& o, const Setup& s, double figure_time, int figure, const st::Options& opt,
                        const st::Sitting& sitting) {
  const std::string dir = opt.out_dir + "/" + s.label + "/" + o.id, who = s.label + " " + o.id, checkpoint = dir + "/checkpoint.h5";
  const bool resumable = s.checkpoint_every > 0, saved = resumable && std::filesystem::exists(checkpoint);
  if (!resumable) std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string text = scene::to_yaml(collision_scene(o, s, kFict * A0),
                                          "chapter5_collision: two red cells pushed together, Fig. 5.3 (" + o.id + ": " + o.what + ")");
  std::ofstream(dir + "/scene.yaml") << text;
  if (saved && io::read_checkpoint_header(checkpoint).scene_yaml != text)
    throw InputError(checkpoint, "its scene", "differs from this driver's scene for " + who + ": remove " + dir + " to start afresh");
  if (resumable && !saved && sitting.remaining() <= 0) {
    st::log(opt, who + ": not begun (this sitting's time is spent)");
    return {};
  }
  run::Options ro;
  ro.t_end = s.t_end;
  ro.ended_keeps_fluid = false;  // an ended run never steps again: its checkpoint keeps cells, series and clock
  if (resumable) ro.checkpoint = checkpoint, ro.sitting = std::max(0.0, sitting.remaining());
  ro.checkpoint_every = {s.checkpoint_every, 0, 0};
  ro.sample_every = {s.measure_every, 0, 0};
  ro.progress_every = {0, 0, 300};
  sim::IbStepReport last;  // the last step's report (max |u|, eq. 5.4's ratio)
  auto take = [&](const sim::ImmersedBoundary& ib, run::SeriesSet& series, int moment) {  // a sample (one a step) and the state
    const Sites at = sites(ib);
    std::vector<std::vector<double>>& rows = series["samples"].rows;
    if (rows.empty() || std::lround(rows.back().at(kStep)) != ib.step_count()) rows.push_back(sample(ib, at, last));
    record_state(series, ib.time(), at, moment, s.h);
  };
  run::Hooks hk;
  hk.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport* rep, run::SeriesSet& series) {
    if (rep) {
      series["samples"].rows.push_back(sample(ib, sites(ib), *rep));
    } else {  // t = 0: the reference and the starting state
      series["reference"].rows.push_back({ib.batch(0).type().reference_volume(), ib.batch(0).type().reference_area()});
      take(ib, series, kStart);
    }
  };
  bool figure_taken = figure_time >= s.t_end * (1 - 1e-12);  // at the end: the end's state is taken anyway
  hk.after_step = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport* rep, run::SeriesSet& series) {
    if (!rep) return;
    last = *rep;
    if (figure_taken || ib.time() < figure_time * (1 - 1e-12)) return;
    figure_taken = true;
    take(ib, series, figure);
  };
  hk.progress = [&](const run::Progress& q) { st::log(opt, who + ": " + q.describe()); };
  run::Run runner(text, dir + "/scene.yaml", ro, hk);
  const bool ended_before = runner.progress().ended();
  for (const std::vector<double>& r : runner.series("shapes").rows) figure_taken = figure_taken || r.at(1) == figure;  // continued
  st::log(opt, who + (runner.continued() ? ": continuing from step " + to_text(runner.ib().step_count())
                                         : " (" + o.what + "): nearest sample sites " + fmt(runner.series("samples").rows.front().at(kGap) / units::um) + " um"));
  const run::Progress q = runner.evolve();
  if (q.ended() && !ended_before) {  // the final state (the last good one when stopped)
    take(runner.ib(), runner.series(), kEnd);
    runner.checkpoint();
  }
  write_csv(dir, runner.series());
  st::log(opt, who + ": " + status(q) + " at step " + to_text(q.clock.step) + ", t = " + fmt(q.clock.t / units::us) + " us");
  return {q, runner.series()};
}

/// The parameters, echoed in the results.
void describe(Json& P, const std::vector<Setup>& setups, double sitting_seconds) {
  P["box_um"] = "16 x 16 x 16; walls at rest in y, periodic in x and z; fluid at rest initially";
  P["fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's public drivers; Sec. 2.1 says 0.1 cP: the variant h0.5_mu0.1 at full scale)";
  P["cells"] = "two red cells, the red_cell preset (Sec. 2.2: Skalak E = 2.5e-3, G = 2.5e-1 dyn/cm; kappa = 2e-12 erg; nu = 2.5e-7 dyn s/cm)";
  P["scheme"] = "Peskin's two-stage scheme, the seed's coupling (a)-(g), the 4-point cosine kernel, eq. 5.4 checked every step";
  for (const Setup& s : setups)
    P["setup_" + s.label] = "h = " + fmt(s.h / units::um) + " um, n_d = " + to_text(s.n_data) + ", n_s = " + to_text(s.n_sample) +
                            ", dt = " + (s.ladder > 0 ? "2^k x " + fmt(s.dt / units::ns) + " ns (k = 0.." + to_text(s.ladder) + " by eq. 5.4, the seed's adaptive step)"
                                                      : fmt(s.dt / units::ns) + " ns") + ", mu = " + fmt(s.mu / units::cP) + " cP, to " +
                            fmt(s.t_end / units::us) + " us or eq. 5.4; sampled every " + to_text(s.measure_every) +
                            " steps; eq. 5.4 stops a run when ||f||_inf > " + fmt(s.h * 1.0 / (16 * s.dt * s.dt), "%.3g") + " dyn/cm^3" +
                            (s.ladder > 0 ? " (at the lowest rung; above it the step is retaken a rung lower)" : "");
  P["initial_hull_gap"] = "4h along d = (e1 + e3)/sqrt 2, centres on x = z, y = 8 um, the gap centred on the box centre";
  P["fictitious_force_density_dyn_cm2"] = kFict;
  P["fictitious_force_per_cell_dyn"] = kFict * A0;
  P["reference_area_um2"] = A0 / (units::um * units::um);
  if (std::isfinite(sitting_seconds)) P["sitting_seconds"] = sitting_seconds;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_collision", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_collision",
                                                   "Sec. 5.1.3, Fig. 5.3: two red cells pushed together in four orientations");
    const bool full = opt.scale == st::Scale::full;

    // ---- 1. Parameters -----------------------------------------------------------------------
    // Quick: h = 0.5 um to 60 us at a fixed 100 ns. Full: each run to the public driver's 10 ms or
    // until eq. 5.4 stops it, on the seed's adaptive ladder (50 ns to 800 ns; eq. 5.4 stops a run
    // when even 50 ns breaks it): h = 0.5 um at 1 cP, the text's 0.1 cP at h = 0.5 um, then the
    // seed's h = 0.2 um (resumable over sittings).
    const double t_end = full ? 10 * units::ms : 60 * units::us;
    const Setup coarse = full ? Setup{"h0.5", 0.5 * units::um, 50 * units::ns, t_end, 1 * units::cP, 400, 1600, 10, 1000, 4}
                              : Setup{"h0.5", 0.5 * units::um, 100 * units::ns, t_end, 1 * units::cP, 400, 1600, 10, opt.keeps_runs() ? 1000 : 0};
    const Setup text_viscosity{"h0.5_mu0.1", 0.5 * units::um, 50 * units::ns, t_end, 0.1 * units::cP, 400, 1600, 10, 1000, 4};
    const Setup seed{"h0.2", 0.2 * units::um, 50 * units::ns, t_end, 1 * units::cP, 2500, 10000, 20, 200, 4};
    std::vector<Setup> setups = {coarse};
    if (full) setups.insert(setups.end(), {text_viscosity, seed});
    const std::string own = full ? seed.label : coarse.label;  // the scale's own resolution, for the time per step
    const st::Sitting sitting(opt);  // full scale: the wall time of this sitting (--sitting)
    Json results = st::make_results(opt);
    describe(results["parameters"], setups, full ? sitting.remaining() : INFINITY);

    // ---- 2. One run per setup and orientation -------------------------------------------------
    Tables T;
    for (const Orientation& o : orientations()) T.fig_rows.push_back({Json(o.id), Json(o.what), Json(o.t_figure_ms)});
    for (const Setup& s : setups) {
      std::size_t k = 0;
      for (const Orientation& o : orientations()) {
        const Outcome r = full ? run_orientation(o, s, o.t_figure_ms * units::ms, kFigure, opt, sitting)
                               : run_orientation(o, s, s.t_end / 2, kMid, opt, sitting);
        tabulate(T, results, s, o, k++, r, full, s.label == own);
      }
    }

    // ---- 3. Results ------------------------------------------------------------------------------
    Json& V = results["values"];
    V["max_eq54_ratio"] = T.peak54;  // dt over eq. 5.4's bound: 1 stops a run
    V["runs_ended"] = T.ended;
    V["seconds_per_step"] = st::median(T.per_step);  // at the scale's own resolution (full: the seed's)
    V["hours_to_go"] = T.hours_to_go;               // to 10 ms at most; a stop by eq. 5.4 comes sooner
    Json& tables = results["tables"];
    tables["runs"] = T.runs, tables["gap_series"] = T.gap_series, tables["fig53"] = T.fig53(setups);
    tables["outlines"] = T.outlines, tables["shapes"] = T.shapes;
    st::write_results(opt, results);
    return 0;
  });
}
