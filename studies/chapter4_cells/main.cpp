// Sec. 4.2.2.3, Table 4.5 (and Fig. 4.5) recast for this machine, and the whole-blood-size step.
//
// Part 1, Table 4.5: red cells obeying Skalak's law (Sec. 4.2.2), n_d = 864 data and n_s = 8,832
// sample sites, dt = 0.1 us, shear 1000/s; the seed grows cells and GPU threads together (1 ... 8
// cells on 64 ... 512 threads). Here 1, 2, 4, 8 cells on 1 and all threads: per call, the seed's
// algorithms (Alg. 4.3; Algs. 4.4 and 4.6) and the binned ones, each with its difference to the
// serial one; and the coupled step (Sec. 2.4) split into interpolation, forces, spreading, fluid.
//
// Part 2, the whole-blood-size step (Sec. 5.2) built from a scene kept beside the results: 16 x 12
// x 16 um, h = 0.2 um, walls in y (shear 1000/s), B3, backward-forward Euler, dt = 50 ns, plasma of
// 1 cP (the seed's code: at 0.1 cP its endothelium is unstable at 50 ns); 8 red cells and 2
// platelets (Sec. 5.2.1 without its random moves) over an endothelium of 16,000 tethered points.
// Reports the step's split, the force calls' dense products against a DGEMM measured in the same
// run, and every cell's volume change.
//
// Run:   build/studies/study_chapter4_cells --scale quick --out runs/chapter4_cells
#include "common/force_call.hpp"
#include "common/machine.hpp"
#include "common/study.hpp"
#include "whole_blood_step.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;
using namespace rbfib::cells_study;

namespace {

const double um = units::um;
using MB = MacBoundary;

/// The shear of Secs. 4.2.2 and 5.2 (1/s).
constexpr double shear = 1000.0;

/// Part 1's cells: two stacks of four along z (axis z, concavities facing z), 16 um apart in x,
/// 4 um apart in z: 1.4 um between neighbours, more than the 1 um that two B3 supports span at
/// h = 0.25 um, so no two cells share a support point (as in the seed's runs).
std::vector<cells::Placement> stacked(index_t count) {
  std::vector<cells::Placement> p(static_cast<std::size_t>(count));
  for (index_t c = 0; c < count; ++c) p[c].center = {(8.0 + 16.0 * double(c % 2)) * um, 8 * um, (2.0 + 4.0 * double(c / 2)) * um};
  return p;
}

/// Part 1's flow: the steady shear u_x = shear (y - L_y / 2) with walls at y = 0 and L_y moving at
/// -+ shear L_y / 2, and the flow set to it.
sim::ImmersedBoundary sheared(const MacGrid& g, double dt, sim::IbOptions io) {
  NavierStokesOptions o;
  o.dt = dt;
  const double Ly = g.length[1], y_zero = Ly / 2;
  auto wall = [=](int a, int d, int side, double, double, double, double) {
    return a == 0 && d == 1 ? shear * ((side ? Ly : 0.0) - y_zero) : 0.0;
  };
  sim::ImmersedBoundary ib(g, FluidParameters{1.0, 0.1 * units::cP}, o, wall, io);
  ib.fluid_state().u[0] = sample(ib.fluid().operators().component_box(0), [=](double, double y, double) { return shear * (y - y_zero); });
  return ib;
}

/// One row of the calls table per algorithm: interpolation at the data sites of `ib`'s first batch,
/// spreading from the sample sites of its forces, each against the serial algorithm. Returns the
/// times of Alg. 4.3, Alg. 4.6, binned interpolation and binned spreading.
std::array<double, 4> time_calls(sim::ImmersedBoundary& ib, ib::Kernel kernel, int repeats, Json& calls, const char* run, int p,
                                 double& worst_diff) {
  const auto& ops = ib.fluid().operators();
  ib::Interaction probe({ops.component_box(0), ops.component_box(1), ops.component_box(2)}, kernel);
  const cells::Batch& batch = ib.batch(0);
  const index_t N = batch.size();
  const dvec X(batch.state().storage().begin(), batch.state().storage().begin() + 3 * N * batch.type().n_data());
  cells::CellForces forces;
  cells::compute_forces(batch, forces);
  const dvec& Xs = forces.positions.storage();
  const dvec& F = forces.force.storage();
  const VectorField& u = ib.fluid_state().u;
  auto row = [&](const char* op, const char* alg, index_t points, double s, double diff) {
    calls["rows"].push(st::row({run, double(p), double(N), op, std::string("Alg. ") + alg, double(points), s, s / double(N), diff}));
    worst_diff = std::max(worst_diff, diff);
  };
  std::array<double, 4> seconds{};
  dvec U_serial, U;
  probe.interpolate(X, u, U_serial, ib::Interpolation::serial);
  for (ib::Interpolation a : {ib::Interpolation::parallel, ib::Interpolation::binned}) {
    const double s = st::median_seconds(repeats, [&] {
      probe.interpolate(X, u, U, a);
      synchronize();
    });
    row("interpolation", ib::algorithm_number(a), index_t(X.size() / 3), s, st::max_rel_diff({&U}, {&U_serial}));
    seconds[a == ib::Interpolation::parallel ? 0 : 2] = s;
  }
  std::array<dvec, 3> f_serial, f;
  probe.spread(Xs, F, f_serial, ib::Spreading::serial);
  for (ib::Spreading a : {ib::Spreading::sort_reduce, ib::Spreading::on_the_fly, ib::Spreading::binned}) {
    const double s = st::median_seconds(repeats, [&] {
      probe.spread(Xs, F, f, a);
      synchronize();
    });
    row("spreading", ib::algorithm_number(a), index_t(Xs.size() / 3), s, st::max_rel_diff(f, f_serial));
    if (a == ib::Spreading::on_the_fly) seconds[1] = s;
    if (a == ib::Spreading::binned) seconds[3] = s;
  }
  return seconds;
}

/// Part 1, Table 4.5: 1, 2, 4, 8 cells on 1 and all threads; per call and the coupled step, split.
/// Returns the largest volume change.
double table45(const st::Options& opt, Json& results, const std::vector<int>& thread_counts, int repeats, int steps) {
  Json& P = results["parameters"];
  Json& V = results["values"];
  const int max_threads = thread_counts.back();
  const double h1 = 0.25 * um;
  const MacGrid g1 = make_mac_grid(3, {128, 64, 64}, {32 * um, 16 * um, 16 * um}, {MB::periodic, MB::dirichlet, MB::periodic});
  P["table45_box_um"] = "32 x 16 x 16 (x, z periodic; walls in y at -+8 mm/s: shear 1000/s)";
  P["table45_h_um"] = h1 / um;
  P["table45_dt_us"] = 0.1;
  P["table45_sites_data_sample"] = "864 / 8832";
  cells::CellTypeSpec spec = cells::red_cell_spec(864, 8832);
  spec.name = "red cell (Skalak only)";
  spec.model.kappa = 0;
  spec.model.nu = 0;
  const auto rbc864 = std::make_shared<const cells::CellType>(spec);
  st::log(opt, "1. " + rbc864->describe());
  // run: "1 thread" or "all threads" (the figures select the latter on any machine).
  Json calls = st::table({"run", "threads", "cells", "operation", "algorithm", "points", "seconds", "seconds_per_cell", "rel_diff_vs_serial"},
                         {"", "", "", "", "", "", "s", "s", ""});
  Json split = st::table({"run", "threads", "cells", "interpolation_seconds", "forces_seconds", "spreading_seconds", "fluid_seconds",
                          "seconds", "interp_spread_share", "volume_change_rel"},
                         {"", "", "", "s", "s", "s", "s", "s", "", ""});
  // Shaped as the seed's table, on all threads: Alg. 4.3 and Alg. 4.6 (the algorithms of its
  // Fig. 4.5), with the binned ones of the coupled step beside them.
  Json t45 = st::table({"threads", "cells", "interpolation_seconds", "spreading_seconds", "binned_interpolation_seconds",
                        "binned_spreading_seconds"},
                       {"", "", "s", "s", "s", "s"});
  double worst_volume = 0, worst_diff = 0;
  for (int p : thread_counts) {
    omp_set_num_threads(p);
    const char* run = p == max_threads ? "all threads" : "1 thread";
    for (index_t N : {index_t(1), index_t(2), index_t(4), index_t(8)}) {
      sim::IbOptions io;
      io.kernel = ib::Kernel::bspline3;
      sim::ImmersedBoundary ib = sheared(g1, 0.1 * units::us, io);
      ib.add(cells::Batch(rbc864, stacked(N)));
      const std::array<double, 4> t = time_calls(ib, io.kernel, repeats, calls, run, p, worst_diff);
      if (p == max_threads) t45["rows"].push(st::row({double(p), double(N), t[0], t[1], t[2], t[3]}));
      const StepSplit s = time_steps(ib, steps);
      worst_volume = std::max(worst_volume, s.volume_change);
      split["rows"].push(st::row({run, double(p), double(N), s.interpolation, s.forces, s.spreading, s.fluid, s.total(),
                                  (s.interpolation + s.spreading) / s.total(), s.volume_change}));
      st::log(opt, "1. " + to_text(p) + " thread(s), " + to_text(N) + " cell(s): " + s.describe());
      if (p == max_threads && N == 1) {
        V["one_cell_interpolation_ms"] = s.interpolation * 1e3;
        V["one_cell_forces_ms"] = s.forces * 1e3;
        V["one_cell_spreading_ms"] = s.spreading * 1e3;
      }
    }
  }
  V["max_rel_diff_vs_serial"] = worst_diff;
  results["tables"]["table45"] = t45;
  results["tables"]["table45_calls"] = calls;
  results["tables"]["table45_step"] = split;
  return worst_volume;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter4_cells", [&] {
    // ---- Parameters and the machine's ceilings ----------------------------------------------------
    const st::Options opt = st::parse_command_line(
        argc, argv, "chapter4_cells",
        "Sec. 4.2.2.3, Table 4.5 recast: per-call interpolation, spreading and force times for 1-8 red cells, and the whole-blood-size step");
    const bool full = opt.scale == st::Scale::full;
    const int repeats = full ? 11 : 5, steps = full ? 7 : 3, max_threads = omp_get_max_threads();
    const index_t dgemm_n = full ? 3000 : 2000, rbc_nd = full ? 2500 : 625, rbc_ns = full ? 10000 : 2500;
    std::vector<int> thread_counts{max_threads};
    if (max_threads > 1) thread_counts.insert(thread_counts.begin(), 1);
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["repeats"] = repeats;
    P["timed_steps"] = steps;
    P["threads"] = max_threads;
    const st::Ceiling c = st::measure_ceiling(results, dgemm_n, repeats);
    st::log(opt, "ceilings, " + to_text(max_threads) + " threads: DGEMM n = " + to_text(dgemm_n) + " at " + to_text(c.dgemm_flops / 1e9) +
                     " GFlop/s, triad " + to_text(c.triad_bytes_per_s / 1e9) + " GB/s");

    // ---- Part 1: Table 4.5 ----------------------------------------------------------------------
    double worst_volume = table45(opt, results, thread_counts, repeats, steps);

    // ---- Part 2: the whole-blood-size step ------------------------------------------------------
    omp_set_num_threads(max_threads);
    whole_blood_parameters(P, rbc_nd, rbc_ns);
    // The scene (docs/scenes.md), kept beside the results, where `rbfib run` reruns it.
    const scene::Scene sc = scene::checked(whole_blood_scene(rbc_nd, rbc_ns), "chapter4_cells: the whole-blood-size step (Sec. 5.2)");
    std::ofstream(opt.out_dir + "/scene_whole_blood.yaml") << sc.source;
    sim::ImmersedBoundary ib = scene::build(sc);
    st::log(opt, "2. " + ib.batch(0).type().describe() + "; " + ib.batch(1).type().describe());
    worst_volume = std::max(worst_volume, whole_blood_step(opt, results, ib, steps, dgemm_n, repeats, c.dgemm_flops));
    results["values"]["max_volume_change_rel"] = worst_volume;
    st::write_results(opt, results);
    return 0;
  });
}
