// Unit tests of Chebyshev iteration (the residual polynomial it must realize exactly) and of the
// cell-centred multigrid transfers (R = P^T / 2^d, P reproduces constants and linears).
#include "../common/random_field.hpp"
#include "rbfib/linalg/chebyshev.hpp"
#include "rbfib/linalg/multigrid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rbfib {
namespace {

double chebyshev_T(int m, double x) {
  if (std::abs(x) <= 1) return std::cos(m * std::acos(x));
  const double v = std::cosh(m * std::acosh(std::abs(x)));
  return (x < 0 && m % 2) ? -v : v;
}

TEST(Chebyshev, RealizesTheResidualPolynomialOnADiagonalOperator) {
  // A = diag(lambda_i), eigenvalues inside and below [1, 10]; x* = 1, b = A x*. From x_0 = 0 the
  // error after m steps is r_m(lambda_i) with r_m(l) = T_m((theta - l)/delta) / T_m(theta/delta).
  const int n = 40;
  host_vector<double> lam(n);
  for (int i = 0; i < n; ++i) lam[i] = 0.2 + 10.0 * i / (n - 1);
  const dvec L(lam);
  auto A = [&](const dvec& x, dvec& y) { blas::multiply(L, x, y); };
  const dvec b = L;  // A * ones
  const ChebyshevBounds bounds{1.0, 10.2};
  const double theta = 5.6, delta = 4.6;
  for (int m : {1, 2, 5, 9}) {
    ChebyshevIteration cheb(bounds, m);
    dvec x;
    cheb.solve(A, b, x, true);
    host_vector<double> h = x;
    for (int i = 0; i < n; ++i) {
      const double r = chebyshev_T(m, (theta - lam[i]) / delta) / chebyshev_T(m, theta / delta);
      // the recurrence is stable: errors of a few eps times the condition of the polynomial
      EXPECT_NEAR(1.0 - h[i], r, 1e-13) << "m = " << m << ", lambda = " << lam[i];
      if (lam[i] >= 1.0) EXPECT_LE(std::abs(1.0 - h[i]), bounds.contraction(m) * (1 + 1e-12));
      else EXPECT_GT(1.0 - h[i], 0.0);  // below lambda_1: 0 < r_m < 1
    }
  }
  EXPECT_EQ(bounds.steps_for(bounds.contraction(7) * 1.0001), 7);
}

TEST(Chebyshev, RefusesBadBounds) {
  EXPECT_THROW(ChebyshevIteration(ChebyshevBounds{0.0, 1.0}, 3, "smoother"), InputError);
  EXPECT_THROW(ChebyshevIteration(ChebyshevBounds{2.0, 1.0}, 3, "smoother"), InputError);
  EXPECT_THROW(ChebyshevIteration(ChebyshevBounds{1.0, 2.0}, 0, "smoother"), InputError);
}

using rbfib::testing::random_vector;

CellCentredTransfer transfer(int dims, std::array<int, 3> fine, std::array<bool, 3> periodic) {
  CellCentredTransfer t;
  t.dims = dims;
  for (int d = 0; d < 3; ++d) {
    t.fine[d] = d < dims ? fine[d] : 1;
    t.coarse[d] = d < dims ? fine[d] / 2 : 1;
    t.periodic[d] = periodic[d];
  }
  return t;
}

TEST(Multigrid, RestrictionIsTheScaledTransposeOfProlongation) {
  for (auto t : {transfer(3, {8, 6, 4}, {true, false, true}), transfer(3, {4, 4, 4}, {false, false, false}),
                 transfer(2, {8, 4, 1}, {true, false, true})}) {
    const dvec f = random_vector(t.fine_size(), 1), c = random_vector(t.coarse_size(), 2);
    dvec Rf, Pc(t.fine_size(), 0.0);
    restrict_to_coarse(t, f, Rf);
    prolong_add(t, c, Pc);
    // <R f, c> = <f, P c> / 2^d: sums of O(n) products of O(1) terms, 32 eps.
    EXPECT_NEAR(blas::dot(Rf, c), blas::dot(f, Pc) / double(1 << t.dims), 32 * 2.2e-16 * t.fine_size());
  }
}

TEST(Multigrid, ProlongationReproducesConstantsAndInteriorLinears) {
  const auto t = transfer(3, {8, 8, 8}, {false, true, false});
  dvec one(t.coarse_size(), 1.0), P(t.fine_size(), 0.0);
  prolong_add(t, one, P);
  blas::axpy(-1.0, dvec(t.fine_size(), 1.0), P);
  EXPECT_LT(blas::norm_inf(P), 1e-15);
  // a linear function of x (coarse centres X = 2 (I + 1/2), fine x = j + 1/2): exact away from walls
  host_vector<double> lin(t.coarse_size());
  for (index_t p = 0; p < t.coarse_size(); ++p) lin[p] = 2.0 * (p % 4 + 0.5);
  dvec Pl(t.fine_size(), 0.0);
  prolong_add(t, dvec(lin), Pl);
  host_vector<double> h = Pl;
  for (index_t p = 0; p < t.fine_size(); ++p) {
    const int j = int(p % 8);
    if (j > 0 && j < 7) {
      EXPECT_NEAR(h[p], j + 0.5, 1e-14);
    }
  }
}

}  // namespace
}  // namespace rbfib
