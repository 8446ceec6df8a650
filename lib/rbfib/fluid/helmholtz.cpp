#include "rbfib/fluid/helmholtz.hpp"

#include <thrust/extrema.h>

#include <cmath>

namespace rbfib {

ChebyshevBounds gershgorin_bounds(const StaggeredLaplacian& L, double alpha, double beta) {
  const index_t n = L.size();
  dvec lo(n), hi(n);
  const auto s = L.stencil();
  double* plo = ptr(lo);
  double* phi = ptr(hi);
  for_each_index(n, [=] RBFIB_HD (index_t p) {
    int i[3];
    s.shape.split(p, i);
    double diag = 0.0, off = 0.0;
    for (int d = 0; d < s.shape.dims; ++d) {
      const AxisStencil& a = s.axis[d];
      const double w = kernels::identity_weight(s, i, d) * a.inv_h2;
      double c = -2.0;
      int neighbours = 0;
      if (a.periodic) {
        if (a.n == 1) c = 0.0;
        else if (a.n == 2) c = -2.0, neighbours = 1, off += 2.0 * w;  // both neighbours are one entry
        else neighbours = 2;
      } else {
        if (i[d] == 0) c += a.lo.ghost; else ++neighbours;
        if (i[d] == a.n - 1) c += a.hi.ghost; else ++neighbours;
      }
      if (!(a.periodic && a.n == 2)) off += neighbours * w;
      diag += c * w;
    }
    const double centre = alpha * kernels::identity_weight(s, i, -1) + beta * diag;
    const double radius = (beta < 0 ? -beta : beta) * off;
    plo[p] = centre - radius;
    phi[p] = centre + radius;
  });
  ChebyshevBounds b;
  b.lambda_min = *thrust::min_element(lo.begin(), lo.end());
  b.lambda_max = *thrust::max_element(hi.begin(), hi.end());
  return b;
}

HelmholtzSolver::HelmholtzSolver(const Box& box, double c, HelmholtzOptions options)
    : lap_(box, Correction::appendix_a), c_(c), options_(std::move(options)) {
  const std::string& name = options_.solver.name;
  require(std::isfinite(c) && c > 0.0, name + ".coefficient", c, "theta dt mu / rho must be positive and finite");
  require(options_.chebyshev_steps >= 1, name + ".chebyshev_steps", options_.chebyshev_steps, "must be at least 1");
  const ChebyshevBounds b = gershgorin_bounds(lap_, 1.0, -c);
  // Appendix A: H is SPD when every 1 - eps > 0; Gershgorin's lower bound is then positive too,
  // since the rows are weakly diagonally dominant with a positive identity part.
  if (!(b.lambda_min > 0.0))
    throw NumericalError(Cause::solver, name + ": Gershgorin lower bound " + to_text(b.lambda_min) +
                         " <= 0 for the Helmholtz operator (limit: > 0)");
  cheb_ = ChebyshevIteration(b, options_.chebyshev_steps, name + ".chebyshev");
}

SolveStats HelmholtzSolver::solve(const dvec& b, dvec& x) const {
  auto A = [this](const dvec& u, dvec& y) { apply(u, y); };
  auto M = [this, &A](const dvec& r, dvec& z) { cheb_.solve(A, r, z, true); };
  return conjugate_gradient(A, b, x, options_.solver, M);
}

}  // namespace rbfib
