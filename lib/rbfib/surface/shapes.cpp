#include "rbfib/surface/shapes.hpp"
#include "rbfib/core/constants.hpp"

#include "rbfib/surface/point_sets.hpp"

#include <cmath>

namespace rbfib::surface {

namespace {
}

Jet PerturbedEllipsoid::jet(double l, double t) const {
  const double cl = std::cos(l), sl = std::sin(l), ct = std::cos(t), st = std::sin(t);
  const double e = std::exp(-st), e1 = -ct * e, e2 = (st + ct * ct) * e;
  // component = A(t) L(l), A = s (1 + beta e) T(t)
  const double scale[3] = {Vf * a, Vf * b, Vf * c};
  const double beta[3] = {B / 5, B, B};
  const double T[3][3] = {{ct, -st, -ct}, {ct, -st, -ct}, {st, ct, -st}};  // T, T', T''
  const double L[3][3] = {{cl, -sl, -cl}, {sl, cl, -sl}, {1, 0, 0}};      // L, L', L''
  Jet j;
  for (int d = 0; d < 3; ++d) {
    const double s = scale[d], bb = beta[d];
    const double A0 = s * (1 + bb * e) * T[d][0];
    const double A1 = s * (bb * e1 * T[d][0] + (1 + bb * e) * T[d][1]);
    const double A2 = s * (bb * e2 * T[d][0] + 2 * bb * e1 * T[d][1] + (1 + bb * e) * T[d][2]);
    j.x[d] = A0 * L[d][0];
    j.xl[d] = A0 * L[d][1];
    j.xt[d] = A1 * L[d][0];
    j.xll[d] = A0 * L[d][2];
    j.xlt[d] = A1 * L[d][1];
    j.xtt[d] = A2 * L[d][0];
  }
  return j;
}

std::vector<Jet> PerturbedEllipsoid::jets(const SphereSites& s) const {
  std::vector<Jet> out(static_cast<std::size_t>(s.size()));
  for (index_t i = 0; i < s.size(); ++i) out[i] = jet(s.lambda[i], s.theta[i]);
  return out;
}

std::vector<double> PerturbedEllipsoid::points(const SphereSites& s) const {
  std::vector<double> out(static_cast<std::size_t>(3 * s.size()));
  for (index_t i = 0; i < s.size(); ++i) {
    const Jet j = jet(s.lambda[i], s.theta[i]);
    for (int d = 0; d < 3; ++d) out[d * s.size() + i] = j.x[d];
  }
  return out;
}

double PerturbedEllipsoid::volume() const {
  std::vector<double> x, w;
  const int nt = 200, nl = 400;
  gauss_legendre(nt, x, w);
  double V = 0;
  for (int i = 0; i < nt; ++i) {
    const double t = 0.5 * pi * x[i];  // theta in (-pi/2, pi/2)
    for (int k = 0; k < nl; ++k) {
      const double l = -pi + 2 * pi * k / nl;
      const Jet j = jet(l, t);
      double c[3];
      cross3(j.xl, j.xt, c);
      V += w[i] * 0.5 * pi * (2 * pi / nl) * dot3(j.x, c);
    }
  }
  return V / 3;
}

PerturbedEllipsoid paper_perturbed_ellipsoid() {
  PerturbedEllipsoid p;
  p.Vf = 1.0;
  const double V1 = p.volume();
  p.Vf = std::cbrt(4 * pi / 3 / V1);
  return p;
}

void ellipsoid_curvatures(double a, double b, double c, const double* x, double& H, double& K) {
  const double a2 = a * a, b2 = b * b, c2 = c * c;
  const double h2 = x[0] * x[0] / (a2 * a2) + x[1] * x[1] / (b2 * b2) + x[2] * x[2] / (c2 * c2);
  const double h = std::sqrt(h2);
  const double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
  H = -(a2 + b2 + c2 - r2) / (2 * a2 * b2 * c2 * h2 * h);
  K = 1.0 / (a2 * b2 * c2 * h2 * h2);
}

}  // namespace rbfib::surface
