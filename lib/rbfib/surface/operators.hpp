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
// - spherical harmonics of degree <= M through m = (M+1)^2 sites (eqs. 85-86), kept factored as
//   in the paper: to_coefficients = Y^{-1} (from the LU factorization, computed once) maps data to
//   coefficients c, and the six matrices hold the harmonics and their derivatives at the sample
//   sites, so L = (L Y)(sample) Y^{-1} is applied as (L Y)(sample) (Y^{-1} X), with Y^{-1} X by
//   forward and back substitution with the stored LU factors (O(m^2), as the paper's Sec. 3.1).
//   This keeps round-off at the level of the coefficients, which decay for smooth surfaces;
//   an assembled product, or an explicit inverse, loses about a decade (measured: relative force
//   error 4e-13 instead of 4e-14 at m = 225 on the perturbed ellipsoid);
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
  /// Empty for assembled operators (RBF). For the factored harmonic form: the LU factors of
  /// P Y = L U (unit lower L and U packed in one m x m matrix) and the row permutation
  /// (row i of P Y is row perm[i] of Y); the six matrices above then act on coefficients.
  DenseMatrix lu;
  std::vector<index_t> perm;
  bool factored() const { return lu.rows > 0; }
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

/// The six operators applied to points X (3 per data site): out[q] holds 3 per sample site, in
/// the order id, d_l, d_t, d_ll, d_lt, d_tt.
void apply_operators(const SurfaceOperators& ops, const std::vector<double>& X, std::vector<double> out[6]);

/// Coefficients c = Y^{-1} x of a factored operator set, for `stride` interleaved right-hand
/// sides (x and c hold n_data * stride doubles).
void solve_coefficients(const SurfaceOperators& ops, const double* x, index_t stride, double* c);

/// I^T F: the transpose of the identity operator applied to F (3 per sample site), giving
/// 3 per data site (the generalized force on the data sites).
std::vector<double> transpose_identity(const SurfaceOperators& ops, const std::vector<double>& F);

/// Spherical-harmonic coefficients c (eq. 86) of data at (M+1)^2 sites, by one LU solve
/// (for tests and diagnostics; the operators above already contain Y^{-1}).
std::vector<double> sh_coefficients(const SphereSites& interp, int M, const std::vector<double>& values);

}  // namespace rbfib::surface
