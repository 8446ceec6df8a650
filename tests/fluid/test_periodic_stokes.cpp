// The periodic MAC Stokes solver: it solves the discrete system exactly (zero divergence and a
// momentum residual at rounding), equals the iterative solves of the same system (multigrid PCG
// for the pressure, Chebyshev PCG for each velocity component), and converges at second order to
// an exact periodic Stokes flow.
#include "../common/random_field.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/fluid/periodic_stokes.hpp"
#include "rbfib/linalg/blas.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib {
namespace {

using MB = MacBoundary;
using rbfib::testing::random_vector;

MacGrid periodic_box(int n, double L) {
  return make_mac_grid(3, {n, n + 2, n - 2}, {L, L * (n + 2) / n, L * (n - 2) / n}, {MB::periodic, MB::periodic, MB::periodic});
}

double max_abs_diff(const dvec& a, const dvec& b) {
  dvec d = a;
  blas::axpy(-1.0, b, d);
  return blas::norm_inf(d);
}

TEST(PeriodicStokes, SolvesTheDiscreteSystemExactly) {
  // alpha u - mu L u + G p = f and D u = 0 hold to rounding, for steady (alpha = 0, the mean of
  // f removed) and unsteady (alpha = rho/dt) Stokes.
  const MacGrid g = periodic_box(12, 1.0);
  for (double alpha : {0.0, 50.0}) {
    PeriodicStokesSolver S(g, 0.7, alpha);
    const MacOperators& ops = S.operators();
    VectorField f, u, Lu, Gp;
    for (int a = 0; a < 3; ++a) f[a] = random_vector(ops.component_box(a).size(), 40 + a);
    dvec p, div;
    const auto removed = S.solve(f, u, p, {0.3, 0, 0});
    ops.divergence(u, nullptr, div);
    double fmax = 0;
    for (int a = 0; a < 3; ++a) fmax = std::max(fmax, blas::norm_inf(f[a]));
    EXPECT_LT(blas::norm_inf(div) * g.h(0), 1e-13 * fmax / 0.7);
    ops.gradient(p, Gp);
    for (int a = 0; a < 3; ++a) {
      StaggeredLaplacian L(ops.component_box(a), Correction::none);
      L.apply(u[a], Lu[a], alpha, -0.7);  // alpha u - mu L u
      blas::axpy(1.0, Gp[a], Lu[a]);
      dvec want = f[a];
      if (alpha == 0) blas::shift(-removed[a], want);
      EXPECT_LT(max_abs_diff(Lu[a], want), 1e-11 * fmax) << "alpha " << alpha << " u" << a;
    }
    if (alpha == 0) {
      EXPECT_NEAR(thrust::reduce(u[0].begin(), u[0].end(), 0.0) / double(u[0].size()), 0.3, 1e-14);
      EXPECT_NE(removed[0], 0.0);
    }
  }
}

TEST(PeriodicStokes, EqualsTheIterativeSolvesOfTheSameSystem) {
  // Unsteady Stokes: -L_c p = -D f by multigrid PCG and (I - (mu/alpha) L) u = (f - G p)/alpha by
  // Chebyshev PCG, both to 1e-13, agree with the direct solve to 1e-10.
  const MacGrid g = periodic_box(16, 1.0);
  const double mu = 0.5, alpha = 20.0;
  PeriodicStokesSolver S(g, mu, alpha);
  const MacOperators& ops = S.operators();
  VectorField f, u;
  for (int a = 0; a < 3; ++a) f[a] = random_vector(ops.component_box(a).size(), 50 + a);
  dvec p;
  S.solve(f, u, p);
  VectorField ui;
  dvec q;
  S.solve_iteratively(f, ui, q, 1e-13);
  EXPECT_LT(max_abs_diff(q, p), 1e-10 * blas::norm_inf(p));
  for (int a = 0; a < 3; ++a) EXPECT_LT(max_abs_diff(ui[a], u[a]), 1e-10 * blas::norm_inf(u[a])) << "u" << a;
}

TEST(PeriodicStokes, ConvergesAtSecondOrderToAnExactFlow) {
  // u = (sin kx cos ky cos kz, -cos kx sin ky cos kz, 0), p = sin kx sin ky sin kz on [0, 1]^3:
  // div u = 0, f = 3 mu k^2 u + grad p. The MAC solution's error falls as h^2 (2 +- 0.15 between
  // the two finest grids).
  const double k = 2 * pi, mu = 0.8;
  double err[3];
  int i = 0;
  for (int n : {8, 16, 32}) {
    const MacGrid g = make_mac_grid(3, {n, n, n}, {1, 1, 1}, {MB::periodic, MB::periodic, MB::periodic});
    PeriodicStokesSolver S(g, mu, 0.0);
    const MacOperators& ops = S.operators();
    auto ue = [&](int a, double x, double y, double z) {
      if (a == 0) return std::sin(k * x) * std::cos(k * y) * std::cos(k * z);
      if (a == 1) return -std::cos(k * x) * std::sin(k * y) * std::cos(k * z);
      return 0.0;
    };
    auto gp = [&](int a, double x, double y, double z) {
      if (a == 0) return k * std::cos(k * x) * std::sin(k * y) * std::sin(k * z);
      if (a == 1) return k * std::sin(k * x) * std::cos(k * y) * std::sin(k * z);
      return k * std::sin(k * x) * std::sin(k * y) * std::cos(k * z);
    };
    VectorField f, u;
    for (int a = 0; a < 3; ++a)
      f[a] = sample(ops.component_box(a), [&](double x, double y, double z) { return 3 * mu * k * k * ue(a, x, y, z) + gp(a, x, y, z); });
    dvec p;
    S.solve(f, u, p);
    double e = 0;
    for (int a = 0; a < 3; ++a)
      e = std::max(e, max_abs_diff(u[a], sample(ops.component_box(a), [&](double x, double y, double z) { return ue(a, x, y, z); })));
    err[i++] = e;
  }
  EXPECT_LT(err[2], 1e-2);
  EXPECT_NEAR(std::log2(err[1] / err[2]), 2.0, 0.15);
}

TEST(PeriodicStokes, BadInputIsNamed) {
  const MacGrid walls = make_mac_grid(3, {8, 8, 8}, {1, 1, 1}, {MB::periodic, MB::dirichlet, MB::periodic});
  EXPECT_THROW(PeriodicStokesSolver(walls, 1.0), InputError);
  const MacGrid g = periodic_box(8, 1.0);
  EXPECT_THROW(PeriodicStokesSolver(g, 0.0), InputError);
  EXPECT_THROW(PeriodicStokesSolver(g, 1.0, -1.0), InputError);
}

}  // namespace
}  // namespace rbfib
