#include "rbfib/surface/point_sets.hpp"
#include "rbfib/core/constants.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/surface/harmonics.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <sstream>

namespace rbfib::surface {

namespace {
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

namespace {

/// log|det Y| at the sites x / |x| (3 per site) and its gradient with respect to the
/// unnormalized x: for site i, (d/dx_i) = (g_lambda / cos theta e_lambda + g_theta e_theta) / |x_i|
/// with g = d log|det Y| / d(angle) = sum_k dY_ik/d(angle) (Y^{-1})_ki.
class LogDet {
 public:
  explicit LogDet(int M) : M_(M), m_(sh_count(M)), Y_(m_, m_), Yl_(m_, m_), Yt_(m_, m_) {}

  double operator()(const Eigen::VectorXd& x, Eigen::VectorXd& grad) {
    std::vector<double> lambda(m_), theta(m_), r(m_);
#pragma omp parallel for
    for (int i = 0; i < m_; ++i) {
      r[i] = x.segment<3>(3 * i).norm();
      theta[i] = std::asin(std::clamp(x[3 * i + 2] / r[i], -1.0, 1.0));
      lambda[i] = std::atan2(x[3 * i + 1], x[3 * i]);
      std::vector<double> y(m_), yl(m_), yt(m_);
      real_harmonics(M_, lambda[i], theta[i], y.data(), yl.data(), yt.data());
      for (int j = 0; j < m_; ++j) {
        Y_(i, j) = y[j];
        Yl_(i, j) = yl[j];
        Yt_(i, j) = yt[j];
      }
    }
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(Y_);
    double value = 0;
    for (int i = 0; i < m_; ++i) value += std::log(std::abs(lu.matrixLU()(i, i)));
    grad.resize(3 * m_);
    if (!std::isfinite(value)) return value;
    const Eigen::MatrixXd Yinv = lu.inverse();
#pragma omp parallel for
    for (int i = 0; i < m_; ++i) {
      const double gl = Yl_.row(i).dot(Yinv.col(i)), gt = Yt_.row(i).dot(Yinv.col(i));
      const double la = lambda[i], th = theta[i];
      const double c = std::max(std::cos(th), 1e-12);
      const double el[3] = {-std::sin(la), std::cos(la), 0.0};
      const double et[3] = {-std::cos(la) * std::sin(th), -std::sin(la) * std::sin(th), std::cos(th)};
      for (int d = 0; d < 3; ++d) grad[3 * i + d] = (gl / c * el[d] + gt * et[d]) / r[i];
    }
    return value;
  }

 private:
  int M_, m_;
  Eigen::MatrixXd Y_, Yl_, Yt_;
};

SphereSites sites_from_points(const Eigen::VectorXd& x) {
  SphereSites s;
  const index_t m = x.size() / 3;
  s.lambda.resize(m);
  s.theta.resize(m);
  for (index_t i = 0; i < m; ++i) {
    const double r = x.segment<3>(3 * i).norm();
    s.theta[i] = std::asin(std::clamp(x[3 * i + 2] / r, -1.0, 1.0));
    s.lambda[i] = std::atan2(x[3 * i + 1], x[3 * i]);
  }
  return s;
}

}  // namespace

MaxDetResult max_determinant_points(int M, int max_iterations, const std::function<void(int, double)>& progress,
                                    int report_every) {
  require(M >= 0, "harmonic degree M", M, "must be >= 0");
  require(max_iterations >= 0, "max_iterations", max_iterations, "must be >= 0");
  const int m = sh_count(M);
  // Small dense matrices: threading them only costs (and contends with the caller's threads).
  const int threads = Eigen::nbThreads();
  if (m < 1000) Eigen::setNbThreads(1);
  const std::vector<double> start = unit_sphere_points(bauer_spiral(m));
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(start.data(), 3 * m);
  LogDet log_det(M);
  // Minimize f = -log|det Y| by L-BFGS (memory 10) with a backtracking line search: Armijo once
  // curvature pairs exist; plain decrease on the first step, where the spiral's nearly singular Y
  // makes the gradient's predicted decrease meaningless. A step moves no site by more than 0.3 h.
  Eigen::VectorXd g;
  double f = -log_det(x, g);
  g = -g;
  MaxDetResult r;
  r.log_det_start = -f;
  require(std::isfinite(f), "Bauer spiral start for M", M, "gives a singular interpolation matrix");
  const double h = std::sqrt(4 * pi / m);  // typical spacing
  std::deque<Eigen::VectorXd> S, G;
  int small_gains = 0, it = 0;
  for (; it < max_iterations && small_gains < 5; ++it) {
    Eigen::VectorXd q = g;
    std::vector<double> alpha(S.size());
    for (int k = int(S.size()) - 1; k >= 0; --k) {
      alpha[k] = S[k].dot(q) / G[k].dot(S[k]);
      q -= alpha[k] * G[k];
    }
    const double gamma =
        S.empty() ? 0.05 * h / g.cwiseAbs().maxCoeff() : S.back().dot(G.back()) / G.back().dot(G.back());
    Eigen::VectorXd d = -gamma * q;
    for (std::size_t k = 0; k < S.size(); ++k) d -= S[k] * (alpha[k] + G[k].dot(d) / G[k].dot(S[k]));
    if (!(d.dot(g) < 0)) {  // not a descent direction: restart from steepest descent
      S.clear();
      G.clear();
      d = -0.05 * h / g.cwiseAbs().maxCoeff() * g;
    }
    double dmax = 0;
    for (int i = 0; i < m; ++i) dmax = std::max(dmax, d.segment<3>(3 * i).norm());
    double t = std::min(1.0, 0.3 * h / dmax);
    Eigen::VectorXd xn, gn;
    double fn = 0;
    bool accepted = false;
    for (int ls = 0; ls < 40 && !accepted; ++ls, t *= 0.5) {
      xn = x + t * d;
      for (int i = 0; i < m; ++i) xn.segment<3>(3 * i).normalize();
      fn = -log_det(xn, gn);
      accepted = std::isfinite(fn) && fn < f && (S.empty() || fn <= f + 1e-4 * t * g.dot(d));
    }
    if (!accepted) break;  // no decrease along the direction: a local maximum to rounding
    gn = -gn;
    const Eigen::VectorXd s = xn - x, y = gn - g;
    if (s.dot(y) > 1e-12 * s.norm() * y.norm()) {
      S.push_back(s);
      G.push_back(y);
      if (S.size() > 10) {
        S.pop_front();
        G.pop_front();
      }
    }
    small_gains = (f - fn) < 1e-10 * std::abs(f) ? small_gains + 1 : 0;
    x = xn;
    g = gn;
    f = fn;
    if (progress && report_every > 0 && it % report_every == 0) progress(it, -f);
  }
  r.sites = sites_from_points(x);
  r.log_det = -f;
  r.gradient_norm = g.norm();
  r.iterations = it;
  r.converged = small_gains >= 5;
  Eigen::setNbThreads(threads);
  return r;
}

SphereSites read_sphere_sites(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("site file", path, "cannot be opened");
  SphereSites s;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    double p[3];
    std::string rest;
    if (!(fields >> p[0] >> p[1] >> p[2]) || (fields >> rest))
      throw InputError(path + " line " + to_text(number), line, "must hold three numbers x y z");
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (!(std::abs(n - 1) <= 1e-9))
      throw InputError(path + " line " + to_text(number), line, "is not a unit vector (length " + to_text(n) + ")");
    s.theta.push_back(std::asin(std::clamp(p[2] / n, -1.0, 1.0)));
    s.lambda.push_back(std::atan2(p[1], p[0]));
  }
  if (s.size() == 0) throw InputError("site file", path, "holds no sites");
  require_distinct(s, path.c_str());
  return s;
}

void write_sphere_sites(const std::string& path, const SphereSites& sites, const std::vector<std::string>& header) {
  std::ofstream out(path);
  if (!out) throw InputError("site file", path, "cannot be written");
  for (const std::string& h : header) out << "# " << h << '\n';
  char buf[96];
  for (index_t i = 0; i < sites.size(); ++i) {
    double p[3];
    unit_sphere_point(sites.lambda[i], sites.theta[i], p);
    std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g\n", p[0], p[1], p[2]);
    out << buf;
  }
  if (!out) throw InputError("site file", path, "write failed");
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
