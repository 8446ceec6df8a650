#pragma once
// The discrete Laplacian on a staggered box with linear ghost extrapolation (eqs. A.4-A.8), built
// as a tensor sum (eq. A.16), optionally with the boundary correction of Appendix A: the modified
// identity I~ = I~_z (x) I~_y (x) I~_x (eq. A.14) and
//   L = sum_d (prod_{e != d} I~_e) (x) L_d,   B_h = sum_d (prod_{e != d} I~_e) (x) B_d   (eq. A.22),
// so that I~ u_t = mu (L u + B_h gamma) + I~ f reproduces quadratics exactly and the Helmholtz
// operator alpha I~ - beta L (alpha, beta > 0) stays symmetric positive definite.
//
// Matrix-free; values at unknowns, x fastest; internal units (1/length^2).
#include "rbfib/fluid/laplacian_kernels.hpp"

namespace rbfib {

class StaggeredLaplacian {
 public:
  StaggeredLaplacian(const Box& box, Correction correction);

  const Box& box() const { return box_; }
  index_t size() const { return box_.size(); }
  Correction correction() const { return correction_; }

  /// out = alpha I~ u + beta L u (homogeneous boundary data).
  void apply(const dvec& u, dvec& out, double alpha, double beta) const;
  /// out = L u (homogeneous boundary data).
  void apply(const dvec& u, dvec& out) const { apply(u, out, 0.0, 1.0); }
  /// out += beta B_h gamma: the boundary data's share of L u (eq. A.8), per face.
  void add_boundary(const BoundaryData& gamma, dvec& out, double beta) const;
  /// out = I~ u (the diagonal modified identity).
  void apply_identity(const dvec& u, dvec& out) const { apply(u, out, 1.0, 0.0); }
  /// Diagonal of alpha I~ + beta L, e.g. for Jacobi scaling or Gershgorin bounds.
  dvec diagonal(double alpha, double beta) const;

  const kernels::LaplacianStencil& stencil() const { return stencil_; }

 private:
  Box box_;
  Correction correction_;
  kernels::LaplacianStencil stencil_;
};

}  // namespace rbfib
