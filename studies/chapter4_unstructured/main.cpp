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
#include "common/study.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/ib/grid.hpp"
#include "rbfib/ib/interaction.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

using namespace rbfib;
using namespace rbfib::ib;
namespace st = rbfib::study;
using st::Json;

namespace {

struct Params {
  double box = 16.0 * units::um;
  double shear_rate = 1000.0;                      // 1/s
  double spring = 1e-2 * units::dyn / units::cm;   // k
  double viscosity = 0.1 * units::cP;              // plasma, seed Sec. 1.1
  double dt = 0.1 * units::us;
  ib::Kernel kernel = ib::Kernel::bspline3;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

host_vector<double> random_points(index_t n, double L, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, L);
  host_vector<double> X(3 * n);
  for (auto& x : X) x = U(rng);
  return X;
}

// The shear flow on the MAC grid (only the z component is nonzero; it lives at y = h (j + 1/2))
// and its background force f_bg = -mu Lap u, nonzero on the two rows next to the seam y = 0.
struct Flow {
  std::array<dvec, 3> u, f_bg;
  double max_background = 0.0;
};

Flow shear_flow(const std::array<Box, 3>& boxes, const Params& p) {
  Flow flow;
  const Box& bz = boxes[2];
  const int ny = bz.n(1);
  const double h = bz.axes[1].h();
  std::vector<double> uz(ny), fz(ny);
  for (int j = 0; j < ny; ++j) uz[j] = p.shear_rate * (bz.x(1, j) - 0.5 * p.box);
  for (int j = 0; j < ny; ++j) {
    const double lap = (uz[(j + 1) % ny] - 2 * uz[j] + uz[(j + ny - 1) % ny]) / (h * h);
    fz[j] = -p.viscosity * lap;
    flow.max_background = std::max(flow.max_background, std::abs(fz[j]));
  }
  for (int c = 0; c < 3; ++c) {
    host_vector<double> u(boxes[c].size(), 0.0), f(boxes[c].size(), 0.0);
    if (c == 2) {
      index_t m = 0;
      for (int k = 0; k < bz.n(2); ++k)
        for (int j = 0; j < bz.n(1); ++j)
          for (int i = 0; i < bz.n(0); ++i, ++m) {
            u[m] = uz[j];
            f[m] = fz[j];
          }
    }
    flow.u[c] = u;
    flow.f_bg[c] = f;
  }
  return flow;
}

struct Timing {
  double interpolate = NAN, spread = NAN;  // median seconds per call
};

// Runs `steps` time steps of the tethered-point problem and returns the median time per call of
// interpolation and of spreading (both components-inclusive: one call handles all three).
Timing run_steps(Interaction& ib, const Flow& flow, const host_vector<double>& X0h, const Params& p, int steps,
                 Interpolation interp, Spreading spread) {
  const index_t n = X0h.size() / 3;
  const dvec X0 = X0h;
  dvec X = X0, Xs(3 * n), F(3 * n), U;
  std::array<dvec, 3> f;
  std::vector<double> ti, ts;
  for (int step = 0; step < steps; ++step) {
    auto t0 = std::chrono::steady_clock::now();
    ib.interpolate(X, flow.u, U, interp);  // (1)
    ti.push_back(seconds_since(t0));
    const double dt = p.dt, k = p.spring;
    thrust::transform(X.begin(), X.end(), U.begin(), Xs.begin(), [dt] RBFIB_HD(double x, double v) { return x + dt * v; });  // (2)
    thrust::transform(Xs.begin(), Xs.end(), X0.begin(), F.begin(), [k] RBFIB_HD(double x, double x0) { return -k * (x - x0); });
    t0 = std::chrono::steady_clock::now();
    ib.spread(Xs, F, f, spread);  // (3)
    ts.push_back(seconds_since(t0));
    for (int c = 0; c < 3; ++c)
      thrust::transform(f[c].begin(), f[c].end(), flow.f_bg[c].begin(), f[c].begin(), thrust::plus<double>());
    t0 = std::chrono::steady_clock::now();
    ib.interpolate(Xs, flow.u, U, interp);  // (4)
    ti.push_back(seconds_since(t0));
    thrust::transform(X.begin(), X.end(), U.begin(), X.begin(), [dt] RBFIB_HD(double x, double v) { return x + dt * v; });  // (5)
  }
  return {st::median(ti), st::median(ts)};
}

double max_abs(const host_vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

using rbfib::study::table;

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter4_unstructured", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "chapter4_unstructured",
                                                   "Seed Sec. 4.2.1: interpolation and spreading of random tethered points (Table 4.1/4.2, Fig. 4.3/4.4)");
    const bool full = opt.scale == st::Scale::full;
    const Params p;
    const index_t n = index_t(1) << 16;
    const std::vector<int> refinements = {16, 32, 64, 128};
    // Steps per timing: the binned variants are cheap, the seed's algorithms (literal per-shift
    // weights, one pass per shift) are not; full scale uses 200 steps (the seed averaged over
    // 1000), and 20 for those.
    const int steps = full ? 200 : 10;
    const int steps_serial = full ? 20 : 1;
    const int max_threads = omp_get_max_threads();
    std::vector<index_t> weak_n = {index_t(1) << 16, index_t(1) << 17, index_t(1) << 18, index_t(1) << 19};
    if (!full) weak_n.resize(3);

    Json results = st::make_results(opt);
    Json& par = results["parameters"];
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
    par["threads"] = max_threads;
    {
      const char* policy = std::getenv("OMP_WAIT_POLICY");
      par["OMP_WAIT_POLICY"] = policy ? policy : "unset (libgomp default: spin, then sleep)";
      std::ifstream in("/proc/loadavg");
      double load = NAN;
      in >> load;
      par["load_average_at_start"] = load;  // this machine is shared: times are indicative
    }
    par["machine_paper"] = "48x Intel Xeon E5-2697 v2 2.70GHz (16 cores used), libiomp5, clang 7.0.1";
    st::log(opt, "parameters: n = " + std::to_string(n) + ", box = 16 um, kernel " + std::string(ib::to_string(p.kernel)) + ", gamma_dot = 1000/s, k = 1e-2 dyn/cm, dt = 0.1 us, " +
                     std::to_string(steps) + " steps (" + std::to_string(steps_serial) + " for the serial algorithms), " +
                     std::to_string(max_threads) + " threads");

    const host_vector<double> X0 = random_points(n, p.box, 2024);

    // 1. Table 4.1 / Fig. 4.3: time per call against grid refinement.
    Json t41 = table({"device", "algorithm", "g16_seconds", "g32_seconds", "g64_seconds", "g128_seconds"}, {"", "", "s", "s", "s", "s"});
    Json tref = table({"algorithm", "refinement", "h_um", "seconds", "speedup_vs_serial"}, {"", "", "um", "s", ""});
    Json tdiff = table({"algorithm", "refinement", "seconds", "max_rel_diff_vs_serial"}, {"", "", "s", ""});
    Json tidiff = table({"algorithm", "refinement", "seconds", "max_rel_diff_vs_serial"}, {"", "", "s", ""});
    struct Row {
      std::string device, algorithm;
      std::vector<double> t;
    };
    std::vector<Row> rows41;
    double worst_spread = 0.0, worst_interp = 0.0, worst_conservation = 0.0, worst_adjoint = 0.0, max_bg = 0.0;
    for (size_t r = 0; r < refinements.size(); ++r) {
      const int N = refinements[r];
      const auto boxes = mac_boxes({N, N, N}, {p.box, p.box, p.box}, {true, true, true});
      Interaction ib(boxes, p.kernel);
      const Flow flow = shear_flow(boxes, p);
      max_bg = std::max(max_bg, flow.max_background);
      st::log(opt, "1. refinement " + std::to_string(N) + " (h = " + std::to_string(p.box / N / units::um) + " um)");
      // serial references: one thread
      omp_set_num_threads(1);
      const Timing serial = run_steps(ib, flow, X0, p, steps_serial, Interpolation::serial, Spreading::serial);
      omp_set_num_threads(max_threads);
      auto put41 = [&](const std::string& dev, const std::string& alg, double t) {
        auto it = std::find_if(rows41.begin(), rows41.end(), [&](const Row& w) { return w.device == dev && w.algorithm == alg; });
        if (it == rows41.end()) {
          rows41.push_back({dev, alg, std::vector<double>(refinements.size(), NAN)});
          it = rows41.end() - 1;
        }
        it->t[r] = t;
      };
      put41("1x CPU", "4.2", serial.spread);
      put41("1x CPU", "4.3", serial.interpolate);
      tref["rows"].push(Json::Array{Json("4.2 (spread)"), Json(N), Json(p.box / N / units::um), Json(serial.spread), Json(1.0)});
      tref["rows"].push(Json::Array{Json("4.3 1 thread (interpolate)"), Json(N), Json(p.box / N / units::um), Json(serial.interpolate), Json(1.0)});
      const std::string dev = std::to_string(max_threads) + "x CPU";
      for (Interpolation a : {Interpolation::parallel, Interpolation::binned}) {
        const Timing t = run_steps(ib, flow, X0, p, a == Interpolation::binned ? steps : steps_serial, a, Spreading::binned);
        put41(dev, std::string(algorithm_number(a)) + (a == Interpolation::binned ? " (interpolate)" : ""), t.interpolate);
        tref["rows"].push(Json::Array{Json(std::string(algorithm_number(a)) + " (interpolate)"), Json(N), Json(p.box / N / units::um), Json(t.interpolate),
                                      Json(serial.interpolate / t.interpolate)});
      }
      for (Spreading a : {Spreading::sort_reduce, Spreading::preallocated, Spreading::on_the_fly, Spreading::binned}) {
        const Timing t = run_steps(ib, flow, X0, p, a == Spreading::binned ? steps : steps_serial, Interpolation::binned, a);
        put41(dev, std::string(algorithm_number(a)) + (a == Spreading::binned ? " (spread)" : ""), t.spread);
        tref["rows"].push(Json::Array{Json(std::string(algorithm_number(a)) + " (spread)"), Json(N), Json(p.box / N / units::um), Json(t.spread),
                                      Json(serial.spread / t.spread)});
      }

      // Agreement with the serial algorithms at the initial positions, with a force of size k h.
      const dvec X = X0;
      host_vector<double> Fh(3 * n);
      std::mt19937_64 rng(7);
      std::uniform_real_distribution<double> Ud(-1.0, 1.0);
      for (auto& v : Fh) v = Ud(rng) * p.spring * p.box / N;
      const dvec F = Fh;
      std::array<dvec, 3> ref;
      ib.spread(X, F, ref, Spreading::serial);
      double scale = 0.0;
      std::array<host_vector<double>, 3> refh;
      for (int c = 0; c < 3; ++c) {
        refh[c] = ref[c];
        scale = std::max(scale, max_abs(refh[c]));
      }
      for (Spreading a : all_spreadings()) {
        if (a == Spreading::serial) continue;
        std::array<dvec, 3> f;
        const double t = st::median_seconds(full ? 5 : 1, [&] { ib.spread(X, F, f, a); });
        double diff = 0.0;
        for (int c = 0; c < 3; ++c) {
          host_vector<double> fh = f[c];
          for (size_t m = 0; m < fh.size(); ++m) diff = std::max(diff, std::abs(fh[m] - refh[c][m]));
          // conservation: sum f h^3 = sum F per component
          double total = 0.0, want = 0.0, absF = 0.0;
          for (double v : fh) total += v * ib.cell_volume();
          for (index_t k = 0; k < n; ++k) {
            want += Fh[c * n + k];
            absF += std::abs(Fh[c * n + k]);
          }
          worst_conservation = std::max(worst_conservation, std::abs(total - want) / absF);
        }
        worst_spread = std::max(worst_spread, diff / scale);
        tdiff["rows"].push(Json::Array{Json(algorithm_number(a)), Json(N), Json(t), Json(diff / scale)});
      }
      dvec Uref, U;
      ib.interpolate(X, flow.u, Uref, Interpolation::serial);
      const host_vector<double> Urefh = Uref;
      const double uscale = max_abs(Urefh);
      for (Interpolation a : {Interpolation::parallel, Interpolation::binned}) {
        const double t = st::median_seconds(full ? 5 : 1, [&] { ib.interpolate(X, flow.u, U, a); });
        const host_vector<double> Uh = U;
        double diff = 0.0;
        for (size_t i = 0; i < Uh.size(); ++i) diff = std::max(diff, std::abs(Uh[i] - Urefh[i]));
        worst_interp = std::max(worst_interp, diff / uscale);
        tidiff["rows"].push(Json::Array{Json(algorithm_number(a)), Json(N), Json(t), Json(diff / uscale)});
      }
      // Adjointness <S F, u> h^3 = <F, I u> with the shear flow as u.
      {
        std::array<dvec, 3> f;
        ib.spread(X, F, f, Spreading::binned);
        ib.interpolate(X, flow.u, U, Interpolation::binned);
        const host_vector<double> Uh = U;
        double lhs = 0.0, rhs = 0.0, mag = 0.0;
        for (int c = 0; c < 3; ++c) {
          host_vector<double> fh = f[c], uh = flow.u[c];
          for (size_t m = 0; m < fh.size(); ++m) lhs += fh[m] * uh[m] * ib.cell_volume();
        }
        for (index_t i = 0; i < 3 * n; ++i) {
          rhs += Fh[i] * Uh[i];
          mag += std::abs(Fh[i] * Uh[i]);
        }
        worst_adjoint = std::max(worst_adjoint, std::abs(lhs - rhs) / mag);
      }
    }
    for (const Row& w : rows41) {
      Json::Array row{Json(w.device), Json(w.algorithm)};
      for (double t : w.t) row.push_back(Json(t));
      t41["rows"].push(Json(row));
    }

    // 2. Fig. 4.4: strong scaling at refinement 64, 2^16 points.
    st::log(opt, "2. strong scaling, refinement 64, threads 1.." + std::to_string(max_threads));
    Json tstrong = table({"threads", "algorithm", "seconds", "speedup_vs_serial"}, {"", "", "s", ""});
    {
      const auto boxes = mac_boxes({64, 64, 64}, {p.box, p.box, p.box}, {true, true, true});
      Interaction ib(boxes, p.kernel);
      const Flow flow = shear_flow(boxes, p);
      omp_set_num_threads(1);
      const Timing serial = run_steps(ib, flow, X0, p, steps_serial, Interpolation::serial, Spreading::serial);
      for (int threads = 1; threads <= max_threads; threads *= 2) {
        omp_set_num_threads(threads);
        const Timing a = run_steps(ib, flow, X0, p, steps_serial, Interpolation::parallel, Spreading::on_the_fly);
        const Timing b = run_steps(ib, flow, X0, p, steps, Interpolation::binned, Spreading::binned);
        tstrong["rows"].push(Json::Array{Json(threads), Json("4.3 (interpolate)"), Json(a.interpolate), Json(serial.interpolate / a.interpolate)});
        tstrong["rows"].push(Json::Array{Json(threads), Json("4.6 (spread)"), Json(a.spread), Json(serial.spread / a.spread)});
        tstrong["rows"].push(Json::Array{Json(threads), Json("binned (interpolate)"), Json(b.interpolate), Json(serial.interpolate / b.interpolate)});
        tstrong["rows"].push(Json::Array{Json(threads), Json("binned (spread)"), Json(b.spread), Json(serial.spread / b.spread)});
        if (threads < max_threads && threads * 2 > max_threads) threads = max_threads / 2;
      }
      omp_set_num_threads(max_threads);
    }

    // 3. Table 4.2: weak scaling at refinement 64 (h = 0.25 um), points doubling with threads
    //    while this machine has them; beyond, the thread count stays at its maximum.
    st::log(opt, "3. weak scaling");
    Json t42 = table({"p", "n", "interpolation_seconds", "spreading_seconds", "spreading_binned_seconds", "interpolation_binned_seconds"},
                     {"", "", "s", "s", "s", "s"});
    {
      const auto boxes = mac_boxes({64, 64, 64}, {p.box, p.box, p.box}, {true, true, true});
      Interaction ib(boxes, p.kernel);
      const Flow flow = shear_flow(boxes, p);
      for (size_t i = 0; i < weak_n.size(); ++i) {
        const int threads = std::min<int>(1 << i, max_threads);
        omp_set_num_threads(threads);
        const host_vector<double> X = random_points(weak_n[i], p.box, 99 + i);
        const Timing a = run_steps(ib, flow, X, p, steps_serial, Interpolation::parallel, Spreading::on_the_fly);
        const Timing b = run_steps(ib, flow, X, p, full ? 100 : steps, Interpolation::binned, Spreading::binned);
        t42["rows"].push(Json::Array{Json(threads), Json(double(weak_n[i])), Json(a.interpolate), Json(a.spread), Json(b.spread), Json(b.interpolate)});
      }
      omp_set_num_threads(max_threads);
    }

    results["tables"]["table41"] = t41;
    results["tables"]["refinement"] = tref;
    results["tables"]["spreading_vs_serial"] = tdiff;
    results["tables"]["interpolation_vs_serial"] = tidiff;
    results["tables"]["strong_scaling"] = tstrong;
    results["tables"]["table42"] = t42;
    Json& v = results["values"];
    v["max_rel_diff_spread_vs_serial"] = worst_spread;
    v["max_rel_diff_interpolation_vs_serial"] = worst_interp;
    v["max_rel_conservation_error"] = worst_conservation;
    v["adjointness_rel_error"] = worst_adjoint;
    v["max_background_force_dyn_per_cm3"] = max_bg;
    st::log(opt, "max relative difference to serial: spreading " + std::to_string(worst_spread) + ", interpolation " + std::to_string(worst_interp));
    st::write_results(opt, results);
    return 0;
  });
}
