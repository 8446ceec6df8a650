#pragma once
// Pointwise continuous-energy force density (paper eqs. 12-15, 34-35) and bending force density
// (paper eq. 84 with the spontaneous curvature of dissertation eq. 2.13). Host+device functions
// of one site. Index 0 = lambda, 1 = theta.
//
// Elastic (eq. 35), per unit reference area:
//   F = (1/sqrt g0) d_j ( sqrt g0 S_kj X_k )
//     = sum_jk [ (d_j S_kj + S_kj d_j ln sqrt g0) X_k + S_kj X_kj ],
//   S = 2 W_1 G0^{-1} + 2 W_2 det C G^{-1}                                   (eq. 34)
// with d_j S expanded by the chain rule through (I1, I2), G and G0, so only the first and second
// derivatives of X and Z at the site are needed.
#include "rbfib/mechanics/energy.hpp"
#include "rbfib/surface/geometry_kernels.hpp"

namespace rbfib::mechanics {

using surface::Jet;

/// Status of a site. There is no per-site "inverted" test: the energy depends on the metrics
/// alone, which a rotation leaves unchanged, and comparing the current normal with the reference
/// normal (an earlier check) rejects every cell that has turned by more than 90 degrees, as a
/// tumbling cell does. A cell turned inside out is caught per cell by the sign of its enclosed
/// volume (cells/batch.hpp).
enum ForceStatus : int { force_ok = 0, force_degenerate_metric = 1, force_bad_energy = 3 };

struct ForceAtSite {
  double F[3];  ///< force density per unit reference area
  double W;     ///< energy density per unit reference area
  double I1, I2;
  int status;   ///< ForceStatus
};

RBFIB_HD inline void inverse2(const double m[2][2], double det, double out[2][2]) {
  out[0][0] = m[1][1] / det;
  out[1][1] = m[0][0] / det;
  out[0][1] = -m[0][1] / det;
  out[1][0] = -m[1][0] / det;
}

/// out = -A B A (derivative of an inverse: d(G^{-1}) = -G^{-1} dG G^{-1}).
RBFIB_HD inline void minus_aba(const double A[2][2], const double B[2][2], double out[2][2]) {
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      double s = 0;
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l) s += A[i][k] * B[k][l] * A[l][j];
      out[i][j] = -s;
    }
}

/// out = P Q R (2 x 2).
RBFIB_HD inline void triple_product(const double P[2][2], const double Q[2][2], const double R[2][2], double out[2][2]) {
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      double s = 0;
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l) s += P[i][k] * Q[k][l] * R[l][j];
      out[i][j] = s;
    }
}

RBFIB_HD inline double trace_ab(const double A[2][2], const double B[2][2]) {
  return A[0][0] * B[0][0] + A[0][1] * B[1][0] + A[1][0] * B[0][1] + A[1][1] * B[1][1];
}

/// Metric G_ab = X_a . X_b and its derivatives dG[j]_ab = X_aj . X_b + X_a . X_bj.
RBFIB_HD inline void metric_and_derivatives(const Jet& X, double G[2][2], double dG[2][2][2]) {
  const double* Xd[2] = {X.xl, X.xt};
  const double* Xdd[2][2] = {{X.xll, X.xlt}, {X.xlt, X.xtt}};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      G[a][b] = surface::dot3(Xd[a], Xd[b]);
      for (int j = 0; j < 2; ++j) dG[j][a][b] = surface::dot3(Xdd[a][j], Xd[b]) + surface::dot3(Xd[a], Xdd[b][j]);
    }
}

/// Current (X) and reference (Z) metrics with their derivatives and determinants.
struct MetricPair {
  double G[2][2], dG[2][2][2], G0[2][2], dG0[2][2][2];
  double det, det0;
};
/// Fills m; false when either metric is degenerate (det <= 0 or not finite).
RBFIB_HD inline bool metric_pair(const Jet& X, const Jet& Z, MetricPair& m) {
  metric_and_derivatives(X, m.G, m.dG);
  metric_and_derivatives(Z, m.G0, m.dG0);
  m.det = m.G[0][0] * m.G[1][1] - m.G[0][1] * m.G[1][0];
  m.det0 = m.G0[0][0] * m.G0[1][1] - m.G0[0][1] * m.G0[1][0];
  return m.det > 0 && m.det0 > 0;
}

/// Elastic force density (eq. 35) at one site, current jet X, reference jet Z.
RBFIB_HD inline ForceAtSite elastic_force_density(const Jet& X, const Jet& Z, const EnergyDensity& energy) {
  ForceAtSite r{{0, 0, 0}, 0, 0, 0, force_ok};
  MetricPair m;
  if (!metric_pair(X, Z, m)) {
    r.status = force_degenerate_metric;
    return r;
  }
  const auto &G = m.G, &G0 = m.G0;
  const auto &dG = m.dG, &dG0 = m.dG0;
  const double det = m.det, det0 = m.det0;
  double Gi[2][2], G0i[2][2];
  inverse2(G, det, Gi);
  inverse2(G0, det0, G0i);
  const double J2 = det / det0;
  r.I1 = trace_ab(G, G0i) - 2;
  r.I2 = J2 - 1;
  const InvariantDerivatives w = energy.evaluate(r.I1, r.I2);
  if (!w.valid) {
    r.status = force_bad_energy;
    return r;
  }
  r.W = w.W;
  double S[2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) S[a][b] = 2 * w.W1 * G0i[a][b] + 2 * w.W2 * J2 * Gi[a][b];
  const double* Xd[2] = {X.xl, X.xt};
  const double* Xdd[2][2] = {{X.xll, X.xlt}, {X.xlt, X.xtt}};
  for (int j = 0; j < 2; ++j) {
    double dGi[2][2], dG0i[2][2];
    minus_aba(Gi, dG[j], dGi);
    minus_aba(G0i, dG0[j], dG0i);
    const double dI1 = trace_ab(dG[j], G0i) + trace_ab(G, dG0i);
    const double dI2 = J2 * (trace_ab(Gi, dG[j]) - trace_ab(G0i, dG0[j]));
    const double dW1 = w.W11 * dI1 + w.W12 * dI2;
    const double dW2J2 = (w.W12 * dI1 + w.W22 * dI2) * J2 + w.W2 * dI2;
    const double dlng0 = 0.5 * trace_ab(G0i, dG0[j]);
    for (int k = 0; k < 2; ++k) {
      const double dS = 2 * dW1 * G0i[k][j] + 2 * w.W1 * dG0i[k][j] + 2 * dW2J2 * Gi[k][j] + 2 * w.W2 * J2 * dGi[k][j];
      const double c1 = dS + S[k][j] * dlng0;
      for (int d = 0; d < 3; ++d) r.F[d] += c1 * Xd[k][d] + S[k][j] * Xdd[k][j][d];
    }
  }
  return r;
}

/// Membrane dissipation (dissertation eq. 2.14), W = nu/2 (ldot1^2/l1^2 + ldot2^2/l2^2), written
/// frame-free as W = nu/8 tr((G^{-1} Gdot)^2), Gdot_ab = U_a . X_b + X_a . U_b (U = dX/dt): equal
/// to eq. (2.14) when the principal directions do not rotate. Its viscous force density is
/// F = -dPhi/dU of Phi = int W dA0, in the divergence form of eq. (35) with
///   S_d = 2 dW/dGdot = nu/2 G^{-1} Gdot G^{-1}.
/// X: position jet; U: velocity jet (same layout); Z: reference jet.
RBFIB_HD inline ForceAtSite dissipative_force_density(const Jet& X, const Jet& U, const Jet& Z, double nu) {
  ForceAtSite r{{0, 0, 0}, 0, 0, 0, force_ok};
  MetricPair m;
  if (!metric_pair(X, Z, m)) {
    r.status = force_degenerate_metric;
    return r;
  }
  const auto &G = m.G, &G0 = m.G0;
  const auto &dG = m.dG, &dG0 = m.dG0;
  const double det = m.det, det0 = m.det0;
  double Gi[2][2];
  inverse2(G, det, Gi);
  const double* Xd[2] = {X.xl, X.xt};
  const double* Xdd[2][2] = {{X.xll, X.xlt}, {X.xlt, X.xtt}};
  const double* Ud[2] = {U.xl, U.xt};
  const double* Udd[2][2] = {{U.xll, U.xlt}, {U.xlt, U.xtt}};
  double Gd[2][2], dGd[2][2][2];
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      Gd[a][b] = surface::dot3(Ud[a], Xd[b]) + surface::dot3(Xd[a], Ud[b]);
      for (int j = 0; j < 2; ++j)
        dGd[j][a][b] = surface::dot3(Udd[a][j], Xd[b]) + surface::dot3(Ud[a], Xdd[b][j]) +
                       surface::dot3(Xdd[a][j], Ud[b]) + surface::dot3(Xd[a], Udd[b][j]);
    }
  // A = G^{-1} Gdot G^{-1}; W = nu/8 tr((G^{-1} Gdot)^2) = nu/8 tr(A Gdot)
  double A[2][2];
  triple_product(Gi, Gd, Gi, A);
  r.W = nu / 8 * trace_ab(A, Gd);
  double G0i[2][2];
  inverse2(G0, det0, G0i);
  for (int j = 0; j < 2; ++j) {
    double dGi[2][2], t1[2][2], t2[2][2], t3[2][2];
    minus_aba(Gi, dG[j], dGi);
    triple_product(dGi, Gd, Gi, t1);
    triple_product(Gi, dGd[j], Gi, t2);
    triple_product(Gi, Gd, dGi, t3);
    const double dlng0 = 0.5 * trace_ab(G0i, dG0[j]);
    for (int k = 0; k < 2; ++k) {
      const double S = nu / 2 * A[k][j];
      const double dS = nu / 2 * (t1[k][j] + t2[k][j] + t3[k][j]);
      for (int d = 0; d < 3; ++d) r.F[d] += (dS + S * dlng0) * Xd[k][d] + S * Xdd[k][j][d];
    }
  }
  return r;
}

/// Bending force density per unit reference area (eq. 84 generalized to W = 2 kappa (H - H')^2):
///   F = -2 kappa sqrt(det G / det G0) [ lap_s H + 2 (H - H')(H^2 + H' H - K) ] n,   K = R/2.
/// With H' = 0 and kappa = 2 k_bend this is eq. (84). lap_H is the surface Laplacian of H.
RBFIB_HD inline void bending_force_density(const surface::PointGeometry& g, double det_g0, double lap_H,
                                           double kappa, double H0, double* F) {
  const double K = 0.5 * g.R;
  const double c = -2 * kappa * sqrt(g.det_g / det_g0) * (lap_H + 2 * (g.H - H0) * (g.H * g.H + H0 * g.H - K));
  for (int d = 0; d < 3; ++d) F[d] = c * g.n[d];
}

}  // namespace rbfib::mechanics
