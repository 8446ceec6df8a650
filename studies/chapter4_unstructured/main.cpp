// Reproduces seed Sec. 4.2.1 (unstructured Lagrangian points): Table 4.1 / Fig. 4.3 (time per
// call of interpolation and of each spreading algorithm against grid refinement), Fig. 4.4
// (strong scaling over the threads of this machine) and Table 4.2 (weak scaling, 2^16..2^19
// points), plus the agreement of every algorithm with the serial one.
//
// The test problem: n points placed at random in the 16 um triply periodic box, tethered to their
// initial positions by Hookean springs (k = 1e-2 dyn/cm), in the shear flow u = (0, 0, gamma_dot
// (y - 8 um)) with gamma_dot = 1000/s, sampled on the MAC grid. One time step is
//   (1) U = I u(X)          interpolate        (2) X* = X + dt U       predict
//   (3) f = f_bg + S F(X*)  spread, F = -k (X* - X0), f_bg = -mu Lap u the background force
//   (4) U* = I u(X*)        interpolate        (5) X = X + dt U*       update
// The fluid is not solved (as in the seed), so the flow stays the initial one.
//
// Run:   build/studies/study_chapter4_unstructured --scale quick --out runs/chapter4_unstructured
//        (--scale full: the seed's sizes, 2^16..2^19 points, more steps; takes much longer)
#include "common/machine.hpp"
#include "common/study.hpp"
#include "problem.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/ib/grid.hpp"
#include "rbfib/ib/interaction.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace rbfib;
using namespace rbfib::ib;
namespace st = rbfib::study;
using st::Json;
using namespace rbfib::unstructured;

namespace {

/// Table 4.1: one row per (device, algorithm) in order of first use, one column per refinement.
struct Table41 {
  std::vector<std::pair<std::vector<std::string>, std::vector<double>>> rows;
  void put(const std::string& device, const std::string& algorithm, std::size_t column, std::size_t columns, double seconds) {
    auto it = std::find_if(rows.begin(), rows.end(), [&](const auto& r) { return r.first == std::vector<std::string>{device, algorithm}; });
    if (it == rows.end()) it = rows.insert(rows.end(), {{device, algorithm}, std::vector<double>(columns, NAN)});
    it->second[column] = seconds;
  }
  Json json() const {
    Json table = st::table({"device", "algorithm", "g16_seconds", "g32_seconds", "g64_seconds", "g128_seconds"}, {"", "", "s", "s", "s", "s"});
    for (const auto& [key, t] : rows) table["rows"].push(st::row({key[0], key[1], t[0], t[1], t[2], t[3]}));
    return table;
  }
};

void record_parameters(Json& par, const Params& p, index_t n, int steps, int steps_serial, int threads) {
  par["box_um"] = p.box / units::um;
  par["points"] = double(n);
  par["kernel"] = ib::to_string(p.kernel);
  par["shear_rate_per_s"] = p.shear_rate;
  par["spring_dyn_per_cm"] = p.spring;
  par["viscosity_cP"] = p.viscosity / units::cP;
  par["dt_us"] = p.dt / units::us;
  par["steps_binned"] = steps;
  par["steps_seed_algorithms"] = steps_serial;
  par["buffer_width_sz"] = buffer_width;
  par["threads"] = threads;
  st::record_wait_policy(par);
  par["load_average_at_start"] = st::load_average();  // this machine is shared: times are indicative
  par["machine_paper"] = "48x Intel Xeon E5-2697 v2 2.70GHz (16 cores used), libiomp5, clang 7.0.1";
}

/// The largest differences to the serial algorithms, over every refinement.
struct Agreement {
  double spread = 0, interp = 0, conservation = 0, adjoint = 0, background = 0;
};

/// Table 4.1 / Fig. 4.3 at one refinement (column r of table41): every algorithm's time per call in
/// the time loop, and its speedup over the serial one.
void time_algorithms(Interaction& ib, const Flow& flow, const host_vector<double>& X0, const Params& p, int N, int steps,
                     int steps_serial, Json& tref, const std::function<void(const std::string&, const std::string&, double)>& put41) {
  const int max_threads = omp_get_max_threads();
  const double h_um = p.box / N / units::um;
  omp_set_num_threads(1);  // the serial references on one thread
  const Timing serial = run_steps(ib, flow, X0, p, steps_serial, Interpolation::serial, Spreading::serial);
  omp_set_num_threads(max_threads);
  put41("1x CPU", "4.2", serial.spread);
  put41("1x CPU", "4.3", serial.interpolate);
  tref["rows"].push(st::row({"4.2 (spread)", N, h_um, serial.spread, 1.0}));
  tref["rows"].push(st::row({"4.3 1 thread (interpolate)", N, h_um, serial.interpolate, 1.0}));
  const std::string dev = std::to_string(max_threads) + "x CPU";
  for (Interpolation a : {Interpolation::parallel, Interpolation::binned}) {
    const Timing t = run_steps(ib, flow, X0, p, a == Interpolation::binned ? steps : steps_serial, a, Spreading::binned);
    put41(dev, std::string(algorithm_number(a)) + (a == Interpolation::binned ? " (interpolate)" : ""), t.interpolate);
    tref["rows"].push(st::row({std::string(algorithm_number(a)) + " (interpolate)", N, h_um, t.interpolate, serial.interpolate / t.interpolate}));
  }
  for (Spreading a : {Spreading::sort_reduce, Spreading::preallocated, Spreading::on_the_fly, Spreading::binned}) {
    const Timing t = run_steps(ib, flow, X0, p, a == Spreading::binned ? steps : steps_serial, Interpolation::binned, a);
    put41(dev, std::string(algorithm_number(a)) + (a == Spreading::binned ? " (spread)" : ""), t.spread);
    tref["rows"].push(st::row({std::string(algorithm_number(a)) + " (spread)", N, h_um, t.spread, serial.spread / t.spread}));
  }
}

/// Agreement with the serial algorithms at the initial positions, with a force of size k h: the
/// relative differences, the conservation sum f h^3 = sum F per component, and the adjointness
/// <S F, u> h^3 = <F, I u> with the shear flow as u.
void agreement(Interaction& ib, const Flow& flow, const host_vector<double>& X0, const Params& p, int N, int repeats, Json& tdiff,
               Json& tidiff, Agreement& w) {
  const index_t n = X0.size() / 3;
  const dvec X = X0;
  host_vector<double> Fh(3 * n);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> Ud(-1.0, 1.0);
  for (auto& v : Fh) v = Ud(rng) * p.spring * p.box / N;
  const dvec F = Fh;
  std::array<dvec, 3> ref, f;
  ib.spread(X, F, ref, Spreading::serial);
  for (Spreading a : all_spreadings()) {
    if (a == Spreading::serial) continue;
    const double t = st::median_seconds(repeats, [&] { ib.spread(X, F, f, a); });
    for (int c = 0; c < 3; ++c) {
      double total = 0.0, want = 0.0, absF = 0.0;
      for (double v : host_vector<double>(f[c])) total += v * ib.cell_volume();
      for (index_t k = 0; k < n; ++k) {
        want += Fh[c * n + k];
        absF += std::abs(Fh[c * n + k]);
      }
      w.conservation = std::max(w.conservation, std::abs(total - want) / absF);
    }
    const double rel = st::max_rel_diff(f, ref);
    w.spread = std::max(w.spread, rel);
    tdiff["rows"].push(st::row({algorithm_number(a), N, t, rel}));
  }
  dvec Uref, U;
  ib.interpolate(X, flow.u, Uref, Interpolation::serial);
  for (Interpolation a : {Interpolation::parallel, Interpolation::binned}) {
    const double t = st::median_seconds(repeats, [&] { ib.interpolate(X, flow.u, U, a); });
    const double rel = st::max_rel_diff({&U}, {&Uref});
    w.interp = std::max(w.interp, rel);
    tidiff["rows"].push(st::row({algorithm_number(a), N, t, rel}));
  }
  ib.spread(X, F, f, Spreading::binned);
  ib.interpolate(X, flow.u, U, Interpolation::binned);
  const host_vector<double> Uh = U;
  double lhs = 0.0, rhs = 0.0, mag = 0.0;
  for (int c = 0; c < 3; ++c) {
    const host_vector<double> fh = f[c], uh = flow.u[c];
    for (size_t m = 0; m < fh.size(); ++m) lhs += fh[m] * uh[m] * ib.cell_volume();
  }
  for (index_t i = 0; i < 3 * n; ++i) {
    rhs += Fh[i] * Uh[i];
    mag += std::abs(Fh[i] * Uh[i]);
  }
  w.adjoint = std::max(w.adjoint, std::abs(lhs - rhs) / mag);
}

/// Fig. 4.4: strong scaling at refinement 64, Algs. 4.3 / 4.6 and the binned ones, 1 ... all threads.
Json strong_scaling(const Params& p, const host_vector<double>& X0, int steps, int steps_serial) {
  const int max_threads = omp_get_max_threads();
  Json tstrong = st::table({"threads", "algorithm", "seconds", "speedup_vs_serial"}, {"", "", "s", ""});
  const auto boxes = mac_boxes({64, 64, 64}, {p.box, p.box, p.box}, {true, true, true});
  Interaction ib(boxes, p.kernel);
  const Flow flow = shear_flow(boxes, p);
  omp_set_num_threads(1);
  const Timing serial = run_steps(ib, flow, X0, p, steps_serial, Interpolation::serial, Spreading::serial);
  for (int threads = 1; threads <= max_threads; threads *= 2) {
    omp_set_num_threads(threads);
    const Timing a = run_steps(ib, flow, X0, p, steps_serial, Interpolation::parallel, Spreading::on_the_fly);
    const Timing b = run_steps(ib, flow, X0, p, steps, Interpolation::binned, Spreading::binned);
    tstrong["rows"].push(st::row({threads, "4.3 (interpolate)", a.interpolate, serial.interpolate / a.interpolate}));
    tstrong["rows"].push(st::row({threads, "4.6 (spread)", a.spread, serial.spread / a.spread}));
    tstrong["rows"].push(st::row({threads, "binned (interpolate)", b.interpolate, serial.interpolate / b.interpolate}));
    tstrong["rows"].push(st::row({threads, "binned (spread)", b.spread, serial.spread / b.spread}));
    if (threads < max_threads && threads * 2 > max_threads) threads = max_threads / 2;
  }
  omp_set_num_threads(max_threads);
  return tstrong;
}

/// Table 4.2: weak scaling at refinement 64 (h = 0.25 um), points doubling with threads while this
/// machine has them; beyond, the thread count stays at its maximum.
Json weak_scaling(const Params& p, const std::vector<index_t>& weak_n, int steps_binned, int steps_serial) {
  const int max_threads = omp_get_max_threads();
  Json t42 = st::table({"p", "n", "interpolation_seconds", "spreading_seconds", "spreading_binned_seconds", "interpolation_binned_seconds"},
                       {"", "", "s", "s", "s", "s"});
  const auto boxes = mac_boxes({64, 64, 64}, {p.box, p.box, p.box}, {true, true, true});
  Interaction ib(boxes, p.kernel);
  const Flow flow = shear_flow(boxes, p);
  for (size_t i = 0; i < weak_n.size(); ++i) {
    const int threads = std::min<int>(1 << i, max_threads);
    omp_set_num_threads(threads);
    const host_vector<double> X = random_points(weak_n[i], p.box, 99 + i);
    const Timing a = run_steps(ib, flow, X, p, steps_serial, Interpolation::parallel, Spreading::on_the_fly);
    const Timing b = run_steps(ib, flow, X, p, steps_binned, Interpolation::binned, Spreading::binned);
    t42["rows"].push(st::row({threads, double(weak_n[i]), a.interpolate, a.spread, b.spread, b.interpolate}));
  }
  omp_set_num_threads(max_threads);
  return t42;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter4_unstructured", [&] {
    // ---- Parameters ---------------------------------------------------------------------------
    const st::Options opt = st::parse_command_line(argc, argv, "chapter4_unstructured",
                                                   "Seed Sec. 4.2.1: interpolation and spreading of random tethered points (Table 4.1/4.2, Fig. 4.3/4.4)");
    const bool full = opt.scale == st::Scale::full;
    const Params p;
    const index_t n = index_t(1) << 16;
    const std::vector<int> refinements = {16, 32, 64, 128};
    // Steps per timing: the binned variants are cheap, the seed's algorithms (literal per-shift
    // weights, one pass per shift) are not; full scale 200 steps (the seed averaged over 1000), 20 for those.
    const int steps = full ? 200 : 10, steps_serial = full ? 20 : 1, max_threads = omp_get_max_threads();
    std::vector<index_t> weak_n = {index_t(1) << 16, index_t(1) << 17, index_t(1) << 18, index_t(1) << 19};
    if (!full) weak_n.resize(3);
    Json results = st::make_results(opt);
    record_parameters(results["parameters"], p, n, steps, steps_serial, max_threads);
    st::log(opt, "parameters: n = " + std::to_string(n) + ", " + std::to_string(steps) + " steps (" + std::to_string(steps_serial) +
                     " for the serial algorithms), " + std::to_string(max_threads) + " threads");
    const host_vector<double> X0 = random_points(n, p.box, 2024);

    // ---- 1. Table 4.1 / Fig. 4.3: time per call against grid refinement; agreement with serial ----
    Json tref = st::table({"algorithm", "refinement", "h_um", "seconds", "speedup_vs_serial"}, {"", "", "um", "s", ""});
    Json tdiff = st::table({"algorithm", "refinement", "seconds", "max_rel_diff_vs_serial"}, {"", "", "s", ""});
    Json tidiff = tdiff;
    Table41 t41;
    Agreement w;
    for (size_t r = 0; r < refinements.size(); ++r) {
      const int N = refinements[r];
      const auto boxes = mac_boxes({N, N, N}, {p.box, p.box, p.box}, {true, true, true});
      Interaction ib(boxes, p.kernel);
      const Flow flow = shear_flow(boxes, p);
      w.background = std::max(w.background, flow.max_background);
      st::log(opt, "1. refinement " + std::to_string(N) + " (h = " + std::to_string(p.box / N / units::um) + " um)");
      time_algorithms(ib, flow, X0, p, N, steps, steps_serial, tref, [&](auto& dev, auto& alg, double t) { t41.put(dev, alg, r, refinements.size(), t); });
      agreement(ib, flow, X0, p, N, full ? 5 : 1, tdiff, tidiff, w);
    }

    // ---- 2. Fig. 4.4 and 3. Table 4.2: strong and weak scaling at refinement 64 -------------------
    st::log(opt, "2. strong scaling, refinement 64, threads 1.." + std::to_string(max_threads));
    results["tables"]["table41"] = t41.json();
    results["tables"]["refinement"] = tref;
    results["tables"]["spreading_vs_serial"] = tdiff;
    results["tables"]["interpolation_vs_serial"] = tidiff;
    results["tables"]["strong_scaling"] = strong_scaling(p, X0, steps, steps_serial);
    st::log(opt, "3. weak scaling");
    results["tables"]["table42"] = weak_scaling(p, weak_n, full ? 100 : steps, steps_serial);
    Json& v = results["values"];
    v["max_rel_diff_spread_vs_serial"] = w.spread;
    v["max_rel_diff_interpolation_vs_serial"] = w.interp;
    v["max_rel_conservation_error"] = w.conservation;
    v["adjointness_rel_error"] = w.adjoint;
    v["max_background_force_dyn_per_cm3"] = w.background;
    st::log(opt, "max relative difference to serial: spreading " + std::to_string(w.spread) + ", interpolation " + std::to_string(w.interp));
    st::write_results(opt, results);
    return 0;
  });
}
