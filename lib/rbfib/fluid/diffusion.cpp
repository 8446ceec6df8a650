#include "rbfib/fluid/diffusion.hpp"

#include <cmath>

namespace rbfib {

CrankNicolsonDiffusion::CrankNicolsonDiffusion(const Box& box, double mu, double dt, Correction correction,
                                               SolverOptions solver)
    : lap_(box, correction), mu_(mu), dt_(dt), solver_(std::move(solver)) {
  require(std::isfinite(mu) && mu > 0.0, "diffusion.mu", mu, "must be positive and finite");
  require(std::isfinite(dt) && dt > 0.0, "diffusion.dt", dt, "must be positive and finite");
}

SolveStats CrankNicolsonDiffusion::step(dvec& u, const dvec& f, const BoundaryData& gamma_half) {
  const double lambda = mu_ * dt_;
  require(index_t(f.size()) == lap_.size(), "diffusion.f.size", f.size(), "does not match the box");
  // rhs = (I~ + lambda/2 L) u + lambda B gamma + dt I~ f
  lap_.apply(u, rhs_, 1.0, 0.5 * lambda);
  lap_.add_boundary(gamma_half, rhs_, lambda);
  lap_.apply_identity(f, tmp_);
  blas::axpy(dt_, tmp_, rhs_);
  auto helmholtz = [this, lambda](const dvec& x, dvec& y) { lap_.apply(x, y, 1.0, -0.5 * lambda); };
  return conjugate_gradient(helmholtz, rhs_, u, solver_);
}

}  // namespace rbfib
