#pragma once
// Discrete surface operators: matrices that map values at n_d data (interpolation) sites to the
// interpolant and its angular derivatives at n_s sample (evaluation) sites (Chapter 2 eq. 2.19;
// Chapter 3 Sec. 3.1). Built once per pair of site sets and shared (std::shared_ptr) by every cell
// of a type. Row i = sample site i, column j = data site j.
//
//   id   : s(site)            d_l : ds/dlambda        d_t : ds/dtheta
//   d_ll : d2s/dlambda2       d_lt: d2s/dlambda dtheta d_tt: d2s/dtheta2
//
// Two interpolants:
// - spherical harmonics of degree <= M through m = (M+1)^2 sites (eqs. 85-86): the LU
//   factorization of Y is computed once, and each operator is (L Y)(eval) Y^{-1};
// - polyharmonic splines phi(r) = r^p (p odd) on the chord distance of S^2 (eq. 2.18), augmented
//   by real harmonics of degree <= sh_degree (eqs. 2.15-2.17): L = [L Phi, L P] A^{-1}, first n_d
//   columns (eq. 2.19). sh_degree = 5 for red cells, 0 (a constant) for platelets.
#include "rbfib/surface/dense.hpp"
#include "rbfib/surface/sphere.hpp"

#include <memory>
#include <string>

namespace rbfib::surface {

struct SurfaceOperators {
  DenseMatrix id, d_l, d_t, d_ll, d_lt, d_tt;
  index_t n_data() const { return id.cols; }
  index_t n_sample() const { return id.rows; }
  double condition_estimate = 0;  ///< reciprocal-condition estimate of the interpolation matrix
  std::string description;
};

/// Spherical-harmonic interpolation operators (eqs. 85-86). Throws InputError if the sites are
/// not (M+1)^2 distinct sites, NumericalError if Y is singular (reciprocal condition < 1e-14).
std::shared_ptr<const SurfaceOperators> sh_operators(const SphereSites& interp, const SphereSites& eval, int M);

struct PhsBasis {
  int power = 7;       ///< phi(r) = r^power, odd, >= 1
  int sh_degree = 5;   ///< augmenting harmonics of degree <= sh_degree; -1 for none
};

/// RBF operators (eqs. 2.15-2.19). Throws InputError for coincident data sites or too few
/// sites, NumericalError if the block matrix of eq. (2.17) is singular.
std::shared_ptr<const SurfaceOperators> rbf_operators(const SphereSites& data, const SphereSites& sample,
                                                      PhsBasis basis);

/// Spherical-harmonic coefficients c (eq. 86) of data at (M+1)^2 sites, by one LU solve
/// (for tests and diagnostics; the operators above already contain Y^{-1}).
std::vector<double> sh_coefficients(const SphereSites& interp, int M, const std::vector<double>& values);

}  // namespace rbfib::surface
