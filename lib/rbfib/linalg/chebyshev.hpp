#pragma once
// Chebyshev iteration (Section 2.1; the three-term recurrence of Saad, Iterative Methods, Alg. 12.1)
// for A x = b with A symmetric and a spectrum bound [lambda_1, lambda_2], 0 < lambda_1 < lambda_2.
// After m steps from x_0 the error is e_m = r_m(A) e_0 with the residual polynomial
//   r_m(lambda) = T_m((theta - lambda) / delta) / T_m(theta / delta),
//   theta = (lambda_2 + lambda_1) / 2, delta = (lambda_2 - lambda_1) / 2,
// which damps every eigenmode in [lambda_1, lambda_2] by at least 1 / T_m(theta / delta) and
// leaves modes below lambda_1 partly damped (0 < r_m < 1 there), so that from x_0 = 0 the map
// b -> x_m is a fixed symmetric polynomial in A, positive definite when the spectrum lies in
// (0, lambda_2]: a valid preconditioner for conjugate gradients. Only products y = A x are needed.
//
// Gershgorin bounds (row centre +- absolute off-diagonal row sum) supply lambda_2, and lambda_1
// for the Helmholtz systems; see fluid/helmholtz.hpp and fluid/poisson.hpp.
#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"

#include <cmath>
#include <string>

namespace rbfib {

namespace kernels {
/// y = s x
struct ChebyshevScale {
  const double* x;
  double s;
  double* y;
  RBFIB_HD void operator()(index_t i) const { y[i] = s * x[i]; }
};
/// d = c1 d + c2 r
struct ChebyshevDirection {
  const double* r;
  double c1, c2;
  double* d;
  RBFIB_HD void operator()(index_t i) const { d[i] = c1 * d[i] + c2 * r[i]; }
};
}  // namespace kernels

struct ChebyshevBounds {
  double lambda_min = 0.0;  ///< lambda_1
  double lambda_max = 0.0;  ///< lambda_2

  /// Throws InputError naming `name` unless 0 < lambda_1 < lambda_2 (both finite).
  void validate(const std::string& name) const {
    require(std::isfinite(lambda_min) && lambda_min > 0.0, name + ".lambda_min", lambda_min, "must be positive and finite");
    require(std::isfinite(lambda_max) && lambda_max > lambda_min, name + ".lambda_max", lambda_max,
            "must exceed lambda_min = " + to_text(lambda_min));
  }
  /// Guaranteed damping factor 1 / T_m(theta / delta) of m steps on [lambda_1, lambda_2].
  double contraction(int m) const {
    const double sigma = (lambda_max + lambda_min) / (lambda_max - lambda_min);
    return 1.0 / std::cosh(m * std::acosh(sigma));
  }
  /// Fewest steps m whose contraction is at most `factor` (0 < factor < 1).
  int steps_for(double factor) const {
    const double sigma = (lambda_max + lambda_min) / (lambda_max - lambda_min);
    return std::max(1, int(std::ceil(std::acosh(1.0 / factor) / std::acosh(sigma))));
  }
};

/// Workspace-holding Chebyshev iteration. `steps` >= 1 products' worth of smoothing per call.
class ChebyshevIteration {
 public:
  ChebyshevIteration() = default;
  ChebyshevIteration(ChebyshevBounds bounds, int steps, const std::string& name = "chebyshev")
      : bounds_(bounds), steps_(steps) {
    bounds.validate(name);
    require(steps >= 1, name + ".steps", steps, "must be at least 1");
  }

  const ChebyshevBounds& bounds() const { return bounds_; }
  int steps() const { return steps_; }

  /// m steps on A x = b. With zero_initial_guess, x is overwritten (x_0 = 0, one product fewer).
  template <class Op>
  void solve(const Op& A, const dvec& b, dvec& x, bool zero_initial_guess) const {
    const index_t n = index_t(b.size());
    const double theta = 0.5 * (bounds_.lambda_max + bounds_.lambda_min);
    const double delta = 0.5 * (bounds_.lambda_max - bounds_.lambda_min);
    const double sigma = theta / delta;
    r_.resize(n);
    d_.resize(n);
    q_.resize(n);
    if (zero_initial_guess) {
      x.resize(n);
      thrust::fill(x.begin(), x.end(), 0.0);
      r_ = b;
    } else {
      A(x, q_);
      r_ = b;
      blas::axpy(-1.0, q_, r_);
    }
    // d = r / theta
    for_each_index(n, kernels::ChebyshevScale{ptr(r_), 1.0 / theta, ptr(d_)});
    double rho = 1.0 / sigma;
    for (int k = 1; k <= steps_; ++k) {
      blas::axpy(1.0, d_, x);
      if (k == steps_) break;
      A(d_, q_);
      blas::axpy(-1.0, q_, r_);
      const double rho_new = 1.0 / (2.0 * sigma - rho);
      const double c1 = rho_new * rho, c2 = 2.0 * rho_new / delta;
      for_each_index(n, kernels::ChebyshevDirection{ptr(r_), c1, c2, ptr(d_)});
      rho = rho_new;
    }
  }

 private:
  ChebyshevBounds bounds_{1.0, 2.0};
  int steps_ = 1;
  mutable dvec r_, d_, q_;
};

}  // namespace rbfib
