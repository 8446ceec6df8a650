// Conjugate gradients: converges on an SPD operator, and fails loudly (naming the solve, the
// residual reached and the limit) instead of returning silently.
#include "rbfib/linalg/cg.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace rbfib {
namespace {

// y = A x with A = tridiag(-1, 2.5, -1): SPD.
void apply_tridiagonal(const dvec& x, dvec& y) {
  const index_t n = index_t(x.size());
  y.resize(n);
  const double* px = ptr(x);
  double* py = ptr(y);
  for_each_index(n, [=] RBFIB_HD (index_t i) {
    py[i] = 2.5 * px[i] - (i > 0 ? px[i - 1] : 0.0) - (i + 1 < n ? px[i + 1] : 0.0);
  });
}

TEST(ConjugateGradient, SolvesSPDToTolerance) {
  const index_t n = 50;
  dvec xe(n), b, x(n, 0.0);
  for (index_t i = 0; i < n; ++i) xe[i] = std::sin(0.3 * double(i));
  apply_tridiagonal(xe, b);
  const SolveStats s = conjugate_gradient(apply_tridiagonal, b, x, SolverOptions{"test", 1e-13, 200});
  EXPECT_LE(s.relative_residual, 1e-13);
  EXPECT_LE(s.iterations, n);
  blas::axpy(-1.0, xe, x);
  // kappa(A) <= 4.5 / 0.5 = 9: error <= kappa * rtol * |x| (plus rounding)
  EXPECT_LT(blas::norm2(x), 9 * 1e-13 * blas::norm2(xe) + 1e-14);
}

TEST(ConjugateGradient, NonConvergenceNamesSolveResidualAndLimit) {
  const index_t n = 50;
  dvec b(n, 1.0), x(n, 0.0);
  try {
    conjugate_gradient(apply_tridiagonal, b, x, SolverOptions{"poisson", 1e-14, 3});
    FAIL() << "returned without converging";
  } catch (const NumericalError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("poisson"), std::string::npos) << m;
    EXPECT_NE(m.find("3 iterations"), std::string::npos) << m;
    EXPECT_NE(m.find("relative residual"), std::string::npos) << m;
  }
}

TEST(ConjugateGradient, NaNRightHandSideIsRefused) {
  dvec b(10, 1.0), x(10, 0.0);
  b[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(conjugate_gradient(apply_tridiagonal, b, x, SolverOptions{"helmholtz", 1e-10, 100}), NumericalError);
}

TEST(ConjugateGradient, IndefiniteOperatorIsReported) {
  auto negative = [](const dvec& x, dvec& y) {
    y = x;
    thrust::transform(y.begin(), y.end(), y.begin(), thrust::negate<double>());
  };
  dvec b(10, 1.0), x(10, 0.0);
  EXPECT_THROW(conjugate_gradient(negative, b, x, SolverOptions{"helmholtz", 1e-10, 100}), NumericalError);
}

}  // namespace
}  // namespace rbfib
