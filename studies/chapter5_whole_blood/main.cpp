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
// than 4% (Fig. 5.6); per red cell the turning of a tracked data site about its centre in the shear
// plane less the turning of its short axis (the tank-treading period of Sec. 5.2.2); the smallest
// distances between cells; volumes; the hematocrit; the platelet placement's attempts.
// Each init run and each run from a starting state is recorded as a run (results' runs): init_<wall>,
// <wall>_<k>, bumpy_no_red_cells_<k>.
//   full:  the seed's sizes (h = 0.2 um, red cells 2,500 / 10,000 sites, platelets 900 / 900,
//          16,000 endothelium points, dt = 50 ns), 4 starting times, 40 ms per run over the bumpy
//          wall and 60 ms over the flat one (the seed's flat-wall unicycling 'lasted over 40 ms'),
//          continued from checkpoints; --sitting SECONDS limits one sitting's wall time;
//   quick: h = 0.4 um, red cells 400 / 1,600, platelets 400 / 400, 4,096 endothelium points (the
//          seed's spacing in units of h), dt = 100 ns (the tethers' explicit limit is about
//          2 mu / (k n_A h), n_A points per area: 128 ns here, 64 ns at the seed's h); the
//          procedure compressed: the wall turns over 20 us, the flow settles to 30 us, one
//          starting time, 80 us per run; the bumpy wall with and without red cells.
//
// Run:   build/studies/study_chapter5_whole_blood --scale quick --out runs/chapter5_whole_blood
#include "chapter5_whole_blood/initialization.hpp"
#include "rbfib/core/constants.hpp"
#include "common/cell_shape.hpp"
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/io/snapshot.hpp"

#include <algorithm>
#include <cctype>
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
  double turn, settle, mean_gap, window, flat_window;  // s; the runs' length over the bumpy and the flat wall
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
                       double t_end, const std::string& what, const std::string& start = "", bool keep_red = false) {
  std::string types, cells_text;
  if (!red.empty() || keep_red)
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
         "ib: {kernel: bspline3}\n" +
         (start.empty() ? std::string() : "start: {checkpoint: " + start + (keep_red ? ", keep: [red cell]" : "") + "}\n") +
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
constexpr int red_cell_count = 8;
struct RunSample {
  double t = 0;
  PlateletSample p[2];
  double red_gap = NAN, platelet_red_gap = NAN;   ///< closest red cells; closest platelet-red cell (cm)
  double red_volume_min = NAN, red_volume_max = NAN;  ///< um^3
  /// Per red cell, in the shear plane (flow_dir, e2): the angle of its tracked data site about its
  /// centre and the angle of its short axis (rad, atan2 of the e2 and flow_dir components); NaN without red cells.
  double material[red_cell_count], short_axis[red_cell_count];
  std::vector<double> u;                         ///< the velocity profile (cm/s)

  RunSample() { std::fill_n(material, red_cell_count, NAN), std::fill_n(short_axis, red_cell_count, NAN); }

  std::vector<double> row() const {
    std::vector<double> r{t};
    for (const PlateletSample& q : p) {
      r.insert(r.end(), q.center.begin(), q.center.end());
      r.insert(r.end(), q.axis.begin(), q.axis.end());
      r.insert(r.end(), q.extent.begin(), q.extent.end());
      r.insert(r.end(), {q.to_endothelium, q.clearance, q.min_speed, q.volume, q.headroom});
    }
    r.insert(r.end(), {red_gap, platelet_red_gap, red_volume_min, red_volume_max});
    r.insert(r.end(), material, material + red_cell_count);
    r.insert(r.end(), short_axis, short_axis + red_cell_count);
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
    for (double& x : s.material) x = r.at(k++);
    for (double& x : s.short_axis) x = r.at(k++);
    s.u.assign(r.begin() + long(k), r.end());
    return s;
  }
};

/// The angle of a vector in the shear plane of the final flow: counterclockwise from flow_dir toward e2 (rad).
double shear_plane_angle(const Vec3& v) { return std::atan2(v[1], v[0] * flow_dir[0] + v[2] * flow_dir[2]); }

/// Per red cell, the data site tracked for its tank-treading: the one farthest from the cell's
/// centre in the shear plane (its rim in that plane) in the sites X (n x 3N, a batch's layout).
std::vector<index_t> tracked_sites(const std::vector<double>& X, index_t n, index_t N) {
  std::vector<index_t> site(std::size_t(N), 0);
  for (index_t c = 0; c < N; ++c) {
    const st::CellShape shape = st::cell_shape(X, n, N, c);
    double best = -1;
    for (index_t i = 0; i < n; ++i) {
      Vec3 d;
      for (int k = 0; k < 3; ++k) d[std::size_t(k)] = X[std::size_t((k * N + c) * n + i)] - shape.center[std::size_t(k)];
      const double a = d[0] * flow_dir[0] + d[2] * flow_dir[2], q = a * a + d[1] * d[1];
      if (q > best) best = q, site[std::size_t(c)] = i;
    }
  }
  return site;
}

RunSample sample_run(const sim::ImmersedBoundary& ib, bool red, const Domain& box, const std::vector<index_t>& tracked) {
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
    for (index_t c = 0; c < Nr && c < red_cell_count; ++c) {
      const st::CellShape shape = st::cell_shape(XR, nr, Nr, c);
      const index_t i = tracked.at(std::size_t(c));
      Vec3 d;
      for (int k = 0; k < 3; ++k) d[std::size_t(k)] = XR[std::size_t((k * Nr + c) * nr + i)] - shape.center[std::size_t(k)];
      out.material[c] = shear_plane_angle(d);
      out.short_axis[c] = shear_plane_angle(shape.axes[0]);
    }
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

/// The longest stretch of consecutive samples with flag set: the time from its first to its last sample (s).
double longest_interval(const std::vector<double>& t, const std::vector<bool>& flag) {
  double longest = 0;
  std::size_t first = 0;
  bool in = false;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (flag[i] && !in) first = i, in = true;
    if (in && (!flag[i] || i + 1 == t.size())) {
      const std::size_t last = flag[i] ? i : i - 1;
      longest = std::max(longest, t[last] - t[first]);
      in = false;
    }
  }
  return longest;
}

/// A value measured over a set of runs: written when every one of them has finished, NaN before.
struct Measured {
  double value;
  bool runs_finished;
};
}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_whole_blood", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_whole_blood",
                                                   "Sec. 5.2: whole blood over a flat and a bumpy endothelium (Figs. 5.4-5.6)");
    const bool full = opt.scale == st::Scale::full;
    const Setup s = full ? Setup{0.2 * um, 50 * units::ns, 2500, 10000, 900, 16000, 7.2 * ms, 17 * ms, 3 * ms, 40 * ms, 60 * ms, 4, {flat, bumpy}, 400}
                         : Setup{0.4 * um, 100 * units::ns, 400, 1600, 400, 4096, 20 * us, 30 * us, 10 * us, 80 * us, 80 * us, 1, {bumpy}, 10};
    auto window = [&](const Wall& w) { return w.bump > 0 ? s.window : s.flat_window; };
    const st::Sitting sitting(opt);  // full scale: this sitting's wall time
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
                     " starting time(s) with exponential gaps of mean " + to_text(s.mean_gap / us) + " us, runs of " + to_text(s.window / us) +
                     " us" + (full ? " over the bumpy wall and " + to_text(s.flat_window / us) + " us over the flat one" : "");
    P["seed"] = double(seed);
    P["kernel_integrator_coupling"] = "B3 kernel, backward-forward Euler, the seed's coupling (a)-(g)";

    const ReferenceSites rbc = reference_sites(cells::red_cell_spec(s.rbc_nd, s.rbc_ns)), plt = reference_sites(cells::platelet_spec(s.plt_n, s.plt_n));

    Json profiles = st::table({"run", "y_um", "u_mm_s"}, {"", "um", "mm/s"});
    for (double y : {0.0, 12.0}) profiles["rows"].push(Json::Array{Json("Couette between the walls"), Json(y), Json(wall_speed * 10 * y / 12)});
    Json platelets_t = st::table({"run", "t_ms", "distance_um", "two_h_um", "unicycling", "min_speed_mm_s", "aspect_change"},
                                 {"", "ms", "um", "um", "", "mm/s", ""});
    Json runs_t = st::table({"run", "t_start_ms", "t_end_ms", "steps", "seconds_per_step", "shear_platelet_layer_1_s", "couette_deviation_start",
                             "couette_deviation", "no_slip_height_um", "closest_red_cells_over_h", "closest_platelet_red_over_h",
                             "platelet_headroom_um", "unicycling_fraction", "longest_unicycling_ms", "max_distance_um", "max_aspect_change",
                             "tank_treading_period_ms", "volume_change"},
                            {"", "ms", "ms", "", "s", "1/s", "", "", "um", "", "", "um", "", "ms", "um", "", "ms", ""});
    Json treading_t = st::table({"run", "cell", "material_turn_deg", "short_axis_turn_deg", "relative_turn_deg", "period_ms"},
                                {"", "", "deg", "deg", "deg", "ms"});
    Json layout_t = st::table({"wall", "moved", "draws", "closest_um", "platelet_draws", "attempts_platelet_1", "attempts_platelet_2",
                               "refused_red_cells", "refused_surface_or_box", "gap1_um", "gap2_um", "starting_times_ms"},
                              {"", "", "", "um", "", "", "", "", "", "um", "um", "ms"});
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
    // Which runs have finished, by kind: the values measured over a kind are written once all its runs have.
    bool inits_done = true, red_runs_done = true, free_runs_done = true, flat_runs_done = true;
    std::map<std::string, double> shear;  // per run: the platelet layer's shear rate
    double worst_volume = 0, worst_couette = 0, closest_red = INFINITY, closest_platelet_red = INFINITY, min_platelet_endothelium = INFINITY;
    double min_headroom = INFINITY, no_slip_sum = 0, min_clearance = INFINITY;
    double max_distance_red = 0, max_aspect = 0, longest_unicycling_flat = 0;
    int free_runs = 0;
    std::vector<double> frequencies;      // tank-treading turns per second, per red cell and run with red cells (1/s)
    std::vector<double> attempts;         // platelet points drawn per platelet placed
    int refused_red = 0, refused_surface = 0;
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
      const double run_window = window(w);
      auto run_tags = [&](std::size_t k) {
        std::vector<std::string> tags{w.name + "_" + to_text(k)};
        if (w.bump > 0) tags.push_back(w.name + "_no_red_cells_" + to_text(k));  // the seed removes the red cells over the bumpy wall only
        return tags;
      };

      // ---- init: endothelium and red cells, the wall turning ------------------------------------
      const std::string init_text = scene_text(s, w, layout.red_cells, {}, starts.back(), "init");
      {
        // An example for `rbfib run` (scenes/whole_blood_*.yaml): the same layout with platelets placed
        // by the same algorithm against the red cells as laid out, the flow from rest, 40 us.
        std::mt19937_64 erng(seed + 50 + wi);
        const std::vector<double> batch = batch_layout(rbc, layout.red_cells);
        PlateletSpec ps;
        ps.min_separation = 3.1 * um + 4 * s.h;
        const scene::Scene init_scene = scene::parse_scene(init_text, "init");
        const std::vector<double> E = scene::point_positions(init_scene.point_sets.at(0).surface, init_scene.grid.length);
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
          if (ib.step_count() == start_steps[k]) io::write_checkpoint(start_file + to_text(k) + ".h5", init_text, ib);
      };
      ih.at_start = [&](const sim::ImmersedBoundary& ib) { v_ref = ib.batch(0).type().reference_volume() / std::pow(um, 3); };
      // A sitting's budget is shared by the walls' init runs still to come.
      const st::SceneRun init = st::run_scene(init_text, "init_" + w.name, s.every, full, opt, ih, remaining() / double(s.walls.size() - wi));
      st::record_run(results, "init_" + w.name, init.progress(starts.back()));
      const long init_needed = std::lround(starts.back() / s.dt);
      add_cost("init " + w.name, double(init.steps), double(init_needed), init.seconds_per_step());
      if (!init.stopped.empty()) throw NumericalError(Cause::solver, "the init run (" + w.name + ") stopped: " + init.stopped);
      for (const auto& r : init.samples) closest_red = std::min(closest_red, r[2] / s.h);
      if (!init.finished) {
        inits_done = red_runs_done = false;
        if (w.bump > 0) free_runs_done = false;
        if (w.bump == 0) flat_runs_done = false;
        // The runs from its starting states are still to come: their steps at the init's rate
        // (they carry two platelets more, a few percent of the step).
        for (std::size_t k = 0; k < starts.size(); ++k)
          for (const std::string& tag : run_tags(k)) {
            add_cost(tag + " (to come)", 0, std::round(run_window / s.dt), init.seconds_per_step());
            st::record_run(results, tag, st::RunProgress{false, 0, run_window, 0, init.seconds_per_step(), ""});
          }
        st::log(opt, w.name + ": init run at t = " + to_text(double(init.steps) * s.dt / ms) + " ms of " + to_text(starts.back() / ms) +
                         " ms; continued at the next start");
        continue;
      }

      // ---- runs from each starting state -------------------------------------------------------
      for (std::size_t k = 0; k < starts.size(); ++k) {
        const io::Checkpoint start = io::read_checkpoint(start_file + to_text(k) + ".h5");
        const index_t nr = rbc.n;
        std::vector<double> red = host(start.state.batches.at(0));
        red.resize(std::size_t(3 * red_cell_count * nr));  // X, the first 3N columns of the n x 6N state
        const std::vector<index_t> tracked = tracked_sites(red, nr, red_cell_count);
        std::mt19937_64 prng(seed + 100 * (wi + 1) + k);
        PlateletSpec ps;
        ps.min_separation = 3.1 * um + 4 * s.h;
        const std::vector<double> E = host(start.state.points.at(0));
        const PlateletPlacement placed = place_platelets(plt, box, E, red, nr, 2, ps, prng);
        for (int a : placed.attempts) attempts.push_back(double(a));
        refused_red += placed.refused_red_cells, refused_surface += placed.refused_surface;
        layout_t["rows"].push(Json::Array{Json(w.name + " start " + to_text(k)), Json(double(layout.moved)), Json(double(layout.draws)),
                                          Json(layout.closest / um), Json(double(placed.draws)), Json(double(placed.attempts.at(0))),
                                          Json(double(placed.attempts.at(1))), Json(double(placed.refused_red_cells)),
                                          Json(double(placed.refused_surface)), Json(placed.gaps[0] / um), Json(placed.gaps[1] / um), Json(start_list)});
        for (bool with_red : {true, false}) {
          if (!with_red && w.bump == 0) continue;  // the seed removes the red cells over the bumpy wall only
          const std::string tag = w.name + (with_red ? "" : "_no_red_cells") + "_" + to_text(k);
          const double t_end = starts[k] + run_window;
          const std::string text = scene_text(s, w, {}, placed.platelets, t_end, "a run from a starting state",
                                              start_file + to_text(k) + ".h5", with_red);
          st::SceneRunHooks h;
          h.sample = [&](const sim::ImmersedBoundary& ib, const sim::IbStepReport*) { return sample_run(ib, with_red, box, tracked).row(); };
          // Snapshots for ParaView (the first starting state's runs): at the start, every tenth of the run, at the end.
          std::unique_ptr<io::SnapshotWriter> writer;
          const long snapshot_every = std::max(1L, std::lround(run_window / s.dt) / 10);
          if (k == 0)
            h.after_step = [&](const sim::ImmersedBoundary& ib) {
              if (!writer) {
                writer = std::make_unique<io::SnapshotWriter>(opt.out_dir + "/snapshots_" + tag, ib);
                writer->resume(ib.time());
              }
              if ((ib.step_count() - start.state.clock.step) % snapshot_every == 0) writer->write(ib);
            };
          const st::SceneRun run = st::run_scene(text, tag, s.every, full, opt, h, remaining());
          const long needed = std::lround(run_window / s.dt);
          const long done = run.steps - start.state.clock.step;
          // The run's own span: from its starting time, steps from its start.
          st::RunProgress progress = run.progress(t_end);
          progress.t -= starts[k], progress.t_end = run_window, progress.steps = done;
          st::record_run(results, tag, progress);
          add_cost(tag, double(done), double(needed), run.seconds_per_step());
          if (!run.finished) {
            (with_red ? red_runs_done : free_runs_done) = false;
            if (with_red && w.bump == 0) flat_runs_done = false;
            continue;
          }
          if (!run.stopped.empty()) throw NumericalError(Cause::solver, "run " + tag + " stopped: " + run.stopped);

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
            no_slip_sum += fit.no_slip_height, ++free_runs;
          }
          // Platelets.
          double unicycling = 0, headroom = INFINITY, volume = 0, red_min = INFINITY, plt_red = INFINITY;
          double longest_uni = 0, max_dist = 0, max_asp = 0;
          std::vector<double> times;
          for (const RunSample& r : rows) times.push_back(r.t);
          for (int c = 0; c < 2; ++c) {
            auto aspect = [](const PlateletSample& q) { return q.extent[0] / std::max(q.extent[1], q.extent[2]); };
            const double aspect0 = aspect(rows.front().p[c]);
            std::vector<bool> uni_flags;
            for (const RunSample& r : rows) {
              const PlateletSample& q = r.p[c];
              const bool uni = st::axis_angle(q.axis, vorticity_dir) < pi / 4;
              const double change = aspect(q) / aspect0 - 1;
              platelets_t["rows"].push(Json::Array{Json(tag + " platelet " + to_text(c + 1)), Json(r.t / ms), Json(q.to_endothelium / um),
                                                   Json(2 * s.h / um), Json(uni ? 1.0 : 0.0), Json(q.min_speed * 10), Json(change)});
              uni_flags.push_back(uni);
              unicycling += (uni ? 1.0 : 0.0) / double(2 * rows.size());
              min_platelet_endothelium = std::min(min_platelet_endothelium, q.to_endothelium / um);
              min_clearance = std::min(min_clearance, q.clearance / um);
              headroom = std::min(headroom, q.headroom);
              max_dist = std::max(max_dist, q.to_endothelium / um);
              max_asp = std::max(max_asp, std::abs(change));
              if (q.volume > 0) volume = std::max(volume, std::abs(q.volume / v_plt_ref - 1));
            }
            longest_uni = std::max(longest_uni, longest_interval(times, uni_flags));
          }
          max_aspect = std::max(max_aspect, max_asp);
          double period_median = NAN;
          if (with_red) {
            for (const RunSample& r : rows) {
              red_min = std::min(red_min, r.red_gap / s.h), plt_red = std::min(plt_red, r.platelet_red_gap / s.h);
              if (r.red_volume_min > 0) volume = std::max({volume, std::abs(r.red_volume_min / v_ref - 1), std::abs(r.red_volume_max / v_ref - 1)});
            }
            closest_red = std::min(closest_red, red_min), closest_platelet_red = std::min(closest_platelet_red, plt_red);
            min_headroom = std::min(min_headroom, headroom);
            max_distance_red = std::max(max_distance_red, max_dist);
            if (w.bump == 0) longest_unicycling_flat = std::max(longest_unicycling_flat, longest_uni);
            // Tank-treading: the tracked site's mean turning about the centre, less the short axis's,
            // over the whole run, in turns per second; one period is a relative turn of 2 pi in the
            // flow's sense. The shear turns shear_plane_angle negatively (u = gdot y flow_dir:
            // d(angle)/dt = -gdot sin^2(angle)), so a membrane that lags its body, or none that turns,
            // tank-treads at 0 per second (an infinite period).
            std::vector<double> run_frequencies;
            for (int c = 0; c < red_cell_count; ++c) {
              std::vector<double> m, a;
              for (const RunSample& r : rows) m.push_back(r.material[c]), a.push_back(r.short_axis[c]);
              m = st::unwrap(m, 2 * pi), a = st::unwrap(a, pi);
              const double dm = m.back() - m.front(), da = a.back() - a.front(), span = times.back() - times.front();
              const double frequency = std::max(0.0, da - dm) / (2 * pi * span), period = 1 / frequency;
              run_frequencies.push_back(frequency);
              frequencies.push_back(frequency);
              treading_t["rows"].push(Json::Array{Json(tag), Json(double(c + 1)), Json(dm * 180 / pi), Json(da * 180 / pi),
                                                  Json((dm - da) * 180 / pi), Json(period / ms)});
            }
            period_median = 1 / st::median(run_frequencies);
          }
          worst_volume = std::max(worst_volume, volume);
          runs_t["rows"].push(Json::Array{Json(tag), Json(starts[k] / ms), Json(t_end / ms), Json(double(done)), Json(run.seconds_per_step()),
                                          Json(gdot), Json(fit0.deviation), Json(fit.deviation), Json(fit.no_slip_height / um), Json(red_min),
                                          Json(plt_red), Json(headroom / um), Json(unicycling), Json(longest_uni / ms), Json(max_dist),
                                          Json(max_asp), Json(period_median / ms), Json(volume)});
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
    // ---- summary values: each written once every run it is measured over has finished (NaN before) ----
    const bool all_runs_done = red_runs_done && free_runs_done;
    auto put = [&](const std::string& name, const Measured& m) { V[name] = m.runs_finished ? m.value : NAN; };
    put("closest_red_cells_over_h", {closest_red, inits_done && red_runs_done});
    put("closest_platelet_red_over_h", {closest_platelet_red, red_runs_done});
    put("min_platelet_endothelium_um", {min_platelet_endothelium, all_runs_done});
    put("min_platelet_clearance_um", {min_clearance, all_runs_done});
    put("platelet_headroom_um", {min_headroom / um, red_runs_done});
    put("no_slip_height_without_red_cells_um", {no_slip_sum / std::max(free_runs, 1) / um, free_runs_done && free_runs > 0});
    put("couette_deviation_without_red_cells", {worst_couette, free_runs_done && free_runs > 0});
    put("volume_change", {worst_volume, all_runs_done});
    put("max_platelet_distance_um", {max_distance_red, red_runs_done});
    put("max_aspect_change", {max_aspect, all_runs_done});
    put("rbc_tank_treading_frequency_1_s", {st::median(frequencies), red_runs_done});
    put("rbc_tank_treading_period_ms", {1 / st::median(frequencies) / ms, red_runs_done});  // infinite (null) for none
    const bool has_flat = std::any_of(s.walls.begin(), s.walls.end(), [](const Wall& w) { return w.bump == 0; });
    put("longest_unicycling_ms_flat", {longest_unicycling_flat / ms, has_flat && flat_runs_done});
    // Shear rates in the platelet layer: the mean over the starting times of each kind of run.
    auto mean_shear = [&](const std::string& prefix) {
      double sum = 0;
      int n = 0;
      for (const auto& [tag, g] : shear)
        if (tag.rfind(prefix, 0) == 0 && std::isdigit(static_cast<unsigned char>(tag[prefix.size()]))) sum += g, ++n;
      return n > 0 ? sum / n : NAN;
    };
    const double with = mean_shear("bumpy_"), without = mean_shear("bumpy_no_red_cells_");
    put("shear_platelet_layer_bumpy", {with, red_runs_done});
    put("shear_platelet_layer_bumpy_no_red_cells", {without, free_runs_done});
    put("shear_ratio_with_over_without_red_cells", {with / without, red_runs_done && free_runs_done});
    if (has_flat) put("shear_platelet_layer_flat", {mean_shear("flat_"), flat_runs_done});
    // The platelet placement (Sec. 5.2.1): attempts per platelet over every starting state.
    put("platelet_attempts_median", {st::median(attempts), inits_done});
    double attempts_mean = 0;
    for (double a : attempts) attempts_mean += a / double(attempts.size());
    put("platelet_attempts_mean", {attempts.empty() ? NAN : attempts_mean, inits_done});
    put("platelet_draws_refused_red_cells", {double(refused_red), inits_done});
    put("platelet_draws_refused_surface_or_box", {double(refused_surface), inits_done});
    // The hematocrit (conventions: hematocrit): 8 red cells of the reference volume over the fluid above
    // the endothelium (mean height 1 um for both shapes), and the other readings for comparison.
    const double area = 16 * 16, above = 12 - 1.0;  // um^2, um
    const double red_volume = red_cell_count * v_ref;  // um^3
    V["red_cell_volume_um3"] = v_ref;
    V["hematocrit_above_endothelium"] = red_volume / (area * above);
    V["hematocrit_above_endothelium_without_top_1um"] = red_volume / (area * (above - 1));
    V["hematocrit_above_endothelium_without_top_2um"] = red_volume / (area * (above - 2));
    V["hematocrit_exclusion_ratio_1um"] = above / (above - 1);
    V["hematocrit_exclusion_ratio_2um"] = above / (above - 2);
    V["hematocrit_whole_box"] = red_volume / (area * 12);
    V["hematocrit_above_3um"] = red_volume / (area * 9.0);
    V["hematocrit_above_3um_below_10um"] = red_volume / (area * 7.0);
    V["red_volume_for_34_percent_um3"] = 0.34 * area * above;
    results["tables"]["profiles"] = profiles;
    results["tables"]["platelets"] = platelets_t;
    results["tables"]["runs"] = runs_t;
    results["tables"]["tank_treading"] = treading_t;
    results["tables"]["procedure"] = layout_t;
    results["tables"]["snapshot"] = snapshot_t;
    results["tables"]["cost"] = cost;
    st::write_results(opt, results);
    return 0;
  });
}
