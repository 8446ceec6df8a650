#pragma once
// The pseudo-pressure Poisson solve of PmII (eq. 2.9):  -L q = b  on the cell-centred box, L the
// discrete Laplacian D G with homogeneous Neumann data on walls (eps = 0 for g = 1/2: no Appendix A
// correction is needed) and periodic wrap elsewhere. The operator is positive semidefinite with the
// constants as null space; the right-hand side is made mean-free and so is the solution.
//
// PCG to ||r|| <= rtol ||b||, preconditioned by one multigrid V-cycle (linalg/multigrid.hpp) on a
// hierarchy of boxes obtained by halving every axis while all cell counts stay even and >= 4.
// Smoother: Chebyshev iteration on [lambda_2 / (2 dims), lambda_2], lambda_2 the Gershgorin upper
// bound; for dims = 1, 2, 3 this range makes one Chebyshev step weighted Jacobi with the optimal
// smoothing weights 2/3, 4/5, 6/7 (Section 2.1: lambda_1 separates low from high frequencies).
// Coarsest level: Chebyshev iteration on [lambda_min, lambda_2], lambda_min the smallest nonzero
// eigenvalue of the coarse box (known in closed form for the tensor-product Laplacian), with as many
// steps as needed to damp every nonzero mode by coarse_contraction.
#include "rbfib/fluid/laplacian.hpp"
#include "rbfib/linalg/cg.hpp"
#include "rbfib/linalg/multigrid.hpp"

#include <vector>

namespace rbfib {

struct PoissonOptions {
  SolverOptions solver{"poisson", 1e-11, 500};
  int levels = 0;                   ///< multigrid levels including the finest; 0: as many as possible
  int smoothing_steps = 3;          ///< Chebyshev degree of pre- and post-smoothing
  double coarse_contraction = 1e-2; ///< damping of the coarsest-level Chebyshev solve
};

class PoissonSolver {
 public:
  /// box: the cell-centred box (g = 1/2 on every axis, Neumann or periodic); throws InputError if
  /// the requested levels exceed the hierarchy the box admits, naming poisson.levels.
  PoissonSolver(const Box& box, PoissonOptions options);
  PoissonSolver(const PoissonSolver&) = delete;  // the levels point into lap_
  PoissonSolver& operator=(const PoissonSolver&) = delete;
  PoissonSolver(PoissonSolver&&) = default;

  /// Solves -L q = b (b made mean-free first) from the initial guess q; q is returned mean-free.
  SolveStats solve(dvec& b, dvec& q) const;
  /// y = -L x
  void apply(const dvec& x, dvec& y) const { lap_.front().apply(x, y, 0.0, -1.0); }

  const StaggeredLaplacian& laplacian() const { return lap_.front(); }
  int levels() const { return mg_.levels(); }
  const Multigrid& multigrid() const { return mg_; }
  /// Most levels a box admits (halving while every axis count is even and the half is >= 4).
  static int max_levels(const Box& box);

 private:
  std::vector<StaggeredLaplacian> lap_;
  PoissonOptions options_;
  Multigrid mg_;
};

/// Subtracts the mean of x.
void remove_mean(dvec& x);

/// Smallest nonzero eigenvalue of -L on a box with periodic or g = 1/2 Neumann axes.
double smallest_nonzero_eigenvalue(const Box& box);

}  // namespace rbfib
