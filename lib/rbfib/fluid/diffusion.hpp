#pragma once
// Crank-Nicolson for u_t = mu Laplacian u + f with boundary data gamma (eqs. A.11-A.12), or its
// corrected form (eqs. A.15, A.22):
//   (I~ - lambda/2 L) u^{n+1} = (I~ + lambda/2 L) u^n + lambda B_h gamma^{n+1/2} + dt I~ f^{n+1/2},
// lambda = mu dt, solved by conjugate gradients (the operator is SPD).
#include "rbfib/fluid/laplacian.hpp"
#include "rbfib/linalg/cg.hpp"

namespace rbfib {

class CrankNicolsonDiffusion {
 public:
  /// mu: diffusivity (length^2/time), dt: time step (time). Throws InputError on non-positive values.
  CrankNicolsonDiffusion(const Box& box, double mu, double dt, Correction correction, SolverOptions solver);

  /// Advances u by one step; f and gamma are evaluated at t^{n+1/2}. Returns the CG statistics.
  SolveStats step(dvec& u, const dvec& f, const BoundaryData& gamma_half);

  const StaggeredLaplacian& laplacian() const { return lap_; }
  double dt() const { return dt_; }

 private:
  StaggeredLaplacian lap_;
  double mu_, dt_;
  SolverOptions solver_;
  dvec rhs_, tmp_;
};

}  // namespace rbfib
