// Benchmark of the cell force call (dissertation Secs. 2.3-2.4 and 5.2): the whole-blood cell
// load of Sec. 5.2, 8 red cells and 2 platelets, with every force of their models (red cell:
// Skalak, bending, dissipation; platelet: neo-Hookean, bending with its reference curvature).
//
// Reports, per cell type: time per force call (median of repeats) split into the dense operator
// products, bending (its data-site products, H kernel and the jets of H - H'), the site kernels
// and the reductions; the flop rate of the products against a square DGEMM measured in the same
// run (this machine's ceiling for dense products); the memory held by each type's operators;
// the time per red cell as the batch grows (N = 1, 2, 4, 8); the red cells' product shape against
// the square GEMM on one thread and on the team, in double and single precision, with the rows
// split among the threads or left to the BLAS's threads; and, as the error of this speed,
// the largest difference between the batched forces and the per-cell host path.
//
// Sizes: full scale, red cells 2,500 data / 10,000 sample sites (Secs. 5.1.3, 5.2); quick scale
// 625 / 2,500 (Sec. 5.1.2); platelets 900 / 900 at both.
//
// Run:   build/studies/study_bench_cells --scale quick --out runs/bench_cells
#include "common/force_call.hpp"
#include "common/machine.hpp"
#include "common/study.hpp"
#include "rbfib/cells/batch.hpp"
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/linalg/dense.hpp"
#include "rbfib/mechanics/shell.hpp"
#include "rbfib/surface/geometry.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>

using namespace rbfib;
using namespace rbfib::cells;
namespace st = rbfib::study;
using st::Json;

namespace {

/// Cells of the whole-blood scene: two rows of four red cells (Sec. 5.2.1: concavities facing z,
/// rows staggered), each turned and slightly stretched so that every force is nonzero.
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

/// Smooth velocities at the data sites (a linear field, 1/s times position): the dissipation
/// term then does real work.
void set_velocities(Batch& b) {
  const std::vector<double> X = b.positions_host();
  std::vector<double> U(X.size());
  const index_t nd = b.type().n_data(), N = b.size();
  for (index_t c = 0; c < N; ++c)
    for (index_t i = 0; i < nd; ++i) {
      const double x = X[(0 * N + c) * nd + i], y = X[(1 * N + c) * nd + i], z = X[(2 * N + c) * nd + i];
      U[(0 * N + c) * nd + i] = 1000 * y;  // shear 1000/s (Sec. 5.2)
      U[(1 * N + c) * nd + i] = 50 * z;
      U[(2 * N + c) * nd + i] = -30 * x;
    }
  thrust::copy(U.begin(), U.end(), b.state().storage().begin() + 3 * N * nd);
}

/// max |batched - per-cell| / max |per-cell| over the force densities of cell c, against the
/// host path of mechanics/shell.hpp (the same kernels, one cell at a time).
double per_cell_difference(const Batch& b, index_t c) {
  const CellType& t = b.type();
  CellForces out;
  compute_forces(b, out);
  const index_t nd = t.n_data(), ns = t.n_sample(), N = b.size();
  const std::vector<double> state = b.state().to_host(), dens = out.density.to_host();
  auto column = [](const std::vector<double>& M, index_t n, index_t N_, index_t cell, index_t col0) {
    std::vector<double> o(static_cast<std::size_t>(3 * n));
    for (index_t d = 0; d < 3; ++d)
      for (index_t i = 0; i < n; ++i) o[d * n + i] = M[(col0 + d * N_ + cell) * n + i];
    return o;
  };
  const std::vector<double> X = column(state, nd, N, c, 0);
  const auto Z = t.reference_jets_host();
  const auto XJ = surface::jets_from_operators(t.to_sample(), X);
  const ForceModel& m = t.model();
  std::vector<double> F(static_cast<std::size_t>(3 * ns), 0.0);
  auto add = [&](const std::vector<double>& G) {
    for (std::size_t k = 0; k < F.size(); ++k) F[k] += G[k];
  };
  for (const auto& e : m.elastic) add(mechanics::elastic_force_density(t.name(), XJ, Z, e));
  if (m.bending()) {
    std::vector<double> H0;
    if (m.H0_reference) {
      H0.resize(t.H0_data().size());
      thrust::copy(t.H0_data().begin(), t.H0_data().end(), H0.begin());
    }
    add(mechanics::bending_force_density(t.name(), *t.at_data(), t.to_sample(), X, Z, {m.kappa, m.H0, H0}));
  }
  if (m.dissipation())
    add(mechanics::dissipative_force_density(t.name(), XJ, surface::jets_from_operators(t.to_sample(), column(state, nd, N, c, 3 * N)),
                                             Z, m.nu));
  const std::vector<double> got = column(dens, ns, N, c, 0);
  double diff = 0, scale = 0;
  for (std::size_t k = 0; k < F.size(); ++k) {
    diff = std::max(diff, std::abs(got[k] - F[k]));
    scale = std::max(scale, std::abs(F[k]));
  }
  return diff / scale;
}

/// The load's sums over its cell types (the whole-blood load: 8 red cells and 2 platelets).
struct Load {
  double seconds = 0, kernel_seconds = 0, product_flops = 0, product_seconds = 0, roofline_seconds = 0;
};

/// A cell type built (and timed) as a row of the cell_types table.
template <class Make>
std::shared_ptr<const CellType> build(const st::Options& opt, Json& types, Make make) {
  const auto t0 = std::chrono::steady_clock::now();
  std::shared_ptr<const CellType> t = make();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  types["rows"].push(st::row({t->name(), double(t->n_data()), double(t->n_sample()), s, double(t->bytes()) / 1048576.0,
                              t->model().describe()}));
  st::log(opt, "2. " + t->describe() + " (built in " + to_text(s) + " s)");
  return t;
}

/// One row of the force_calls table: a batch of `type` at `placements`, its median force call split
/// by phase, its products against the ceilings, and the difference to the per-cell path; added to
/// `load` when given. Roofline of the products: each streams its operator once and does 2 k flops
/// per operator entry for k columns, so its time is at least max(flops / DGEMM rate, bytes / triad
/// bandwidth).
void measure(const st::Options& opt, Json& calls, const std::shared_ptr<const CellType>& type,
             const std::vector<Placement>& placements, int repeats, const st::Ceiling& c, Load* load = nullptr) {
  Batch b(type, placements);
  if (type->model().dissipation()) set_velocities(b);
  double total = 0;
  const ForceTimings t = st::median_force_timings(b, repeats, total);
  const ProductFlops f = product_flops(type->spec(), b.size());
  const double rate = (f.jets + f.bending) / t.products();
  const double roofline = std::max((f.jets + f.bending) / c.dgemm_flops, f.bytes / c.triad_bytes_per_s);
  const double kernel_seconds = t.kernels + t.bending_kernel + t.reductions;  // site launch, bending's H kernel, reductions
  const double diff = per_cell_difference(b, b.size() - 1);
  calls["rows"].push(st::row({type->name(), double(b.size()), total, t.products(), t.bending(), t.kernels, t.reductions,
                              total / double(b.size()), rate / 1e9, rate / c.dgemm_flops, roofline / t.products(),
                              kernel_seconds / total, diff}));
  st::log(opt, "3. " + type->name() + " x " + to_text(b.size()) + ": " + to_text(total * 1e3) + " ms per call (products " +
                   to_text(t.products() * 1e3) + " of which bending " + to_text(t.bending_products * 1e3) + ", bending H kernel " +
                   to_text(t.bending_kernel * 1e3) + ", site kernels " + to_text(t.kernels * 1e3) + ", reductions " +
                   to_text(t.reductions * 1e3) + " ms); products at " + to_text(rate / 1e9) + " GFlop/s = " +
                   to_text(rate / c.dgemm_flops) + " of DGEMM; batched vs per-cell " + to_text(diff));
  if (load) {
    load->seconds += total;
    load->kernel_seconds += kernel_seconds;
    load->product_flops += f.jets + f.bending;
    load->product_seconds += t.products();
    load->roofline_seconds += roofline;
  }
}

/// Flop rate of C (m x n) = A (m x k) B (k x n) in precision T through linalg/dense on `threads`
/// threads, tall products split by rows among them or left to the BLAS (median of repeats).
template <class T>
double product_rate(index_t m, index_t k, index_t n, int threads, bool split, int repeats) {
  std::vector<T> a(static_cast<std::size_t>(m * k)), b(static_cast<std::size_t>(k * n));
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = T(std::sin(0.001 * double(i)));
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = T(std::cos(0.003 * double(i)));
  const auto A = linalg::Matrix<T>::from_host(m, k, a.data()), B = linalg::Matrix<T>::from_host(k, n, b.data());
  linalg::Matrix<T> C(m, n);
  const int team = omp_get_max_threads();
  const bool was = linalg::rows_per_thread();
  omp_set_num_threads(threads);
  linalg::set_rows_per_thread(split);
  auto call = [&] { linalg::gemm(linalg::Op::none, linalg::Op::none, T(1), A.view(), B.view(), T(0), C.view()); };
  call();
  const double t = st::median_seconds(repeats, [&] {
    call();
    synchronize();
  });
  linalg::set_rows_per_thread(was);
  omp_set_num_threads(team);
  return 2.0 * double(m) * double(k) * double(n) / t;
}

/// The products table: a square DGEMM and the red cells' product (one sample-site operator of
/// n_s x n_d on the 56 columns of 8 cells) in double and single precision, on one thread and on
/// the whole team, tall products split by rows among the threads or left to the BLAS.
void measure_products(const st::Options& opt, Json& results, index_t ns, index_t nd, index_t square, int repeats) {
  Json T = st::table({"product", "precision", "threads", "threading", "gflops"}, {"", "", "", "", "GFlop/s"});
  const int team = omp_get_max_threads();
  Json& V = results["values"];
  for (const bool single : {false, true}) {
    const std::string prec = single ? "single" : "double";
    for (int threads = 1; threads <= team; threads *= 2) {
      const double sq = single ? product_rate<float>(square, square, square, threads, true, repeats)
                               : product_rate<double>(square, square, square, threads, true, repeats);
      T["rows"].push(st::row({"square " + to_text(square), prec, double(threads), "BLAS", sq / 1e9}));
      V[(single ? "sgemm_gflops_" : "dgemm_gflops_") + to_text(threads) + "_threads"] = sq / 1e9;
      for (const bool split : {false, true}) {
        if (split && threads == 1) continue;
        const double r = single ? product_rate<float>(ns, nd, 56, threads, split, repeats)
                                : product_rate<double>(ns, nd, 56, threads, split, repeats);
        T["rows"].push(st::row({to_text(ns) + " x " + to_text(nd) + " x 56", prec, double(threads), split ? "rows per thread" : "BLAS",
                                r / 1e9}));
        if (threads == team && team > 1)
          V[std::string(single ? "tall_sgemm" : "tall_dgemm") + (split ? "_rows_per_thread" : "_blas_threads") + "_fraction_of_square"] =
              r / sq;
        st::log(opt, "1. " + prec + " " + to_text(ns) + " x " + to_text(nd) + " x 56 on " + to_text(threads) + " thread(s), " +
                         (split ? "rows per thread: " : "BLAS threads: ") + to_text(r / 1e9) + " GFlop/s (square " +
                         to_text(sq / 1e9) + ")");
      }
    }
  }
  results["tables"]["products"] = T;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("bench_cells", [&] {
    // ---- 1. Parameters and the machine's ceilings ----------------------------------------------
    const st::Options opt = st::parse_command_line(
        argc, argv, "bench_cells", "Time per force call of the whole-blood cell load, split by phase, against a DGEMM ceiling");
    const bool full = opt.scale == st::Scale::full;
    const index_t rbc_nd = full ? 2500 : 625, rbc_ns = full ? 10000 : 2500, plt_nd = 900, plt_ns = 900, red_cells = 8;
    const int repeats = full ? 11 : 7;
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["red_cells"] = double(red_cells);
    P["red_cell_sites_data_sample"] = to_text(rbc_nd) + " / " + to_text(rbc_ns);
    P["platelets"] = 2;
    P["platelet_sites_data_sample"] = to_text(plt_nd) + " / " + to_text(plt_ns);
    P["repeats"] = repeats;
    P["threads"] = omp_get_max_threads();
    P["dense_backend"] = linalg::dense_backend_name();
    st::record_wait_policy(P);
    const st::Ceiling c = st::measure_ceiling(results, full ? 3000 : 2000, repeats);
    st::log(opt, "1. " + linalg::dense_backend_name() + ", " + to_text(omp_get_max_threads()) + " threads: square DGEMM at " +
                     to_text(c.dgemm_flops / 1e9) + " GFlop/s, triad " + to_text(c.triad_bytes_per_s / 1e9) + " GB/s");
    measure_products(opt, results, rbc_ns, rbc_nd, full ? 3000 : 2000, repeats);

    // ---- 2. Cell types -----------------------------------------------------------------------
    Json types = st::table({"type", "n_data", "n_sample", "build_seconds", "operator_MiB", "forces"}, {"", "", "", "s", "MiB", ""});
    const auto rbc = build(opt, types, [&] { return red_cell(rbc_nd, rbc_ns); });
    const auto plt = build(opt, types, [&] { return platelet(plt_nd, plt_ns); });

    // ---- 3. The whole-blood load: time per call, split, product rate -------------------------
    Json calls = st::table({"type", "cells", "seconds", "products_seconds", "bending_seconds", "kernels_seconds", "reductions_seconds",
                            "seconds_per_cell", "product_gflops", "product_fraction_of_dgemm", "product_fraction_of_roofline",
                            "kernel_share", "max_rel_diff_vs_per_cell"},
                           {"", "", "s", "s", "s", "s", "s", "s", "GFlop/s", "", "", "", ""});
    Load load;
    for (index_t n : {index_t(1), index_t(2), index_t(4)}) measure(opt, calls, rbc, red_cell_placements(n), repeats, c);
    measure(opt, calls, rbc, red_cell_placements(red_cells), repeats, c, &load);
    const double red_cells_seconds = load.seconds;
    measure(opt, calls, plt, platelet_placements(), repeats, c, &load);
    Json& V = results["values"];
    if (omp_get_max_threads() > 1) {  // the red cells' call with the products left to the BLAS's threads
      linalg::set_rows_per_thread(false);
      Batch b(rbc, red_cell_placements(red_cells));
      set_velocities(b);
      double total = 0;
      const ForceTimings t = st::median_force_timings(b, repeats, total);
      linalg::set_rows_per_thread(true);
      V["red_cells_seconds_per_call_blas_threads"] = total;
      V["red_cells_product_seconds_blas_threads"] = t.products();
      V["red_cells_rows_per_thread_speedup"] = total / red_cells_seconds;
      st::log(opt, "3. red cell x 8 with the BLAS's own threads: " + to_text(total * 1e3) + " ms per call (products " +
                       to_text(t.products() * 1e3) + " ms)");
    }
    V["load_seconds_per_call"] = load.seconds;
    V["load_kernel_share"] = load.kernel_seconds / load.seconds;
    V["load_product_fraction_of_dgemm"] = load.product_flops / load.product_seconds / c.dgemm_flops;
    V["load_product_fraction_of_roofline"] = load.roofline_seconds / load.product_seconds;
    if (full) {  // the red cell of the seed's Sec. 4.2.2.2 runs (864 data / 8,832 sample sites), one cell
      const auto rbc864 = build(opt, types, [] {
        CellTypeSpec spec = red_cell_spec(864, 8832);
        spec.name = "red cell (864 / 8832 sites)";
        return std::make_shared<const CellType>(std::move(spec));
      });
      measure(opt, calls, rbc864, red_cell_placements(1), repeats, c);
    }
    st::log(opt, "3. whole-blood cell load: " + to_text(load.seconds * 1e3) + " ms per force call; kernels and reductions " +
                     to_text(100 * load.kernel_seconds / load.seconds) + "% of it");
    results["tables"]["cell_types"] = types;
    results["tables"]["force_calls"] = calls;
    st::write_results(opt, results);
    return 0;
  });
}
