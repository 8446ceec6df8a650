#include "rbfib/fluid/periodic_stokes.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/fluid/helmholtz.hpp"
#include "rbfib/fluid/poisson.hpp"
#include "rbfib/linalg/blas.hpp"

#include <thrust/reduce.h>

#include <cmath>
#include <string>

namespace rbfib {

PeriodicStokesSolver::PeriodicStokesSolver(const MacGrid& grid, double viscosity, double alpha)
    : ops_(grid), mu_(viscosity), alpha_(alpha) {
  for (int d = 0; d < grid.dims; ++d)
    require(grid.periodic(d), std::string("grid.") + "xyz"[d] + ".boundary", "walls",
            "the periodic Stokes solver needs every axis periodic");
  require(std::isfinite(viscosity) && viscosity > 0, "fluid.viscosity", viscosity, "must be positive and finite (poise)");
  require(std::isfinite(alpha) && alpha >= 0, "stokes.alpha (rho / dt)", alpha, "must be finite and >= 0 (g/(cm^3 s))");
  for (int a = 0; a < grid.dims; ++a)
    velocity_[a] = std::make_unique<FourierSolver>(ops_.component_box(a), Correction::none, alpha, -viscosity,
                                                   "stokes u" + std::to_string(a));
  pressure_ = std::make_unique<FourierSolver>(ops_.scalar_box(), Correction::none, 0.0, -1.0, "stokes pressure");
}

std::array<double, 3> PeriodicStokesSolver::solve(const VectorField& f, VectorField& u, dvec& p,
                                                  std::array<double, 3> mean_velocity) const {
  const int dims = ops_.dims();
  for (int a = 0; a < dims; ++a)
    require(index_t(f[a].size()) == ops_.component_box(a).size(), "stokes force[" + std::to_string(a) + "].size",
            f[a].size(), "must be " + to_text(ops_.component_box(a).size()));
  // L_c p = D f  <=>  -L_c p = -D f (the pressure solver's form; D f has zero mean on a periodic grid).
  ops_.divergence(f, nullptr, div_);
  blas::scale(-1.0, div_);
  pressure_->solve(div_, p);
  // (alpha - mu L) u = f - G p, per component.
  ops_.gradient(p, rhs_);
  std::array<double, 3> removed{0, 0, 0};
  for (int a = 0; a < dims; ++a) {
    blas::xpby(f[a], -1.0, rhs_[a]);  // rhs = f - G p
    if (alpha_ == 0) removed[a] = thrust::reduce(f[a].begin(), f[a].end(), 0.0) / double(f[a].size());
    velocity_[a]->solve(rhs_[a], u[a]);  // alpha = 0: mean removed, u mean-free
    if (alpha_ == 0 && mean_velocity[a] != 0) blas::shift(mean_velocity[a], u[a]);
  }
  return removed;
}

void PeriodicStokesSolver::solve_iteratively(const VectorField& f, VectorField& u, dvec& p, double rtol) const {
  require(alpha_ > 0, "stokes.alpha (rho / dt)", alpha_, "must be > 0 for the iterative solve (the steady operator is singular)");
  PoissonOptions po;
  po.solver = SolverOptions{"stokes pressure (PCG)", rtol, 1000};
  PoissonSolver P(ops_.scalar_box(), po);
  dvec b;
  ops_.divergence(f, nullptr, b);
  blas::scale(-1.0, b);  // -D f
  p.assign(b.size(), 0.0);
  P.solve(b, p);
  VectorField Gp;
  ops_.gradient(p, Gp);
  HelmholtzOptions ho;
  ho.solver = SolverOptions{"stokes velocity (PCG)", rtol, 2000};
  for (int a = 0; a < ops_.dims(); ++a) {
    HelmholtzSolver H(ops_.component_box(a), mu_ / alpha_, ho);
    dvec rhs = f[a];
    blas::axpy(-1.0, Gp[a], rhs);
    blas::scale(1.0 / alpha_, rhs);  // (f - G p) / alpha
    u[a].assign(rhs.size(), 0.0);
    H.solve(rhs, u[a]);
  }
}

}  // namespace rbfib
