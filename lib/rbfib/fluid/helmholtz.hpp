#pragma once
// The Helmholtz solves of eq. 2.6 (and of the Crank-Nicolson stage), one per velocity component:
//   H x = b,   H = I~ - c L,   c = theta dt mu / rho > 0 (cm^2),
// with L and I~ the corrected staggered Laplacian and modified identity of Appendix A (eq. A.22):
// symmetric positive definite, solved by PCG to ||r|| <= rtol ||b|| preconditioned by a fixed
// number of Chebyshev steps on [lambda_1, lambda_2] from Gershgorin's theorem (Section 2.1).
#include "rbfib/fluid/laplacian.hpp"
#include "rbfib/linalg/cg.hpp"
#include "rbfib/linalg/chebyshev.hpp"

#include <string>

namespace rbfib {

/// Gershgorin bounds [min_p (a_pp - R_p), max_p (a_pp + R_p)] of alpha I~ + beta L, R_p the absolute
/// off-diagonal sum of row p. The lower bound may be <= 0 (then the caller must supply its own).
ChebyshevBounds gershgorin_bounds(const StaggeredLaplacian& L, double alpha, double beta);

struct HelmholtzOptions {
  SolverOptions solver{"helmholtz", 1e-11, 1000};
  int chebyshev_steps = 4;  ///< degree of the Chebyshev preconditioner (products of H per PCG step)
};

class HelmholtzSolver {
 public:
  /// box: one velocity component's box; c: theta dt mu / rho (> 0). Throws InputError on bad input.
  HelmholtzSolver(const Box& box, double c, HelmholtzOptions options);

  /// Solves H x = b from the initial guess x.
  SolveStats solve(const dvec& b, dvec& x) const;
  /// y = H x
  void apply(const dvec& x, dvec& y) const { lap_.apply(x, y, 1.0, -c_); }

  const StaggeredLaplacian& laplacian() const { return lap_; }
  const ChebyshevBounds& bounds() const { return cheb_.bounds(); }
  double coefficient() const { return c_; }

 private:
  StaggeredLaplacian lap_;
  double c_;
  HelmholtzOptions options_;
  ChebyshevIteration cheb_;
};

}  // namespace rbfib
