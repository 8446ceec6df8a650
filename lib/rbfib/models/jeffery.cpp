#include "rbfib/models/jeffery.hpp"

#include "rbfib/core/error.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib::models {

namespace {
double dot3(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
}  // namespace

std::vector<Vec3> jeffery_axis(const Vec3& p0, double r, double gdot, int f, int g, const std::vector<double>& times) {
  require(f >= 0 && f < 3 && g >= 0 && g < 3 && f != g, "jeffery_axis axes", to_text(f) + ", " + to_text(g), "expected two different axes 0..2");
  const double B = (r * r - 1) / (r * r + 1);
  // grad u = gdot e_f e_g^T: W p = (gdot/2)(p_g e_f - p_f e_g), E p = (gdot/2)(p_g e_f + p_f e_g).
  auto rhs = [&](const Vec3& p) {
    Vec3 Wp{0, 0, 0}, Ep{0, 0, 0};
    Wp[f] = 0.5 * gdot * p[g], Wp[g] = -0.5 * gdot * p[f];
    Ep[f] = 0.5 * gdot * p[g], Ep[g] = 0.5 * gdot * p[f];
    const double pEp = dot3(p, Ep);
    return Vec3{Wp[0] + B * (Ep[0] - pEp * p[0]), Wp[1] + B * (Ep[1] - pEp * p[1]), Wp[2] + B * (Ep[2] - pEp * p[2])};
  };
  std::vector<Vec3> out;
  Vec3 p = p0;
  double t = 0;
  const double hmax = 1e-3 / std::abs(gdot);
  for (double target : times) {
    while (t < target) {
      const double h = std::min(hmax, target - t);
      auto add = [](const Vec3& a, const Vec3& b, double s) { return Vec3{a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; };
      const Vec3 k1 = rhs(p), k2 = rhs(add(p, k1, h / 2)), k3 = rhs(add(p, k2, h / 2)), k4 = rhs(add(p, k3, h));
      for (int d = 0; d < 3; ++d) p[d] += h / 6 * (k1[d] + 2 * k2[d] + 2 * k3[d] + k4[d]);
      const double norm = std::sqrt(dot3(p, p));
      for (double& v : p) v /= norm;
      t += h;
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace rbfib::models
