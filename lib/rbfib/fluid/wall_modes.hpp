#pragma once
// One Fourier mode (k_x, k_z) of (alpha I~ + beta L) on a channel (x and z periodic, walls in y):
// the tridiagonal system in y of fourier_solver.hpp, solved in place by the Thomas algorithm.
// Shared by the solver on one process and the one on slabs of several ranks, which store a mode's
// y-line with different strides.
#include "rbfib/grid/axis.hpp"
#include "rbfib/linalg/fft.hpp"

#include "rbfib/core/constants.hpp"

#include <cmath>

namespace rbfib::kernels {

/// Eigenvalues mu(k) = -(2 - 2 cos(2 pi k / n)) / h^2 of the periodic second difference along an
/// axis (fourier_solver.hpp); zeros along a wall axis.
inline host_vector<double> periodic_eigenvalues(const AxisStencil& a, int n) {
  host_vector<double> mu(static_cast<std::size_t>(n), 0.0);
  if (a.periodic)
    for (int k = 0; k < n; ++k) mu[k] = -(2.0 - 2.0 * std::cos(2 * pi * k / n)) * a.inv_h2;
  return mu;
}

struct WallModes {
  AxisStencil ay;  ///< the y axis (walls), with its ghosts and modified-identity weights
  double alpha = 0.0, beta = 0.0;

  /// Diagonal entry j of the mode whose periodic second differences have eigenvalue mu = mu_x + mu_z.
  RBFIB_HD double diagonal(int j, double mu) const {
    const double ends = (j == 0 ? ay.lo.ghost : 0.0) + (j == ay.n - 1 ? ay.hi.ghost : 0.0);
    const double wj = ay.weight(j);
    return alpha * wj + beta * (wj * mu + (ends - 2.0) * ay.inv_h2);
  }

  /// Solves the mode's line w[base + j st] (j < n_y) in place; cp is scratch at the same positions.
  /// pin: x_0 = 0 replaces the redundant first equation (the null mode of a singular operator).
  RBFIB_HD void solve(double mu, bool pin, linalg::complex* w, double* cp, index_t base, index_t st) const {
    const double off = beta * ay.inv_h2;
    double d0 = pin ? 1.0 : diagonal(0, mu);
    double c = pin ? 0.0 : off / d0;
    linalg::complex r = pin ? linalg::complex(0.0, 0.0) : w[base] / d0;
    cp[base] = c;
    w[base] = r;
    for (int j = 1; j < ay.n; ++j) {  // forward sweep
      const index_t p = base + j * st;
      const double den = diagonal(j, mu) - off * c;
      c = off / den;
      r = (w[p] - off * r) / den;
      cp[p] = c;
      w[p] = r;
    }
    for (int j = ay.n - 2; j >= 0; --j) {  // back substitution
      const index_t p = base + j * st;
      w[p] = w[p] - cp[p] * w[p + st];
    }
  }
};

}  // namespace rbfib::kernels
