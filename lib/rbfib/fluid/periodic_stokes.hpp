#pragma once
// The Stokes problem on a triply (or doubly, in 2D) periodic MAC grid, solved exactly: the
// spectral Stokes solver of the paper's Sec. 3.2, made the exact inverse of the discrete
// operators instead of the continuous ones:
//   alpha u - mu L u + G p = f,   D u = 0,
// alpha >= 0 (alpha = rho / dt: a backward Euler step of unsteady Stokes; 0: steady Stokes), mu the
// viscosity, L the MAC Laplacian of each component, D and G the MAC divergence and gradient
// (mac_operators.hpp). On a periodic MAC grid D G = L_c (the cell-centred Laplacian) and D L = L_c D,
// so the divergence of the momentum equation gives
//   L_c p = D f,    then    (alpha - mu L) u = f - G p,
// the discrete Leray projection of f followed by the discrete Helmholtz inverse, each a diagonal
// solve in Fourier space (fourier_solver.hpp: the modified wavenumbers (2/h) sin(k h/2) come out of
// the discrete operators themselves). Cost: a few FFTs of the grid; exact to rounding.
//
// The mean mode: with alpha = 0, a net force cannot be balanced by a periodic flow, so the mean of
// f is removed (and returned, dyn/cm^3) and the mean of u is the imposed mean velocity (cm/s);
// with alpha > 0 the mean of u is mean(f) / alpha, as the equation says.
// Units (CGS): f dyn/cm^3, mu poise, alpha g/(cm^3 s), u cm/s, p dyn/cm^2.
#include "rbfib/fluid/fourier_solver.hpp"
#include "rbfib/fluid/mac_operators.hpp"

#include <array>
#include <memory>

namespace rbfib {

class PeriodicStokesSolver {
 public:
  /// Throws InputError naming the field for a grid with walls, mu <= 0 or alpha < 0.
  PeriodicStokesSolver(const MacGrid& grid, double viscosity, double alpha = 0.0);

  /// Solves for u and p (resized); returns the mean force density removed (zero when alpha > 0).
  std::array<double, 3> solve(const VectorField& f, VectorField& u, dvec& p,
                              std::array<double, 3> mean_velocity = {0, 0, 0}) const;

  /// The same system (alpha > 0) by the iterative solvers, for verification: -L_c p = -D f by
  /// multigrid-preconditioned CG, then (I - (mu/alpha) L) u = (f - G p) / alpha by Chebyshev-
  /// preconditioned CG, both to ||r|| <= rtol ||b||.
  void solve_iteratively(const VectorField& f, VectorField& u, dvec& p, double rtol) const;

  const MacOperators& operators() const { return ops_; }
  double viscosity() const { return mu_; }
  double alpha() const { return alpha_; }

 private:
  MacOperators ops_;
  double mu_, alpha_;
  std::array<std::unique_ptr<FourierSolver>, 3> velocity_;
  std::unique_ptr<FourierSolver> pressure_;
  mutable dvec div_;
  mutable VectorField rhs_;
};

}  // namespace rbfib
