#include "procedure.hpp"

#include "rbfib/cells/presets.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/io/snapshot.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <memory>
#include <sstream>

namespace rbfib::whole_blood {

namespace {
const double um = units::um, ms = units::ms, us = units::us;

/// A number for a log line: ten significant digits (0.4, not 0.40000000000000002).
std::string num(double x) {
  std::ostringstream o;
  o.precision(10);
  o << x;
  return o.str();
}
std::string um_text(double x) { return num(x / um) + " um"; }

/// The scene of the init run or of a run from a starting state (docs/scenes.md): the box of
/// Sec. 5.2.1, its upper wall at 16 mm/s turning from z toward x by 45 degrees, the endothelium
/// of eq. 5.5 as tethered points; a run from a starting state keeps the start's red cells (or
/// none) and adds the platelets.
scene::Scene whole_blood_scene(const Setup& s, const Wall& w, const std::vector<cells::Placement>& red,
                               const std::vector<cells::Placement>& platelets, double t_end, const scene::Start& start = {}) {
  scene::Scene sc;
  sc.name = "whole_blood_" + w.name;
  sc.grid.dims = 3;
  sc.grid.length = {16 * um, 12 * um, 16 * um};
  for (int d = 0; d < 3; ++d) {
    sc.grid.cells[d] = int(std::lround(sc.grid.length[d] / s.h));
    sc.grid.lower[d] = sc.grid.upper[d] = d == 1 ? MacBoundary::dirichlet : MacBoundary::periodic;
  }
  scene::WallMotion& top = sc.walls[1][1];
  top.turning = true;
  top.speed = 16 * units::mm;
  top.to = 45 * (pi / 180);
  top.over = s.turn;
  sc.fluid.density = 1;
  sc.fluid.viscosity = 1 * units::cP;
  sc.fluid_options.integrator = TimeIntegrator::backward_forward_euler;
  sc.fluid_options.dt = s.dt;
  sc.t_end = t_end;
  if (s.ladder > 0) sc.ib.adaptive = {true, s.dt, s.ladder, 16, INFINITY};
  sc.ib.kernel = ib::Kernel::bspline3;
  sc.start = start;
  const bool red_type = !red.empty() || !start.keep.empty();
  if (red_type) sc.types.push_back(scene::cell_type("red cell", "red_cell", s.rbc_nd, s.rbc_ns));
  if (!platelets.empty()) sc.types.push_back(scene::cell_type("platelet", "platelet", s.plt_n, s.plt_n));
  for (const cells::Placement& p : red) sc.cells.push_back({"red cell", p, {0, 0, 0}});
  for (const cells::Placement& p : platelets) sc.cells.push_back({"platelet", p, {0, 0, 0}});
  if (s.tether_gain > 0)
    sc.point_sets.push_back({"endothelium", {true, 1, w.y0, {0, 0}, s.endothelium, w.bump}, 0, 0, s.tether_gain});
  else
    sc.point_sets.push_back({"endothelium", {true, 1, w.y0, {0, 0}, s.endothelium, w.bump}, 2.5, 2.5e-7});
  return sc;
}

std::string run_tag(const Wall& w, bool with_red, std::size_t k) { return w.name + (with_red ? "" : "_no_red_cells") + "_" + to_text(k); }

/// Seconds per step of a scene from rest: the median of `steps` steps after a first one (which
/// sizes the workspaces). The price of the runs without red cells before they begin: their sets
/// (platelets, the endothelium) cost a fraction of the red cells' step.
double probe_seconds_per_step(const scene::Scene& sc, int steps) {
  sim::ImmersedBoundary ib = scene::build(sc);
  ib.step();
  std::vector<double> t;
  for (int k = 0; k < steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    ib.step();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return median(t);
}


}  // namespace

void WholeBlood::wall(const Wall& w, std::size_t wi) {
  const Domain box{Lx, Ly, Lz, scene::EndotheliumSurface{w.y0, w.bump, Lx, Lz}};
  std::mt19937_64 rng(seed + wi);
  LayoutSpec ls;
  ls.h = s.h;
  const Layout layout = red_cell_layout(rbc, box, ls, rng);
  std::vector<double> starts = starting_times(s.settle, s.mean_gap, s.starts, rng);
  std::vector<long> start_steps;
  std::string start_list;  // ms
  for (double& t : starts) {
    start_steps.push_back(std::lround(t / s.dt)), t = double(start_steps.back()) * s.dt;
    start_list += to_text(t / ms) + " ";
  }
  start_list.pop_back();
  st::log(opt, w.name + ": red cells moved " + to_text(layout.moved) + " of 8 in " + to_text(layout.draws) + " draws, closest " +
                   um_text(layout.closest) + "; starting times (ms): " + start_list);
  const double window = w.bump > 0 ? s.window : s.flat_window;
  PlateletSpec ps;
  ps.min_separation = 3.1 * um + 4 * s.h;
  // ---- init: endothelium and red cells, the wall turning ------------------------------------------
  const scene::Scene init_scene = whole_blood_scene(s, w, layout.red_cells, {}, starts.back());
  const std::string init_text = scene::to_yaml(init_scene, "chapter5_whole_blood: init (Sec. 5.2.1), " + w.name + " endothelium");
  // An example for `rbfib run`: the same layout with platelets placed against it, the flow from rest, 40 us.
  std::mt19937_64 erng(seed + 50 + wi);
  const PlateletPlacement ex = place_platelets(plt, box, scene::point_positions(init_scene.point_sets.at(0).surface, init_scene.grid.length),
                                               batch_layout(rbc, layout.red_cells), rbc.n, 2, ps, erng);
  {
    scene::Scene example = whole_blood_scene(s, w, layout.red_cells, ex.platelets, 40 * us);
    example.diagnostics_every = 10;
    example.snapshot_every = 10 * us;
    std::ofstream(opt.out_dir + "/example_" + w.name + ".yaml")
        << scene::to_yaml(example, "chapter5_whole_blood: an example: the layout of the procedure with platelets placed against it (Sec. 5.2.1), " +
                                       w.name + " endothelium");
  }
  st::SceneRunHooks ih;
  ih.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r) {
    const cells::Batch& R = ib.batch(0);
    const auto& vol = ib.diagnostics(0).volume;
    return std::vector<double>{ib.time(), r ? r->max_velocity : 0.0, closest_cells(R.positions_host(), R.type().n_data(), R.size(), box),
                               vol.empty() ? NAN : vol[0] / std::pow(um, 3)};
  };
  const std::string start_file = opt.out_dir + "/start_" + w.name + "_";
  ih.record = [&](const sim::ImmersedBoundary& ib, run::SeriesSet& series) {  // at the first step reaching each starting time (ticks of dt)
    for (std::size_t k = 0; k < starts.size(); ++k)
      if (std::lround(ib.time() / s.dt) >= start_steps[k] && !series.count("start_" + to_text(k))) {
        io::write_checkpoint(start_file + to_text(k) + ".h5", init_text, ib);
        series["start_" + to_text(k)].rows = {{ib.time()}};
      }
  };
  ih.at_start = [&](const sim::ImmersedBoundary& ib) { measures.v_ref = ib.batch(0).type().reference_volume() / std::pow(um, 3); };
  const st::SceneRun init = st::run_scene(init_text, "init_" + w.name, s.samples(), opt.keeps_runs(), opt, ih,
                                             sitting.remaining() / double(s.walls.size() - wi));  // shared by the inits to come
  st::record_run(results, "init_" + w.name, init.progress(starts.back()));
  // Steps needed at the mean step so far (the ladder's), or at dt.
  const double init_t = init.samples.empty() ? 0 : init.samples.back().at(0), mean_dt = init.steps > 0 ? init_t / double(init.steps) : s.dt;
  add_cost("init " + w.name, double(init.steps), s.ladder > 0 ? std::round(starts.back() / mean_dt) : double(std::lround(starts.back() / s.dt)),
           init.seconds_per_step(), init.steps > 0 ? "its own steps" : "not begun");
  if (!init.stopped.empty()) throw NumericalError(Cause::solver, "the init run (" + w.name + ") stopped: " + init.stopped);
  for (const auto& r : init.samples) measures.closest_red = std::min(measures.closest_red, r[2] / s.h);
  if (!init.finished) {
    done.inits = done.red_runs = false;
    (w.bump > 0 ? done.free_runs : done.flat_runs) = false;
    // The runs from its starting states are still to come. With red cells: the init's sets and two
    // platelets, at the init's seconds per step and mean step. Without them (the bumpy wall's): at
    // the seconds per step of a probe of their own sets (the platelets and the endothelium, from
    // rest), and the init's mean step (their own, platelet-held, is not known before they run).
    const double free_step = w.bump > 0 ? probe_seconds_per_step(whole_blood_scene(s, w, {}, ex.platelets, 40 * us), 5) : NAN;
    for (std::size_t k = 0; k < starts.size(); ++k)
      for (bool with_red : {true, false})
        if (with_red || w.bump > 0) {  // the seed removes the red cells over the bumpy wall only
          const double sps = with_red ? init.seconds_per_step() : free_step;
          add_cost(run_tag(w, with_red, k) + " (to come)", 0, std::round(window / mean_dt), sps,
                   with_red ? "the init's s per step and mean step" : "a probe of 5 steps of its sets from rest; the init's mean step");
          st::record_run(results, run_tag(w, with_red, k), st::RunProgress{false, 0, window, 0, sps, ""});
        }
    st::log(opt, w.name + ": init run at t = " + to_text(init_t / ms) + " ms of " + to_text(starts.back() / ms) +
                     " ms; continued at the next start");
    return;
  }
  // ---- runs from each starting state ---------------------------------------------------------------
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const io::Checkpoint start = io::read_checkpoint(start_file + to_text(k) + ".h5");
    std::vector<double> red = host(start.state.batches.at(0));
    red.resize(std::size_t(3 * red_count * rbc.n));  // X, the first 3N columns of the n x 6N state
    const std::vector<index_t> tracked = tracked_sites(red, rbc.n, red_count);
    std::mt19937_64 prng(seed + 100 * (wi + 1) + k);
    const PlateletPlacement placed = place_platelets(plt, box, host(start.state.points.at(0)), red, rbc.n, 2, ps, prng);
    for (int a : placed.attempts) attempts.push_back(double(a));
    refused_red += placed.refused_red_cells, refused_surface += placed.refused_surface;
    procedure["rows"].push(row({w.name + " start " + to_text(k), double(layout.moved), double(layout.draws), layout.closest / um, double(placed.draws),
                                double(placed.attempts.at(0)), double(placed.attempts.at(1)), double(placed.refused_red_cells),
                                double(placed.refused_surface), placed.gaps[0] / um, placed.gaps[1] / um, start_list}));
    for (bool with_red : {true, false})
      if (with_red || w.bump > 0)  // with the ladder the start lies at the first step reaching its time
        run_from(w, box, k, with_red, s.ladder > 0 ? start.state.clock.t : starts[k], start_file + to_text(k) + ".h5", start, placed.platelets, tracked);
  }
}

void WholeBlood::run_from(const Wall& w, const Domain& box, std::size_t k, bool with_red, double t_start, const std::string& start_file,
                          const io::Checkpoint& start, const std::vector<cells::Placement>& platelets, const std::vector<index_t>& tracked) {
  const std::string tag = run_tag(w, with_red, k);
  const double window = w.bump > 0 ? s.window : s.flat_window, t_end = t_start + window;
  // The start's fluid, clock and endothelium, its red cells (or none), the platelets added.
  scene::Start from{start_file, with_red ? std::vector<std::string>{"red cell"} : std::vector<std::string>{}};
  const std::string text = scene::to_yaml(whole_blood_scene(s, w, {}, platelets, t_end, from),
                                          "chapter5_whole_blood: a run from a starting state (Sec. 5.2.1), " + w.name + " endothelium");
  st::SceneRunHooks h;
  h.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport*) { return sample(ib, with_red, box, tracked); };
  // Snapshots for ParaView (the first starting state's runs): at the start, every tenth of the run, at the end.
  std::unique_ptr<io::SnapshotWriter> writer;
  long last_snapshot = -1;
  const long snapshot_every = std::max(1L, std::lround(window / s.dt) / 10);  // in ticks of dt from the start
  const long start_tick = std::lround(t_start / s.dt);
  if (k == 0)
    h.after_step = [&](const sim::ImmersedBoundary& ib) {
      const long ticks = std::lround(ib.time() / s.dt) - start_tick;  // a snapshot at the first step of each tenth
      if (!writer) {  // continued: the tenths before this step are written
        writer = std::make_unique<io::SnapshotWriter>(opt.out_dir + "/snapshots_" + tag, ib), writer->resume(ib.time());
        last_snapshot = ticks > 0 ? (ticks - 1) / snapshot_every : -1;
      }
      if (ticks / snapshot_every != last_snapshot) last_snapshot = ticks / snapshot_every, writer->write(ib);
    };
  const st::SceneRun run = st::run_scene(text, tag, s.samples(), opt.keeps_runs(), opt, h, sitting.remaining());
  const long steps = run.steps - start.state.clock.step;  // the run's own span: steps from its starting time
  st::RunProgress progress = run.progress(t_end);
  progress.t -= t_start, progress.t_end = window, progress.steps = steps;
  st::record_run(results, tag, progress);
  const double mean_dt = steps > 0 ? progress.t / double(steps) : s.dt;  // the ladder's mean step so far, or dt
  add_cost(tag, double(steps), s.ladder > 0 ? std::round(window / mean_dt) : double(std::lround(window / s.dt)), run.seconds_per_step(),
           steps > 0 ? "its own steps" : "not begun");
  if (!run.finished) {
    (with_red ? done.red_runs : done.free_runs) = false;
    if (with_red && w.bump == 0) done.flat_runs = false;
    return;
  }
  if (!run.stopped.empty()) throw NumericalError(Cause::solver, "run " + tag + " stopped: " + run.stopped);
  runs["rows"].push(measures.analyse(tag, w.bump == 0, with_red, run.samples, {tag, t_start / ms, t_end / ms, double(steps), run.seconds_per_step()}, opt));
  if (k > 0 || !with_red) return;
  measures.side_view(host(run.final_points.at(0)), run.final_positions, rbc.n, plt.n, Lz);
}

void WholeBlood::summarize() {
  Json& V = results["values"];
  V["hours_to_solution"] = hours_left;
  cost["rows"].push(row({"all", s.h / um, s.dt / units::ns, NAN, NAN, NAN, hours_left, ""}));
  const bool has_flat = std::any_of(s.walls.begin(), s.walls.end(), [](const Wall& w) { return w.bump == 0; });
  measures.values(V, done, has_flat);
  auto put = [&](const std::string& name, double value, bool runs_finished) { V[name] = runs_finished ? value : NAN; };
  double attempts_mean = 0;  // the platelet placement of Sec. 5.2.1, over every starting state
  for (double a : attempts) attempts_mean += a / double(attempts.size());
  put("platelet_attempts_median", st::median(attempts), done.inits);
  put("platelet_attempts_mean", attempts.empty() ? NAN : attempts_mean, done.inits);
  put("platelet_draws_refused_red_cells", double(refused_red), done.inits);
  put("platelet_draws_refused_surface_or_box", double(refused_surface), done.inits);
  // The hematocrit (conventions: hematocrit): 8 red cells of the reference volume over the fluid
  // above the endothelium (mean height 1 um for both shapes), and other readings for comparison.
  const double area = 16 * 16, above = 12 - 1.0, red_volume = red_count * measures.v_ref;  // um^2, um, um^3
  V["red_cell_volume_um3"] = measures.v_ref;
  for (auto [name, height] : {std::pair{"above_endothelium", above}, {"above_endothelium_without_top_1um", above - 1},
                              {"above_endothelium_without_top_2um", above - 2}, {"whole_box", 12.0}, {"above_3um", 9.0}, {"above_3um_below_10um", 7.0}})
    V[std::string("hematocrit_") + name] = red_volume / (area * height);  // heights in um
  V["hematocrit_exclusion_ratio_1um"] = above / (above - 1);
  V["hematocrit_exclusion_ratio_2um"] = above / (above - 2);
  V["red_volume_for_34_percent_um3"] = 0.34 * area * above;
  for (auto [name, table] : {std::pair{"profiles", &measures.profiles}, {"platelets", &measures.platelets}, {"runs", &runs},
                             {"tank_treading", &measures.treading}, {"procedure", &procedure}, {"snapshot", &measures.snapshot}, {"cost", &cost}})
    results["tables"][name] = *table;
}

}  // namespace rbfib::whole_blood
