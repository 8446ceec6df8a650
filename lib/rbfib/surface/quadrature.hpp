#pragma once
// Quadrature weights on S^2 and on reference shapes (area weights dA0 of each site).
//
// - rbf_sphere_weights (dissertation eq. 2.22): [Phi 1; 1^T 0][w; I_phi] = [0; 4 pi] with
//   Phi_ij = |chi_i - chi_j|^p; -I_phi approximates the (constant) integral of phi over S^2.
// - nnls_sh_weights (paper eq. 45): the nonnegative least-squares solution of
//   Y^T w = sqrt(4 pi) e_1 for the harmonics of degree <= N (Lawson-Hanson active set; for a
//   square system with a nonnegative exact solution, that solution by one LU solve).
// - reference_shape_weights (paper eq. 51): w_L = sqrt(det G0(Z_L) / det G0(Z_S2)) w_S2.
#include "rbfib/surface/sphere.hpp"

#include <vector>

namespace rbfib::surface {

struct RbfWeights {
  std::vector<double> w;
  double I_phi = 0;
  double rcond = 0;  ///< reciprocal condition estimate of the block matrix
};
/// Throws NumericalError if the block matrix is singular.
RbfWeights rbf_sphere_weights(const SphereSites& sites, int power = 1);

struct NnlsWeights {
  std::vector<double> w;
  double residual = 0;  ///< || Y^T w - sqrt(4 pi) e_1 ||_2
  int iterations = 0;  ///< active-set steps (0: square system solved directly)
};
NnlsWeights nnls_sh_weights(const SphereSites& sites, int N);

/// Eq. (51): det_g0_shape[i] = det G0 of the reference shape at site i, and the unit sphere's
/// det G0 = cos^2 theta_i. Throws InputError for a site at a pole or a negative determinant.
std::vector<double> reference_shape_weights(const SphereSites& sites, const std::vector<double>& w_sphere,
                                            const std::vector<double>& det_g0_shape);

/// sum_i w_i f(site i) for f given at the sites.
double integrate(const std::vector<double>& w, const std::vector<double>& f);

}  // namespace rbfib::surface
