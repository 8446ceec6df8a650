#pragma once
// Pointwise kernels of the corrected staggered Laplacian (eqs. A.8, A.16, A.22). One grid index
// per call; the launch is in laplacian.cpp.
#include "rbfib/grid/box.hpp"

namespace rbfib::kernels {

struct LaplacianStencil {
  BoxShape shape;
  AxisStencil axis[3];
};

/// Product of the modified-identity weights of every axis but `skip` (skip = -1: all axes).
RBFIB_HD inline double identity_weight(const LaplacianStencil& s, const int i[3], int skip) {
  double w = 1.0;
  for (int d = 0; d < s.shape.dims; ++d)
    if (d != skip) w *= s.axis[d].weight(i[d]);
  return w;
}

/// Homogeneous second difference along axis d at p (ghosts from eq. A.7 with gamma = 0).
RBFIB_HD inline double second_difference(const LaplacianStencil& s, const double* u, index_t p, const int i[3], int d) {
  const AxisStencil& a = s.axis[d];
  const index_t st = s.shape.stride[d];
  const double c = u[p];
  double lo, hi;
  if (i[d] > 0) lo = u[p - st];
  else if (a.periodic) lo = u[p + index_t(a.n - 1) * st];
  else lo = a.lo.ghost * c;
  if (i[d] < a.n - 1) hi = u[p + st];
  else if (a.periodic) hi = u[p - index_t(a.n - 1) * st];
  else hi = a.hi.ghost * c;
  return (lo - 2.0 * c + hi) * a.inv_h2;
}

/// out = alpha I~ u + beta L u, L = sum_d (prod_{e != d} I~_e) (x) L_d  (eq. A.22).
struct HelmholtzApply {
  LaplacianStencil s;
  const double* u;
  double* out;
  double alpha, beta;

  RBFIB_HD void operator()(index_t p) const {
    int i[3];
    s.shape.split(p, i);
    double lap = 0.0;
    for (int d = 0; d < s.shape.dims; ++d) lap += identity_weight(s, i, d) * second_difference(s, u, p, i, d);
    out[p] = alpha * identity_weight(s, i, -1) * u[p] + beta * lap;
  }
};

/// out[p] += beta (prod_{e != d} I~_e) data * gamma_f / h_d^2 at the unknowns next to one face (B_h gamma, eq. A.22).
struct BoundaryApply {
  LaplacianStencil s;
  int d, side;
  const double* gamma;
  double* out;
  double beta;

  RBFIB_HD void operator()(index_t f) const {
    const int a = d == 0 ? 1 : 0, b = d == 2 ? 1 : 2;  // other axes, lower first
    int i[3];
    i[a] = int(f % s.shape.n[a]);
    i[b] = int(f / s.shape.n[a]);
    i[d] = side ? s.axis[d].n - 1 : 0;
    const index_t p = i[0] + s.shape.stride[1] * i[1] + s.shape.stride[2] * i[2];
    const AxisEnd& end = side ? s.axis[d].hi : s.axis[d].lo;
    out[p] += beta * identity_weight(s, i, d) * end.data * gamma[f] * s.axis[d].inv_h2;
  }
};

}  // namespace rbfib::kernels
