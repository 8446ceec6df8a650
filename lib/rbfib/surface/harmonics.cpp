#include "rbfib/surface/harmonics.hpp"
#include "rbfib/core/constants.hpp"

#include "rbfib/core/error.hpp"

#include <cmath>

namespace rbfib::surface {

void real_harmonics(int M, double lambda, double theta, double* y, double* yl, double* yt,
                    double* yll, double* ylt, double* ytt) {
  require(M >= 0, "harmonic degree M", M, "must be >= 0");
  const double x = std::sin(theta);  // cos(colatitude)
  const double s = std::cos(theta);  // sin(colatitude) >= 0
  const int w = M + 2;               // row width: k = 0..M+1 (k = l+1 holds zero)
  std::vector<double> Q(static_cast<std::size_t>((M + 1) * w), 0.0);
  std::vector<double> dQ(Q.size(), 0.0), ddQ(Q.size(), 0.0);
  auto at = [w](int l, int k) { return static_cast<std::size_t>(l * w + k); };

  // Q_l^k(x): diagonal, first off-diagonal, then the three-term recurrence in l.
  Q[at(0, 0)] = 1.0 / std::sqrt(4.0 * pi);
  for (int k = 1; k <= M; ++k)
    Q[at(k, k)] = std::sqrt((2.0 * k + 1.0) / (2.0 * k)) * s * Q[at(k - 1, k - 1)];
  for (int k = 0; k < M; ++k) Q[at(k + 1, k)] = std::sqrt(2.0 * k + 3.0) * x * Q[at(k, k)];
  for (int k = 0; k <= M; ++k) {
    for (int l = k + 2; l <= M; ++l) {
      const double ll = double(l) * l, kk = double(k) * k, l1 = double(l - 1) * (l - 1);
      const double a = std::sqrt((4.0 * ll - 1.0) / (ll - kk));
      const double b = std::sqrt((l1 - kk) / (4.0 * l1 - 1.0));
      Q[at(l, k)] = a * (x * Q[at(l - 1, k)] - b * Q[at(l - 2, k)]);
    }
  }
  // d/d(colatitude): a linear map from row l onto itself, applied twice.
  auto differentiate = [&](const std::vector<double>& f, std::vector<double>& df) {
    for (int l = 0; l <= M; ++l) {
      df[at(l, 0)] = l > 0 ? -std::sqrt(double(l) * (l + 1)) * f[at(l, 1)] : 0.0;
      for (int k = 1; k <= l; ++k)
        df[at(l, k)] = 0.5 * (std::sqrt(double(l + k) * (l - k + 1)) * f[at(l, k - 1)] -
                              std::sqrt(double(l + k + 1) * (l - k)) * f[at(l, k + 1)]);
    }
  };
  differentiate(Q, dQ);
  differentiate(dQ, ddQ);

  // d/dtheta = -d/d(colatitude); d2/dtheta2 = d2/d(colatitude)2.
  const double r2 = std::sqrt(2.0);
  for (int l = 0; l <= M; ++l) {
    {
      const int j = sh_index(l, 0);
      if (y) y[j] = Q[at(l, 0)];
      if (yl) yl[j] = 0.0;
      if (yt) yt[j] = -dQ[at(l, 0)];
      if (yll) yll[j] = 0.0;
      if (ylt) ylt[j] = 0.0;
      if (ytt) ytt[j] = ddQ[at(l, 0)];
    }
    for (int k = 1; k <= l; ++k) {
      const double c = std::cos(k * lambda), sn = std::sin(k * lambda);
      const double q = r2 * Q[at(l, k)], dq = -r2 * dQ[at(l, k)], ddq = r2 * ddQ[at(l, k)];
      const int jp = sh_index(l, k), jm = sh_index(l, -k);
      if (y) { y[jp] = q * c; y[jm] = q * sn; }
      if (yl) { yl[jp] = -k * q * sn; yl[jm] = k * q * c; }
      if (yt) { yt[jp] = dq * c; yt[jm] = dq * sn; }
      if (yll) { yll[jp] = -double(k) * k * q * c; yll[jm] = -double(k) * k * q * sn; }
      if (ylt) { ylt[jp] = -k * dq * sn; ylt[jm] = k * dq * c; }
      if (ytt) { ytt[jp] = ddq * c; ytt[jm] = ddq * sn; }
    }
  }
}

}  // namespace rbfib::surface
