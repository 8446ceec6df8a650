// The adaptive step's stability criterion (sim/ib_step.hpp; docs/derivations/membrane_stability)
// judged by speed against error, as the project requires before any default changes: each of three
// Chapter 5 scenes is run three times over the same window,
//   ladder      the seed's adaptive step, 2^k x 50 ns by eq. 5.4 (k <= 4, the studies' ladder),
//   stability   the stability criterion: rungs 2^k x 50 ns (k <= 8) capped by the membranes' bound
//               at gain 1/2, the growth guard on, eq. 5.4 the stop condition at 50 ns,
//   perturbed   the ladder from a start whose first cell is moved by 1e-7 um,
// each landing on the window's end. The divergence of a run is the largest distance between its
// cells' data sites and the ladder run's at the end (um, and in grid spacings h). Beside it the
// steps, the mean step, the seconds per step and the simulated time per wall hour.
// The scenes: one red cell in shear 1000/s (chapter5_shear's), two platelets over the grid's wall
// (chapter5_platelets' grid-wall variant), and whole blood's initialization over the flat
// endothelium (chapter5_whole_blood's: eight red cells, the endothelium's constants following the
// step, the top wall turning), all at 1 cP.
// Scales: quick, 50 us windows at coarse sizes (h = 0.8 / 0.4 um, 400 / 1,600 red-cell and 400 /
// 400 platelet sites); full, 1 ms with the studies' sizes (shear h = 0.4 um and 625 / 2,500 sites;
// platelets and whole blood h = 0.2 um, 900 / 900 and 2,500 / 10,000 sites), kept over sittings.
//
// Run:   build/studies/study_bench_step --scale quick --out runs/bench_step
#include "common/machine.hpp"
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/scene/scene.hpp"

#include <omp.h>

#include <cmath>
#include <string>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;

namespace {

/// The time section of a variant: the seed's ladder, or the stability criterion.
std::string time_section(const std::string& window, bool stability) {
  return "time: {integrator: backward_forward_euler, coupling: seed, dt: 50 ns, end: " + window + ", adaptive: " +
         (stability ? "{criterion: stability, dt_min: 50 ns, max_level: 8, grow_after: 4}}"
                    : "{dt_min: 50 ns, max_level: 4, grow_after: 16}}");
}

struct Sizes {
  int shear_cells, wall_cells[3], rbc_nd, rbc_ns, shear_nd, shear_ns, plt_n, endothelium;
};

/// One red cell in shear 1000/s between walls in y, lying flat and turned 1 rad about x (chapter5_shear).
std::string shear_scene(const Sizes& z, const std::string& time, double shift_um) {
  return "name: shear\ndomain:\n  size: [16 um, 16 um, 16 um]\n  periodic: [x, z]\n  walls:\n"
         "    y: {lower: [0 cm/s, 0 cm/s, -0.8 cm/s], upper: [0 cm/s, 0 cm/s, 0.8 cm/s]}\n  initial_flow: shear\n"
         "fluid: {density: 1 g/cm^3, viscosity: 1 cP}\ngrid: {cells: [" +
         to_text(z.shear_cells) + ", " + to_text(z.shear_cells) + ", " + to_text(z.shear_cells) + "]}\n" + time +
         "\nib: {kernel: bspline3}\ncell_types:\n  - {name: red cell, preset: red_cell, data_sites: " + to_text(z.shear_nd) +
         ", sample_sites: " + to_text(z.shear_ns) + "}\ncells:\n  - {type: red cell, center: [" + to_text(8 + shift_um) +
         " um, 8 um, 8 um], axis: [1, 0, 0], angle: -0.5707963267948966 rad}\noutput: {diagnostics_every: 1}\n";
}

/// Two platelets over the grid's flat wall in shear (chapter5_platelets' grid-wall variant: their
/// centres 4 h and 5 h above it, 0.8 and 1 um at h = 0.2 um).
std::string platelets_scene(const Sizes& z, const std::string& time, double shift_um) {
  const double h = 16.0 / z.wall_cells[0];  // um
  return "name: platelets\ndomain:\n  size: [16 um, 12 um, 16 um]\n  periodic: [x, z]\n  walls:\n"
         "    y: {lower: [0 cm/s, 0 cm/s, 0 cm/s], upper: [0 cm/s, 0 cm/s, 1.3090909090909093 cm/s]}\n  initial_flow: shear\n"
         "fluid: {density: 1 g/cm^3, viscosity: 1 cP}\ngrid: {cells: [" +
         to_text(z.wall_cells[0]) + ", " + to_text(z.wall_cells[1]) + ", " + to_text(z.wall_cells[2]) + "]}\n" + time +
         "\nib: {kernel: bspline3}\ncell_types:\n  - {name: platelet, preset: platelet, data_sites: " + to_text(z.plt_n) +
         ", sample_sites: " + to_text(z.plt_n) +
         "}\ncells:\n"
         "  - {type: platelet, center: [" + to_text(4 + shift_um) + " um, " + to_text(4 * h) + " um, 4 um], axis: [1, 0, 0], angle: 1.5707963267948966 rad}\n"
         "  - {type: platelet, center: [12 um, " + to_text(5 * h) + " um, 12 um], axis: [1, 0, 0], angle: 1.5707963267948966 rad}\n"
         "output: {diagnostics_every: 1}\n";
}

/// Whole blood's initialization over the flat endothelium (chapter5_whole_blood's first layout).
std::string whole_blood_scene(const Sizes& z, const std::string& time, double shift_um) {
  const double c[8][3] = {{4.3178191382, 5.8916072575, 1.7111930780},   {4.0278956945, 6.1331533796, 5.1173304155},
                          {4.1031741810, 6.6389428989, 10.434012051},   {4.0282113525, 6.1665101971, 13.916426052},
                          {12.069970255, 6.5634537165, 3.7160006675},   {12.490266597, 6.7963425254, 8.0179000909},
                          {12.153931965, 6.8475140804, 12.710776653},   {12.161293802, 5.6131580738, -0.006545756492}};
  const double a[8][4] = {{-0.07926482134, -0.42555845127, -0.90145276784, 0.18057977241}, {-0.90849787720, -0.36694737139, 0.19995307890, 0.13601866085},
                          {-0.93884600806, 0.17474200309, 0.29670423911, 0.12532359097},   {0.41133457348, 0.18855212960, -0.89176900770, 0.18037905588},
                          {0.95223850233, 0.28267085694, 0.11549468091, 0.06185796885},    {0.80078595454, 0.26259867855, 0.53831569644, 0.33939375757},
                          {0.26121981318, 0.38773423595, -0.88398324163, 0.17319536692},   {0.68644236726, -0.35979437269, -0.63193740656, 0.04671754118}};
  std::string cells;
  for (int k = 0; k < 8; ++k)
    cells += "  - {type: red cell, center: [" + to_text(c[k][0] + (k == 0 ? shift_um : 0.0)) + " um, " + to_text(c[k][1]) + " um, " +
             to_text(c[k][2]) + " um], axis: [" + to_text(a[k][0]) + ", " + to_text(a[k][1]) + ", " + to_text(a[k][2]) +
             "], angle: " + to_text(a[k][3]) + " rad}\n";
  return "name: whole_blood_flat\ndomain:\n  size: [16 um, 12 um, 16 um]\n  periodic: [x, z]\n  walls:\n"
         "    y: {lower: [0 cm/s, 0 cm/s, 0 cm/s], upper: {speed: 1.6 cm/s, turn: {from: 0 rad, to: 0.7853981633974483 rad, over: 7.2 ms}}}\n"
         "fluid: {density: 1 g/cm^3, viscosity: 1 cP}\ngrid: {cells: [" +
         to_text(z.wall_cells[0]) + ", " + to_text(z.wall_cells[1]) + ", " + to_text(z.wall_cells[2]) + "]}\n" + time +
         "\nib: {kernel: bspline3}\ncell_types:\n  - {name: red cell, preset: red_cell, data_sites: " + to_text(z.rbc_nd) +
         ", sample_sites: " + to_text(z.rbc_ns) + "}\ncells:\n" + cells +
         "tethered_points:\n  - {name: endothelium, spiral: {y: 1 um, bump: 0 um, points: " + to_text(z.endothelium) +
         "}, follow_step: {gain: 0.5}}\noutput: {diagnostics_every: 1}\n";
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("bench_step", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "bench_step",
                                                   "The stability criterion of the adaptive step against the seed's ladder: speed against error");
    const bool full = opt.scale == st::Scale::full;
    const Sizes z = full ? Sizes{40, {80, 60, 80}, 2500, 10000, 625, 2500, 900, 16000} : Sizes{20, {40, 30, 40}, 400, 1600, 400, 1600, 400, 4096};
    const double window = full ? 1 * units::ms : 50 * units::us, shift = 1e-7;  // um
    const std::string window_text = full ? "1 ms" : "50 us";
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["window_us"] = window / units::us;
    P["perturbation_um"] = shift;
    P["threads"] = omp_get_max_threads();
    st::record_wait_policy(P);

    Json runs = st::table({"scene", "run", "steps", "mean_dt_ns", "largest_dt_ns", "refused_by_guard", "seconds_per_step", "simulated_us_per_hour",
                           "divergence_um", "divergence_over_h", "stopped"},
                          {"", "", "", "ns", "ns", "", "s", "us/h", "um", "", ""});
    Json verdicts = st::table({"scene", "h_um", "stability_um", "perturbed_um", "stability_over_perturbed", "stability_over_h",
                               "speedup_simulated_time"},
                              {"", "um", "um", "um", "", "", ""});
    const st::Sitting sitting(opt);
    const char* ids[3] = {"ladder", "stability", "perturbed"};
    int stopped_stability = 0;
    double worst_over_h = 0;
    struct Scene {
      std::string name;
      std::string (*make)(const Sizes&, const std::string&, double);
      double h_um;
    };
    const Scene scenes[3] = {{"red_cell_shear", shear_scene, 16.0 / z.shear_cells},
                             {"platelets_wall", platelets_scene, 16.0 / z.wall_cells[0]},
                             {"whole_blood_flat", whole_blood_scene, 16.0 / z.wall_cells[0]}};
    for (const Scene& sc : scenes) {
      st::SceneRunHooks hooks;  // every step: its size and the growth guard's refusals
      hooks.sample = [](const sim::ImmersedBoundary& ib, const sim::IbStepReport* r) {
        return std::vector<double>{ib.time(), r ? r->dt : 0.0, r ? double(r->refused_by_guard) : 0.0};
      };
      st::SceneRun r[3];
      bool finished = true;
      for (int k = 0; k < 3; ++k) {
        const std::string id = sc.name + "_" + ids[k];
        const std::string text = "# bench_step: " + sc.name + ", " + ids[k] + "\n" +
                                 sc.make(z, time_section(window_text, k == 1), k == 2 ? shift : 0.0);
        r[k] = st::run_scene(text, id, run::Cadence{1}, opt.keeps_runs(), opt, hooks, sitting.remaining(), true);
        st::record_run(results, id, r[k].progress(window));
        finished = finished && r[k].finished;
        if (!r[k].stopped.empty()) st::log(opt, sc.name + " (" + ids[k] + ") stopped: " + r[k].stopped);
      }
      if (!r[1].stopped.empty()) ++stopped_stability;
      const bool ran = finished && r[0].stopped.empty() && r[1].stopped.empty() && r[2].stopped.empty();
      const double ds = ran ? st::divergence_um(r[1], r[0]) : NAN, dp = ran ? st::divergence_um(r[2], r[0]) : NAN;
      double per_hour[3];
      for (int k = 0; k < 3; ++k) {
        const auto& rows = r[k].samples;
        double largest = 0, guard = 0;
        for (std::size_t i = 1; i < rows.size(); ++i) largest = std::max(largest, rows[i][1]), guard += rows[i][2];
        const double t = rows.empty() ? 0 : rows.back()[0];
        const long steps = long(rows.size()) - 1;
        per_hour[k] = t / units::us / (r[k].seconds_per_step() * double(steps) / 3600);
        runs["rows"].push(st::row({sc.name, ids[k], double(steps), steps > 0 ? t / double(steps) / units::ns : NAN, largest / units::ns, guard,
                                   r[k].seconds_per_step(), per_hour[k], k == 0 ? 0.0 : (k == 1 ? ds : dp),
                                   k == 0 ? 0.0 : (k == 1 ? ds : dp) / sc.h_um, r[k].stopped.empty() ? "no" : r[k].stopped}));
      }
      worst_over_h = std::max(worst_over_h, ran ? ds / sc.h_um : INFINITY);
      verdicts["rows"].push(st::row({sc.name, sc.h_um, ds, dp, ds / dp, ds / sc.h_um, per_hour[1] / per_hour[0]}));
      st::log(opt, sc.name + " over " + window_text + ": the stability criterion moves the cells by " + to_text(ds) + " um (" +
                       to_text(ds / sc.h_um) + " h), the 1e-7 um perturbation by " + to_text(dp) + " um; simulated time per hour " +
                       to_text(per_hour[1] / per_hour[0]) + " times the ladder's");
    }
    Json& V = results["values"];
    V["stability_runs_stopped"] = double(stopped_stability);
    V["worst_stability_divergence_over_h"] = worst_over_h;
    // The rule: the default criterion changes only where the stability criterion is shown
    // negligible; the library's default is the seed's ladder.
    V["default_stability"] = sim::AdaptiveStep{}.criterion == sim::StepCriterion::stability ? 1.0 : 0.0;
    results["tables"]["runs"] = runs;
    results["tables"]["divergence"] = verdicts;
    st::write_results(opt, results);
    return 0;
  });
}
