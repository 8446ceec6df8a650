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
//   limited-memory BFGS on log|det Y(x / |x|)| over unnormalized Cartesian points x in R^(3m),
//   started from the Bauer spiral. A stand-in for the downloaded maximal-determinant points of the
//   paper, which we do not have. Each iteration costs an LU factorization and an inverse of the
//   m x m matrix Y (about 3 m^3 flops); the generated sets for the paper's evaluation sizes are
//   stored under reference/point_sets (see read_sphere_sites).
// - read_sphere_sites / write_sphere_sites: text files of unit vectors "x y z", one site per
//   line, '#' starting a comment line.
// - gauss_product_sites(nt, nl): Gauss-Legendre in sin(theta) times uniform in lambda, with their
//   exact-for-polynomials weights (a reference quadrature for tests).
#include "rbfib/surface/sphere.hpp"

#include <functional>
#include <string>
#include <vector>

namespace rbfib::surface {

SphereSites bauer_spiral(index_t N);
SphereSites toroidal_spiral(index_t N);

struct MaxDetResult {
  SphereSites sites;
  double log_det_start = 0;  ///< log|det Y| of the starting spiral
  double log_det = 0;        ///< log|det Y| reached
  double gradient_norm = 0;  ///< 2-norm of the gradient of log|det Y| at the end (per unit length)
  int iterations = 0;
  bool converged = false;    ///< relative gain below 1e-10 for 5 iterations in a row
};
/// progress(iteration, log|det Y|), when given, is called every `report_every` iterations.
MaxDetResult max_determinant_points(int M, int max_iterations = 2000,
                                    const std::function<void(int, double)>& progress = {},
                                    int report_every = 20);

/// Reads a site file (see above). Throws InputError naming the file and line for a missing file,
/// a malformed line, or a vector whose length differs from 1 by more than 1e-9.
SphereSites read_sphere_sites(const std::string& path);
/// Writes sites as unit vectors with 17 significant digits; `header` lines are written as
/// '#' comments first.
void write_sphere_sites(const std::string& path, const SphereSites& sites, const std::vector<std::string>& header);

/// Gauss-Legendre nodes x_i and weights w_i on [-1, 1] (n >= 1), by Newton iteration.
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w);

/// nt latitudes (Gauss-Legendre in sin theta) times nl equispaced longitudes; weights[i] is the
/// area weight of site i (sum 4 pi), exact for harmonics of degree <= min(2 nt - 1, nl - 1).
SphereSites gauss_product_sites(int nt, int nl, std::vector<double>& weights);

}  // namespace rbfib::surface
