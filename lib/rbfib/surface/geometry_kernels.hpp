#pragma once
// Pointwise differential geometry of a parametrized surface X(lambda, theta) (paper eqs. 12,
// 75-78, 82-83). Host+device functions of one site's "jet": X and its first and second partial
// derivatives in (lambda, theta). Index 0 = lambda, 1 = theta.
#include "rbfib/core/exec.hpp"

#include <cmath>

namespace rbfib::surface {

/// X, X_lambda, X_theta, X_lambda lambda, X_lambda theta, X_theta theta at one site (Cartesian).
struct Jet {
  double x[3], xl[3], xt[3], xll[3], xlt[3], xtt[3];
};

/// Scalar field u and its derivatives at one site.
struct ScalarJet {
  double u, ul, ut, ull, ult, utt;
};

/// Jets of fields as apply_operators writes them (docs/math.md): for N cells, component a of
/// cell c is column a N + c; its value at site i is v[i + col ldv] and derivative q (lambda,
/// theta, lambda lambda, lambda theta, theta theta) is d[q n + i + col ldd]. A scalar field has
/// one column per cell (column c).
struct JetView {
  const double* v = nullptr;
  index_t ldv = 0;
  const double* d = nullptr;
  index_t ldd = 0;
  index_t n = 0;      ///< sites per cell
  index_t cells = 1;  ///< N

  RBFIB_HD double value(index_t col, index_t i) const { return v[i + col * ldv]; }
  RBFIB_HD double derivative(int q, index_t col, index_t i) const { return d[q * n + i + col * ldd]; }
  /// The jet of cell c at site i; its value is 0 where v is null (only derivatives computed: the
  /// geometry, the elastic and the dissipative forces read derivatives alone).
  RBFIB_HD Jet jet(index_t c, index_t i) const {
    Jet j;
    for (int a = 0; a < 3; ++a) {
      const index_t col = a * cells + c;
      j.x[a] = v ? value(col, i) : 0.0;
      j.xl[a] = derivative(0, col, i);
      j.xt[a] = derivative(1, col, i);
      j.xll[a] = derivative(2, col, i);
      j.xlt[a] = derivative(3, col, i);
      j.xtt[a] = derivative(4, col, i);
    }
    return j;
  }
  /// Scalar jet of column c; the value is 0 where v is null (only derivatives computed).
  RBFIB_HD ScalarJet scalar(index_t c, index_t i) const {
    return ScalarJet{v ? value(c, i) : 0.0, derivative(0, c, i), derivative(1, c, i), derivative(2, c, i),
                     derivative(3, c, i), derivative(4, c, i)};
  }
};

struct PointGeometry {
  double E, F, G;    ///< first fundamental form (eq. 77), metric G = [[E, F], [F, G]] (eq. 12)
  double det_g;      ///< E G - F^2
  double n[3];       ///< unit normal (X_lambda x X_theta)/|.| (eq. 75)
  double e, f, g;    ///< second fundamental form (eq. 78)
  double H;          ///< mean curvature (eq. 76); -1/r on a sphere of radius r (outward normal)
  double R;          ///< scalar curvature, twice the Gaussian curvature (eq. 83)
};

RBFIB_HD inline double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
RBFIB_HD inline void cross3(const double* a, const double* b, double* c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/// Geometry at one site; det_g <= 0 (a degenerate parametrization) leaves n, H, R as zero.
RBFIB_HD inline PointGeometry point_geometry(const Jet& j) {
  PointGeometry p{};
  p.E = dot3(j.xl, j.xl);
  p.F = dot3(j.xl, j.xt);
  p.G = dot3(j.xt, j.xt);
  p.det_g = p.E * p.G - p.F * p.F;
  double c[3];
  cross3(j.xl, j.xt, c);
  const double nc = sqrt(dot3(c, c));
  if (!(p.det_g > 0) || !(nc > 0)) return p;
  for (int d = 0; d < 3; ++d) p.n[d] = c[d] / nc;
  p.e = dot3(j.xll, p.n);
  p.f = dot3(j.xlt, p.n);
  p.g = dot3(j.xtt, p.n);
  p.H = (p.e * p.G - 2 * p.f * p.F + p.g * p.E) / (2 * p.det_g);
  // det(G^{-1} b) = det b / det G
  p.R = 2 * (p.e * p.g - p.f * p.f) / p.det_g;
  return p;
}

/// Surface Laplacian (eq. 82) of u: g^{ij} (u_ij - Gamma^k_ij u_k), Gamma^k_ij = g^{kl} X_ij . X_l.
RBFIB_HD inline double laplace_beltrami(const Jet& j, const ScalarJet& u) {
  const double E = dot3(j.xl, j.xl), F = dot3(j.xl, j.xt), G = dot3(j.xt, j.xt);
  const double det = E * G - F * F;
  const double gi[2][2] = {{G / det, -F / det}, {-F / det, E / det}};
  const double* Xd[2] = {j.xl, j.xt};
  const double* Xdd[2][2] = {{j.xll, j.xlt}, {j.xlt, j.xtt}};
  const double ud[2] = {u.ul, u.ut};
  const double udd[2][2] = {{u.ull, u.ult}, {u.ult, u.utt}};
  double lap = 0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      double christoffel_u = 0;  // Gamma^k_ab u_k
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l) christoffel_u += gi[k][l] * dot3(Xdd[a][b], Xd[l]) * ud[k];
      lap += gi[a][b] * (udd[a][b] - christoffel_u);
    }
  return lap;
}

/// Surface gradient of u: g^{ab} u_b X_a (a tangent vector), written to grad[0..2].
RBFIB_HD inline void surface_gradient(const Jet& j, const ScalarJet& u, double* grad) {
  const double E = dot3(j.xl, j.xl), F = dot3(j.xl, j.xt), G = dot3(j.xt, j.xt);
  const double det = E * G - F * F;
  const double cl = (G * u.ul - F * u.ut) / det, ct = (E * u.ut - F * u.ul) / det;
  for (int d = 0; d < 3; ++d) grad[d] = cl * j.xl[d] + ct * j.xt[d];
}

}  // namespace rbfib::surface
