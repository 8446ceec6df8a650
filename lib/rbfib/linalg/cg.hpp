#pragma once
// Preconditioned conjugate gradients for a symmetric positive definite operator A, given as a
// callable A(x, y) computing y = A x, and a preconditioner M(r, z) computing z = M^{-1} r
// (identity_preconditioner for plain CG). Stops when ||r||_2 <= rtol ||b||_2; a solve that does
// not get there within max_iterations, or meets a NaN, throws NumericalError naming the solve,
// the residual reached and the limit.
#include "rbfib/core/error.hpp"
#include "rbfib/linalg/blas.hpp"

#include <string>

namespace rbfib {

struct SolverOptions {
  std::string name = "cg";   ///< what the solve is, for messages ("helmholtz u", "poisson")
  double rtol = 1e-11;       ///< relative residual ||r|| / ||b|| to reach
  int max_iterations = 1000;
};

struct SolveStats {
  int iterations = 0;
  double relative_residual = 0.0;
};

struct identity_preconditioner {
  void operator()(const dvec& r, dvec& z) const { z = r; }
};

template <class Op, class Precond = identity_preconditioner>
SolveStats conjugate_gradient(const Op& A, const dvec& b, dvec& x, const SolverOptions& opt,
                              const Precond& M = Precond{}) {
  const index_t n = index_t(b.size());
  require(index_t(x.size()) == n, opt.name + ".x.size", x.size(), "does not match the right-hand side");
  require(opt.rtol > 0.0, opt.name + ".rtol", opt.rtol, "must be positive");
  require(opt.max_iterations > 0, opt.name + ".max_iterations", opt.max_iterations, "must be positive");
  const double bnorm = blas::norm2(b);
  if (!std::isfinite(bnorm)) throw NumericalError(Cause::non_finite, opt.name + ": right-hand side is not finite (NaN or Inf)");
  SolveStats stats;
  if (bnorm == 0.0) {
    thrust::fill(x.begin(), x.end(), 0.0);
    return stats;
  }
  dvec r(n), z(n), p(n), q(n);
  A(x, q);
  r = b;
  blas::axpy(-1.0, q, r);  // r = b - A x
  double rnorm = blas::norm2(r);
  stats.relative_residual = rnorm / bnorm;
  if (stats.relative_residual <= opt.rtol) return stats;
  M(r, z);
  p = z;
  double rz = blas::dot(r, z);
  for (int it = 1; it <= opt.max_iterations; ++it) {
    A(p, q);
    const double pq = blas::dot(p, q);
    if (!(pq > 0.0))
      throw NumericalError(std::isfinite(pq) ? Cause::solver : Cause::non_finite, opt.name + ": p^T A p = " + to_text(pq) + " at iteration " + std::to_string(it) +
                           " (operator not positive definite, or NaN)");
    const double step = rz / pq;
    blas::axpy(step, p, x);
    blas::axpy(-step, q, r);
    rnorm = blas::norm2(r);
    stats.iterations = it;
    stats.relative_residual = rnorm / bnorm;
    if (!std::isfinite(rnorm)) throw NumericalError(Cause::non_finite, opt.name + ": residual became NaN/Inf at iteration " + std::to_string(it));
    if (stats.relative_residual <= opt.rtol) return stats;
    M(r, z);
    const double rz_new = blas::dot(r, z);
    blas::xpby(z, rz_new / rz, p);  // p = z + (rz_new / rz) p
    rz = rz_new;
  }
  throw NumericalError(Cause::solver, opt.name + ": did not converge in " + std::to_string(opt.max_iterations) +
                       " iterations (relative residual " + to_text(stats.relative_residual) + ", tolerance " +
                       to_text(opt.rtol) + ")");
}

}  // namespace rbfib
