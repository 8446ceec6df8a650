// Benchmark of interpolation and spreading (seed Chapter 4): per-call times of every algorithm
// for 2^16 random points on the 64^3 grid of the 16 um periodic box (all three MAC components,
// B3 kernel), points per second per core, the fraction of a simple roofline bound, and the grid
// refinement beyond which the buffered spreading variants (Algs. 4.5/4.6) stop paying off against
// Alg. 4.4 (the seed: beyond about 128^3).
//
// Roofline model per call (all three components): flops = 3 n (2 s^3 + 2 s^2 + 2 s) for the
// tensor-product sums plus 6 n s kernel evaluations of about 10 flops; bytes = the point data
// (3 coordinates and 3 values, 48 n) plus one sweep over the three grid components (read for
// interpolation, read and write for spreading). Peak flops: 8 double flops per cycle per core
// (two 128-bit multiply and two 128-bit add pipes, the SSE4 target of this build) at the nominal
// clock from /proc/cpuinfo; bandwidth: measured here with a streaming triad. The bound is
// max(flops/peak, bytes/bandwidth); the fraction reported is bound/measured.
//
// Run:   build/studies/study_bench_ib --scale quick --out runs/bench_ib
#include "common/study.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/ib/grid.hpp"
#include "rbfib/ib/interaction.hpp"
#include "rbfib/ib/kernels.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

using namespace rbfib;
using namespace rbfib::ib;
namespace st = rbfib::study;
using st::Json;

namespace {

double cpu_mhz() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("cpu MHz", 0) == 0) return std::stod(line.substr(line.find(':') + 1));
  return NAN;
}

// Streaming triad a = b + s c over 3 x 32 MiB, bytes per second (median of repeats).
double triad_bandwidth() {
  const index_t n = index_t(1) << 22;
  dvec a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double t = st::median_seconds(7, [&] {
    thrust::transform(b.begin(), b.end(), c.begin(), a.begin(), [] RBFIB_HD(double x, double y) { return x + 3.0 * y; });
  });
  return 3.0 * 8.0 * n / t;
}

struct Times {
  double median = NAN, min = NAN;
};

// Median and minimum wall time of `repeats` calls (after one warm-up call when repeats > 2). On a
// shared machine the minimum is the closest to the uncontended time; the median is what a user sees.
Times time_calls(int repeats, const std::function<void()>& fn) {
  if (repeats > 2) fn();
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  const size_t m = t.size() / 2;
  return {t.size() % 2 ? t[m] : 0.5 * (t[m - 1] + t[m]), t.front()};
}

double load_average() {
  std::ifstream in("/proc/loadavg");
  double l = NAN;
  in >> l;
  return l;
}

using rbfib::study::table;

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("bench_ib", [&] {
    const st::Options opt = st::parse_command_line(argc, argv, "bench_ib", "Per-call times, points/s/core and roofline fraction of IB interpolation and spreading");
    const bool full = opt.scale == st::Scale::full;
    const double box = 16.0 * units::um;
    const index_t n = index_t(1) << 16;
    const int N = 64;
    const ib::Kernel kernel = ib::Kernel::bspline3;
    const int s = kernel_support(kernel);
    const int threads = omp_get_max_threads();
    const int repeats = full ? 21 : 7;
    const int repeats_slow = full ? 5 : 1;

    Json results = st::make_results(opt);
    Json& par = results["parameters"];
    par["points"] = double(n);
    par["refinement"] = N;
    par["box_um"] = box / units::um;
    par["kernel"] = ib::to_string(kernel);
    par["threads"] = threads;
    par["repeats"] = repeats;
    par["cpu_mhz"] = cpu_mhz();
    const char* policy = std::getenv("OMP_WAIT_POLICY");
    par["OMP_WAIT_POLICY"] = policy ? policy : "unset (libgomp default: spin, then sleep)";

    // 1. Machine model.
    const double bw = triad_bandwidth();
    const double peak = 8.0 * cpu_mhz() * 1e6 * threads;
    par["triad_bandwidth_GB_per_s"] = bw / 1e9;
    par["peak_gflops_model"] = peak / 1e9;
    st::log(opt, "1. " + std::to_string(threads) + " threads, triad bandwidth " + std::to_string(bw / 1e9) + " GB/s, model peak " +
                     std::to_string(peak / 1e9) + " GFlop/s");

    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> U(0.0, box), Uf(-1.0, 1.0);
    host_vector<double> Xh(3 * n), Fh(3 * n);
    for (auto& x : Xh) x = U(rng);
    for (auto& f : Fh) f = Uf(rng) * 1e-9;
    const dvec X = Xh, F = Fh;

    // 2. Per-call times at 64^3.
    Json tops = table({"operation", "algorithm", "threads", "seconds", "min_seconds", "points_per_s_per_core", "roofline_fraction",
                       "max_rel_diff_vs_serial"},
                      {"", "", "", "s", "s", "1/s", "", ""});
    par["load_average_at_start"] = load_average();
    const auto boxes = mac_boxes({N, N, N}, {box, box, box}, {true, true, true});
    Interaction ib(boxes, kernel);
    std::array<dvec, 3> u;
    for (int c = 0; c < 3; ++c) {
      host_vector<double> v(boxes[c].size());
      for (auto& x : v) x = Uf(rng);
      u[c] = v;
    }
    const double grid_values = 3.0 * boxes[0].size();
    const double flops = 3.0 * n * (2.0 * s * s * s + 2.0 * s * s + 2.0 * s) + 6.0 * n * s * 10.0;
    auto roofline = [&](double bytes) { return std::max(flops / peak, bytes / bw); };
    dvec Uref, Ut;
    ib.interpolate(X, u, Uref, Interpolation::serial);
    const host_vector<double> Urefh = Uref;
    double uscale = 0.0;
    for (double v : Urefh) uscale = std::max(uscale, std::abs(v));
    double best_interp = INFINITY, best_spread = INFINITY;
    for (Interpolation a : all_interpolations()) {
      const int th = a == Interpolation::serial ? 1 : threads;
      omp_set_num_threads(th);
      const Times tt = time_calls(a == Interpolation::binned ? repeats : repeats_slow, [&] { ib.interpolate(X, u, Ut, a); });
      const double t = tt.median;
      omp_set_num_threads(threads);
      const host_vector<double> Uh = Ut;
      double diff = 0.0;
      for (size_t i = 0; i < Uh.size(); ++i) diff = std::max(diff, std::abs(Uh[i] - Urefh[i]));
      const double bound = roofline(48.0 * n + 8.0 * grid_values) * threads / th;
      tops["rows"].push(Json::Array{Json("interpolate"), Json(algorithm_number(a)), Json(th), Json(t), Json(tt.min), Json(n / t / th), Json(bound / t),
                                    Json(diff / uscale)});
      if (a != Interpolation::serial) best_interp = std::min(best_interp, t);
      st::log(opt, std::string("2. interpolate ") + algorithm_number(a) + ": median " + std::to_string(t * 1e3) + " ms, min " +
                       std::to_string(tt.min * 1e3) + " ms");
    }
    std::array<dvec, 3> fref, f;
    ib.spread(X, F, fref, Spreading::serial);
    std::array<host_vector<double>, 3> frefh;
    double fscale = 0.0;
    for (int c = 0; c < 3; ++c) {
      frefh[c] = fref[c];
      for (double v : frefh[c]) fscale = std::max(fscale, std::abs(v));
    }
    for (Spreading a : all_spreadings()) {
      const bool slow = a != Spreading::binned;
      const int th = a == Spreading::serial ? 1 : threads;
      omp_set_num_threads(th);
      const Times tt = time_calls(slow ? repeats_slow : repeats, [&] { ib.spread(X, F, f, a); });
      const double t = tt.median;
      omp_set_num_threads(threads);
      double diff = 0.0;
      for (int c = 0; c < 3; ++c) {
        const host_vector<double> fh = f[c];
        for (size_t m = 0; m < fh.size(); ++m) diff = std::max(diff, std::abs(fh[m] - frefh[c][m]));
      }
      const double bound = roofline(48.0 * n + 16.0 * grid_values) * threads / th;
      tops["rows"].push(Json::Array{Json("spread"), Json(algorithm_number(a)), Json(th), Json(t), Json(tt.min), Json(n / t / th), Json(bound / t),
                                    Json(diff / fscale)});
      if (a != Spreading::serial) best_spread = std::min(best_spread, t);
      st::log(opt, std::string("2. spread ") + algorithm_number(a) + ": median " + std::to_string(t * 1e3) + " ms, min " +
                       std::to_string(tt.min * 1e3) + " ms");
    }

    // 2b. The binned variants on one thread (the per-core rate without parallel overhead).
    omp_set_num_threads(1);
    {
      const Times ti = time_calls(repeats, [&] { ib.interpolate(X, u, Ut, Interpolation::binned); });
      const Times ts = time_calls(repeats, [&] { ib.spread(X, F, f, Spreading::binned); });
      const double bi = roofline(48.0 * n + 8.0 * grid_values) * threads, bs = roofline(48.0 * n + 16.0 * grid_values) * threads;
      const host_vector<double> Uh = Ut;
      double di = 0.0, ds = 0.0;
      for (size_t i = 0; i < Uh.size(); ++i) di = std::max(di, std::abs(Uh[i] - Urefh[i]));
      for (int c = 0; c < 3; ++c) {
        const host_vector<double> fh = f[c];
        for (size_t m = 0; m < fh.size(); ++m) ds = std::max(ds, std::abs(fh[m] - frefh[c][m]));
      }
      tops["rows"].push(Json::Array{Json("interpolate"), Json("binned"), Json(1), Json(ti.median), Json(ti.min), Json(n / ti.median),
                                    Json(bi / ti.median), Json(di / uscale)});
      tops["rows"].push(Json::Array{Json("spread"), Json("binned"), Json(1), Json(ts.median), Json(ts.min), Json(n / ts.median),
                                    Json(bs / ts.median), Json(ds / fscale)});
      st::log(opt, "2b. one thread: interpolate binned median " + std::to_string(ti.median * 1e3) + " ms, spread binned median " +
                       std::to_string(ts.median * 1e3) + " ms");
    }
    omp_set_num_threads(threads);
    par["load_average_after_timing"] = load_average();

    // 3. Crossover: Algs. 4.4, 4.5, 4.6 and binned against refinement.
    std::vector<int> refinements = {16, 32, 64, 128};
    if (full) refinements.push_back(256);
    Json tcross = table({"refinement", "algorithm", "seconds"}, {"", "", "s"});
    int crossover = -1;
    for (int R : refinements) {
      const auto bx = mac_boxes({R, R, R}, {box, box, box}, {true, true, true});
      Interaction ibr(bx, kernel);
      double t44 = 0.0, t45 = 0.0;
      for (Spreading a : {Spreading::sort_reduce, Spreading::preallocated, Spreading::on_the_fly, Spreading::binned}) {
        const double t = time_calls(a == Spreading::binned ? repeats : repeats_slow, [&] { ibr.spread(X, F, f, a); }).median;
        tcross["rows"].push(Json::Array{Json(R), Json(algorithm_number(a)), Json(t)});
        if (a == Spreading::sort_reduce) t44 = t;
        if (a == Spreading::preallocated) t45 = t;
      }
      if (crossover < 0 && t45 > t44) crossover = R;
      st::log(opt, "3. refinement " + std::to_string(R) + ": 4.4 " + std::to_string(t44) + " s, 4.5 " + std::to_string(t45) + " s");
    }

    results["tables"]["operations"] = tops;
    results["tables"]["crossover"] = tcross;
    Json& v = results["values"];
    v["best_interpolation_seconds"] = best_interp;
    v["best_spreading_seconds"] = best_spread;
    v["goal_interpolation_seconds"] = 4e-3;
    v["goal_spreading_seconds"] = 6e-3;
    v["buffered_crossover_refinement"] = crossover < 0 ? Json() : Json(crossover);
    st::write_results(opt, results);
    return 0;
  });
}
