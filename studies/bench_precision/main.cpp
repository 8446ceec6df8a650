// Single-precision products of the cell force call (surface/operators.hpp, in_single_precision)
// judged by speed against error, as the project requires before any default changes:
//
// 1. The force call on the whole-blood cell load (8 red cells and 2 platelets, as bench_cells):
//    median time per call and of its products in double and in single precision, against a
//    square DGEMM and a square SGEMM measured in the same run, and the largest difference of the
//    single-precision forces from the double ones.
// 2. The example scenes of Chapter 5 (scenes/: one red cell in shear, platelets over a tethered
//    wall, whole blood over the bumpy endothelium), each run three times over the same window:
//    double, single, and double with one cell's centre moved by 1e-7 um. The divergence of a run
//    is the largest distance between its cells' data sites and the double run's at the window's
//    end (um). Single precision is negligible on a scene when it moves the cells less than that
//    perturbation of the starting state does.
//
// Scales: quick, 10 us windows on the scenes as written (400 / 1,600 red-cell sites) and the
// force call at 625 / 2,500 red-cell sites; full, 1 ms windows with the seed's sites
// (2,500 / 10,000 red cell, 900 / 900 platelet) and the force call at those sites; the full
// runs keep checkpoints and continue over sittings (--sitting), their divergence measured once
// all three runs of a scene have finished.
//
// Run:   build/studies/study_bench_precision --scale quick --out runs/bench_precision
#include "common/force_call.hpp"
#include "common/machine.hpp"
#include "common/scene_run.hpp"
#include "common/study.hpp"
#include "rbfib/cells/batch.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/linalg/dense.hpp"
#include "rbfib/scene/scene.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace rbfib;
using namespace rbfib::cells;
namespace st = rbfib::study;
using st::Json;

namespace {

/// Flop rate (flop/s) of a square n x n x n SGEMM through linalg/dense, median of repeats: the
/// ceiling of single-precision products, as dgemm_rate is of double ones.
double sgemm_rate(index_t n, int repeats) {
  std::vector<double> h(static_cast<std::size_t>(n * n));
  for (std::size_t k = 0; k < h.size(); ++k) h[k] = std::sin(0.001 * double(k));
  const linalg::DeviceMatrix A64 = linalg::DeviceMatrix::from_host(n, n, h.data());
  linalg::FloatMatrix A(n, n), C(n, n);
  linalg::narrow(A64.view(), A.view());
  auto call = [&] { linalg::gemm(linalg::Op::none, linalg::Op::none, 1.0f, A.view(), A.view(), 0.0f, C.view()); };
  call();
  const double t = st::median_seconds(repeats, [&] {
    call();
    synchronize();
  });
  return 2.0 * double(n) * n * n / t;
}

/// The whole-blood load of bench_cells: two rows of four red cells, turned and slightly stretched.
std::vector<Placement> red_cell_placements(index_t count) {
  std::vector<Placement> p;
  for (index_t c = 0; c < count; ++c) {
    Placement q;
    q.center = {(2.0 + 4.0 * double(c % 4)) * units::um, 6.0 * units::um, (4.0 + 8.0 * double(c / 4) + (c % 2)) * units::um};
    q.axis = {1.0, 0.3 * double(c), 0.2};
    q.angle = 0.2 * double(c);
    q.stretch = {1.02, 1.0 / 1.02, 1.0};
    p.push_back(q);
  }
  return p;
}

std::vector<Placement> platelet_placements() {
  Placement a, b;
  a.center = {4 * units::um, 2.5 * units::um, 4 * units::um};
  a.stretch = {1.03, 1.0, 1.0 / 1.03};
  b.center = {12 * units::um, 2.5 * units::um, 12 * units::um};
  b.axis = {0, 0, 1};
  b.angle = 1.0;
  b.stretch = {1.0, 1.03, 1.0 / 1.03};
  return {a, b};
}

/// Velocities at the data sites: shear 1000/s along x (Sec. 5.2), so that dissipation works.
void set_velocities(Batch& b) {
  const std::vector<double> X = b.positions_host();
  std::vector<double> U(X.size(), 0.0);
  const index_t nd = b.type().n_data(), N = b.size();
  for (index_t c = 0; c < N; ++c)
    for (index_t i = 0; i < nd; ++i) U[(0 * N + c) * nd + i] = 1000 * X[(1 * N + c) * nd + i];
  thrust::copy(U.begin(), U.end(), b.state().storage().begin() + 3 * N * nd);
}

std::shared_ptr<const CellType> with_precision(CellTypeSpec spec, bool single) {
  spec.single_precision_products = single;
  if (single) spec.name += " (single)";
  return std::make_shared<const CellType>(std::move(spec));
}

/// The double call's response to float rounding: max |F(X') - F(X)| / max |F(X)| with X' the data
/// sites' positions shifted by each cell's site 0 (as the single path shifts them), perturbed by
/// u_f = 2^-24 relative in random signs. The single call's products equal exact products of
/// operands perturbed by at most gamma_{k+4}(u_f) (the operator entries, the shifted positions, the
/// k-term sums), so to first order its forces differ from the double ones by at most about k + 4
/// times this (k = n_d).
double float_rounding_response(const Batch& b, const CellForces& f) {
  const index_t nd = b.type().n_data(), N = b.size();
  std::vector<double> state = b.state().to_host();
  unsigned seed = 12345;
  const double uf = std::numeric_limits<float>::epsilon() / 2;
  for (index_t col = 0; col < 3 * N; ++col)
    for (index_t i = 0; i < nd; ++i) {
      seed = seed * 1664525u + 1013904223u;
      double& x = state[std::size_t(col * nd + i)];
      x += ((seed >> 16) % 2 ? uf : -uf) * (x - state[std::size_t(col * nd)]);
    }
  Batch p = Batch::from_state(b.type_ptr(), N, state, b.body_force());
  CellForces g;
  compute_forces(p, g);
  const std::vector<double> a = f.force.to_host(), c = g.force.to_host();
  double diff = 0, scale = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    diff = std::max(diff, std::abs(c[k] - a[k]));
    scale = std::max(scale, std::abs(a[k]));
  }
  return diff / scale;
}

struct Ceilings {
  double dgemm = 0, sgemm = 0;
};

/// One type's batch in both precisions: rows of the force_calls table; returns the double and the
/// single call's median times (s) through `seconds`.
void measure(const st::Options& opt, Json& calls, const CellTypeSpec& spec, const std::vector<Placement>& placements, int repeats,
             const Ceilings& c, double seconds[2]) {
  CellForces reference;
  std::vector<double> responses;
  for (int single = 0; single < 2; ++single) {
    const auto type = with_precision(spec, single == 1);
    Batch b(type, placements);
    if (type->model().dissipation()) set_velocities(b);
    double total = 0;
    const ForceTimings t = st::median_force_timings(b, repeats, total);
    CellForces out;
    compute_forces(b, out);
    double diff = 0, response = 0;
    if (single == 0) {
      response = float_rounding_response(b, out);
      reference = std::move(out);
    } else {
      const std::vector<double> f64 = reference.force.to_host(), f32 = out.force.to_host();
      double scale = 0;
      for (std::size_t k = 0; k < f64.size(); ++k) {
        diff = std::max(diff, std::abs(f32[k] - f64[k]));
        scale = std::max(scale, std::abs(f64[k]));
      }
      diff /= scale;
      response = responses.back();
    }
    responses.push_back(response);
    const double bound = double(spec.data_sites.size() + 4) * response;
    const ProductFlops f = product_flops(type->spec(), b.size());
    const double rate = f.total() / t.products();
    const double ceiling = single ? c.sgemm : c.dgemm;
    seconds[single] = total;
    calls["rows"].push(st::row({spec.name, single ? "single" : "double", double(b.size()), total, t.products(), rate / 1e9,
                                rate / ceiling, rate / c.dgemm, response, diff, single ? diff / bound : 0.0}));
    st::log(opt, "1. " + spec.name + " x " + to_text(b.size()) + ", " + (single ? "single" : "double") + ": " +
                     to_text(total * 1e3) + " ms per call, products " + to_text(t.products() * 1e3) + " ms at " +
                     to_text(rate / 1e9) + " GFlop/s (" + to_text(rate / ceiling) + " of " + (single ? "SGEMM" : "DGEMM") +
                     ")" + (single ? "; forces differ from double by " + to_text(diff) + " of the largest" : ""));
  }
}

/// A scene of scenes/ over the window [0, t_end]: its cell types at the given precision (and, at
/// full scale, the seed's site counts), the first cell's centre moved by `shift` along x.
std::string variant(const scene::Scene& base, double t_end, bool seed_sites, bool single, double shift) {
  scene::Scene s = base;
  s.t_end = t_end;
  s.snapshot_every = 0;
  s.checkpoint_every = 0;
  for (scene::CellTypeEntry& t : s.types) {
    if (seed_sites) {
      const cells::ForceModel model = t.spec.model;
      t = scene::cell_type(t.spec.name, t.preset, 0, 0, t.radius, t.degree);
      t.spec.model = model;
    }
    t.spec.single_precision_products = single;
  }
  require(!s.cells.empty(), "bench_precision: scene '" + base.name + "' cells", "none", "must hold a cell");
  s.cells[0].placement.center[0] += shift;
  return scene::to_yaml(s, "bench_precision: " + base.name + (single ? ", single-precision products" : "") +
                               (shift != 0 ? ", first cell moved by " + to_text(shift / units::um) + " um" : ""));
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("bench_precision", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "bench_precision",
                                                   "Single-precision products of the force call: speed against error");
    const bool full = opt.scale == st::Scale::full;
    const index_t rbc_nd = full ? 2500 : 625, rbc_ns = full ? 10000 : 2500, red_cells = 8;
    const int repeats = full ? 11 : 7;
    const double window = full ? 1 * units::ms : 10 * units::us, shift = 1e-7 * units::um;
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["red_cells"] = double(red_cells);
    P["red_cell_sites_data_sample"] = to_text(rbc_nd) + " / " + to_text(rbc_ns);
    P["platelet_sites_data_sample"] = "900 / 900";
    P["repeats"] = repeats;
    P["threads"] = omp_get_max_threads();
    P["dense_backend"] = linalg::dense_backend_name();
    P["window_us"] = window / units::us;
    P["perturbation_um"] = shift / units::um;
    st::record_wait_policy(P);

    // ---- 1. The force call in both precisions ---------------------------------------------
    Ceilings c;
    c.dgemm = st::measure_ceiling(results, full ? 3000 : 2000, repeats).dgemm_flops;
    c.sgemm = sgemm_rate(full ? 3000 : 2000, repeats);
    Json& V = results["values"];
    V["sgemm_gflops"] = c.sgemm / 1e9;
    st::log(opt, "1. square DGEMM " + to_text(c.dgemm / 1e9) + " GFlop/s, SGEMM " + to_text(c.sgemm / 1e9) + " GFlop/s");
    Json calls = st::table({"type", "precision", "cells", "seconds", "products_seconds", "product_gflops", "fraction_of_own_gemm",
                            "fraction_of_dgemm", "response_to_float_rounding", "max_rel_diff_vs_double", "diff_over_rounding_bound"},
                           {"", "", "", "s", "s", "GFlop/s", "", "", "", "", ""});
    double rbc[2], plt[2];
    measure(opt, calls, red_cell_spec(rbc_nd, rbc_ns), red_cell_placements(red_cells), repeats, c, rbc);
    measure(opt, calls, platelet_spec(900, 900), platelet_placements(), repeats, c, plt);
    V["load_seconds_double"] = rbc[0] + plt[0];
    V["load_seconds_single"] = rbc[1] + plt[1];
    V["load_speedup_single"] = (rbc[0] + plt[0]) / (rbc[1] + plt[1]);
    results["tables"]["force_calls"] = calls;

    // ---- 2. The Chapter 5 example scenes: double, single, double perturbed -----------------
    Json runs = st::table({"scene", "run", "steps", "seconds_per_step", "divergence_um", "stopped"}, {"", "", "", "s", "um", ""});
    Json verdicts = st::table({"scene", "single_um", "perturbed_um", "single_over_perturbed", "step_speedup_single"},
                              {"", "um", "um", "", ""});
    double worst_ratio = 0;
    const st::Sitting sitting(opt);
    const char* run_ids[3] = {"double", "single", "perturbed"};
    for (const std::string name : {"red_cell_in_shear", "platelets_near_wall", "whole_blood_bumpy"}) {
      const scene::Scene base = scene::load_scene(st::source_path(opt, "scenes/" + name + ".yaml"));
      st::SceneRunHooks hooks;
      hooks.sample = [](const sim::ImmersedBoundary& ib, const sim::IbStepReport*) { return std::vector<double>{ib.time()}; };
      const run::Cadence every{0, window, 0};
      st::SceneRun r[3];
      const char* labels[3] = {"double", "single", "double, perturbed"};
      bool finished = true;
      for (int k = 0; k < 3; ++k) {
        const std::string id = name + "_" + run_ids[k];
        const std::string text = variant(base, window, full, k == 1, k == 2 ? shift : 0.0);
        r[k] = st::run_scene(text, id, every, opt.keeps_runs(), opt, hooks, sitting.remaining());
        st::record_run(results, id, r[k].progress(window));
        finished = finished && r[k].finished;
        if (!r[k].stopped.empty()) st::log(opt, "2. " + name + " (" + labels[k] + ") stopped: " + r[k].stopped);
      }
      const double ds = finished ? st::divergence_um(r[1], r[0]) : NAN, dp = finished ? st::divergence_um(r[2], r[0]) : NAN;
      for (int k = 0; k < 3; ++k)
        runs["rows"].push(st::row({name, labels[k], double(r[k].steps), r[k].seconds_per_step(), k == 0 ? 0.0 : (k == 1 ? ds : dp),
                                   r[k].stopped.empty() ? "no" : r[k].stopped}));
      const bool ran = finished && r[0].stopped.empty() && r[1].stopped.empty() && r[2].stopped.empty();
      const double ratio = ran ? ds / dp : NAN;
      worst_ratio = std::max(worst_ratio, ran ? ratio : INFINITY);
      verdicts["rows"].push(st::row({name, ds, dp, ratio, r[0].seconds_per_step() / r[1].seconds_per_step()}));
      st::log(opt, "2. " + name + " over " + to_text(window / units::us) + " us: single precision moves the cells by " + to_text(ds) +
                       " um, the 1e-7 um perturbation by " + to_text(dp) + " um (ratio " + to_text(ratio) + "); step " +
                       to_text(r[0].seconds_per_step()) + " s double, " + to_text(r[1].seconds_per_step()) + " s single");
    }
    V["worst_single_over_perturbed"] = worst_ratio;
    // The rule: the default changes to single precision only where it is shown negligible.
    V["single_negligible"] = worst_ratio <= 1.0 ? 1.0 : 0.0;
    V["default_single"] = CellTypeSpec{}.single_precision_products ? 1.0 : 0.0;
    V["default_beyond_verdict"] = (CellTypeSpec{}.single_precision_products ? 1.0 : 0.0) - (worst_ratio <= 1.0 ? 1.0 : 0.0);
    results["tables"]["runs"] = runs;
    results["tables"]["divergence"] = verdicts;
    st::write_results(opt, results);
    return 0;
  });
}
