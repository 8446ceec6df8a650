#pragma once
// Pointwise kernels of the corrected staggered Laplacian (eqs. A.8, A.16, A.22). One grid index
// per call; the launch is in laplacian.cpp.
#include "rbfib/grid/box.hpp"

namespace rbfib::kernels {

struct LaplacianStencil {
  BoxShape shape;
  AxisStencil axis[3];
  double inv_n0 = 1.0, inv_n1 = 1.0;  ///< 1 / n_x, 1 / n_y: index split by multiplication

  /// shape.split(p, i) without integer division: q = floor((p + 1/2) / n) is exact in double
  /// arithmetic while p < 2^40 (the rounding error p 2^-53 stays below the margin 1/(2n)).
  RBFIB_HD void split(index_t p, int i[3]) const {
    const index_t q = index_t((double(p) + 0.5) * inv_n0);
    i[0] = int(p - q * shape.n[0]);
    const index_t r = index_t((double(q) + 0.5) * inv_n1);
    i[1] = int(q - r * shape.n[1]);
    i[2] = int(r);
  }
};

inline LaplacianStencil make_laplacian_stencil(const BoxShape& shape) {
  LaplacianStencil s;
  s.shape = shape;
  s.inv_n0 = 1.0 / shape.n[0];
  s.inv_n1 = 1.0 / shape.n[1];
  return s;
}

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

/// out = alpha I~ u + beta L u, L = sum_d (prod_{e != d} I~_e) (x) L_d  (eq. A.22), one unknown per call.
struct HelmholtzApply {
  LaplacianStencil s;
  const double* u;
  double* out;
  double alpha, beta;

  /// The general formula at p = (i, j, k): weights and ghosts wherever needed.
  RBFIB_HD void general(index_t p, const int i[3]) const {
    double lap = 0.0;
    for (int d = 0; d < s.shape.dims; ++d) lap += identity_weight(s, i, d) * second_difference(s, u, p, i, d);
    out[p] = alpha * identity_weight(s, i, -1) * u[p] + beta * lap;
  }

  RBFIB_HD void operator()(index_t p) const {
    int i[3];
    s.split(p, i);
    // Away from every end (and from the periodic wrap) all weights are 1 and no ghost is needed.
    bool interior = true;
    for (int d = 0; d < s.shape.dims; ++d) interior = interior && i[d] > 0 && i[d] < s.axis[d].n - 1;
    if (!interior) return general(p, i);
    const double c = u[p];
    double lap = 0.0;
    for (int d = 0; d < s.shape.dims; ++d) {
      const index_t st = s.shape.stride[d];
      lap += (u[p - st] + u[p + st] - 2.0 * c) * s.axis[d].inv_h2;
    }
    out[p] = alpha * c + beta * lap;
  }
};

/// The same operator, one x-row (fixed j, k) per call: the interior of the row is a loop with
/// constant strides that the host compiler vectorizes; the two ends and every row next to a
/// y or z end take the general formula. Used by the CPU backend, where a row is a cache-friendly
/// unit of work; the CUDA backend launches HelmholtzApply per unknown.
struct HelmholtzApplyRows {
  HelmholtzApply k;

  RBFIB_HD void operator()(index_t row) const {
    const LaplacianStencil& s = k.s;
    const int n0 = s.shape.n[0];
    int i[3];
    i[1] = int(row % s.shape.n[1]);
    i[2] = int(row / s.shape.n[1]);
    const index_t base = row * n0;
    bool inner = n0 > 2;
    for (int d = 1; d < s.shape.dims; ++d) inner = inner && i[d] > 0 && i[d] < s.axis[d].n - 1;
    if (!inner) {
      for (int i0 = 0; i0 < n0; ++i0) {
        i[0] = i0;
        k.general(base + i0, i);
      }
      return;
    }
    i[0] = 0;
    k.general(base, i);
    i[0] = n0 - 1;
    k.general(base + n0 - 1, i);
    const double* u = k.u + base;
    double* out = k.out + base;
    const index_t sy = s.shape.stride[1], sz = s.shape.dims > 2 ? s.shape.stride[2] : 0;
    const double cx = s.axis[0].inv_h2, cy = s.shape.dims > 1 ? s.axis[1].inv_h2 : 0.0,
                 cz = s.shape.dims > 2 ? s.axis[2].inv_h2 : 0.0;
    const double a = k.alpha, b = k.beta;
    const double centre = a - 2.0 * b * (cx + cy + cz);
    if (s.shape.dims == 3) {
      for (int j = 1; j < n0 - 1; ++j)
        out[j] = centre * u[j] + b * (cx * (u[j - 1] + u[j + 1]) + cy * (u[j - sy] + u[j + sy]) + cz * (u[j - sz] + u[j + sz]));
    } else if (s.shape.dims == 2) {
      for (int j = 1; j < n0 - 1; ++j)
        out[j] = centre * u[j] + b * (cx * (u[j - 1] + u[j + 1]) + cy * (u[j - sy] + u[j + sy]));
    } else {
      for (int j = 1; j < n0 - 1; ++j) out[j] = centre * u[j] + b * cx * (u[j - 1] + u[j + 1]);
    }
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
