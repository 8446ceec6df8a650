// Study appendixA: boundary error correction for staggered grids (seed, Appendix A).
//
// Reproduces Table A.1 (Dirichlet) and Table A.2 (Neumann), Fig. A.1 (propagation of the boundary
// error), shows the same problems recovered to rounding with the correction of eqs. A.13-A.15, and
// checks in 2D and 3D (eqs. A.16, A.19-A.22) that the corrected operator reproduces quadratics at
// every staggering and boundary type while CG converges on the corrected Helmholtz operator.
// A 3D manufactured-solution convergence study gives the speed-versus-error curves.
// Conventions recovered from the paper's numbers (reference/appendixA.yaml): time in seconds (dt =
// 4 ms at N = 25, dt = 0.1/N s), T = 0.1 s, errors in the grid 2-norm sqrt(h sum e_i^2) and the max
// norm, tabulated in units of 1e-6.
//
// Run:   build/studies/study_appendixA --scale quick --out runs/appendixA
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "common/tables.hpp"
#include "quadratics.hpp"
#include "rbfib/fluid/diffusion.hpp"
#include "rbfib/fluid/grid_norms.hpp"
#include "rbfib/grid/boundary_values.hpp"

namespace {

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;
using st::row;
using BC = BoundaryCondition;
using namespace rbfib::appendix_a;

constexpr double kTableUnit = 1e-6;  // the tables' errors are in units of 1e-6

// ---- The 1D test problem of Tables A.1/A.2: u_t = u_xx + 1, u(x,0) = x(1-x)/2 -------------------
struct TableRun {
  GridNorms err;
  double seconds = 0;
  int max_cg_iterations = 0;
};

Box table_box(int N, bool dirichlet) {
  Box box;
  box.dims = 1;
  // Fig. A.1: Dirichlet at cell centres x_i = h(i - 1/2) (g = 1/2); Neumann at x_i = h i, i = 1..N-1 (g = 1).
  const BC bc = dirichlet ? BC::dirichlet() : BC::neumann();
  box.axes[0] = Axis{N, 1.0, dirichlet ? 0.5 : 1.0, bc, bc, 0.0};
  return box;
}

// Runs `steps` steps of dt and returns u(T) - u(0) in norms; at `profile_steps` u - u0 along x is
// appended to `profiles`.
TableRun run_table_problem(int N, bool dirichlet, Correction corr, double dt, int steps,
                           const std::vector<int>& profile_steps = {},
                           std::vector<std::vector<double>>* profiles = nullptr) {
  const Box box = table_box(N, dirichlet);
  // Neumann data u_x(0) = -u_x(1) = 1/2, i.e. du/dnu = 1/2 at both ends (nu inward); Dirichlet 0.
  const BoundaryData gamma =
      sample_boundary(box, [&](int, int, double, double, double) { return dirichlet ? 0.0 : 0.5; });
  const dvec u0 = sample(box, [](double x, double, double) { return 0.5 * x * (1.0 - x); }), f(u0.size(), 1.0);
  TableRun run;
  dvec u;
  run.seconds = st::median_seconds(3, [&] {
    u = u0;
    if (profiles) profiles->clear();
    CrankNicolsonDiffusion cn(box, 1.0, dt, corr, SolverOptions{"helmholtz (Crank-Nicolson)", 1e-15, 10 * N});
    size_t next = 0;
    for (int s = 1; s <= steps; ++s) {
      run.max_cg_iterations = std::max(run.max_cg_iterations, cn.step(u, f, gamma).iterations);
      if (profiles && next < profile_steps.size() && s == profile_steps[next]) {
        dvec e = u;
        blas::axpy(-1.0, u0, e);
        host_vector<double> h = e;
        profiles->emplace_back(h.begin(), h.end());
        ++next;
      }
    }
  });
  if (!blas::all_finite(u))
    throw NumericalError(Cause::non_finite, "appendixA: non-finite solution at N = " + std::to_string(N));
  run.err = grid_error_norms(box, u, u0);
  return run;
}

// Table A.1 (Dirichlet) or A.2 (Neumann): the errors u(T) - u(0) in units of 1e-6 and relative.
Json table_a(const st::Options& opt, const std::vector<int>& Ns, double T, bool dirichlet, Correction corr) {
  Json t = st::table({"N", "h", "dt_ms", "err2", "err_inf", "err2_rel", "err_inf_rel", "cg_iterations", "seconds"},
                     {"", "", "ms", "1e-6", "1e-6", "", "", "", "s"});
  for (int N : Ns) {
    const double dt = 0.1 / N, umax = 0.125;  // max of x(1-x)/2
    const TableRun r = run_table_problem(N, dirichlet, corr, dt, int(std::lround(T / dt)));
    t["rows"].push(row({N, 1.0 / N, dt / 1e-3, r.err.l2 / kTableUnit, r.err.linf / kTableUnit, r.err.l2 / umax,
                        r.err.linf / umax, r.max_cg_iterations, r.seconds}));
    st::log(opt, std::string(dirichlet ? "Dirichlet" : "Neumann") + ", N = " + to_text(N) + ": ||u - u0||_2 = " +
                     to_text(r.err.l2) + ", " + to_text(r.max_cg_iterations) + " CG iterations/step");
  }
  return t;
}

// Fig. A.1: u - u0 along x at h = 0.01, dt = 1 ms, after each of `steps` steps.
Json fig_a1_profiles(bool dirichlet, Correction corr, const std::vector<int>& steps) {
  std::vector<std::vector<double>> prof;
  run_table_problem(100, dirichlet, corr, 1e-3, steps.back(), steps, &prof);
  std::vector<std::string> cols = {"x"};
  for (int s : steps) cols.push_back("t_" + std::to_string(s) + "ms");
  Json t = st::table(cols);
  const Box box = table_box(100, dirichlet);
  for (int i = 0; i < box.n(0); ++i) {
    Json::Array r{box.x(0, i)};
    for (auto& p : prof) r.push_back(p[i]);
    t["rows"].push(Json(r));
  }
  return t;
}

// ---- 3D manufactured solution: u = exp(-t) cos(1.3x + 0.2) cos(0.9y - 0.1) (2 + cos 2 pi z) ------
struct Manufactured {
  double t = 0;
  static constexpr double kx = 1.3, ky = 0.9, kz = 2 * std::numbers::pi;
  double X(double x) const { return std::cos(kx * x + 0.2); }
  double Y(double y) const { return std::cos(ky * y - 0.1); }
  double Z(double z) const { return 2.0 + std::cos(kz * z); }
  double operator()(double x, double y, double z) const { return std::exp(-t) * X(x) * Y(y) * Z(z); }
  double grad(int d, double x, double y, double z) const {
    const double e = std::exp(-t);
    if (d == 0) return -e * kx * std::sin(kx * x + 0.2) * Y(y) * Z(z);
    if (d == 1) return -e * ky * X(x) * std::sin(ky * y - 0.1) * Z(z);
    return -e * kz * X(x) * Y(y) * std::sin(kz * z);
  }
  // f = u_t - Lap u
  double forcing(double x, double y, double z) const {
    const double e = std::exp(-t);
    const double lap = e * (-(kx * kx + ky * ky) * X(x) * Y(y) * Z(z) - kz * kz * X(x) * Y(y) * std::cos(kz * z));
    return -(*this)(x, y, z) - lap;
  }
};

// Two MAC x-velocity boxes: on x-faces (g = 1) with walls in x, cell-centred in y (Dirichlet) and z
// (periodic); and the same with Neumann on the x-faces (eps = -1/2; Dirichlet in y: eps = 1/4).
std::vector<std::pair<const char*, Box>> scenes_3d(int N) {
  Box a;
  a.dims = 3;
  a.axes[0] = Axis{N, 1.0, 1.0, BC::dirichlet(), BC::dirichlet(), 0.0};
  a.axes[1] = Axis{N, 1.0, 0.5, BC::dirichlet(), BC::dirichlet(), 0.0};
  a.axes[2] = Axis{N, 1.0, 0.5, BC::periodic(), BC::periodic(), 0.0};
  Box b = a;
  b.axes[0].lower = b.axes[0].upper = BC::neumann();
  return {{"dirichlet g=(1,1/2,1/2)", a}, {"neumann x g=1, dirichlet y g=1/2", b}};
}

// Crank-Nicolson to time T with dt ~ h/2: relative max and 2-norm errors, CG iterations, time.
Json::Array run_manufactured(const Box& box, Correction corr, double T) {
  const int steps = int(std::lround(T / (0.5 * box.axes[0].h())));
  const double dt = T / steps;
  Manufactured m;
  int cg_iterations = 0;
  dvec u;
  const double seconds = st::median_seconds(3, [&] {
    m.t = 0;
    u = sample(box, m);
    CrankNicolsonDiffusion cn(box, 1.0, dt, corr, SolverOptions{"helmholtz (3D manufactured)", 1e-13, 5000});
    for (int s = 0; s < steps; ++s) {
      m.t = (s + 0.5) * dt;
      const dvec f = sample(box, [&](double x, double y, double z) { return m.forcing(x, y, z); });
      cg_iterations = std::max(cg_iterations, cn.step(u, f, boundary_data_of(box, m)).iterations);
    }
  });
  m.t = steps * dt;
  const dvec exact = sample(box, m);
  const GridNorms n = grid_error_norms(box, u, exact);
  const double scale = blas::norm_inf(exact);
  return {n.linf / scale, n.l2 / scale, cg_iterations, seconds};
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("appendixA", [&] {
    const auto opt = st::parse_command_line(argc, argv, "appendixA",
                                            "Boundary error correction for staggered grids: Tables A.1, A.2, Fig. A.1 "
                                            "and their corrected counterparts; 2D/3D exactness; speed versus error.");
    const bool full = opt.scale == st::Scale::full;

    // 1. Parameters (the seed's Table A.1/A.2 setup).
    const double T = 0.1;  // s (100 ms)
    std::vector<int> Ns = {25, 50, 100, 200};
    if (full) Ns.insert(Ns.end(), {400, 800});
    const std::vector<int> fig_steps = {10, 50, 100, 500, full ? 5000 : 1000};  // Fig. A.1, dt = 1 ms
    const std::vector<int> sizes = full ? std::vector<int>{8, 16, 32, 64} : std::vector<int>{8, 16, 32};
    Json results = st::make_results(opt);
    Json& par = results["parameters"];
    par["equation"] = "u_t = mu u_xx + f on (0,1), mu = 1, f = 1, u(x,0) = x(1-x)/2";
    par["final_time_s"] = T;
    par["dt_s"] = "0.1 / N (4 ms at N = 25)";
    par["N"] = std::vector<double>(Ns.begin(), Ns.end());
    par["table_error_unit"] = kTableUnit;
    par["cg_rtol"] = 1e-15;
    par["dirichlet_grid"] = "g = 1/2: x_i = h(i - 1/2), i = 1..N; u = 0 at x = 0, 1";
    par["neumann_grid"] = "g = 1: x_i = h i, i = 1..N-1; u_x(0) = -u_x(1) = 1/2";
    Json& tables = results["tables"];
    const std::pair<Correction, std::string> corrections[] = {{Correction::none, ""},
                                                              {Correction::appendix_a, "_corrected"}};

    // 2. Tables A.1 and A.2, without and with the correction; Fig. A.1: u - u0 at h = 0.01 over time.
    for (int dirichlet = 1; dirichlet >= 0; --dirichlet)
      for (const auto& [corr, suffix] : corrections)
        tables[(dirichlet ? "tableA1" : "tableA2") + suffix] = table_a(opt, Ns, T, dirichlet, corr);
    for (int dirichlet = 1; dirichlet >= 0; --dirichlet)
      for (const auto& [corr, suffix] : corrections)
        tables[std::string("figA1_") + (dirichlet ? "dirichlet" : "neumann") + suffix] =
            fig_a1_profiles(dirichlet, corr, fig_steps);
    st::log(opt, "Fig. A.1 profiles done");

    // 3. Quadratics in 2D and 3D at every staggering and boundary type (eqs. A.16, A.22).
    tables["quadratics"] = quadratics_table();
    st::log(opt, "quadratic exactness: 2D and 3D, g in {1/2, 1, 1/4}, Dirichlet/Neumann/Robin");

    // 4. 3D manufactured solution: convergence and speed versus error, with and without correction.
    Json t = st::table({"scene", "corrected", "N", "h", "err_inf", "err_l2", "cg_iterations", "seconds"});
    for (int N : sizes)
      for (const auto& [name, box] : scenes_3d(N))
        for (Correction corr : {Correction::none, Correction::appendix_a}) {
          Json::Array r{name, corr == Correction::appendix_a ? "corrected" : "uncorrected", N, 1.0 / N};
          for (const Json& x : run_manufactured(box, corr, 0.25)) r.push_back(x);
          t["rows"].push(Json(r));
          st::log(opt, std::string("3D ") + name + (corr == Correction::none ? " uncorrected" : " corrected") +
                           ": N = " + std::to_string(N) + " done");
        }
    tables["manufactured3d"] = t;
    par["manufactured3d"] =
        "u = exp(-t) cos(1.3x+0.2) cos(0.9y-0.1) (2+cos 2 pi z) on [0,1]^3, mu = 1, T = 0.25, dt ~ h/2, CN";
    st::write_results(opt, results);
    return 0;
  });
}
