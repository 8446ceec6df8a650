#include "rbfib/surface/quadrature.hpp"
#include "rbfib/core/constants.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/linalg/dense.hpp"
#include "rbfib/surface/harmonics.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace rbfib::surface {

namespace {
}

RbfWeights rbf_sphere_weights(const SphereSites& sites, int power) {
  require(power >= 1 && power % 2 == 1, "PHS power", power, "must be odd and >= 1");
  require_distinct(sites, "quadrature sites");
  const index_t n = sites.size();
  const std::vector<double> x = unit_sphere_points(sites);
  // The block matrix, column-major, factored on the device (LAPACK's dgetrf: the O(n^3) step,
  // seconds for n = 10^4 sample sites), with the 1-norm condition estimate of dgecon.
  const index_t m = n + 1;
  std::vector<double> A(static_cast<std::size_t>(m * m));
  double norm1 = double(n);  // the last column: n ones
#pragma omp parallel for schedule(static) reduction(max : norm1)
  for (index_t j = 0; j < n; ++j) {
    double column = 1.0;
    for (index_t i = 0; i < n; ++i) {
      const double t = x[3 * i] * x[3 * j] + x[3 * i + 1] * x[3 * j + 1] + x[3 * i + 2] * x[3 * j + 2];
      A[i + j * m] = std::pow(std::max(2.0 - 2.0 * t, 0.0), 0.5 * power);
      column += std::abs(A[i + j * m]);
    }
    A[n + j * m] = A[j + n * m] = 1.0;
    norm1 = std::max(norm1, column);
  }
  A[n + n * m] = 0.0;
  const std::string what = "RBF quadrature system (eq. 2.22, phi = r^" + to_text(power) + ", n = " + to_text(n) + ")";
  const linalg::LuFactors lu = linalg::lu_factor(linalg::DeviceMatrix::from_host(m, m, A.data()), what.c_str());
  RbfWeights r;
  r.rcond = linalg::lu_rcond(lu, norm1);
  if (!(r.rcond > std::numeric_limits<double>::epsilon() * 1e-3))
    throw NumericalError(Cause::solver, what + ": reciprocal condition " + to_text(r.rcond) + ", singular");
  std::vector<double> b(static_cast<std::size_t>(m), 0.0);
  b[n] = 4 * pi;
  linalg::DeviceMatrix s = linalg::DeviceMatrix::from_host(m, 1, b.data());
  linalg::lu_solve(lu, linalg::Op::none, s.view());
  const std::vector<double> w = s.to_host();
  r.w.assign(w.begin(), w.begin() + n);
  r.I_phi = w[n];
  for (double v : r.w)
    if (!std::isfinite(v))
      throw NumericalError(Cause::non_finite, "RBF quadrature weights (eq. 2.22): non-finite weight");
  return r;
}

NnlsWeights nnls_sh_weights(const SphereSites& sites, int N) {
  require(N >= 0, "quadrature degree N", N, "must be >= 0");
  const index_t n = sites.size();
  const int k = sh_count(N);
  Eigen::MatrixXd A(k, n);  // A = Y^T
  std::vector<double> y(k);
  for (index_t i = 0; i < n; ++i) {
    real_harmonics(N, sites.lambda[i], sites.theta[i], y.data());
    for (int j = 0; j < k; ++j) A(j, i) = y[j];
  }
  Eigen::VectorXd b = Eigen::VectorXd::Zero(k);
  b(0) = std::sqrt(4 * pi);
  NnlsWeights r;
  if (n == k) {
    // Square system (n = (N+1)^2, the paper's choice): if its exact solution is nonnegative it is
    // the NNLS solution (residual 0), found by one LU solve instead of O(n) active-set steps.
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
    if (lu.rcond() > 1e3 * std::numeric_limits<double>::epsilon()) {
      const Eigen::VectorXd x = lu.solve(b);
      if (x.allFinite() && x.minCoeff() >= 0) {
        r.residual = (A * x - b).norm();
        r.w.assign(x.data(), x.data() + n);
        return r;
      }
    }
  }
  // Lawson-Hanson: passive set P, x >= 0 minimizing ||A x - b||.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(n, false);
  const double tol = 1e-12 * A.norm() * b.norm();
  int outer = 0;
  for (; outer < 3 * n + 10; ++outer) {
    Eigen::VectorXd wgrad = A.transpose() * (b - A * x);
    index_t best = -1;
    double wmax = tol;
    for (index_t i = 0; i < n; ++i)
      if (!passive[i] && wgrad(i) > wmax) { wmax = wgrad(i); best = i; }
    if (best < 0) break;
    passive[best] = true;
    for (int inner = 0; inner < 3 * n + 10; ++inner) {
      std::vector<index_t> idx;
      for (index_t i = 0; i < n; ++i)
        if (passive[i]) idx.push_back(i);
      Eigen::MatrixXd Ap(k, idx.size());
      for (std::size_t c = 0; c < idx.size(); ++c) Ap.col(c) = A.col(idx[c]);
      Eigen::VectorXd z = Ap.colPivHouseholderQr().solve(b);
      bool feasible = true;
      for (std::size_t c = 0; c < idx.size(); ++c)
        if (z(c) <= 0) feasible = false;
      if (feasible) {
        x.setZero();
        for (std::size_t c = 0; c < idx.size(); ++c) x(idx[c]) = z(c);
        break;
      }
      double alpha = 1.0;
      for (std::size_t c = 0; c < idx.size(); ++c)
        if (z(c) <= 0) alpha = std::min(alpha, x(idx[c]) / (x(idx[c]) - z(c)));
      for (std::size_t c = 0; c < idx.size(); ++c) {
        x(idx[c]) += alpha * (z(c) - x(idx[c]));
        if (x(idx[c]) <= 1e-300) { x(idx[c]) = 0; passive[idx[c]] = false; }
      }
    }
  }
  r.iterations = outer;
  r.residual = (A * x - b).norm();
  r.w.assign(x.data(), x.data() + n);
  return r;
}

std::vector<double> reference_shape_weights(const SphereSites& sites, const std::vector<double>& w_sphere,
                                            const std::vector<double>& det_g0_shape) {
  require(static_cast<index_t>(w_sphere.size()) == sites.size(), "w_sphere.size()", w_sphere.size(),
          "must equal the number of sites");
  require(static_cast<index_t>(det_g0_shape.size()) == sites.size(), "det_g0_shape.size()", det_g0_shape.size(),
          "must equal the number of sites");
  std::vector<double> w(w_sphere.size());
  for (index_t i = 0; i < sites.size(); ++i) {
    const double c = std::cos(sites.theta[i]);
    require(c * c > 1e-28, "site " + to_text(i) + " latitude", sites.theta[i],
            "is a pole, where det G0 of the sphere vanishes (eq. 51 undefined)");
    require(det_g0_shape[i] >= 0, "det G0 of the reference shape at site " + to_text(i), det_g0_shape[i],
            "must be >= 0");
    w[i] = std::sqrt(det_g0_shape[i] / (c * c)) * w_sphere[i];
  }
  return w;
}

double integrate(const std::vector<double>& w, const std::vector<double>& f) {
  require(w.size() == f.size(), "f.size()", f.size(), "must equal the number of weights " + to_text(w.size()));
  double s = 0;
  for (std::size_t i = 0; i < w.size(); ++i) s += w[i] * f[i];
  return s;
}

}  // namespace rbfib::surface
