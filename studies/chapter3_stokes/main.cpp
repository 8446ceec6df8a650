// The periodic Stokes solver of the paper's Sec. 3.2 ("a spectral fluid solver ... in
// O(eta^3 log eta^3) operations") as the exact inverse of the discrete MAC operators
// (fluid/periodic_stokes.hpp): its error against an exact periodic Stokes flow as the grid is
// refined, the divergence it leaves, its agreement with iterative solves of the same discrete
// system, and its time per solve against eta^3 log eta^3.
//
// Domain [-L, L]^3 with 2L = 24 um (the capillary box of the paper's Sec. 4.2), mu = 1.2 cP (the
// paper's plasma), exact flow with k = 2 pi / (2L):
//   u = U (sin kx cos ky cos kz, -cos kx sin ky cos kz, 0),  p = P sin kx sin ky sin kz,
//   f = 3 mu k^2 u + grad p   (div u = 0, -mu lap u + grad p = f).
//
// Run:   build/studies/study_chapter3_stokes --scale quick --out runs/chapter3_stokes
#include <cmath>

#include "common/study.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/fluid/periodic_stokes.hpp"
#include "rbfib/linalg/blas.hpp"

using namespace rbfib;
namespace st = rbfib::study;
using st::Json;

namespace {

/// The exact flow (velocity, pressure gradient) of the header.
struct ExactFlow {
  double k, U, P, mu;
  double u(int a, double x, double y, double z) const {
    if (a == 0) return U * std::sin(k * x) * std::cos(k * y) * std::cos(k * z);
    if (a == 1) return -U * std::cos(k * x) * std::sin(k * y) * std::cos(k * z);
    return 0.0;
  }
  double grad_p(int a, double x, double y, double z) const {
    if (a == 0) return P * k * std::cos(k * x) * std::sin(k * y) * std::sin(k * z);
    if (a == 1) return P * k * std::sin(k * x) * std::cos(k * y) * std::sin(k * z);
    return P * k * std::sin(k * x) * std::sin(k * y) * std::cos(k * z);
  }
  double f(int a, double x, double y, double z) const { return 3 * mu * k * k * u(a, x, y, z) + grad_p(a, x, y, z); }
};

MacGrid periodic_grid(int eta, double L) {
  MacGrid g = make_mac_grid(3, {eta, eta, eta}, {2 * L, 2 * L, 2 * L},
                            {MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic});
  g.origin = {-L, -L, -L};
  return g;
}

double max_diff(const dvec& a, const dvec& b) {
  dvec d = a;
  blas::axpy(-1.0, b, d);
  return blas::norm_inf(d);
}
/// The solver on grids of eta^3 cells: error against the exact flow, the divergence it leaves
/// (relative: max |D u| h / U) and the median time per solve.
Json refinement(const st::Options& opt, const ExactFlow& flow, double L, const std::vector<int>& etas, int repeats,
                double& worst_div) {
  Json conv = st::table({"eta", "h_um", "err_inf", "max_div_rel", "seconds", "seconds_per_eta3_log_eta3"},
                        {"", "um", "", "", "s", "s"});
  worst_div = 0;
  for (int eta : etas) {
    const MacGrid g = periodic_grid(eta, L);
    PeriodicStokesSolver S(g, flow.mu);
    const MacOperators& ops = S.operators();
    VectorField f, u, ue;
    for (int a = 0; a < 3; ++a) {
      f[a] = sample(ops.component_box(a), [&](double x, double y, double z) { return flow.f(a, x, y, z); });
      ue[a] = sample(ops.component_box(a), [&](double x, double y, double z) { return flow.u(a, x, y, z); });
    }
    dvec p, div;
    S.solve(f, u, p);
    const double t = st::median_seconds(repeats, [&] { S.solve(f, u, p); });
    double err = 0;
    for (int a = 0; a < 3; ++a) err = std::max(err, max_diff(u[a], ue[a]));
    err /= flow.U;
    ops.divergence(u, nullptr, div);
    const double div_rel = blas::norm_inf(div) * g.h(0) / flow.U;
    worst_div = std::max(worst_div, div_rel);
    const double n3 = double(eta) * eta * eta;
    conv["rows"].push(st::row({eta, g.h(0) / units::um, err, div_rel, t, t / (n3 * std::log(n3))}));
    st::log(opt, "2. eta = " + to_text(eta) + ": err_inf " + to_text(err) + ", max |D u| h / U " + to_text(div_rel) +
                     ", " + to_text(t * 1e3) + " ms per solve");
  }
  return conv;
}

/// The largest relative difference of velocity and pressure between the direct solve and PCG to
/// 1e-13 on the unsteady system (rho/dt, dt = 50 ns, Sec. 5.2) at eta = 32, a non-Stokes forcing.
double agreement_with_iterative(const ExactFlow& flow, double L) {
  const double alpha = 1.0 / (50 * units::ns);
  const MacGrid g = periodic_grid(32, L);
  PeriodicStokesSolver S(g, flow.mu, alpha);
  const MacOperators& ops = S.operators();
  VectorField f, u, ui;
  for (int a = 0; a < 3; ++a)
    f[a] = sample(ops.component_box(a),
                  [&](double x, double y, double z) { return flow.f(a, x, y, z) * (1 + 0.3 * std::sin(3 * x / L)); });
  dvec p, q;
  S.solve(f, u, p);
  S.solve_iteratively(f, ui, q, 1e-13);
  double diff = max_diff(q, p) / blas::norm_inf(p);
  for (int a = 0; a < 3; ++a) diff = std::max(diff, max_diff(ui[a], u[a]) / blas::norm_inf(u[a]));
  return diff;
}

}  // namespace

int main(int argc, char** argv) {
  return st::run_main("chapter3_stokes", [&] {
    const st::Options opt =
        st::parse_command_line(argc, argv, "chapter3_stokes",
                               "Periodic Stokes solver of Sec. 3.2: order, divergence, agreement, time per solve");
    const bool full = opt.scale == st::Scale::full;

    // ---- 1. Parameters -----------------------------------------------------------------------
    const double L = 12 * units::um, mu = 1.2 * units::cP;
    const ExactFlow flow{2 * pi / (2 * L), 1 * units::mm / units::s, 1.0, mu};
    const std::vector<int> etas = full ? std::vector<int>{16, 32, 64, 128, 256} : std::vector<int>{16, 32, 64, 128};
    const int repeats = full ? 11 : 5;
    Json results = st::make_results(opt);
    Json& P = results["parameters"];
    P["box_um"] = "[-12, 12]^3 (2L = 24 um, periodic)";
    P["viscosity_cP"] = mu / units::cP;
    P["exact_flow"] =
        "u = U (sin kx cos ky cos kz, -cos kx sin ky cos kz, 0), p = P sin kx sin ky sin kz, k = 2 pi / 24 um";
    P["U_mm_per_s"] = flow.U / (units::mm / units::s);
    P["P_dyn_per_cm2"] = flow.P;
    P["repeats"] = repeats;

    // ---- 2. Refinement: error, divergence, time per solve -----------------------------------
    double worst_div = 0;
    results["tables"]["convergence"] = refinement(opt, flow, L, etas, repeats, worst_div);
    results["values"]["max_div_rel"] = worst_div;

    // ---- 3. Agreement with iterative solves of the same discrete (unsteady) system ----------
    const double diff = agreement_with_iterative(flow, L);
    results["values"]["max_rel_diff_vs_iterative"] = diff;
    P["agreement_case"] = "eta = 32, unsteady Stokes with rho/dt, dt = 50 ns; PCG to 1e-13";
    st::log(opt, "3. unsteady Stokes, eta = 32: direct vs iterative max relative difference " + to_text(diff));
    st::write_results(opt, results);
    return 0;
  });
}
