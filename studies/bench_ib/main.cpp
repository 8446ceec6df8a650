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
#include "common/machine.hpp"
#include "common/study.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/ib/grid.hpp"
#include "rbfib/ib/interaction.hpp"
#include "rbfib/ib/kernels.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
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

/// The operations at 64^3: the points and forces, the grid velocity, the serial references, and the
/// roofline bound of a call (all three components) given the bytes it moves.
struct Problem {
  index_t n = 0;
  dvec X, F;
  std::array<dvec, 3> u, f_serial;
  dvec U_serial;
  double grid_values = 0, flops = 0, peak = 0, bandwidth = 0;
  double roofline(double bytes) const { return std::max(flops / peak, bytes / bandwidth); }
  double interpolation_bound(int threads, int th) const { return roofline(48.0 * n + 8.0 * grid_values) * threads / th; }
  double spreading_bound(int threads, int th) const { return roofline(48.0 * n + 16.0 * grid_values) * threads / th; }
};

/// Times one operation on `th` threads and adds its row: median and minimum, points per second per
/// core, the roofline fraction, and the relative difference to the serial reference.
double add_row(Json& table, const char* op, const std::string& algorithm, int th, int repeats, const std::function<void()>& call,
               double bound, const std::function<double()>& diff, index_t n) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(th);
  const Times tt = time_calls(repeats, call);
  omp_set_num_threads(threads);
  table["rows"].push(st::row({op, algorithm, th, tt.median, tt.min, n / tt.median / th, bound / tt.median, diff()}));
  return tt.median;
}

/// Random points, forces and grid velocity (seeded) on the grid of `ib`, and the serial references.
Problem make_problem(index_t n, double box, const std::array<Box, 3>& boxes, Interaction& ib, int s, double peak, double bandwidth) {
  Problem P;
  P.n = n;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> U(0.0, box), Uf(-1.0, 1.0);
  host_vector<double> Xh(3 * n), Fh(3 * n);
  for (auto& x : Xh) x = U(rng);
  for (auto& f : Fh) f = Uf(rng) * 1e-9;
  P.X = Xh, P.F = Fh;
  for (int c = 0; c < 3; ++c) {
    host_vector<double> v(boxes[c].size());
    for (auto& x : v) x = Uf(rng);
    P.u[c] = v;
  }
  P.grid_values = 3.0 * boxes[0].size();
  P.flops = 3.0 * n * (2.0 * s * s * s + 2.0 * s * s + 2.0 * s) + 6.0 * n * s * 10.0;
  P.peak = peak, P.bandwidth = bandwidth;
  ib.interpolate(P.X, P.u, P.U_serial, Interpolation::serial);
  ib.spread(P.X, P.F, P.f_serial, Spreading::serial);
  return P;
}

/// Every interpolation and spreading algorithm (the serial ones on one thread), then the binned ones
/// on one thread (the per-core rate without parallel overhead); the best parallel times.
std::pair<double, double> operations(const st::Options& opt, Json& tops, Interaction& ib, const Problem& P, int repeats, int repeats_slow) {
  const int threads = omp_get_max_threads();
  dvec Ut;
  std::array<dvec, 3> f;
  auto interp_diff = [&] { return st::max_rel_diff({&Ut}, {&P.U_serial}); };
  auto spread_diff = [&] { return st::max_rel_diff(f, P.f_serial); };
  double best_interp = INFINITY, best_spread = INFINITY;
  for (Interpolation a : all_interpolations()) {
    const int th = a == Interpolation::serial ? 1 : threads;
    const double t = add_row(tops, "interpolate", algorithm_number(a), th, a == Interpolation::binned ? repeats : repeats_slow,
                             [&] { ib.interpolate(P.X, P.u, Ut, a); }, P.interpolation_bound(threads, th), interp_diff, P.n);
    if (a != Interpolation::serial) best_interp = std::min(best_interp, t);
    st::log(opt, std::string("2. interpolate ") + algorithm_number(a) + ": median " + std::to_string(t * 1e3) + " ms");
  }
  for (Spreading a : all_spreadings()) {
    const int th = a == Spreading::serial ? 1 : threads;
    const double t = add_row(tops, "spread", algorithm_number(a), th, a == Spreading::binned ? repeats : repeats_slow,
                             [&] { ib.spread(P.X, P.F, f, a); }, P.spreading_bound(threads, th), spread_diff, P.n);
    if (a != Spreading::serial) best_spread = std::min(best_spread, t);
    st::log(opt, std::string("2. spread ") + algorithm_number(a) + ": median " + std::to_string(t * 1e3) + " ms");
  }
  const double ti = add_row(tops, "interpolate", "binned", 1, repeats, [&] { ib.interpolate(P.X, P.u, Ut, Interpolation::binned); },
                            P.interpolation_bound(threads, 1), interp_diff, P.n);
  const double ts = add_row(tops, "spread", "binned", 1, repeats, [&] { ib.spread(P.X, P.F, f, Spreading::binned); },
                            P.spreading_bound(threads, 1), spread_diff, P.n);
  st::log(opt, "2b. one thread: interpolate binned median " + std::to_string(ti * 1e3) + " ms, spread binned median " +
                   std::to_string(ts * 1e3) + " ms");
  return {best_interp, best_spread};
}

/// Spreading by Algs. 4.4, 4.5, 4.6 and binned on each refinement; the first refinement at which
/// Alg. 4.5 (buffered) is slower than Alg. 4.4, or -1.
int crossover_refinement(const st::Options& opt, Json& table, const Problem& P, const std::vector<int>& refinements, double box,
                         ib::Kernel kernel, int repeats, int repeats_slow) {
  int crossover = -1;
  std::array<dvec, 3> f;
  for (int R : refinements) {
    Interaction ib(mac_boxes({R, R, R}, {box, box, box}, {true, true, true}), kernel);
    double t44 = 0.0, t45 = 0.0;
    for (Spreading a : {Spreading::sort_reduce, Spreading::preallocated, Spreading::on_the_fly, Spreading::binned}) {
      const double t = time_calls(a == Spreading::binned ? repeats : repeats_slow, [&] { ib.spread(P.X, P.F, f, a); }).median;
      table["rows"].push(st::row({R, algorithm_number(a), t}));
      if (a == Spreading::sort_reduce) t44 = t;
      if (a == Spreading::preallocated) t45 = t;
    }
    if (crossover < 0 && t45 > t44) crossover = R;
    st::log(opt, "3. refinement " + std::to_string(R) + ": 4.4 " + std::to_string(t44) + " s, 4.5 " + std::to_string(t45) + " s");
  }
  return crossover;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("bench_ib", [&] {
    // 1. Parameters and the machine model.
    const st::Options opt = st::parse_command_line(argc, argv, "bench_ib", "Per-call times, points/s/core and roofline fraction of IB interpolation and spreading");
    const bool full = opt.scale == st::Scale::full;
    const double box = 16.0 * units::um;
    const index_t n = index_t(1) << 16;
    const int N = 64, threads = omp_get_max_threads(), repeats = full ? 21 : 7, repeats_slow = full ? 5 : 1;
    const ib::Kernel kernel = ib::Kernel::bspline3;
    Json results = st::make_results(opt);
    Json& par = results["parameters"];
    par["points"] = double(n);
    par["refinement"] = N;
    par["box_um"] = box / units::um;
    par["kernel"] = ib::to_string(kernel);
    par["threads"] = threads;
    par["repeats"] = repeats;
    par["cpu_mhz"] = cpu_mhz();
    st::record_wait_policy(par);
    const double bandwidth = triad_bandwidth(), peak = 8.0 * cpu_mhz() * 1e6 * threads;
    par["triad_bandwidth_GB_per_s"] = bandwidth / 1e9;
    par["peak_gflops_model"] = peak / 1e9;
    st::log(opt, "1. " + std::to_string(threads) + " threads, triad bandwidth " + std::to_string(bandwidth / 1e9) +
                     " GB/s, model peak " + std::to_string(peak / 1e9) + " GFlop/s");

    // 2. Per-call times at 64^3, every algorithm, against the serial one.
    const auto boxes = mac_boxes({N, N, N}, {box, box, box}, {true, true, true});
    Interaction ib(boxes, kernel);
    const Problem P = make_problem(n, box, boxes, ib, kernel_support(kernel), peak, bandwidth);
    par["load_average_at_start"] = st::load_average();
    Json tops = st::table({"operation", "algorithm", "threads", "seconds", "min_seconds", "points_per_s_per_core", "roofline_fraction",
                           "max_rel_diff_vs_serial"},
                          {"", "", "", "s", "s", "1/s", "", ""});
    const auto [best_interp, best_spread] = operations(opt, tops, ib, P, repeats, repeats_slow);
    par["load_average_after_timing"] = st::load_average();

    // 3. Crossover: Algs. 4.4, 4.5, 4.6 and binned against refinement.
    Json tcross = st::table({"refinement", "algorithm", "seconds"}, {"", "", "s"});
    const int crossover = crossover_refinement(opt, tcross, P, full ? std::vector<int>{16, 32, 64, 128, 256} : std::vector<int>{16, 32, 64, 128},
                                               box, kernel, repeats, repeats_slow);
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
