#include "rbfib/cells/reference_geometry.hpp"

#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::cells {

double evans_fung_area(double R0, int intervals) {
  require(intervals > 0 && intervals % 2 == 0, "evans_fung_area intervals", intervals, "must be even and > 0");
  auto integrand = [R0](double phi) {
    const double c = std::cos(phi), s = std::sin(phi), s2 = c * c;
    const double r = R0 * c, dr = -R0 * s;
    const double zeta = 0.105 + s2 - 0.56 * s2 * s2, dzeta = (1 - 1.12 * s2) * (-2 * c * s);
    const double dz = R0 * (dzeta * s + zeta * c);
    return 2 * pi * r * std::sqrt(dr * dr + dz * dz);
  };
  const double a = -pi / 2, h = pi / intervals;
  double sum = integrand(a) + integrand(-a);
  for (int i = 1; i < intervals; ++i) sum += (i % 2 ? 4 : 2) * integrand(a + i * h);
  return sum * h / 3;
}

double support(const ReferenceShape& shape, const Mat3& R, const Vec3& u, int n_lambda, int n_theta) {
  require(n_lambda > 0 && n_theta > 0, "support grid", n_lambda * n_theta, "needs n_lambda, n_theta > 0");
  double best = -1e300;
  for (int i = 0; i <= n_lambda; ++i)
    for (int j = 0; j <= n_theta; ++j) {
      double X[3];
      shape.position(2 * pi * i / n_lambda, -pi / 2 + pi * j / n_theta, X);
      double v = 0;
      for (int a = 0; a < 3; ++a) v += (R[a][0] * X[0] + R[a][1] * X[1] + R[a][2] * X[2]) * u[a];
      best = std::max(best, v);
    }
  return best;
}

}  // namespace rbfib::cells
