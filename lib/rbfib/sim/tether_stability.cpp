#include "rbfib/sim/tether_stability.hpp"

#include "rbfib/core/error.hpp"

#include <cmath>
#include <vector>

namespace rbfib::sim {

double sliding_mobility(const TetherSheet& s, double dt) {
  require(s.h > 0 && std::isfinite(s.h), "tether sheet: grid spacing h (cm)", s.h, "must be positive");
  const double cells = s.channel / s.h;
  require(std::abs(cells - std::round(cells)) < 1e-6 && cells >= 4, "tether sheet: channel (cm)", s.channel,
          "must be a whole number (>= 4) of cells of h");
  require(s.plane > 0 && s.plane < s.channel, "tether sheet: plane (cm)", s.plane, "must lie between the walls");
  require(s.points_per_area > 0, "tether sheet: points per area (1/cm^2)", s.points_per_area, "must be positive");
  require(s.rho > 0 && s.mu > 0, "tether sheet: rho, mu", s.mu, "must be positive");
  require(dt > 0, "tether sheet: dt (s)", dt, "must be positive");
  const std::size_t n = std::size_t(std::lround(cells));
  std::vector<double> w(n, 0.0);
  ib::with_kernel(s.kernel, [&](auto kernel) {
    for (std::size_t j = 0; j < n; ++j) w[j] = decltype(kernel)::phi(((double(j) + 0.5) * s.h - s.plane) / s.h);
  });
  // (2 rho/dt - mu L_h) x = w / h, L_h the second difference with u = 0 on the walls (a ghost
  // value -u at each end): tridiagonal, solved by elimination.
  const double a = 2 * s.rho / dt, off = -s.mu / (s.h * s.h);
  std::vector<double> diag(n), rhs(n);
  for (std::size_t j = 0; j < n; ++j) {
    diag[j] = a + s.mu * ((j == 0 || j == n - 1) ? 3 : 2) / (s.h * s.h);
    rhs[j] = w[j] / s.h;
  }
  for (std::size_t j = 1; j < n; ++j) {
    const double m = off / diag[j - 1];
    diag[j] -= m * off;
    rhs[j] -= m * rhs[j - 1];
  }
  std::vector<double> x(n);
  x[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t j = n - 1; j-- > 0;) x[j] = (rhs[j] - off * x[j + 1]) / diag[j];
  double g = 0;
  for (std::size_t j = 0; j < n; ++j) g += w[j] * x[j];
  return s.points_per_area * g;
}

double tether_gain(const TetherSheet& s, double k, double eta, double dt, bool predicted) {
  return (eta + (predicted ? 1.5 : 0.5) * k * dt) * sliding_mobility(s, dt);
}

double tether_dt_limit(const TetherSheet& s, double k, double eta, bool predicted, double lo, double hi) {
  require(lo > 0 && hi > lo, "tether_dt_limit: [lo, hi] (s)", hi, "must be an interval of positive steps");
  if (tether_gain(s, k, eta, lo, predicted) > 1) return lo;
  if (tether_gain(s, k, eta, hi, predicted) <= 1) return hi;
  for (int i = 0; i < 60; ++i) {
    const double m = std::sqrt(lo * hi);
    (tether_gain(s, k, eta, m, predicted) > 1 ? hi : lo) = m;
  }
  return lo;
}

TetherConstants tether_constants_for_step(const TetherSheet& s, double dt, double safety) {
  require(safety > 0 && safety < 1, "tether rule: safety (gain)", safety, "must lie in (0, 1)");
  const double g = sliding_mobility(s, dt);
  return {0.4 * safety / (dt * g), 0.8 * safety / g};
}

}  // namespace rbfib::sim
