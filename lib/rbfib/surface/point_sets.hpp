#pragma once
// Point sets for cell surfaces (material coordinates, see sphere.hpp).
//
// - bauer_spiral(N): dissertation eq. (5.1): latitude_j = asin(-1 + (2j-1)/N),
//   longitude_j = mod(sqrt(N pi) latitude_j + pi, 2 pi) - pi, j = 1..N. Avoids the poles.
// - toroidal_spiral(N): dissertation Appendix B: phi_i = 2 pi (i-1)/N,
//   theta_i = mod(ceil(sqrt N) phi_i, 2 pi), i = 1..N, on [0, 2 pi)^2 (returned as
//   lambda = theta_i, theta = phi_i: both periodic angles, not sphere coordinates).
// - max_determinant_points(M): (M+1)^2 sites that locally maximize |det Y| (Y the interpolation
//   matrix of eq. 86, so det(Y Y^T) = det(Y)^2, the Gram determinant of Sec. 3.1), found by
//   gradient ascent on log|det Y| from the Bauer spiral. A stand-in for the downloaded
//   maximal-determinant points of the paper, which we do not have.
// - gauss_product_sites(nt, nl): Gauss-Legendre in sin(theta) times uniform in lambda, with their
//   exact-for-polynomials weights (a reference quadrature for tests).
#include "rbfib/surface/sphere.hpp"

namespace rbfib::surface {

SphereSites bauer_spiral(index_t N);
SphereSites toroidal_spiral(index_t N);

struct MaxDetResult {
  SphereSites sites;
  double log_det_start = 0;  ///< log|det Y| of the starting spiral
  double log_det = 0;        ///< log|det Y| reached
  int iterations = 0;
};
MaxDetResult max_determinant_points(int M, int max_iterations = 300);

/// Gauss-Legendre nodes x_i and weights w_i on [-1, 1] (n >= 1), by Newton iteration.
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w);

/// nt latitudes (Gauss-Legendre in sin theta) times nl equispaced longitudes; weights[i] is the
/// area weight of site i (sum 4 pi), exact for harmonics of degree <= min(2 nt - 1, nl - 1).
SphereSites gauss_product_sites(int nt, int nl, std::vector<double>& weights);

}  // namespace rbfib::surface
