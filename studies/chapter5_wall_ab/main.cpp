// The wall treatments on whole blood over the bumpy endothelium (seed Sec. 5.2, eq. 5.5), side by
// side over a short window: the seed's tethered endothelium (eq. 2.10, k = 2.5 dyn/cm, eta = 2.5e-7
// dyn s/cm per point) at its fixed 50 ns, against the two walls that let the step climb the seed's
// ladder (2^k x 50 ns, k = 0..4, by eq. 5.4):
//   rule:  the same tethers with k and eta following the step by the seed's own rule at gain 0.5
//          (sim/tether_stability.hpp), the wall chapter5_whole_blood runs;
//   held:  beyond the seed, the endothelium's surface held exactly by a solve (sim/held_wall.hpp),
//          markers about 2h apart on the same spiral (a bumpy wall: the dense mobility, built once
//          per rung of the ladder).
// The grid's own wall cannot carry the bumps, so it is compared on the flat wall only
// (chapter5_platelets). The scene is scenes/whole_blood_bumpy.yaml: eight red cells, two platelets
// placed facing the endothelium (Sec. 5.2.1), the top wall at 16 mm/s turning from z toward x.
//
// Measured at the window's end, each wall against the seed's tethers: the endothelium's largest
// displacement from its anchors and the RMS slip at them (at the held wall's markers: the flow the
// solve leaves), the platelets' clearance above the wall (the lowest data site above eq. 5.5's
// surface), the largest distance between a platelet's centre and its centre in the seed's run, the
// angle between their short axes, and the largest distance between red-cell centres; the mean step
// and the time per step (speed against error).
//   quick: the scene as written (h = 0.4 um, 400 / 1,600 red-cell and 400 / 400 platelet sites,
//          4,096 endothelium points, the turn over 20 us), 40 us; held wall 400 markers;
//   full:  the seed's sizes (h = 0.2 um, 2,500 / 10,000 and 900 / 900 sites, 16,000 points, the
//          turn over 7.2 ms), 0.2 ms, continued from checkpoints; held wall 1,600 markers.
//
// Run:   build/studies/study_chapter5_wall_ab --scale quick --out runs/chapter5_wall_ab
#include "common/scene_run.hpp"
#include "common/study.hpp"
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

namespace {

enum class Wall { tethers, rule, held };

struct Setup {
  double h = 0;           // cm
  bool seed_sites = false;
  index_t points = 0;     // tethered points on the spiral
  index_t markers = 0;    // held wall markers on the spiral
  double dt = 0;          // s: the seed's fixed step, the ladder's lowest rung
  double window = 0;      // s
  double turn = 0;        // s: the top wall's turn from z toward x
};

/// The bumpy whole-blood scene with the given wall.
scene::Scene wall_scene(const scene::Scene& base, const Setup& s, Wall w) {
  scene::Scene sc = base;
  const std::array<double, 3> L = base.grid.length;
  sc.grid = make_mac_grid(3, {int(std::lround(L[0] / s.h)), int(std::lround(L[1] / s.h)), int(std::lround(L[2] / s.h))}, L,
                          {MacBoundary::periodic, MacBoundary::dirichlet, MacBoundary::periodic});
  sc.walls[1][1].over = s.turn;
  sc.fluid_options.dt = s.dt;
  sc.t_end = s.window;
  sc.snapshot_every = 0;
  sc.checkpoint_every = 0;
  if (s.seed_sites)
    for (scene::CellTypeEntry& t : sc.types) {
      const cells::ForceModel model = t.spec.model;
      t = scene::cell_type(t.spec.name, t.preset, 0, 0, t.radius, t.degree);
      t.spec.model = model;
    }
  require(sc.point_sets.size() == 1 && sc.point_sets[0].surface.spiral, "chapter5_wall_ab: the scene's endothelium",
          to_text(sc.point_sets.size()) + " point sets", "must be one set on the spiral");
  scene::PointSetEntry& e = sc.point_sets[0];
  e.surface.points = s.points;
  if (w != Wall::tethers) sc.ib.adaptive = {true, s.dt, 4, 16, INFINITY};
  if (w == Wall::rule) e.k = 0, e.eta = 0, e.follow_gain = 0.5;
  if (w == Wall::held) {
    scene::PointSurface markers = e.surface;
    markers.points = s.markers;
    sc.held_walls.push_back({"endothelium", markers});
    sc.point_sets.clear();
  }
  return sc;
}

/// The endothelium's surface of eq. 5.5 under the scene's spiral.
scene::EndotheliumSurface surface_of(const scene::Scene& sc) {
  const scene::PointSurface& p = sc.point_sets.empty() ? sc.held_walls.at(0).surface : sc.point_sets[0].surface;
  return {p.at, p.bump, sc.grid.length[0], sc.grid.length[2]};
}

/// A sample: t, the endothelium's largest displacement from its anchors (cm; 0 for the held wall),
/// the RMS velocity at its anchors or markers (cm/s).
std::vector<double> sample(const sim::ImmersedBoundary& ib) {
  if (ib.held_walls() > 0) {
    const std::vector<double> U(ib.held_wall(0).velocity().begin(), ib.held_wall(0).velocity().end());
    double s = 0;
    for (double u : U) s += u * u;
    return {ib.time(), 0.0, U.empty() ? 0.0 : std::sqrt(3 * s / double(U.size()))};
  }
  const sim::TetherMotion m = sim::tether_motion(ib, 0);
  return {ib.time(), m.max_displacement, m.slip_rms};
}

/// What a run leaves at the window's end.
struct End {
  st::SceneRun run;
  std::vector<cells::CellShape> platelets, red_cells;
  double clearance[2] = {NAN, NAN};  // cm
  double displacement = NAN, slip_mean = NAN, slip_end = NAN, setup_seconds = 0;
};

/// The batches' index of a cell type in the scene (batches follow the order of the types).
index_t batch_of(const scene::Scene& sc, const std::string& type) {
  for (std::size_t b = 0; b < sc.types.size(); ++b)
    if (sc.types[b].spec.name == type) return index_t(b);
  throw InputError("chapter5_wall_ab: cell type", type, "is not in the scene");
}

End run_wall(const scene::Scene& sc, const std::string& id, const Setup& s, const st::Sitting& sitting, double share,
             const st::Options& opt, Json& results) {
  st::SceneRunHooks hooks;
  End e;
  hooks.sample = [](const sim::ImmersedBoundary& ib, const sim::IbStepReport*) { return sample(ib); };
  hooks.after_step = [&e](const sim::ImmersedBoundary& ib) {
    if (ib.held_walls() > 0) e.setup_seconds = ib.held_wall(0).seconds_building();
  };
  const std::string text = scene::to_yaml(sc, "chapter5_wall_ab: whole blood over the bumpy endothelium (Sec. 5.2), " + id);
  e.run = st::run_scene(text, id, run::Cadence{0, s.window / 100}, opt.keeps_runs(), opt, hooks, sitting.remaining() / share);
  st::record_run(results, id, e.run.progress(s.window));
  if (!e.run.finished || !e.run.stopped.empty()) return e;
  const index_t rb = batch_of(sc, "red cell"), pb = batch_of(sc, "platelet");
  const index_t nr = sc.types[std::size_t(rb)].spec.data_sites.size(), np = sc.types[std::size_t(pb)].spec.data_sites.size();
  const std::vector<double>& R = e.run.final_positions.at(std::size_t(rb));
  const std::vector<double>& P = e.run.final_positions.at(std::size_t(pb));
  const index_t Nr = index_t(R.size()) / (3 * nr), Np = index_t(P.size()) / (3 * np);
  for (index_t c = 0; c < Nr; ++c) e.red_cells.push_back(cells::cell_shape(R, nr, Nr, c));
  const scene::EndotheliumSurface wall = surface_of(sc);
  for (index_t c = 0; c < Np && c < 2; ++c) {
    e.platelets.push_back(cells::cell_shape(P, np, Np, c));
    double lowest = INFINITY;
    for (index_t i = 0; i < np; ++i) {
      const auto at = [&](index_t d) { return P[std::size_t((d * Np + c) * np + i)]; };
      lowest = std::min(lowest, at(1) - wall.height(at(0), at(2)));
    }
    e.clearance[c] = lowest;
  }
  e.displacement = 0;
  double s2 = 0;
  for (const auto& r : e.run.samples) e.displacement = std::max(e.displacement, r[1]), s2 += r[2] * r[2];
  e.slip_mean = std::sqrt(s2 / double(e.run.samples.size()));
  e.slip_end = e.run.samples.back()[2];
  return e;
}

double distance(const Vec3& a, const Vec3& b) { return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])); }

/// The angle between two axes taken as lines (deg).
double axis_angle(const Vec3& a, const Vec3& b) {
  const double c = std::abs(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
  return std::acos(std::min(1.0, c)) * 180 / pi;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter5_wall_ab", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter5_wall_ab",
                                                   "Sec. 5.2: the wall treatments against the seed's tethers on whole blood over the bumpy endothelium");
    const bool full = opt.scale == st::Scale::full;
    const double um = units::um, us = units::us, ns = units::ns;
    const Setup s = full ? Setup{0.2 * um, true, 16000, 1600, 50 * ns, 200 * us, 7.2 * units::ms}
                         : Setup{0.4 * um, false, 4096, 400, 50 * ns, 40 * us, 20 * us};
    const scene::Scene base = scene::load_scene(st::source_path(opt, "scenes/whole_blood_bumpy.yaml"));
    // The top wall's speed, from the scene: the slip is reported as a fraction of it.
    const scene::WallMotion& top = base.walls[1][1];
    const double top_speed = top.turning ? top.speed : std::hypot(top.velocity[0], top.velocity[1], top.velocity[2]);
    require(top_speed > 0, "chapter5_wall_ab: the scene's top wall speed", top_speed, "must be > 0 (the slip is a fraction of it)");
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["scene"] = "scenes/whole_blood_bumpy.yaml: 16 x 12 x 16 um, 8 red cells, 2 platelets, the top wall at " +
                 to_text(top_speed / units::mm) + " mm/s turning from z toward x by 45 deg";
    P["h_um"] = s.h / um;
    P["sites"] = s.seed_sites ? "the seed's: red cell 2,500 / 10,000, platelet 900 / 900" : "the scene's: red cell 400 / 1,600, platelet 400 / 400";
    P["endothelium_points"] = double(s.points);
    P["held_wall_markers"] = double(s.markers);
    P["dt_seed_ns"] = s.dt / ns;
    P["ladder"] = "2^k x 50 ns, k = 0..4, by eq. 5.4 (rule and held wall)";
    P["window_us"] = s.window / us;
    P["turn_us"] = s.turn / us;
    P["fluid"] = "rho = 1 g/cm^3, mu = 1 cP, backward-forward Euler, B3 kernel, the seed's coupling";

    const st::Sitting sitting(opt);
    struct Case {
      Wall wall;
      const char* id;
      const char* label;
      double share;
    };
    const Case cases[3] = {{Wall::tethers, "tethers", "tethers at 50 ns (k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm)", 3},
                           {Wall::rule, "tether_rule", "tethers following the step (gain 0.5), ladder", 2},
                           {Wall::held, "held_wall", "held wall (solved), ladder", 1}};
    End end[3];
    for (int k = 0; k < 3; ++k) end[k] = run_wall(wall_scene(base, s, cases[k].wall), cases[k].id, s, sitting, cases[k].share, opt, results);

    Json ab = st::table({"wall", "steps", "dt_mean_ns", "seconds_per_step", "setup_seconds", "speedup_over_seed", "wall_displacement_um",
                         "slip_rms_mean_um_s", "slip_rms_end_um_s", "clearance_um_0", "clearance_um_1", "platelet_shift_um", "platelet_turn_deg",
                         "red_cell_shift_um"},
                        {"", "", "ns", "s", "s", "", "um", "um/s", "um/s", "um", "um", "um", "deg", "um"});
    const End& seed = end[0];
    const bool seed_done = !seed.platelets.empty();
    Json& V = results["values"];
    for (int k = 0; k < 3; ++k) {
      const End& e = end[k];
      const bool done = !e.platelets.empty();
      const double steps = double(e.run.steps), t = e.run.samples.empty() ? 0.0 : e.run.samples.back()[0];
      const double mean_dt = steps > 0 ? t / steps : NAN;
      const double sps = e.run.steps_timed > 0 ? (e.run.seconds - e.setup_seconds) / double(e.run.steps_timed) : NAN;
      const double seed_sps = seed.run.steps_timed > 0 ? seed.run.seconds / double(seed.run.steps_timed) : NAN;
      // time to the window: the seed's steps x its time per step over this wall's
      const double speedup = (s.window / s.dt * seed_sps) / (s.window / mean_dt * sps);
      double shift = NAN, turn = NAN, red = NAN;
      if (done && seed_done) {
        shift = turn = red = 0;
        for (std::size_t c = 0; c < e.platelets.size(); ++c) {
          shift = std::max(shift, distance(e.platelets[c].center, seed.platelets[c].center));
          turn = std::max(turn, axis_angle(e.platelets[c].axes[0], seed.platelets[c].axes[0]));
        }
        for (std::size_t c = 0; c < e.red_cells.size(); ++c) red = std::max(red, distance(e.red_cells[c].center, seed.red_cells[c].center));
      }
      ab["rows"].push(row({cases[k].label, steps, mean_dt / ns, sps, e.setup_seconds, speedup, e.displacement / um, e.slip_mean / um,
                           e.slip_end / um, e.clearance[0] / um, e.clearance[1] / um, shift / um, turn, red / um}));
      const std::string key = std::string("_") + cases[k].id;
      V["platelet_shift_um" + key] = shift / um;
      V["platelet_shift_over_h" + key] = shift / s.h;
      V["red_cell_shift_over_h" + key] = red / s.h;
      V["slip_over_top_wall_speed" + key] = e.slip_end / top_speed;
      V["platelet_turn_deg" + key] = turn;
      V["red_cell_shift_um" + key] = red / um;
      V["slip_rms_end_um_s" + key] = e.slip_end / um;
      V["wall_displacement_um" + key] = e.displacement / um;
      st::log(opt, std::string(cases[k].id) + ": mean step " + to_text(mean_dt / ns) + " ns, " + to_text(sps) + " s per step; wall moved " +
                       to_text(e.displacement / um) + " um, slip " + to_text(e.slip_end / um) + " um/s; platelets " + to_text(shift / um) +
                       " um and " + to_text(turn) + " deg from the seed's, red cells " + to_text(red / um) + " um");
    }
    V["h_um"] = s.h / um;
    V["top_wall_speed_um_s"] = top_speed / um;
    results["tables"]["wall_ab"] = ab;
    st::write_results(opt, results);
    return 0;
  });
}
