// Reproduces dissertation Sec. 5.2 (Figs. 5.4-5.6): whole blood over a flat and a bumpy
// endothelium, and over the bumpy one without red cells. The 16 x 12 x 16 um box, periodic in x
// and z, walls in y; the endothelium (eq. 5.5) as points on the toroidal spiral of Appendix B
// tethered with k = 2.5 dyn/cm and damped with eta = 2.5e-7 dyn s/cm (Sec. 2.2); red cells (Skalak +
// bending + dissipation) and platelets (neo-Hookean + bending about the reference curvature);
// B3 kernel, backward-forward Euler, plasma of 1 cP (the seed's code: at the 0.1 cP of Sec. 2.1
// its endothelium is unstable at 50 ns, reference/chapter4_cells.yaml).
//
// The procedure of Sec. 5.2.1 (initialization.hpp), for each endothelium:
//   init:  the endothelium and 8 red cells (two staggered rows, randomly moved keeping 2h), the
//          flow at rest, the top wall at 16 mm/s (sin alpha e1 + cos alpha e3) with alpha from 0 to
//          pi/4 over 7.2 ms, run past the settling time (17 ms) to the last starting time; its state at
//          each starting time (a Poisson process of mean gap 3 ms) is kept (start_<wall>_<k>.h5);
//   runs:  from each starting state, two platelets placed by the algorithm of Sec. 5.2.1 against
//          the red cells there; the same with the red cells removed (bumpy wall only).
// Measured in each run: the x-z averaged velocity along the wall's direction against y (Fig. 5.4)
// and the effective shear rate in the platelet layer (y = 1-4 um); per platelet its distance to the
// endothelium with the intervals of unicycling (short axis within 45 deg of the vorticity) and 2h
// (Fig. 5.5), its smallest surface speed with the intervals where its aspect ratio changes by more
// than 4% (Fig. 5.6); the smallest distances between cells; volumes; the hematocrit.
//   full:  the seed's sizes (h = 0.2 um, red cells 2,500 / 10,000 sites, platelets 900 / 900,
//          16,000 endothelium points, dt = 50 ns), 4 starting times, 40 ms per run, continued from
//          checkpoints; RBFIB_SITTING_SECONDS limits one sitting's wall time;
//   quick: h = 0.4 um, red cells 400 / 1,600, platelets 400 / 400, 4,096 endothelium points (the
//          seed's spacing in units of h), dt = 100 ns (the tethers' explicit limit is about
//          2 mu / (k n_A h), n_A points per area: 128 ns here, 64 ns at the seed's h); the
//          procedure compressed: the wall turns over 20 us, the flow settles to 30 us, one
//          starting time, 80 us per run; the bumpy wall with and without red cells.
//
// Run:   build/studies/study_chapter5_whole_blood --scale quick --out runs/chapter5_whole_blood
#include "chapter5_whole_blood/initialization.hpp"
#include "common/cell_shape.hpp"
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/scene/checkpoint.hpp"
#include "rbfib/scene/snapshot.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

using namespace rbfib;
using namespace rbfib::chapter5_whole_blood;
namespace st = rbfib::study;
using st::Json;
using st::Vec3;

namespace {
constexpr double pi = 3.14159265358979323846;
const double um = units::um, ms = units::ms, us = units::us;
const double Lx = 16 * um, Ly = 12 * um, Lz = 16 * um;
const double wall_speed = 1.6;              // cm/s: 16 mm/s (Sec. 5.2.1)
const double alpha_end = pi / 4;            // the wall's final direction
const Vec3 flow_dir{std::sin(alpha_end), 0, std::cos(alpha_end)};
const Vec3 vorticity_dir{std::cos(alpha_end), 0, -std::sin(alpha_end)};  // of u = gdot y flow_dir
const unsigned long long seed = 5021;       // the procedure's random numbers

struct Wall {
  std::string name;
  double y0, bump;  // eq. 5.5
};
const Wall flat{"flat", 1 * um, 0}, bumpy{"bumpy", 0.75 * um, 1 * um};

struct Setup {
  double h, dt;
  int rbc_nd, rbc_ns, plt_n;
  long endothelium;
  double turn, settle, mean_gap, window;
  int starts;
  std::vector<Wall> walls;
  int every;  // steps between samples
};

/// A number for a scene file: ten significant digits (0.4, not 0.40000000000000002).
std::string num(double x) {
  std::ostringstream o;
  o.precision(10);
  o << x;
  return o.str();
}
std::string um_text(double x) { return num(x / um) + " um"; }

/// The scene of the init run or of a run from a starting state (docs/scenes.md).
std::string scene_text(const Setup& s, const Wall& w, const std::vector<cells::Placement>& red, const std::vector<cells::Placement>& platelets,
                       double t_end, const std::string& what) {
  std::string types, cells_text;
  if (!red.empty())
    types += "  - {name: red cell, preset: red_cell, data_sites: " + to_text(s.rbc_nd) + ", sample_sites: " + to_text(s.rbc_ns) + "}\n";
  if (!platelets.empty())
    types += "  - {name: platelet, preset: platelet, data_sites: " + to_text(s.plt_n) + ", sample_sites: " + to_text(s.plt_n) + "}\n";
  for (const cells::Placement& p : red) cells_text += "  - " + placement_yaml("red cell", p) + "\n";
  for (const cells::Placement& p : platelets) cells_text += "  - " + placement_yaml("platelet", p) + "\n";
  std::string spiral = "{y: " + um_text(w.y0) + (w.bump > 0 ? ", bump: " + um_text(w.bump) : "") + ", points: " + to_text(s.endothelium) + "}";
  return "# chapter5_whole_blood: " + what + " (Sec. 5.2.1), " + w.name + " endothelium\n"
         "name: whole_blood_" + w.name + "\n"
         "domain:\n  size: [16 um, 12 um, 16 um]\n  periodic: [x, z]\n"
         "  walls:\n    y: {lower: [0 mm/s, 0 mm/s, 0 mm/s], upper: {speed: 16 mm/s, turn: {from: 0 deg, to: 45 deg, over: " +
         num(s.turn / ms) + " ms}}}\n"
         "fluid: {density: 1 g/cm^3, viscosity: 1 cP}\n"
         "grid: {h: " + um_text(s.h) + "}\n"
         "time: {integrator: backward_forward_euler, dt: " + num(s.dt / units::ns) + " ns, end: " + num(t_end / us) + " us}\n"
         "ib: {kernel: bspline3}\n"
         "cell_types:\n" + types + "cells:\n" + cells_text +
         "tethered_points:\n  - {name: endothelium, spiral: " + spiral + ", k: 2.5 dyn/cm, eta: 2.5e-7 dyn s/cm}\n";
}

std::vector<double> host(const dvec& v) {
  const host_vector<double> h = v;
  return std::vector<double>(h.begin(), h.end());
}

/// Cell c's data sites (n x 3) from a batch layout (n x 3N, or the n x 6N state).
std::vector<double> cell_sites(const std::vector<double>& X, index_t n, index_t N, index_t c) {
  std::vector<double> Y(std::size_t(3 * n));
  for (int d = 0; d < 3; ++d) std::copy_n(X.begin() + long((d * N + c) * n), n, Y.begin() + long(d * n));
  return Y;
}

/// The smallest distance between two cells of a batch layout.
double closest_pair(const std::vector<double>& X, index_t n, index_t N, const Domain& box) {
  double best = INFINITY;
  for (index_t a = 0; a < N; ++a)
    for (index_t b = a + 1; b < N; ++b) best = std::min(best, cell_distance(cell_sites(X, n, N, a), n, cell_sites(X, n, N, b), n, box));
  return best;
}

/// The x-z average of the velocity along the wall's final direction at each cell-centre level y_j.
std::vector<double> velocity_profile(const sim::ImmersedBoundary& ib) {
  std::vector<double> u;
  for (int a : {0, 2}) {
    const rbfib::Box& b = ib.fluid().operators().component_box(a);
    const host_vector<double> v = ib.fluid_state().u[a];
    const int nx = b.n(0), ny = b.n(1), nz = b.n(2);
    u.resize(std::size_t(ny), 0.0);
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) u[std::size_t(j)] += flow_dir[std::size_t(a)] * v[std::size_t(i + nx * (j + ny * index_t(k)))] / (double(nx) * nz);
  }
  return u;
}

/// The starting state of a run: the init's fluid, red cells (when kept) and endothelium, with the
/// run's platelets (the last batch of the freshly built step) added.
void start_from(sim::ImmersedBoundary& ib, const scene::Checkpoint& start, bool with_red_cells) {
  sim::ImmersedBoundary::Carried c = ib.carried();
  const dvec platelets = c.batches.back();
  c.fluid = start.state.fluid;
  c.batches.clear();
  if (with_red_cells) c.batches.push_back(start.state.batches.at(0));
  c.batches.push_back(platelets);
  c.points = start.state.points;
  c.steps = start.state.steps, c.dt = start.state.dt, c.level = start.state.level, c.allowing = start.state.allowing;
  ib.restore(c);
}

/// What a run with platelets records at each sample (a row of numbers in the run's samples file).
struct PlateletSample {
  Vec3 center{}, axis{}, extent{};  ///< cm; the short axis; extents along the principal axes (cm)
  double to_endothelium = 0;        ///< the smallest distance from its data sites to the endothelium points (cm)
  double clearance = 0;             ///< the lowest height of a data site above the endothelium's surface (eq. 5.5; cm)
  double min_speed = 0;             ///< the smallest speed of its data sites (cm/s)
  double volume = 0;                ///< um^3
  /// The lowest red-cell site over the platelet (within its radius across the flow plane) above
  /// its centre (cm): negative when a red cell has come between it and the wall; +inf without.
  double headroom = INFINITY;
};
struct RunSample {
  double t = 0;
  PlateletSample p[2];
  double red_gap = NAN, platelet_red_gap = NAN;   ///< closest red cells; closest platelet-red cell (cm)
  double red_volume_min = NAN, red_volume_max = NAN;  ///< um^3
  std::vector<double> u;                         ///< the velocity profile (cm/s)

  std::vector<double> row() const {
    std::vector<double> r{t};
    for (const PlateletSample& q : p) {
      r.insert(r.end(), q.center.begin(), q.center.end());
      r.insert(r.end(), q.axis.begin(), q.axis.end());
      r.insert(r.end(), q.extent.begin(), q.extent.end());
      r.insert(r.end(), {q.to_endothelium, q.clearance, q.min_speed, q.volume, q.headroom});
    }
    r.insert(r.end(), {red_gap, platelet_red_gap, red_volume_min, red_volume_max});
    r.insert(r.end(), u.begin(), u.end());
    return r;
  }
  static RunSample from(const std::vector<double>& r) {
    RunSample s;
    std::size_t k = 0;
    s.t = r.at(k++);
    for (PlateletSample& q : s.p) {
      for (Vec3* v : {&q.center, &q.axis, &q.extent})
        for (double& x : *v) x = r.at(k++);
      q.to_endothelium = r.at(k++), q.clearance = r.at(k++), q.min_speed = r.at(k++), q.volume = r.at(k++), q.headroom = r.at(k++);
    }
    s.red_gap = r.at(k++), s.platelet_red_gap = r.at(k++), s.red_volume_min = r.at(k++), s.red_volume_max = r.at(k++);
    s.u.assign(r.begin() + long(k), r.end());
    return s;
  }
};

RunSample sample_run(const sim::ImmersedBoundary& ib, bool red, const Domain& box) {
  RunSample out;
  out.t = ib.time();
  const index_t pb = red ? 1 : 0;
  const cells::Batch& P = ib.batch(pb);
  const index_t n = P.type().n_data(), N = P.size();
  const std::vector<double> S = P.state().to_host();  // n x 6N: X then U
  const std::vector<double> X(S.begin(), S.begin() + long(3 * N * n));
  const std::vector<double> E = host(ib.points(0).X);
  std::vector<double> XR;
  index_t nr = 0, Nr = 0;
  if (red) XR = ib.batch(0).positions_host(), nr = ib.batch(0).type().n_data(), Nr = ib.batch(0).size();
  if (red) out.platelet_red_gap = INFINITY;
  for (index_t c = 0; c < N && c < 2; ++c) {
    PlateletSample& q = out.p[c];
    const st::CellShape shape = st::cell_shape(X, n, N, c);
    q.center = shape.center, q.axis = shape.axes[0], q.extent = shape.extent;
    const std::vector<double> Y = cell_sites(X, n, N, c);
    q.to_endothelium = sheet_distance(Y, n, E, box);
    if (red) out.platelet_red_gap = std::min(out.platelet_red_gap, distance_to_red_cells(Y, n, XR, nr, box));
    q.clearance = INFINITY;
    for (index_t i = 0; i < n; ++i)
      q.clearance = std::min(q.clearance, Y[std::size_t(n + i)] - box.endothelium.height(Y[std::size_t(i)], Y[std::size_t(2 * n + i)]));
    q.min_speed = INFINITY;
    for (index_t i = 0; i < n; ++i) {
      double v2 = 0;
      for (int d = 0; d < 3; ++d) v2 += std::pow(S[std::size_t((3 * N + d * N + c) * n + i)], 2);
      q.min_speed = std::min(q.min_speed, std::sqrt(v2));
    }
    const auto& vol = ib.diagnostics(pb).volume;
    q.volume = vol.empty() ? NAN : vol[std::size_t(c)] / std::pow(um, 3);
    const double radius = 1.55 * um;
    const std::size_t m = XR.size() / 3;
    for (std::size_t i = 0; i < m; ++i) {
      const double dx = std::remainder(XR[i] - q.center[0], box.Lx), dz = std::remainder(XR[2 * m + i] - q.center[2], box.Lz);
      if (dx * dx + dz * dz < radius * radius) q.headroom = std::min(q.headroom, XR[m + i] - q.center[1]);
    }
  }
  if (red) {
    out.red_gap = closest_pair(XR, nr, Nr, box);
    const auto& vol = ib.diagnostics(0).volume;
    if (!vol.empty()) {
      out.red_volume_min = *std::min_element(vol.begin(), vol.end()) / std::pow(um, 3);
      out.red_volume_max = *std::max_element(vol.begin(), vol.end()) / std::pow(um, 3);
    }
  }
  out.u = velocity_profile(ib);
  return out;
}

/// Least-squares slope of the profile over levels y in [lo, hi].
double profile_slope(const std::vector<double>& y, const std::vector<double>& u, double lo, double hi) {
  std::vector<double> a, b;
  for (std::size_t j = 0; j < y.size(); ++j)
    if (y[j] >= lo && y[j] <= hi) a.push_back(y[j]), b.push_back(u[j]);
  return st::slope(a, b);
}

/// The straight line u = g (y - y0) fitted to the profile over [lo, hi]: y0 is where the flow
/// above sees its no-slip wall; deviation is the largest departure from the line over the wall speed.
struct Couette {
  double gdot = 0, no_slip_height = 0, deviation = 0;
};
Couette couette_fit(const std::vector<double>& y, const std::vector<double>& u, double lo, double hi) {
  std::vector<double> a, b;
  for (std::size_t j = 0; j < y.size(); ++j)
    if (y[j] >= lo && y[j] <= hi) a.push_back(y[j]), b.push_back(u[j]);
  Couette c;
  c.gdot = st::slope(a, b);
  double ya = 0, ua = 0;
  for (std::size_t j = 0; j < a.size(); ++j) ya += a[j] / double(a.size()), ua += b[j] / double(a.size());
  c.no_slip_height = ya - ua / c.gdot;
  for (std::size_t j = 0; j < a.size(); ++j) c.deviation = std::max(c.deviation, std::abs(b[j] - (ua + c.gdot * (a[j] - ya))) / wall_speed);
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_whole_blood", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_whole_blood",
                                                   "Sec. 5.2: whole blood over a flat and a bumpy endothelium (Figs. 5.4-5.6)");
    const bool full = opt.scale == st::Scale::full;
    const Setup s = full ? Setup{0.2 * um, 50 * units::ns, 2500, 10000, 900, 16000, 7.2 * ms, 17 * ms, 3 * ms, 40 * ms, 4, {flat, bumpy}, 400}
                         : Setup{0.4 * um, 100 * units::ns, 400, 1600, 400, 4096, 20 * us, 30 * us, 10 * us, 80 * us, 1, {bumpy}, 10};
    const st::Sitting sitting;  // full scale: this sitting's wall time
    auto remaining = [&] { return sitting.remaining(); };

    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "16 x 12 x 16, periodic x and z, walls in y; the top wall at 16 mm/s turning from z toward x by 45 deg (Sec. 5.2.1)";
    P["fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's code; Sec. 2.1 says 0.1 cP)";
    P["h_um"] = s.h / um;
    P["dt_ns"] = s.dt / units::ns;
    P["red_cells"] = "8 at " + to_text(s.rbc_nd) + " / " + to_text(s.rbc_ns) + " sites (Skalak, bending, dissipation)";
    P["platelets"] = "2 at " + to_text(s.plt_n) + " / " + to_text(s.plt_n) + " sites (neo-Hookean, bending about the reference curvature)";
    P["endothelium"] = to_text(s.endothelium) + " points on the toroidal spiral (Appendix B), flat y = 1 um or bumpy y = 0.75 um + 1 um cos^2(theta - phi) sin^2(phi/2) (eq. 5.5); k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm";
    P["procedure"] = "wall turning over " + to_text(s.turn / us) + " us, settling " + to_text(s.settle / us) + " us, " + to_text(s.starts) +
                     " starting time(s) with exponential gaps of mean " + to_text(s.mean_gap / us) + " us, runs of " + to_text(s.window / us) + " us";
    P["seed"] = double(seed);
    P["kernel_integrator_coupling"] = "B3 kernel, backward-forward Euler, the seed's coupling (a)-(g)";

    const ReferenceSites rbc = reference_sites(cells::red_cell_spec(s.rbc_nd, s.rbc_ns)), plt = reference_sites(cells::platelet_spec(s.plt_n, s.plt_n));

    Json profiles = st::table({"run", "y_um", "u_mm_s"}, {"", "um", "mm/s"});
    for (double y : {0.0, 12.0}) profiles["rows"].push(Json::Array{Json("Couette between the walls"), Json(y), Json(wall_speed * 10 * y / 12)});
    Json platelets_t = st::table({"run", "t_ms", "distance_um", "two_h_um", "unicycling", "min_speed_mm_s", "aspect_change"},
                                 {"", "ms", "um", "um", "", "mm/s", ""});
    Json runs_t = st::table({"run", "t_start_ms", "t_end_ms", "steps", "seconds_per_step", "shear_platelet_layer_1_s", "couette_deviation_start",
                             "couette_deviation", "no_slip_height_um", "closest_red_cells_over_h", "closest_platelet_red_over_h",
                             "platelet_headroom_um", "unicycling_fraction", "volume_change"},
                            {"", "ms", "ms", "", "s", "1/s", "", "", "um", "", "", "um", "", ""});
    Json layout_t = st::table({"wall", "moved", "draws", "closest_um", "platelet_draws", "gap1_um", "gap2_um", "starting_times_ms"},
                              {"", "", "", "um", "", "um", "um", "ms"});
    Json snapshot_t = st::table({"cell", "z_um", "y_um"}, {"", "um", "um"});
    Json cost = st::table({"run", "h_um", "dt_ns", "steps_done", "steps_needed", "seconds_per_step", "hours_to_solution"},
                          {"", "um", "ns", "", "", "s", "h"});
    Json& V = results["values"];
    double hours_left = 0;  // the time to solution at the measured rates (h)
    auto add_cost = [&](const std::string& run, double done, double needed, double seconds_per_step) {
      const double hours = (needed - done) * seconds_per_step / 3600;
      hours_left += hours;
      cost["rows"].push(Json::Array{Json(run), Json(s.h / um), Json(s.dt / units::ns), Json(done), Json(needed), Json(seconds_per_step), Json(hours)});
    };
    double v_ref = NAN;  // the red cell's reference volume (um^3), from the init run's cell type
    bool all_done = true;
    std::map<std::string, double> shear;  // per run: the platelet layer's shear rate
    double worst_volume = 0, worst_couette = 0, closest_red = INFINITY, closest_platelet_red = INFINITY, min_platelet_endothelium = INFINITY;
    double min_headroom = INFINITY, no_slip_height = NAN, min_clearance = INFINITY;
    const double v_plt_ref = 4.0 / 3 * pi * 1.55 * 1.55 * 0.5;  // the platelet ellipsoid (um^3)

    for (std::size_t wi = 0; wi < s.walls.size(); ++wi) {
      const Wall& w = s.walls[wi];
      const Domain box{Lx, Ly, Lz, scene::EndotheliumSurface{w.y0, w.bump, Lx, Lz}};
      std::mt19937_64 rng(seed + wi);
      LayoutSpec ls;
      ls.h = s.h;
      const Layout layout = red_cell_layout(rbc, box, ls, rng);
      std::vector<double> starts = starting_times(s.settle, s.mean_gap, s.starts, rng);
      std::vector<long> start_steps;
      for (double& t : starts) start_steps.push_back(std::lround(t / s.dt)), t = double(start_steps.back()) * s.dt;
      std::string start_list;  // ms
      for (double x : starts) {
        if (!start_list.empty()) start_list += ' ';
        start_list += to_text(x / ms);
      }
      st::log(opt, w.name + ": red cells moved " + to_text(layout.moved) + " of 8 in " + to_text(layout.draws) + " draws, closest " +
                       um_text(layout.closest) + "; starting times (ms): " + start_list);

      // ---- init: endothelium and red cells, the wall turning ------------------------------------
      const std::string init_text = scene_text(s, w, layout.red_cells, {}, starts.back(), "init");
      {
        // An example for `rbfib run` (scenes/whole_blood_*.yaml): the same layout with platelets placed
        // by the same algorithm against the red cells as laid out, the flow from rest, 40 us.
        std::mt19937_64 erng(seed + 50 + wi);
        const std::vector<double> batch = batch_layout(rbc, layout.red_cells);
        PlateletSpec ps;
        ps.min_separation = 3.1 * um + 4 * s.h;
        const std::vector<double> E = host(scene::parse_scene(init_text, "init").point_sets.at(0).X);
        const PlateletPlacement ex = place_platelets(plt, box, E, batch, rbc.n, 2, ps, erng);
        std::ofstream(opt.out_dir + "/example_" + w.name + ".yaml")
            << scene_text(s, w, layout.red_cells, ex.platelets, 40 * us, "an example: the layout of the procedure with platelets placed against it")
            << "output: {diagnostics_every: 10, snapshot_every: 10 us}\n";
      }
      st::SceneRunHooks ih;
      ih.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r) {
        const cells::Batch& R = ib.batch(0);
        const auto& vol = ib.diagnostics(0).volume;
        return std::vector<double>{ib.time(), r ? r->max_velocity : 0.0, closest_pair(R.positions_host(), R.type().n_data(), R.size(), box),
                                   vol.empty() ? NAN : vol[0] / std::pow(um, 3)};
      };
      const std::string start_file = opt.out_dir + "/start_" + w.name + "_";
      ih.after_step = [&](const sim::ImmersedBoundary& ib) {
        for (std::size_t k = 0; k < starts.size(); ++k)
          if (ib.step_count() == start_steps[k]) scene::write_checkpoint(start_file + to_text(k) + ".h5", init_text, ib);
      };
      ih.at_start = [&](const sim::ImmersedBoundary& ib) { v_ref = ib.batch(0).type().reference_volume() / std::pow(um, 3); };
      // A sitting's budget is shared by the walls' init runs still to come.
      const st::SceneRun init = st::run_scene(init_text, "init_" + w.name, s.every, full, opt, ih, remaining() / double(s.walls.size() - wi));
      const long init_needed = std::lround(starts.back() / s.dt);
      add_cost("init " + w.name, double(init.steps), double(init_needed), init.seconds_per_step());
      if (!init.stopped.empty()) throw NumericalError("the init run (" + w.name + ") stopped: " + init.stopped);
      for (const auto& r : init.samples) closest_red = std::min(closest_red, r[2] / s.h);
      if (!init.finished) {
        all_done = false;
        // The runs from its starting states are still to come: their steps at the init's rate
        // (they carry two platelets more, a few percent of the step).
        for (std::size_t k = 0; k < starts.size(); ++k)
          for (int copies = 0; copies < (w.bump > 0 ? 2 : 1); ++copies) {
            add_cost(w.name + (copies ? "_no_red_cells_" : "_") + to_text(k) + " (to come)", 0, std::round(s.window / s.dt), init.seconds_per_step());
          }
        st::log(opt, w.name + ": init run at t = " + to_text(double(init.steps) * s.dt / ms) + " ms of " + to_text(starts.back() / ms) +
                         " ms; continued at the next start");
        continue;
      }

      // ---- runs from each starting state -------------------------------------------------------
      for (std::size_t k = 0; k < starts.size(); ++k) {
        const scene::Checkpoint start = scene::read_checkpoint(start_file + to_text(k) + ".h5");
        const index_t nr = rbc.n;
        std::vector<double> red = host(start.state.batches.at(0));
        red.resize(std::size_t(3 * 8 * nr));  // X, the first 3N columns of the n x 6N state
        std::mt19937_64 prng(seed + 100 * (wi + 1) + k);
        PlateletSpec ps;
        ps.min_separation = 3.1 * um + 4 * s.h;
        const std::vector<double> E = host(start.state.points.at(0));
        const PlateletPlacement placed = place_platelets(plt, box, E, red, nr, 2, ps, prng);
        layout_t["rows"].push(Json::Array{Json(w.name + " start " + to_text(k)), Json(double(layout.moved)), Json(double(layout.draws)),
                                          Json(layout.closest / um), Json(double(placed.draws)), Json(placed.gaps[0] / um),
                                          Json(placed.gaps[1] / um), Json(start_list)});
        for (bool with_red : {true, false}) {
          if (!with_red && w.bump == 0) continue;  // the seed removes the red cells over the bumpy wall only
          const std::string tag = w.name + (with_red ? "" : "_no_red_cells") + "_" + to_text(k);
          const double t_end = starts[k] + s.window;
          const std::string text =
              scene_text(s, w, with_red ? layout.red_cells : std::vector<cells::Placement>{}, placed.platelets, t_end, "a run from a starting state");
          st::SceneRunHooks h;
          h.prepare = [&](sim::ImmersedBoundary& ib) { start_from(ib, start, with_red); };
          h.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport*) { return sample_run(ib, with_red, box).row(); };
          // Snapshots for ParaView (the first starting state's runs): at the start, every tenth of the run, at the end.
          std::unique_ptr<scene::SnapshotWriter> writer;
          const long snapshot_every = std::max(1L, std::lround(s.window / s.dt) / 10);
          if (k == 0)
            h.after_step = [&](const sim::ImmersedBoundary& ib) {
              if (!writer) {
                writer = std::make_unique<scene::SnapshotWriter>(opt.out_dir + "/snapshots_" + tag, ib);
                writer->resume(ib.time());
              }
              if ((ib.step_count() - start.state.steps) % snapshot_every == 0) writer->write(ib);
            };
          const st::SceneRun run = st::run_scene(text, tag, s.every, full, opt, h, remaining());
          const long needed = std::lround(s.window / s.dt);
          const long done = run.steps - start.state.steps;
          add_cost(tag, double(done), double(needed), run.seconds_per_step());
          if (!run.finished) {
            all_done = false;
            continue;
          }
          if (!run.stopped.empty()) throw NumericalError("run " + tag + " stopped: " + run.stopped);

          // ---- analysis of the run ----------------------------------------------------------------
          std::vector<RunSample> rows;
          for (const std::vector<double>& r : run.samples) rows.push_back(RunSample::from(r));
          const std::size_t first = rows.size() / 2;  // the profile: averaged over the second half
          const std::size_t ny = rows.front().u.size();
          std::vector<double> y(ny), u(ny, 0.0);
          for (std::size_t j = 0; j < ny; ++j) y[j] = (double(j) + 0.5) * Ly / double(ny);
          for (std::size_t i = first; i < rows.size(); ++i)
            for (std::size_t j = 0; j < ny; ++j) u[j] += rows[i].u[j] / double(rows.size() - first);
          for (std::size_t j = 0; j < ny; ++j)
            profiles["rows"].push(Json::Array{Json(tag), Json(y[j] / um), Json(u[j] * 10)});
          const double gdot = profile_slope(y, u, 1 * um, 4 * um);
          shear[tag] = gdot;
          const Couette fit = couette_fit(y, u, 3 * um, 11.5 * um), fit0 = couette_fit(y, rows.front().u, 3 * um, 11.5 * um);
          if (!with_red) {
            worst_couette = std::max(worst_couette, fit.deviation);
            no_slip_height = fit.no_slip_height;
          }
          // Platelets.
          double unicycling = 0, headroom = INFINITY, volume = 0, red_min = INFINITY, plt_red = INFINITY;
          for (int c = 0; c < 2; ++c) {
            auto aspect = [](const PlateletSample& q) { return q.extent[0] / std::max(q.extent[1], q.extent[2]); };
            const double aspect0 = aspect(rows.front().p[c]);
            for (const RunSample& r : rows) {
              const PlateletSample& q = r.p[c];
              const bool uni = st::axis_angle(q.axis, vorticity_dir) < pi / 4;
              platelets_t["rows"].push(Json::Array{Json(tag + " platelet " + to_text(c + 1)), Json(r.t / ms), Json(q.to_endothelium / um),
                                                   Json(2 * s.h / um), Json(uni ? 1.0 : 0.0), Json(q.min_speed * 10), Json(aspect(q) / aspect0 - 1)});
              unicycling += (uni ? 1.0 : 0.0) / double(2 * rows.size());
              min_platelet_endothelium = std::min(min_platelet_endothelium, q.to_endothelium / um);
              min_clearance = std::min(min_clearance, q.clearance / um);
              headroom = std::min(headroom, q.headroom);
              if (q.volume > 0) volume = std::max(volume, std::abs(q.volume / v_plt_ref - 1));
            }
          }
          if (with_red) {
            for (const RunSample& r : rows) {
              red_min = std::min(red_min, r.red_gap / s.h), plt_red = std::min(plt_red, r.platelet_red_gap / s.h);
              if (r.red_volume_min > 0) volume = std::max({volume, std::abs(r.red_volume_min / v_ref - 1), std::abs(r.red_volume_max / v_ref - 1)});
            }
            closest_red = std::min(closest_red, red_min), closest_platelet_red = std::min(closest_platelet_red, plt_red);
            min_headroom = std::min(min_headroom, headroom);
          }
          worst_volume = std::max(worst_volume, volume);
          runs_t["rows"].push(Json::Array{Json(tag), Json(starts[k] / ms), Json(t_end / ms), Json(double(done)), Json(run.seconds_per_step()),
                                          Json(gdot), Json(fit0.deviation), Json(fit.deviation), Json(fit.no_slip_height / um), Json(red_min),
                                          Json(plt_red), Json(headroom / um), Json(unicycling), Json(volume)});
          st::log(opt, tag + ": shear in the platelet layer " + to_text(gdot) + " 1/s (start of the run: " +
                           to_text(profile_slope(y, rows.front().u, 1 * um, 4 * um)) + "), deviation from Couette " + to_text(fit0.deviation) + " -> " +
                           to_text(fit.deviation) + ", no-slip height " + to_text(fit.no_slip_height / um) + " um" +
                           ", closest red cells " + to_text(red_min) + " h, platelet-red " + to_text(plt_red) + " h, volume change " + to_text(volume));
          // A side view (along x) of the cells and the endothelium at the end.
          if (k == 0 && with_red) {
            const std::vector<double> Ee = host(run.final_points.at(0));
            const std::size_t m = Ee.size() / 3;
            for (std::size_t i = 0; i < m; i += 8)
              snapshot_t["rows"].push(Json::Array{Json("endothelium"), Json(Ee[2 * m + i] / um), Json(Ee[m + i] / um)});
          }
          if (k == 0 && with_red)
            for (std::size_t b = 0; b < run.final_positions.size(); ++b) {
              const std::vector<double>& X = run.final_positions[b];
              const index_t n = b == 0 ? rbc.n : plt.n, N = index_t(X.size() / std::size_t(3 * n));
              for (index_t c = 0; c < N; ++c)
                for (index_t i = 0; i < n; i += (n > 1000 ? 4 : 1))
                  snapshot_t["rows"].push(Json::Array{Json((b == 0 ? "red cell " : "platelet ") + to_text(c + 1)),
                                                      Json(std::fmod(X[std::size_t((2 * N + c) * n + i)] + 16 * Lz, Lz) / um),
                                                      Json(X[std::size_t((N + c) * n + i)] / um)});
            }
        }
      }
    }

    V["hours_to_solution"] = hours_left;
    cost["rows"].push(Json::Array{Json("all"), Json(s.h / um), Json(s.dt / units::ns), Json(NAN), Json(NAN), Json(NAN), Json(hours_left)});
    // ---- summary values -------------------------------------------------------------------------
    V["completed"] = all_done ? 1.0 : 0.0;
    V["red_cell_volume_um3"] = v_ref;
    V["hematocrit_above_endothelium"] = 8 * v_ref / (16 * 12 * 16 - 16 * 16 * 1.0);
    V["hematocrit_above_3um"] = 8 * v_ref / (16 * 16 * 9.0);
    V["hematocrit_above_3um_below_10um"] = 8 * v_ref / (16 * 16 * 7.0);
    if (all_done) {
      V["closest_red_cells_over_h"] = closest_red;
      V["closest_platelet_red_over_h"] = closest_platelet_red;
      V["min_platelet_endothelium_um"] = min_platelet_endothelium;
      V["min_platelet_clearance_um"] = min_clearance;
      V["platelet_headroom_um"] = min_headroom / um;
      V["no_slip_height_without_red_cells_um"] = no_slip_height / um;
      V["couette_deviation_without_red_cells"] = worst_couette;
      V["volume_change"] = worst_volume;
      const auto with = shear.find("bumpy_0"), without = shear.find("bumpy_no_red_cells_0");
      if (with != shear.end() && without != shear.end()) {
        V["shear_platelet_layer_bumpy"] = with->second;
        V["shear_platelet_layer_bumpy_no_red_cells"] = without->second;
        V["shear_ratio_with_over_without_red_cells"] = with->second / without->second;
      }
      if (shear.count("flat_0")) V["shear_platelet_layer_flat"] = shear["flat_0"];
    }
    results["tables"]["profiles"] = profiles;
    results["tables"]["platelets"] = platelets_t;
    results["tables"]["runs"] = runs_t;
    results["tables"]["procedure"] = layout_t;
    results["tables"]["snapshot"] = snapshot_t;
    results["tables"]["cost"] = cost;
    st::write_results(opt, results);
    return 0;
  });
}
