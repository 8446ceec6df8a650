#pragma once
// Direct solves of the Helmholtz and Poisson operators of Section 2.1 on the seed's geometries,
// boxes periodic along x (and z) and either periodic or bounded by walls along y:
//   (alpha I~ + beta L) x = b,
// L and I~ the staggered Laplacian and modified identity of Appendix A (eq. A.22), any boundary
// conditions on the y walls (Dirichlet or Neumann, corrected or not), the same discrete operator as
// StaggeredLaplacian::apply. The Helmholtz solve of eq. 2.6 is alpha = 1, beta = -c; the Poisson
// solve of eq. 2.9 is alpha = 0, beta = -1.
//
// Along a periodic axis the second difference is diagonalized by the DFT, with eigenvalues
//   mu_d(k) = -(2 - 2 cos(2 pi k / n_d)) / h_d^2,
// the same for every staggering (a shift only multiplies a mode by a phase), and I~ is the identity
// there. So, with x and z periodic, each Fourier mode (k_x, k_z) leaves one tridiagonal system in y:
//   [alpha w_j + beta (w_j (mu_x + mu_z) - (2 - ghost_lo [j = 0] - ghost_hi [j = n_y - 1]) / h_y^2)] x_j
//     + (beta / h_y^2) (x_{j-1} + x_{j+1}) = b_j,
// w_j the modified-identity weights of the y axis and the ghosts those of eq. A.7: symmetric,
// solved by the Thomas algorithm (no pivoting: the systems are definite, or semidefinite with the
// constant null space of the Neumann Poisson problem, removed as below). With y periodic too the
// operator is diagonal in (k_x, k_y, k_z). The data are real and each mode's operator has real
// coefficients, so the modes k_x > n_x / 2 are the conjugates of the others: real transforms keep
// k_x = 0 .. n_x / 2 only (half the transform and half the tridiagonal systems). Cost: two real
// FFTs of the box and O(n) work: exact to rounding, no iteration.
//
// A singular operator (alpha = 0 with no Dirichlet condition: the pressure Poisson problem) has the
// constants as null space: b is made mean-free and so is the solution, as PoissonSolver does.
#include "rbfib/fluid/laplacian.hpp"
#include "rbfib/linalg/fft.hpp"

#include <memory>
#include <string>

namespace rbfib {

class FourierSolver {
 public:
  /// Whether a box is one this solver handles: every axis periodic except possibly y, at least two
  /// points along x, and the FFT backend able to batch it.
  static bool applies(const Box& box);

  /// Throws InputError naming `name` if the box does not apply, or if alpha I~ + beta L is not
  /// definite or semidefinite (beta > 0, or alpha < 0).
  FourierSolver(const Box& box, Correction correction, double alpha, double beta, const std::string& name);

  /// x = (alpha I~ + beta L)^{-1} b (x is resized). For a singular operator, b's mean is removed
  /// first and x is returned mean-free.
  void solve(const dvec& b, dvec& x) const;
  /// y = (alpha I~ + beta L) x
  void apply(const dvec& x, dvec& y) const { lap_.apply(x, y, alpha_, beta_); }

  bool singular() const { return singular_; }
  const StaggeredLaplacian& laplacian() const { return lap_; }
  const std::string& name() const { return name_; }

 private:
  StaggeredLaplacian lap_;
  double alpha_, beta_;
  std::string name_;
  bool wall_ = false, singular_ = false;
  std::unique_ptr<linalg::RealFourierTransform> fft_;
  std::array<dvec, 3> mu_;  // eigenvalues of the periodic second differences, per mode
  mutable linalg::cvec work_;
  mutable dvec thomas_, mean_free_;
};

}  // namespace rbfib
