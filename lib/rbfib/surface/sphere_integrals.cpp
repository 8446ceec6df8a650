#include "rbfib/surface/sphere_integrals.hpp"

#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"

#include <cmath>

namespace rbfib::surface {

double sphere_integral_exp(const std::array<double, 3>& a) {
  const double na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  return na == 0 ? 4 * pi : 4 * pi * std::sinh(na) / na;
}

double sphere_integral_distance_power(int p) {
  require(p > -2, "sphere_integral_distance_power: power p", p, "must exceed -2 (the integral diverges)");
  // In the distance r = |x - y|, dA = 2 pi r dr on r in [0, 2].
  return 2 * pi * std::pow(2.0, p + 2) / (p + 2);
}

double exp_quadrature_error(const SphereSites& sites, const std::vector<double>& w, const std::array<double, 3>& a) {
  require(w.size() == std::size_t(sites.size()), "exp_quadrature_error: number of weights", w.size(),
          "must equal the number of sites " + to_text(sites.size()));
  double I = 0;
  for (index_t i = 0; i < sites.size(); ++i) {
    double x[3];
    unit_sphere_point(sites.lambda[i], sites.theta[i], x);
    I += w[i] * std::exp(a[0] * x[0] + a[1] * x[1] + a[2] * x[2]);
  }
  return std::abs(I - sphere_integral_exp(a));
}

}  // namespace rbfib::surface
