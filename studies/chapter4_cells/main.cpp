// Sec. 4.2.2.3, Table 4.5 (and Fig. 4.5) recast for this machine, and the whole-blood-size step.
//
// Part 1, Table 4.5: red cells obeying Skalak's law (Sec. 4.2.2: "elastic, obeying Skalak's Law")
// with n_d = 864 data and n_s = 8,832 sample sites, dt = 0.1 us, shear 1000/s. The seed's table
// grows cells and GPU threads together (1, 2, 4, 8 cells on 64 ... 512 threads) and reports the
// time per interpolation and spreading call. Here: 1, 2, 4, 8 cells on 1 and 2 threads; per call,
// the seed's algorithms (Alg. 4.3 interpolation; Algs. 4.4 and 4.6 spreading) and the binned
// ones the coupled step uses, each with its difference to the serial reference (the error of
// that speed); the force call; and the coupled step (Sec. 2.4) split into interpolation, forces,
// spreading and the fluid, median over steps (the force call's time is the step's forces).
//
// Part 2, the whole-blood-size step (Sec. 5.2): 16 x 12 x 16 um, h = 0.2 um (80 x 60 x 80),
// periodic in x and z, walls in y, the top one moving (shear 1000/s), B3 kernel, backward-forward
// Euler, dt = 50 ns, plasma of 1 cP (the seed's code: at the 0.1 cP of Sec. 2.1 the seed's
// endothelium is unstable at 50 ns, see the reference); 8 red cells (Skalak, bending,
// dissipation; 2,500 / 10,000 sites at full scale, 625 / 2,500 at quick scale) in the two rows of
// Sec. 5.2.1 without its random moves, 2 platelets (neo-Hookean, bending about the reference
// curvature; 900 / 900) 0.3 um above a flat endothelium of 16,000 tethered points at y = 1 um
// (k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm); built from a scene kept beside the results.
// Reports the step's split, the dense products of the force calls against a DGEMM measured in
// the same run, and every cell's volume change.
//
// Run:   build/studies/study_chapter4_cells --scale quick --out runs/chapter4_cells
#include "common/force_call.hpp"
#include "common/study.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/grid/box.hpp"
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

/// Per-component medians of the step's timings over `steps` steps (after one warm-up step), and
/// the largest relative volume change of any cell of the first batch over all of them.
struct StepSplit {
  double interpolation = 0, forces = 0, spreading = 0, fluid = 0;
  double total() const { return interpolation + forces + spreading + fluid; }
  double volume_change = 0;
};

std::vector<double> volumes(const cells::Batch& b) {
  cells::CellForces f;
  cells::compute_forces(b, f);
  return f.cells.volume;
}

StepSplit time_steps(sim::ImmersedBoundary& ib, int steps) {
  std::vector<std::vector<double>> v0;
  for (index_t b = 0; b < ib.batches(); ++b) v0.push_back(volumes(ib.batch(b)));
  ib.step();
  std::vector<double> t[4];
  for (int n = 0; n < steps; ++n) {
    const sim::IbStepReport r = ib.step();
    t[0].push_back(r.seconds_interpolation);
    t[1].push_back(r.seconds_forces);
    t[2].push_back(r.seconds_spreading);
    t[3].push_back(r.seconds_fluid);
  }
  StepSplit s{st::median(t[0]), st::median(t[1]), st::median(t[2]), st::median(t[3]), 0};
  for (index_t b = 0; b < ib.batches(); ++b) {
    const std::vector<double> v = volumes(ib.batch(b));
    for (std::size_t c = 0; c < v.size(); ++c) s.volume_change = std::max(s.volume_change, std::abs(v[c] / v0[b][c] - 1));
  }
  return s;
}

/// max |a - b| / max |b| over three component vectors (or one vector, c = 1).
double rel_diff(const std::vector<const dvec*>& a, const std::vector<const dvec*>& b) {
  double d = 0, m = 0;
  for (std::size_t c = 0; c < a.size(); ++c) {
    const host_vector<double> x(*a[c]), y(*b[c]);
    for (std::size_t k = 0; k < x.size(); ++k) {
      d = std::max(d, std::abs(x[k] - y[k]));
      m = std::max(m, std::abs(y[k]));
    }
  }
  return m > 0 ? d / m : d;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter4_cells", [&] {
    const st::Options opt = st::parse_command_line(
        argc, argv, "chapter4_cells",
        "Sec. 4.2.2.3, Table 4.5 recast: per-call interpolation, spreading and force times for 1-8 red cells, and the whole-blood-size step");
    const bool full = opt.scale == st::Scale::full;
    const int repeats = full ? 11 : 5;
    const int steps = full ? 7 : 3;
    const index_t dgemm_n = full ? 3000 : 2000;
    const int max_threads = omp_get_max_threads();
    std::vector<int> thread_counts{max_threads};
    if (max_threads > 1) thread_counts.insert(thread_counts.begin(), 1);

    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    Json& V = results["values"];
    P["repeats"] = repeats;
    P["timed_steps"] = steps;
    P["threads"] = max_threads;
    const double ceiling = st::dgemm_rate(dgemm_n, repeats);
    const double bandwidth = 3.0 * 8.0 * double(1 << 24) / st::triad_seconds(1 << 24);
    P["dgemm_n"] = double(dgemm_n);
    V["dgemm_gflops"] = ceiling / 1e9;
    V["triad_GBps"] = bandwidth / 1e9;
    st::log(opt, "ceilings, " + to_text(max_threads) + " threads: DGEMM n = " + to_text(dgemm_n) + " at " + to_text(ceiling / 1e9) +
                     " GFlop/s, triad " + to_text(bandwidth / 1e9) + " GB/s");

    // ---- Part 1: Table 4.5 ----------------------------------------------------------------------
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
    auto t0 = std::chrono::steady_clock::now();
    const auto rbc864 = std::make_shared<const cells::CellType>(spec);
    st::log(opt, "1. " + rbc864->describe() + " built in " +
                     to_text(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()) + " s");

    // run: "1 thread" or "all threads" (the figures select the latter on any machine).
    Json calls = st::table({"run", "threads", "cells", "operation", "algorithm", "points", "seconds", "seconds_per_cell",
                            "rel_diff_vs_serial"},
                           {"", "", "", "", "", "", "s", "s", ""});
    Json split = st::table({"run", "threads", "cells", "interpolation_seconds", "forces_seconds", "spreading_seconds", "fluid_seconds",
                            "seconds", "interp_spread_share", "volume_change_rel"},
                           {"", "", "", "s", "s", "s", "s", "s", "", ""});
    // Shaped as the seed's table, on all threads: Alg. 4.3 and Alg. 4.6 (the algorithms of its
    // Fig. 4.5), with the binned ones of the coupled step beside them.
    Json table45 = st::table({"threads", "cells", "interpolation_seconds", "spreading_seconds", "binned_interpolation_seconds",
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
        // Per call: interpolation at the data sites, spreading from the sample sites of the forces.
        ib::Interaction probe({ib.fluid().operators().component_box(0), ib.fluid().operators().component_box(1),
                               ib.fluid().operators().component_box(2)},
                              io.kernel);
        const cells::Batch& batch = ib.batch(0);
        const dvec X(batch.state().storage().begin(), batch.state().storage().begin() + 3 * N * rbc864->n_data());
        cells::CellForces forces;
        cells::compute_forces(batch, forces);
        const dvec& Xs = forces.positions.storage();
        const dvec& F = forces.force.storage();
        const VectorField& u = ib.fluid_state().u;
        auto row = [&](const char* op, const std::string& alg, index_t points, double s, double diff) {
          calls["rows"].push(Json::Array{Json(run), Json(double(p)), Json(double(N)), Json(op), Json(alg), Json(double(points)), Json(s),
                                         Json(s / double(N)), Json(diff)});
          worst_diff = std::max(worst_diff, diff);
        };
        double seconds45[4] = {0, 0, 0, 0};  // Alg. 4.3, Alg. 4.6, binned interpolation, binned spreading
        dvec U_serial, U;
        probe.interpolate(X, u, U_serial, ib::Interpolation::serial);
        for (ib::Interpolation a : {ib::Interpolation::parallel, ib::Interpolation::binned}) {
          const double s = st::median_seconds(repeats, [&] {
            probe.interpolate(X, u, U, a);
            synchronize();
          });
          row("interpolation", std::string("Alg. ") + ib::algorithm_number(a), index_t(X.size() / 3), s, rel_diff({&U}, {&U_serial}));
          seconds45[a == ib::Interpolation::parallel ? 0 : 2] = s;
        }
        std::array<dvec, 3> f_serial, f;
        probe.spread(Xs, F, f_serial, ib::Spreading::serial);
        for (ib::Spreading a : {ib::Spreading::sort_reduce, ib::Spreading::on_the_fly, ib::Spreading::binned}) {
          const double s = st::median_seconds(repeats, [&] {
            probe.spread(Xs, F, f, a);
            synchronize();
          });
          row("spreading", std::string("Alg. ") + ib::algorithm_number(a), index_t(Xs.size() / 3), s,
              rel_diff({&f[0], &f[1], &f[2]}, {&f_serial[0], &f_serial[1], &f_serial[2]}));
          if (a == ib::Spreading::on_the_fly) seconds45[1] = s;
          if (a == ib::Spreading::binned) seconds45[3] = s;
        }
        if (p == max_threads)
          table45["rows"].push(Json::Array{Json(double(p)), Json(double(N)), Json(seconds45[0]), Json(seconds45[1]), Json(seconds45[2]),
                                           Json(seconds45[3])});
        // The coupled step, split.
        const StepSplit s = time_steps(ib, steps);
        worst_volume = std::max(worst_volume, s.volume_change);
        const double share = (s.interpolation + s.spreading) / s.total();
        split["rows"].push(Json::Array{Json(run), Json(double(p)), Json(double(N)), Json(s.interpolation), Json(s.forces), Json(s.spreading),
                                       Json(s.fluid), Json(s.total()), Json(share), Json(s.volume_change)});
        st::log(opt, "1. " + to_text(p) + " thread(s), " + to_text(N) + " cell(s): step " + to_text(s.total() * 1e3) +
                         " ms (interpolation " + to_text(s.interpolation * 1e3) + ", forces " + to_text(s.forces * 1e3) +
                         ", spreading " + to_text(s.spreading * 1e3) + ", fluid " + to_text(s.fluid * 1e3) + " ms); volume change " +
                         to_text(s.volume_change));
        if (p == max_threads && N == 1) {
          V["one_cell_interpolation_ms"] = s.interpolation * 1e3;
          V["one_cell_forces_ms"] = s.forces * 1e3;
          V["one_cell_spreading_ms"] = s.spreading * 1e3;
        }
      }
    }
    V["max_rel_diff_vs_serial"] = worst_diff;
    results["tables"]["table45"] = table45;
    results["tables"]["table45_calls"] = calls;
    results["tables"]["table45_step"] = split;

    // ---- Part 2: the whole-blood-size step ------------------------------------------------------
    omp_set_num_threads(max_threads);
    const index_t rbc_nd = full ? 2500 : 625, rbc_ns = full ? 10000 : 2500;
    P["whole_blood_box_um"] = "16 x 12 x 16 (x, z periodic; walls in y, the top one at 12 mm/s: shear 1000/s)";
    P["whole_blood_grid"] = "80 x 60 x 80, h = 0.2 um";
    P["whole_blood_red_cells"] = "8 at " + to_text(rbc_nd) + " / " + to_text(rbc_ns) + " sites (Skalak, bending, dissipation)";
    P["whole_blood_platelets"] = "2 at 900 / 900 sites (neo-Hookean, bending about the reference curvature)";
    P["whole_blood_endothelium"] = "16,000 tethered points (128 x 125 lattice) at y = 1 um, k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm";
    P["whole_blood_dt_ns"] = 50;
    P["whole_blood_fluid"] = "rho = 1 g/cm^3, mu = 1 cP (the seed's code; at 0.1 cP its endothelium is unstable at 50 ns)";
    // The scene (docs/scenes.md), kept beside the results, where `rbfib run` reruns it: two rows of
    // four red cells at y = 6 um, concavities facing z, the rows staggered by 2 um; platelets lying
    // flat (1 um thick) 0.3 um above the endothelium, between the rows (under a red cell at
    // x = 12 um the rim, 2.1 um above the wall, would cut the platelet).
    std::string cells_text;
    for (int c = 0; c < 8; ++c)
      cells_text += "  - {type: red cell, center: [" + to_text(4 + 8 * (c / 4)) + " um, 6 um, " + to_text(2 + 4 * (c % 4) + 2 * (c / 4)) + " um]}\n";
    for (int c = 0; c < 2; ++c)  // between the rows, clear of the red cells' rims
      cells_text += "  - {type: platelet, center: [8 um, 1.8 um, " + to_text(4 + 8 * c) + " um], axis: [1, 0, 0], angle: 90 deg}\n";
    const std::string text =
        "# chapter4_cells: the whole-blood-size step (Sec. 5.2)\n"
        "name: whole_blood_step\n"
        "domain:\n  size: [16 um, 12 um, 16 um]\n  periodic: [x, z]\n"
        "  walls:\n    y: {lower: [0 mm/s, 0 mm/s, 0 mm/s], upper: [0 mm/s, 0 mm/s, 12 mm/s]}\n  initial_flow: shear\n"
        "fluid: {density: 1 g/cm^3, viscosity: 1 cP}\n"
        "grid: {cells: [80, 60, 80]}\n"
        "time: {integrator: backward_forward_euler, dt: 50 ns, end: 1 ms}\n"
        "ib: {kernel: bspline3}\n"
        "cell_types:\n  - {name: red cell, preset: red_cell, data_sites: " + to_text(rbc_nd) + ", sample_sites: " + to_text(rbc_ns) + "}\n"
        "  - {name: platelet, preset: platelet, data_sites: 900, sample_sites: 900}\n"
        "cells:\n" + cells_text +
        "tethered_points:\n  - {name: endothelium, plane: {y: 1 um, points: [128, 125]}, k: 2.5 dyn/cm, eta: 2.5e-7 dyn s/cm}\n";
    std::ofstream(opt.out_dir + "/scene_whole_blood.yaml") << text;
    t0 = std::chrono::steady_clock::now();
    sim::ImmersedBoundary ib = scene::build(scene::parse_scene(text, "scene_whole_blood.yaml"));
    st::log(opt, "2. " + ib.batch(0).type().describe() + "; " + ib.batch(1).type().describe() + " (scene built in " +
                     to_text(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()) + " s)");
    const StepSplit s = time_steps(ib, steps);
    const double step = s.total();
    V["whole_blood_step_seconds"] = step;
    V["whole_blood_interp_spread_share"] = (s.interpolation + s.spreading) / step;
    V["whole_blood_volume_change_rel"] = s.volume_change;
    worst_volume = std::max(worst_volume, s.volume_change);
    Json wb = st::table({"component", "seconds", "share"}, {"", "s", ""});
    const std::pair<const char*, double> parts[4] = {
        {"interpolation", s.interpolation}, {"forces", s.forces}, {"spreading", s.spreading}, {"fluid", s.fluid}};
    for (const auto& [name, sec] : parts) wb["rows"].push(Json::Array{Json(name), Json(sec), Json(sec / step)});
    // The dense products of the force calls against the DGEMM ceiling, measured once more just
    // before them (this shared machine's speed drifts over a run): the larger of the two.
    const double ceiling_now = st::dgemm_rate(dgemm_n, repeats);
    V["dgemm_gflops_before_whole_blood"] = ceiling_now / 1e9;
    const double best = std::max(ceiling, ceiling_now);
    double flops = 0, product_seconds = 0;
    Json fc = st::table({"type", "cells", "seconds", "products_seconds", "product_fraction_of_dgemm"}, {"", "", "s", "s", ""});
    for (index_t b = 0; b < ib.batches(); ++b) {
      double total = 0;
      const cells::ForceTimings t = st::median_force_timings(ib.batch(b), repeats, total);
      const cells::ProductFlops pf = cells::product_flops(ib.batch(b).type().spec(), ib.batch(b).size());
      flops += pf.total();
      product_seconds += t.products();
      fc["rows"].push(Json::Array{Json(ib.batch(b).type().name()), Json(double(ib.batch(b).size())), Json(total), Json(t.products()),
                                  Json(pf.total() / t.products() / best)});
    }
    V["whole_blood_product_fraction_of_dgemm"] = flops / product_seconds / best;
    V["max_volume_change_rel"] = worst_volume;
    results["tables"]["whole_blood_step"] = wb;
    results["tables"]["whole_blood_force_calls"] = fc;
    st::log(opt, "2. whole-blood-size step: " + to_text(step * 1e3) + " ms (interpolation " + to_text(s.interpolation * 1e3) +
                     ", forces " + to_text(s.forces * 1e3) + ", spreading " + to_text(s.spreading * 1e3) + ", fluid " +
                     to_text(s.fluid * 1e3) + " ms); products at " + to_text(flops / product_seconds / best) +
                     " of DGEMM; volume change " + to_text(s.volume_change));
    st::write_results(opt, results);
    return 0;
  });
}
