// Reproduces dissertation Sec. 5.2 (Figs. 5.4-5.6): whole blood over a flat and a bumpy
// endothelium, and over the bumpy one without red cells. The 16 x 12 x 16 um box, periodic in x
// and z, walls in y; the endothelium (eq. 5.5) as points on the toroidal spiral of Appendix B
// tethered with k = 2.5 dyn/cm and damped with eta = 2.5e-7 dyn s/cm (Sec. 2.2); red cells (Skalak +
// bending + dissipation) and platelets (neo-Hookean + bending about the reference curvature);
// B3 kernel, backward-forward Euler, plasma of 1 cP (the seed's code: at the 0.1 cP of Sec. 2.1
// its endothelium is unstable at 50 ns, reference/chapter4_cells.yaml).
// The procedure of Sec. 5.2.1 (scene/packing.hpp), for each endothelium:
//   init:  the endothelium and 8 red cells, the flow at rest, the top wall at 16 mm/s turning from
//          z toward x by 45 deg over 7.2 ms, run past the settling time (17 ms) to the last starting
//          time (a Poisson process of mean gap 3 ms); its state at each is kept (start_<wall>_<k>.h5);
//   runs:  from each starting state, two platelets placed against the red cells there; the same
//          with the red cells removed (bumpy wall only).
// Measured per run: the x-z averaged velocity against y (Fig. 5.4) and the shear rate in the
// platelet layer (y = 1-4 um); per platelet its distance to the endothelium, unicycling (short axis
// within 45 deg of the vorticity; Fig. 5.5), its smallest surface speed and aspect-ratio change
// (Fig. 5.6); per red cell a tracked site's turning about its centre in the shear plane less its
// short axis's (tank-treading, Sec. 5.2.2); closest approaches; volumes; the hematocrit.
//   full:  the seed's sizes (h = 0.2 um, red cells 2,500 / 10,000 sites, platelets 900 / 900,
//          16,000 endothelium points, dt = 50 ns), 4 starting times, runs of 40 ms (bumpy) and
//          60 ms (flat: the seed's unicycling 'lasted over 40 ms'), continued over sittings;
//   quick: h = 0.4 um, 400 / 1,600 and 400 / 400 sites, 4,096 points, dt = 100 ns (the tethers'
//          explicit limit is about 128 ns here); the wall turns over 20 us, settles to 30 us, one
//          starting time, 80 us per run; the bumpy wall only.
#include "common/cell_shape.hpp"
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "rbfib/cells/measure.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/series.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/io/snapshot.hpp"
#include "rbfib/scene/packing.hpp"
#include "rbfib/sim/flow_profile.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

using namespace rbfib;
using namespace rbfib::scene;
namespace st = rbfib::study;
using st::Json;
using st::row;

namespace {
const double um = units::um, ms = units::ms, us = units::us;
const double Lx = 16 * um, Ly = 12 * um, Lz = 16 * um;
const double wall_speed = 1.6;  // cm/s: 16 mm/s (Sec. 5.2.1)
const Vec3 flow_dir{std::sin(pi / 4), 0, std::cos(pi / 4)}, vorticity_dir{std::cos(pi / 4), 0, -std::sin(pi / 4)};  // the wall's final direction
const unsigned long long seed = 5021;  // the procedure's random numbers
constexpr int red_count = 8;

struct Wall {
  std::string name;
  double y0, bump;  // eq. 5.5
};
const Wall flat{"flat", 1 * um, 0}, bumpy{"bumpy", 0.75 * um, 1 * um};

struct Setup {
  double h, dt;
  int rbc_nd, rbc_ns, plt_n;
  long endothelium;
  double turn, settle, mean_gap, window, flat_window;  // s; the runs' length over the bumpy and the flat wall
  int starts;
  std::vector<Wall> walls;
  int every;  // steps of dt between samples (with the ladder: that much simulated time)
  // > 0: the seed's adaptive step, dt = 2^k dt for k = 0..ladder by eq. 5.4, with the endothelium's
  // k and eta following the step by the seed's rule at this gain (sim/tether_stability.hpp).
  int ladder = 0;
  double tether_gain = 0;
  run::Cadence samples() const { return ladder > 0 ? run::Cadence{0, every * dt} : run::Cadence{every}; }
};

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

std::vector<double> host(const dvec& v) {
  const host_vector<double> h = v;
  return std::vector<double>(h.begin(), h.end());
}

/// The angle of a vector in the shear plane of the final flow: counterclockwise from flow_dir toward e2 (rad).
double shear_plane_angle(const Vec3& v) { return std::atan2(v[1], v[0] * flow_dir[0] + v[2] * flow_dir[2]); }

/// Cell c's site i less its centre (cm), from a batch's layout X (n x 3N).
Vec3 from_center(const std::vector<double>& X, index_t n, index_t N, index_t c, index_t i, const Vec3& center) {
  Vec3 d;
  for (int k = 0; k < 3; ++k) d[std::size_t(k)] = X[std::size_t((k * N + c) * n + i)] - center[std::size_t(k)];
  return d;
}

/// Per red cell, the data site tracked for its tank-treading: its rim in the shear plane.
std::vector<index_t> tracked_sites(const std::vector<double>& X, index_t n, index_t N) {
  std::vector<index_t> site(std::size_t(N), 0);
  for (index_t c = 0; c < N; ++c) {
    const st::CellShape shape = st::cell_shape(X, n, N, c);
    double best = -1;
    for (index_t i = 0; i < n; ++i) {
      const Vec3 d = from_center(X, n, N, c, i, shape.center);
      const double a = d[0] * flow_dir[0] + d[2] * flow_dir[2], q = a * a + d[1] * d[1];
      if (q > best) best = q, site[std::size_t(c)] = i;
    }
  }
  return site;
}

/// A sample's row: t; per platelet its centre, short axis and extents (3 each), then the columns
/// below; the closest red cells and platelet-red cell (cm), the red cells' least and largest
/// volume (um^3); per red cell the angles of its tracked site and of its short axis in the shear
/// plane; the velocity profile along flow_dir (cm/s). NaN for red cells' columns without them.
namespace col {
enum { distance = 9, clearance, min_speed, volume, headroom, per_platelet };
}
const std::size_t red_at = 1 + 2 * col::per_platelet, material_at = red_at + 4, axis_at = material_at + red_count, profile_at = axis_at + red_count;

std::vector<double> sample(const sim::ImmersedBoundary& ib, bool red, const Domain& box, const std::vector<index_t>& tracked) {
  std::vector<double> row{ib.time()}, R(4 + 2 * red_count, NAN);
  const cells::Batch& P = ib.batch(red ? 1 : 0);
  const index_t n = P.type().n_data(), N = P.size();
  const std::vector<double> S = P.state().to_host(), E = host(ib.points(0).X);  // S: n x 6N, X then U
  const std::vector<double> X(S.begin(), S.begin() + long(3 * N * n)), XR = red ? ib.batch(0).positions_host() : std::vector<double>{};
  const index_t nr = red ? ib.batch(0).type().n_data() : 0, Nr = red ? ib.batch(0).size() : 0;
  if (red) R[1] = INFINITY;
  for (index_t c = 0; c < 2; ++c) {
    const st::CellShape shape = st::cell_shape(X, n, N, c);
    const std::vector<double> Y = cells::cell_points(X, n, N, c);
    if (red) R[1] = std::min(R[1], distance_to_red_cells(Y, n, XR, nr, box));
    double lowest = INFINITY, slowest = INFINITY, top = INFINITY;  // clearance, min speed, headroom
    for (index_t i = 0; i < n; ++i) {
      lowest = std::min(lowest, Y[std::size_t(n + i)] - box.endothelium.height(Y[std::size_t(i)], Y[std::size_t(2 * n + i)]));
      double v2 = 0;
      for (int d = 0; d < 3; ++d) v2 += std::pow(S[std::size_t((3 * N + d * N + c) * n + i)], 2);
      slowest = std::min(slowest, std::sqrt(v2));
    }
    // Headroom: the lowest red-cell site over the platelet (within its radius across the flow
    // plane) above its centre; negative when a red cell has come between it and the wall.
    const std::size_t m = XR.size() / 3;
    const double radius = 1.55 * um;
    for (std::size_t i = 0; i < m; ++i) {
      const double dx = std::remainder(XR[i] - shape.center[0], box.Lx), dz = std::remainder(XR[2 * m + i] - shape.center[2], box.Lz);
      if (dx * dx + dz * dz < radius * radius) top = std::min(top, XR[m + i] - shape.center[1]);
    }
    const auto& vol = ib.diagnostics(red ? 1 : 0).volume;
    for (const Vec3& v : {shape.center, shape.axes[0], shape.extent}) row.insert(row.end(), v.begin(), v.end());
    row.insert(row.end(), {sheet_distance(Y, n, E, box), lowest, slowest, vol.empty() ? NAN : vol[std::size_t(c)] / std::pow(um, 3), top});
  }
  if (red) {
    for (index_t c = 0; c < Nr && c < red_count; ++c) {
      const st::CellShape shape = st::cell_shape(XR, nr, Nr, c);
      R[std::size_t(4 + c)] = shear_plane_angle(from_center(XR, nr, Nr, c, tracked.at(std::size_t(c)), shape.center));
      R[std::size_t(4 + red_count + c)] = shear_plane_angle(shape.axes[0]);
    }
    R[0] = closest_cells(XR, nr, Nr, box);
    const auto& vol = ib.diagnostics(0).volume;
    if (!vol.empty()) R[2] = *std::min_element(vol.begin(), vol.end()) / std::pow(um, 3), R[3] = *std::max_element(vol.begin(), vol.end()) / std::pow(um, 3);
  }
  const std::vector<double> u = sim::velocity_profile(ib, flow_dir);
  row.insert(row.end(), R.begin(), R.end());
  row.insert(row.end(), u.begin(), u.end());
  return row;
}

std::string run_tag(const Wall& w, bool with_red, std::size_t k) { return w.name + (with_red ? "" : "_no_red_cells") + "_" + to_text(k); }

/// The study: its tables, and what the runs add up to. A value over a kind of run is written once
/// every run of that kind has finished (NaN before).
struct WholeBlood {
  const st::Options& opt;
  const Setup& s;
  Json& results;
  const st::Sitting sitting{opt};  // full scale: this sitting's wall time
  Json profiles = st::table({"run", "y_um", "u_mm_s"}, {"", "um", "mm/s"});
  Json platelets = st::table({"run", "t_ms", "distance_um", "two_h_um", "unicycling", "min_speed_mm_s", "aspect_change"},
                             {"", "ms", "um", "um", "", "mm/s", ""});
  Json runs = st::table({"run", "t_start_ms", "t_end_ms", "steps", "seconds_per_step", "shear_platelet_layer_1_s", "couette_deviation_start",
                         "couette_deviation", "no_slip_height_um", "closest_red_cells_over_h", "closest_platelet_red_over_h",
                         "platelet_headroom_um", "unicycling_fraction", "longest_unicycling_ms", "max_distance_um", "max_aspect_change",
                         "tank_treading_period_ms", "volume_change"},
                        {"", "ms", "ms", "", "s", "1/s", "", "", "um", "", "", "um", "", "ms", "um", "", "ms", ""});
  Json treading = st::table({"run", "cell", "material_turn_deg", "short_axis_turn_deg", "relative_turn_deg", "period_ms"}, {"", "", "deg", "deg", "deg", "ms"});
  Json procedure = st::table({"wall", "moved", "draws", "closest_um", "platelet_draws", "attempts_platelet_1", "attempts_platelet_2",
                              "refused_red_cells", "refused_surface_or_box", "gap1_um", "gap2_um", "starting_times_ms"},
                             {"", "", "", "um", "", "", "", "", "", "um", "um", "ms"});
  Json snapshot = st::table({"cell", "z_um", "y_um"}, {"", "um", "um"});
  Json cost = st::table({"run", "h_um", "dt_ns", "steps_done", "steps_needed", "seconds_per_step", "hours_to_solution"}, {"", "um", "ns", "", "", "s", "h"});
  ReferenceSites rbc = reference_sites(cells::red_cell_spec(s.rbc_nd, s.rbc_ns)), plt = reference_sites(cells::platelet_spec(s.plt_n, s.plt_n));
  double hours_left = 0, v_ref = NAN;  // the time to solution at the measured rates (h); the red cell's reference volume (um^3)
  const double v_plt_ref = 4.0 / 3 * pi * 1.55 * 1.55 * 0.5;  // the platelet ellipsoid (um^3)
  bool inits_done = true, red_runs_done = true, free_runs_done = true, flat_runs_done = true;
  std::map<std::string, double> shear{};  // per run: the platelet layer's shear rate
  double worst_volume = 0, worst_couette = 0, closest_red = INFINITY, closest_platelet_red = INFINITY, min_platelet_endothelium = INFINITY;
  double min_headroom = INFINITY, no_slip_sum = 0, min_clearance = INFINITY, max_distance_red = 0, max_aspect = 0, longest_unicycling_flat = 0;
  int free_runs = 0, refused_red = 0, refused_surface = 0;
  std::vector<double> frequencies{}, attempts{};  // tank-treading turns per second per red cell and run; points drawn per platelet placed

  void add_cost(const std::string& run, double done, double needed, double seconds_per_step) {
    const double hours = (needed - done) * seconds_per_step / 3600;
    hours_left += hours;
    cost["rows"].push(row({run, s.h / um, s.dt / units::ns, done, needed, seconds_per_step, hours}));
  }
  void wall(const Wall& w, std::size_t wi);
  void run_from(const Wall& w, const Domain& box, std::size_t k, bool with_red, double t_start, const std::string& start_file,
                const io::Checkpoint& start, const std::vector<cells::Placement>& platelets, const std::vector<index_t>& tracked);
  Json analyse(const std::string& tag, const Wall& w, bool with_red, const std::vector<std::vector<double>>& rows, Json::Array out);
  void summarize();
};

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
  {  // An example for `rbfib run`: the same layout with platelets placed against it, the flow from rest, 40 us.
    std::mt19937_64 erng(seed + 50 + wi);
    const std::vector<double> E = scene::point_positions(init_scene.point_sets.at(0).surface, init_scene.grid.length);
    const PlateletPlacement ex = place_platelets(plt, box, E, batch_layout(rbc, layout.red_cells), rbc.n, 2, ps, erng);
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
  ih.at_start = [&](const sim::ImmersedBoundary& ib) { v_ref = ib.batch(0).type().reference_volume() / std::pow(um, 3); };
  const st::SceneRun init = st::run_scene(init_text, "init_" + w.name, s.samples(), opt.keeps_runs(), opt, ih,
                                             sitting.remaining() / double(s.walls.size() - wi));  // shared by the inits to come
  st::record_run(results, "init_" + w.name, init.progress(starts.back()));
  // Steps needed at the mean step so far (the ladder's), or at dt.
  const double init_t = init.samples.empty() ? 0 : init.samples.back().at(0), mean_dt = init.steps > 0 ? init_t / double(init.steps) : s.dt;
  add_cost("init " + w.name, double(init.steps), s.ladder > 0 ? std::round(starts.back() / mean_dt) : double(std::lround(starts.back() / s.dt)),
           init.seconds_per_step());
  if (!init.stopped.empty()) throw NumericalError(Cause::solver, "the init run (" + w.name + ") stopped: " + init.stopped);
  for (const auto& r : init.samples) closest_red = std::min(closest_red, r[2] / s.h);
  if (!init.finished) {
    inits_done = red_runs_done = false;
    (w.bump > 0 ? free_runs_done : flat_runs_done) = false;
    // The runs from its starting states are still to come: their steps at the init's rate.
    for (std::size_t k = 0; k < starts.size(); ++k)
      for (bool with_red : {true, false})
        if (with_red || w.bump > 0) {  // the seed removes the red cells over the bumpy wall only
          add_cost(run_tag(w, with_red, k) + " (to come)", 0, std::round(window / mean_dt), init.seconds_per_step());
          st::record_run(results, run_tag(w, with_red, k), st::RunProgress{false, 0, window, 0, init.seconds_per_step(), ""});
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
  const long done = run.steps - start.state.clock.step;  // the run's own span: steps from its starting time
  st::RunProgress progress = run.progress(t_end);
  progress.t -= t_start, progress.t_end = window, progress.steps = done;
  st::record_run(results, tag, progress);
  const double mean_dt = done > 0 ? progress.t / double(done) : s.dt;  // the ladder's mean step so far, or dt
  add_cost(tag, double(done), s.ladder > 0 ? std::round(window / mean_dt) : double(std::lround(window / s.dt)), run.seconds_per_step());
  if (!run.finished) {
    (with_red ? red_runs_done : free_runs_done) = false;
    if (with_red && w.bump == 0) flat_runs_done = false;
    return;
  }
  if (!run.stopped.empty()) throw NumericalError(Cause::solver, "run " + tag + " stopped: " + run.stopped);
  runs["rows"].push(analyse(tag, w, with_red, run.samples, {tag, t_start / ms, t_end / ms, double(done), run.seconds_per_step()}));
  if (k > 0 || !with_red) return;
  // A side view (along x) of the cells and the endothelium at the end.
  const std::vector<double> E = host(run.final_points.at(0));
  const std::size_t m = E.size() / 3;
  for (std::size_t i = 0; i < m; i += 8) snapshot["rows"].push(row({"endothelium", E[2 * m + i] / um, E[m + i] / um}));
  for (std::size_t b = 0; b < run.final_positions.size(); ++b) {
    const std::vector<double>& X = run.final_positions[b];
    const index_t n = b == 0 ? rbc.n : plt.n, N = index_t(X.size() / std::size_t(3 * n));
    for (index_t c = 0; c < N; ++c)
      for (index_t i = 0; i < n; i += (n > 1000 ? 4 : 1))
        snapshot["rows"].push(row({(b == 0 ? "red cell " : "platelet ") + to_text(c + 1), std::fmod(X[std::size_t((2 * N + c) * n + i)] + 16 * Lz, Lz) / um,
                                   X[std::size_t((N + c) * n + i)] / um}));
  }
}

/// The measures of one finished run (the runs table's row after `row`), adding to the totals.
Json WholeBlood::analyse(const std::string& tag, const Wall& w, bool with_red, const std::vector<std::vector<double>>& rows, Json::Array out) {
  // The profile averaged over the second half of the run (Fig. 5.4).
  const std::size_t first = rows.size() / 2, ny = rows.front().size() - profile_at;
  std::vector<double> y(ny), u(ny, 0.0), u0(rows.front().begin() + long(profile_at), rows.front().end()), times;
  for (std::size_t j = 0; j < ny; ++j) y[j] = (double(j) + 0.5) * Ly / double(ny);
  for (std::size_t i = first; i < rows.size(); ++i)
    for (std::size_t j = 0; j < ny; ++j) u[j] += rows[i][profile_at + j] / double(rows.size() - first);
  for (std::size_t j = 0; j < ny; ++j) profiles["rows"].push(row({tag, y[j] / um, u[j] * 10}));
  const double gdot = shear[tag] = fit_line(y, u, 1 * um, 4 * um).slope;
  const LineFit fit = fit_line(y, u, 3 * um, 11.5 * um), fit0 = fit_line(y, u0, 3 * um, 11.5 * um);  // Couette above the platelet layer
  if (!with_red) worst_couette = std::max(worst_couette, fit.max_departure / wall_speed), no_slip_sum += fit.x_intercept(), ++free_runs;
  // Platelets (Figs. 5.5, 5.6).
  double unicycling = 0, room = INFINITY, vol_change = 0, red_min = INFINITY, plt_red = INFINITY, longest_uni = 0, max_dist = 0, max_asp = 0;
  for (const auto& r : rows) times.push_back(r[0]);
  for (std::size_t o : {std::size_t(1), std::size_t(1 + col::per_platelet)}) {
    auto aspect = [&](const std::vector<double>& r) { return r[o + 6] / std::max(r[o + 7], r[o + 8]); };
    std::vector<bool> uni_flags;
    for (const auto& r : rows) {
      const bool uni = st::axis_angle(Vec3{r[o + 3], r[o + 4], r[o + 5]}, vorticity_dir) < pi / 4;
      const double change = aspect(r) / aspect(rows.front()) - 1, distance = r[o + col::distance] / um;
      platelets["rows"].push(row({tag + " platelet " + to_text(o == 1 ? 1 : 2), r[0] / ms, distance, 2 * s.h / um, uni ? 1.0 : 0.0, r[o + col::min_speed] * 10, change}));
      uni_flags.push_back(uni);
      unicycling += (uni ? 1.0 : 0.0) / double(2 * rows.size());
      min_platelet_endothelium = std::min(min_platelet_endothelium, distance), max_dist = std::max(max_dist, distance);
      min_clearance = std::min(min_clearance, r[o + col::clearance] / um);
      room = std::min(room, r[o + col::headroom]);
      max_asp = std::max(max_asp, std::abs(change));
      if (r[o + col::volume] > 0) vol_change = std::max(vol_change, std::abs(r[o + col::volume] / v_plt_ref - 1));
    }
    longest_uni = std::max(longest_uni, longest_interval(times, uni_flags));
  }
  max_aspect = std::max(max_aspect, max_asp);
  double period_median = NAN;
  if (with_red) {
    for (const auto& r : rows) {
      red_min = std::min(red_min, r[red_at] / s.h), plt_red = std::min(plt_red, r[red_at + 1] / s.h);
      if (r[red_at + 2] > 0) vol_change = std::max({vol_change, std::abs(r[red_at + 2] / v_ref - 1), std::abs(r[red_at + 3] / v_ref - 1)});
    }
    closest_red = std::min(closest_red, red_min), closest_platelet_red = std::min(closest_platelet_red, plt_red);
    min_headroom = std::min(min_headroom, room), max_distance_red = std::max(max_distance_red, max_dist);
    if (w.bump == 0) longest_unicycling_flat = std::max(longest_unicycling_flat, longest_uni);
    // Tank-treading: the tracked site's mean turning about the centre, less the short axis's, in
    // turns per second; the shear turns shear_plane_angle negatively (d(angle)/dt = -gdot sin^2),
    // so a membrane that lags its body, or none that turns, tank-treads at 0 per second.
    std::vector<double> run_frequencies;
    for (std::size_t c = 0; c < red_count; ++c) {
      std::vector<double> m, a;
      for (const auto& r : rows) m.push_back(r[material_at + c]), a.push_back(r[axis_at + c]);
      m = st::unwrap(m, 2 * pi), a = st::unwrap(a, pi);
      const double dm = m.back() - m.front(), da = a.back() - a.front(), span = times.back() - times.front();
      const double frequency = std::max(0.0, da - dm) / (2 * pi * span);
      run_frequencies.push_back(frequency), frequencies.push_back(frequency);
      treading["rows"].push(row({tag, double(c + 1), dm * 180 / pi, da * 180 / pi, (dm - da) * 180 / pi, 1 / frequency / ms}));
    }
    period_median = 1 / st::median(run_frequencies);
  }
  worst_volume = std::max(worst_volume, vol_change);
  st::log(opt, tag + ": shear in the platelet layer " + to_text(gdot) + " 1/s (start of the run: " + to_text(fit_line(y, u0, 1 * um, 4 * um).slope) +
                   "), deviation from Couette " + to_text(fit0.max_departure / wall_speed) + " -> " + to_text(fit.max_departure / wall_speed) +
                   ", no-slip height " + to_text(fit.x_intercept() / um) + " um, closest red cells " + to_text(red_min) + " h, platelet-red " +
                   to_text(plt_red) + " h, volume change " + to_text(vol_change));
  for (double x : {gdot, fit0.max_departure / wall_speed, fit.max_departure / wall_speed, fit.x_intercept() / um, red_min, plt_red, room / um, unicycling,
                   longest_uni / ms, max_dist, max_asp, period_median / ms, vol_change})
    out.push_back(x);
  return Json(out);
}

void WholeBlood::summarize() {
  Json& V = results["values"];
  V["hours_to_solution"] = hours_left;
  cost["rows"].push(row({"all", s.h / um, s.dt / units::ns, NAN, NAN, NAN, hours_left}));
  const bool all_runs_done = red_runs_done && free_runs_done;
  const bool has_flat = std::any_of(s.walls.begin(), s.walls.end(), [](const Wall& w) { return w.bump == 0; });
  auto put = [&](const std::string& name, double value, bool runs_finished) { V[name] = runs_finished ? value : NAN; };
  put("closest_red_cells_over_h", closest_red, inits_done && red_runs_done);
  put("closest_platelet_red_over_h", closest_platelet_red, red_runs_done);
  put("min_platelet_endothelium_um", min_platelet_endothelium, all_runs_done);
  put("min_platelet_clearance_um", min_clearance, all_runs_done);
  put("platelet_headroom_um", min_headroom / um, red_runs_done);
  put("no_slip_height_without_red_cells_um", no_slip_sum / std::max(free_runs, 1) / um, free_runs_done && free_runs > 0);
  put("couette_deviation_without_red_cells", worst_couette, free_runs_done && free_runs > 0);
  put("volume_change", worst_volume, all_runs_done);
  put("max_platelet_distance_um", max_distance_red, red_runs_done);
  put("max_aspect_change", max_aspect, all_runs_done);
  put("rbc_tank_treading_frequency_1_s", st::median(frequencies), red_runs_done);
  put("rbc_tank_treading_period_ms", 1 / st::median(frequencies) / ms, red_runs_done);  // infinite (null) for none
  put("longest_unicycling_ms_flat", longest_unicycling_flat / ms, has_flat && flat_runs_done);
  auto mean_shear = [&](const std::string& kind) {  // over the starting times of one kind of run
    double sum = 0;
    int n = 0;
    for (const auto& [tag, g] : shear)
      if (tag.rfind(kind, 0) == 0 && std::isdigit(static_cast<unsigned char>(tag[kind.size()]))) sum += g, ++n;
    return n > 0 ? sum / n : NAN;
  };
  const double with = mean_shear("bumpy_"), without = mean_shear("bumpy_no_red_cells_");
  put("shear_platelet_layer_bumpy", with, red_runs_done);
  put("shear_platelet_layer_bumpy_no_red_cells", without, free_runs_done);
  put("shear_ratio_with_over_without_red_cells", with / without, red_runs_done && free_runs_done);
  if (has_flat) put("shear_platelet_layer_flat", mean_shear("flat_"), flat_runs_done);
  double attempts_mean = 0;  // the platelet placement of Sec. 5.2.1, over every starting state
  for (double a : attempts) attempts_mean += a / double(attempts.size());
  put("platelet_attempts_median", st::median(attempts), inits_done);
  put("platelet_attempts_mean", attempts.empty() ? NAN : attempts_mean, inits_done);
  put("platelet_draws_refused_red_cells", double(refused_red), inits_done);
  put("platelet_draws_refused_surface_or_box", double(refused_surface), inits_done);
  // The hematocrit (conventions: hematocrit): 8 red cells of the reference volume over the fluid
  // above the endothelium (mean height 1 um for both shapes), and other readings for comparison.
  const double area = 16 * 16, above = 12 - 1.0, red_volume = red_count * v_ref;  // um^2, um, um^3
  V["red_cell_volume_um3"] = v_ref;
  for (auto [name, height] : {std::pair{"above_endothelium", above}, {"above_endothelium_without_top_1um", above - 1},
                              {"above_endothelium_without_top_2um", above - 2}, {"whole_box", 12.0}, {"above_3um", 9.0}, {"above_3um_below_10um", 7.0}})
    V[std::string("hematocrit_") + name] = red_volume / (area * height);  // heights in um
  V["hematocrit_exclusion_ratio_1um"] = above / (above - 1);
  V["hematocrit_exclusion_ratio_2um"] = above / (above - 2);
  V["red_volume_for_34_percent_um3"] = 0.34 * area * above;
  for (auto [name, table] : {std::pair{"profiles", &profiles}, {"platelets", &platelets}, {"runs", &runs}, {"tank_treading", &treading},
                             {"procedure", &procedure}, {"snapshot", &snapshot}, {"cost", &cost}})
    results["tables"][name] = *table;
}
}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_whole_blood", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_whole_blood",
                                                   "Sec. 5.2: whole blood over a flat and a bumpy endothelium (Figs. 5.4-5.6)");
    const bool full = opt.scale == st::Scale::full;
    // Full scale: the seed's ladder with the endothelium's constants following the step (gain 0.5;
    // docs/derivations/tether_stability, chapter5_tether_stability); quick: the seed's fixed ones.
    const Setup s = full ? Setup{0.2 * um, 50 * units::ns, 2500, 10000, 900, 16000, 7.2 * ms, 17 * ms, 3 * ms, 40 * ms, 60 * ms, 4, {flat, bumpy}, 400, 4, 0.5}
                         : Setup{0.4 * um, 100 * units::ns, 400, 1600, 400, 4096, 20 * us, 30 * us, 10 * us, 80 * us, 80 * us, 1, {bumpy}, 10};
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "16 x 12 x 16, periodic x and z, walls in y; the top wall at 16 mm/s turning from z toward x by 45 deg (Sec. 5.2.1)";
    P["fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's code; Sec. 2.1 says 0.1 cP)";
    P["h_um"] = s.h / um;
    P["dt_ns"] = s.dt / units::ns;
    P["red_cells"] = "8 at " + to_text(s.rbc_nd) + " / " + to_text(s.rbc_ns) + " sites (Skalak, bending, dissipation)";
    P["platelets"] = "2 at " + to_text(s.plt_n) + " / " + to_text(s.plt_n) + " sites (neo-Hookean, bending about the reference curvature)";
    P["endothelium"] = to_text(s.endothelium) + " points on the toroidal spiral (Appendix B), flat y = 1 um or bumpy y = 0.75 um + 1 um cos^2(theta - phi) sin^2(phi/2) (eq. 5.5); " +
                       (s.tether_gain > 0 ? "k and eta following the step by the seed's rule at gain " + to_text(s.tether_gain) + " (sim/tether_stability.hpp)"
                                          : std::string("k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm"));
    if (s.ladder > 0) P["step"] = "the seed's adaptive step: dt = 2^k x " + to_text(s.dt / units::ns) + " ns, k = 0.." + to_text(s.ladder) + ", by eq. 5.4";
    P["procedure"] = "wall turning over " + to_text(s.turn / us) + " us, settling " + to_text(s.settle / us) + " us, " + to_text(s.starts) +
                     " starting time(s) with exponential gaps of mean " + to_text(s.mean_gap / us) + " us, runs of " + to_text(s.window / us) +
                     " us" + (full ? " over the bumpy wall and " + to_text(s.flat_window / us) + " us over the flat one" : "");
    P["seed"] = double(seed);
    P["kernel_integrator_coupling"] = "B3 kernel, backward-forward Euler, the seed's coupling (a)-(g)";
    WholeBlood study{opt, s, results};
    for (double y : {0.0, 12.0}) study.profiles["rows"].push(row({"Couette between the walls", y, wall_speed * 10 * y / 12}));
    for (std::size_t wi = 0; wi < s.walls.size(); ++wi) study.wall(s.walls[wi], wi);
    study.summarize();
    st::write_results(opt, results);
    return 0;
  });
}
