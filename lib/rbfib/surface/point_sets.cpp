#include "rbfib/surface/point_sets.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/surface/harmonics.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace rbfib::surface {

namespace {
constexpr double pi = 3.14159265358979323846;
double positive_mod(double a, double n) { return a - std::abs(n) * std::floor(a / std::abs(n)); }
}  // namespace

SphereSites bauer_spiral(index_t N) {
  require(N >= 1, "spiral N", N, "must be >= 1");
  SphereSites s;
  s.lambda.resize(N);
  s.theta.resize(N);
  for (index_t j = 1; j <= N; ++j) {
    const double phi = std::asin(-1.0 + (2.0 * j - 1.0) / double(N));
    s.theta[j - 1] = phi;
    s.lambda[j - 1] = positive_mod(std::sqrt(N * pi) * phi + pi, 2 * pi) - pi;
  }
  return s;
}

SphereSites toroidal_spiral(index_t N) {
  require(N >= 1, "spiral N", N, "must be >= 1");
  SphereSites s;
  s.lambda.resize(N);
  s.theta.resize(N);
  const double turns = std::ceil(std::sqrt(double(N)));
  for (index_t i = 1; i <= N; ++i) {
    const double phi = 2 * pi * double(i - 1) / double(N);
    s.theta[i - 1] = phi;
    s.lambda[i - 1] = positive_mod(turns * phi, 2 * pi);
  }
  return s;
}

MaxDetResult max_determinant_points(int M, int max_iterations) {
  require(M >= 0, "harmonic degree M", M, "must be >= 0");
  const int m = sh_count(M);
  // Small dense matrices: threading them only costs (and contends with the caller's threads).
  const int threads = Eigen::nbThreads();
  Eigen::setNbThreads(1);
  MaxDetResult r;
  r.sites = bauer_spiral(m);
  std::vector<double> row(m), rl(m), rt(m);
  Eigen::MatrixXd Y(m, m), Yl(m, m), Yt(m, m);
  auto assemble = [&](const SphereSites& s, bool derivs) {
    for (int i = 0; i < m; ++i) {
      real_harmonics(M, s.lambda[i], s.theta[i], row.data(), derivs ? rl.data() : nullptr,
                     derivs ? rt.data() : nullptr);
      for (int j = 0; j < m; ++j) {
        Y(i, j) = row[j];
        if (derivs) { Yl(i, j) = rl[j]; Yt(i, j) = rt[j]; }
      }
    }
  };
  auto log_abs_det = [&](const Eigen::PartialPivLU<Eigen::MatrixXd>& lu) {
    double v = 0;
    for (int i = 0; i < m; ++i) v += std::log(std::abs(lu.matrixLU()(i, i)));
    return v;
  };
  assemble(r.sites, true);
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(Y);
  double f = log_abs_det(lu);
  r.log_det_start = f;
  const double h = std::sqrt(4 * pi / m);  // typical spacing
  double step = 0.05 * h;
  int it = 0;
  for (; it < max_iterations && step > 1e-6 * h; ++it) {
    // d log|det Y| / d p_i = sum_k dY_ik/dp_i (Y^{-1})_ki.
    const Eigen::MatrixXd Yinv = lu.inverse();
    std::vector<double> d3(3 * m);
    double gmax = 0;
    for (int i = 0; i < m; ++i) {
      const double gl = Yl.row(i).dot(Yinv.col(i)), gt = Yt.row(i).dot(Yinv.col(i));
      const double la = r.sites.lambda[i], th = r.sites.theta[i];
      const double c = std::max(std::cos(th), 1e-12);
      // gradient on S^2 = (g_lambda / cos theta) e_lambda + g_theta e_theta
      const double el[3] = {-std::sin(la), std::cos(la), 0.0};
      const double et[3] = {-std::cos(la) * std::sin(th), -std::sin(la) * std::sin(th), std::cos(th)};
      for (int d = 0; d < 3; ++d) d3[3 * i + d] = gl / c * el[d] + gt * et[d];
      gmax = std::max(gmax, std::sqrt(d3[3 * i] * d3[3 * i] + d3[3 * i + 1] * d3[3 * i + 1] + d3[3 * i + 2] * d3[3 * i + 2]));
    }
    if (!(gmax > 0)) break;
    bool accepted = false;
    while (!accepted && step > 1e-6 * h) {
      SphereSites trial = r.sites;
      for (int i = 0; i < m; ++i) {
        double p[3];
        unit_sphere_point(r.sites.lambda[i], r.sites.theta[i], p);
        for (int d = 0; d < 3; ++d) p[d] += step / gmax * d3[3 * i + d];
        const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        trial.theta[i] = std::asin(std::clamp(p[2] / n, -1.0, 1.0));
        trial.lambda[i] = std::atan2(p[1], p[0]);
      }
      assemble(trial, true);
      Eigen::PartialPivLU<Eigen::MatrixXd> lu2(Y);
      const double f2 = log_abs_det(lu2);
      if (std::isfinite(f2) && f2 > f) {
        r.sites = trial;
        lu = lu2;
        f = f2;
        step *= 1.2;
        accepted = true;
      } else {
        step *= 0.5;
      }
    }
    if (!accepted) {
      assemble(r.sites, true);
      break;
    }
  }
  r.log_det = f;
  r.iterations = it;
  Eigen::setNbThreads(threads);
  return r;
}

void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  require(n >= 1, "Gauss-Legendre n", n, "must be >= 1");
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(pi * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = z;
    w[i] = 2.0 / ((1 - z * z) * dp * dp);
  }
}

SphereSites gauss_product_sites(int nt, int nl, std::vector<double>& weights) {
  require(nl >= 1, "longitudes nl", nl, "must be >= 1");
  std::vector<double> x, w;
  gauss_legendre(nt, x, w);
  SphereSites s;
  weights.clear();
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < nl; ++j) {
      s.theta.push_back(std::asin(x[i]));
      s.lambda.push_back(-pi + 2 * pi * (j + 0.5) / nl);
      weights.push_back(w[i] * 2 * pi / nl);
    }
  return s;
}

}  // namespace rbfib::surface
