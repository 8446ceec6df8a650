#pragma once
// Real spherical harmonics (Chapter 3, eq. 38) with first and second derivatives in both angles.
//
//   Y_l^0    = Q_l^0(sin theta)
//   Y_l^k    = sqrt(2) Q_l^k(sin theta) cos(k lambda),   k > 0
//   Y_l^{-k} = sqrt(2) Q_l^k(sin theta) sin(k lambda),   k > 0
// with Q_l^k = sqrt((2l+1)/(4 pi) (l-k)!/(l+k)!) P_l^k, P_l^k the associated Legendre function
// without the Condon-Shortley phase. The factor sqrt(2) makes the set orthonormal on S^2 (eq. 38
// as printed omits it, so its k != 0 functions have norm 1/sqrt(2); interpolation, eq. 85-86, and
// the weights of eq. 45 do not depend on it). Q is computed by the standard three-term
// recurrences of the normalized functions, stable to degree >= 100 (no factorials formed).
// Derivatives in theta use d/d(colatitude) Q_l^k = (sqrt((l+k)(l-k+1)) Q_l^{k-1}
// - sqrt((l+k+1)(l-k)) Q_l^{k+1}) / 2, applied twice, so the poles need no special case.
//
// Index order: j = l^2 + l + k for l = 0..M, k = -l..l; (M+1)^2 functions in all.
#include <vector>

namespace rbfib::surface {

inline int sh_count(int degree) { return (degree + 1) * (degree + 1); }
inline int sh_index(int l, int k) { return l * l + l + k; }

/// Values and derivatives of every real harmonic of degree <= M at one point. Any output pointer
/// may be null; non-null ones must hold sh_count(M) doubles.
/// y: Y; yl: dY/dlambda; yt: dY/dtheta; yll, ylt, ytt: second derivatives.
void real_harmonics(int M, double lambda, double theta, double* y, double* yl = nullptr,
                    double* yt = nullptr, double* yll = nullptr, double* ylt = nullptr,
                    double* ytt = nullptr);

}  // namespace rbfib::surface
