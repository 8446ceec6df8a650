#pragma once
// Discrete surface operators: matrices that map values at n_d data (interpolation) sites to the
// interpolant and its angular derivatives at n_s sample (evaluation) sites (Chapter 2 eq. 2.19;
// Chapter 3 Sec. 3.1). Built once per pair of site sets on the host (Eigen), uploaded once to the
// execution device, and shared (std::shared_ptr) by every cell of a type.
//
// Stored as two column-major device matrices acting on k columns (k = n_d, or the m coefficients
// of the factored form below), stacked by operator:
//   value        (n_s x k):   row i      = s(site i)
//   derivatives  (5 n_s x k): row q n_s + i = D_q s(site i), q = 0..4 for
//                             d/dlambda, d/dtheta, d2/dlambda2, d2/dlambda dtheta, d2/dtheta2,
// so the jets of any number of fields (3 columns per cell for positions, 3 more for velocities,
// one per cell for a scalar) are two products: value X and derivatives X (see docs/math.md for
// the Lagrangian layout). The value block is the sample-site layout that ib/ spreads from.
//
// Two interpolants:
// - spherical harmonics of degree <= M through m = (M+1)^2 sites (eqs. 85-86), kept factored as
//   in the paper: the LU factors of Y (LAPACK form) map data to coefficients c = Y^{-1} X by
//   forward and back substitution (O(m^2) per column, paper Sec. 3.1), and value/derivatives hold
//   the harmonics and their derivatives at the sample sites, so L X = (L Y)(sample) (Y^{-1} X).
//   This keeps round-off at the level of the coefficients, which decay for smooth surfaces;
//   an assembled product, or an explicit inverse, loses about a decade (measured: relative force
//   error 4e-13 instead of 4e-14 at m = 225 on the perturbed ellipsoid);
// - polyharmonic splines phi(r) = r^p (p odd) on the chord distance of S^2 (eq. 2.18), augmented
//   by real harmonics of degree <= sh_degree (eqs. 2.15-2.17): L = [L Phi, L P] A^{-1}, first n_d
//   columns (eq. 2.19), assembled. sh_degree = 5 for red cells, 0 (a constant) for platelets.
//
// Single precision (in_single_precision, optional, beyond the seed): value and derivatives are
// also kept rounded to float and the products run in float (sgemm, accumulated in float by the
// BLAS kernels: no BLAS offers float operators with double accumulation, and on the CPU only the
// float arithmetic, not the halved operator bytes, buys speed: the products are compute bound).
// Each column of F is first shifted by its value at data site 0 (for positions, by a point of the
// cell, so that float rounds the cell's shape, not its place in the box): the derivative
// operators annihilate constants and the value operator reproduces them (both interpolants here
// contain the constant), so the shift is added back to the values in double and the derivatives
// need none. The coefficients of the factored form are still solved in double.
#include "rbfib/linalg/dense.hpp"
#include "rbfib/surface/sphere.hpp"

#include <memory>
#include <string>

namespace rbfib::surface {

/// Number of derivative operators stacked in SurfaceOperators::derivatives.
inline constexpr int derivative_count = 5;

struct SurfaceOperators {
  linalg::DeviceMatrix value;        ///< n_s x k
  linalg::DeviceMatrix derivatives;  ///< 5 n_s x k
  /// Factored harmonic form: the LU factors of Y (m x m); empty for assembled operators (RBF).
  linalg::LuFactors lu;
  /// Single precision: value and derivatives rounded to float (empty unless in_single_precision).
  linalg::FloatMatrix value32, derivatives32;
  /// The interpolant contains the constant (value reproduces it, derivatives annihilate it).
  bool reproduces_constants = false;
  index_t data_sites = 0;
  double condition_estimate = 0;  ///< reciprocal-condition estimate of the interpolation matrix
  std::string description;

  bool factored() const { return lu.n() > 0; }
  bool single_precision() const { return !value32.empty(); }
  index_t n_data() const { return data_sites; }
  index_t n_sample() const { return value.rows(); }
  /// Device bytes held (what each cell type costs in memory).
  std::size_t bytes() const { return value.bytes() + derivatives.bytes() + lu.bytes() + value32.bytes() + derivatives32.bytes(); }
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

/// The same operators, with value and derivatives also rounded to float: apply_operators and the
/// variants below then run their products in single precision (see the top of this file).
/// Throws InputError for an interpolant without the constant (an RBF set with sh_degree < 0).
std::shared_ptr<const SurfaceOperators> in_single_precision(const SurfaceOperators& ops);

/// Workspace of apply_operators (the coefficients of the factored form; the shifted columns and
/// the float operands and results of the single-precision products), reused between calls.
struct OperatorWorkspace {
  linalg::DeviceMatrix coefficients;
  dvec shift;
  linalg::FloatMatrix in32, out32;
};

/// value = V F and derivatives = D F for the fields F (n_d x cols, any number of columns): two
/// products on the device (after Y^{-1} F for the factored form). value must be n_s x cols and
/// derivatives 5 n_s x cols; either may be left empty (rows = 0) to skip it.
void apply_operators(const SurfaceOperators& ops, linalg::ConstMatrixView F, linalg::MatrixView value,
                     linalg::MatrixView derivatives, OperatorWorkspace& work);

/// The same for the sample sites [row0, row0 + rows) only: value is rows x c (c <= cols: the
/// values of F's first c columns alone, for fields whose values nothing reads) and derivatives
/// 5 rows x cols (derivative q of site row0 + i in row q rows + i), by one product for the values
/// and one strided batch of five for the derivatives.
void apply_operators_rows(const SurfaceOperators& ops, linalg::ConstMatrixView F, index_t row0, index_t rows,
                          linalg::MatrixView value, linalg::MatrixView derivatives, OperatorWorkspace& work);

/// The operators of the sample sites [row0, row0 + rows) as a set of their own (device copies;
/// the LU factors of a factored set are copied too; double precision only).
std::shared_ptr<const SurfaceOperators> select_sample_sites(const SurfaceOperators& ops, index_t row0, index_t rows);

/// G = I^T F: the transpose of the value operator applied to F (n_s x cols), giving n_d x cols
/// (the generalized force on the data sites).
void apply_value_transpose(const SurfaceOperators& ops, linalg::ConstMatrixView F, linalg::MatrixView G);

/// Host convenience for one cell: I^T F with F and the result n x 3, column-major (docs/math.md).
std::vector<double> transpose_identity(const SurfaceOperators& ops, const std::vector<double>& F);

/// Spherical-harmonic coefficients c (eq. 86) of data at (M+1)^2 sites, by one LU solve
/// (for tests and diagnostics; the operators above already contain Y^{-1}).
std::vector<double> sh_coefficients(const SphereSites& interp, int M, const std::vector<double>& values);

}  // namespace rbfib::surface
