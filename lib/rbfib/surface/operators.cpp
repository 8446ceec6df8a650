#include "rbfib/surface/operators.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/surface/harmonics.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace rbfib::surface {

namespace {
using Mat = Eigen::MatrixXd;

/// The six evaluation matrices of the harmonics of degree <= M at the sites (rows = sites).
void harmonic_matrices(const SphereSites& s, int M, Mat* out[6]) {
  const int np = sh_count(M);
  for (int q = 0; q < 6; ++q)
    if (out[q]) out[q]->resize(s.size(), np);
  std::vector<double> v[6];
  for (auto& x : v) x.resize(np);
  for (index_t i = 0; i < s.size(); ++i) {
    real_harmonics(M, s.lambda[i], s.theta[i], v[0].data(), v[1].data(), v[2].data(), v[3].data(),
                   v[4].data(), v[5].data());
    for (int q = 0; q < 6; ++q)
      if (out[q])
        for (int j = 0; j < np; ++j) (*out[q])(i, j) = v[q][j];
  }
}

DenseMatrix to_dense(const Mat& A) {
  DenseMatrix D(A.rows(), A.cols());
  for (index_t i = 0; i < A.rows(); ++i)
    for (index_t j = 0; j < A.cols(); ++j) D(i, j) = A(i, j);
  return D;
}

double rcond_of(const Eigen::PartialPivLU<Mat>& lu) { return lu.rcond(); }
}  // namespace

std::shared_ptr<const SurfaceOperators> sh_operators(const SphereSites& interp, const SphereSites& eval, int M) {
  require(M >= 0, "harmonic degree M", M, "must be >= 0");
  require(interp.size() == sh_count(M), "interpolation sites", interp.size(),
          "must number (M+1)^2 = " + to_text(sh_count(M)) + " for degree M = " + to_text(M));
  require_distinct(interp, "interpolation sites");
  Mat Y;
  Mat* one[6] = {&Y, nullptr, nullptr, nullptr, nullptr, nullptr};
  harmonic_matrices(interp, M, one);
  // The factorization, computed once.
  Eigen::PartialPivLU<Mat> lu(Y);
  auto ops = std::make_shared<SurfaceOperators>();
  ops->condition_estimate = rcond_of(lu);
  if (!(ops->condition_estimate > 1e-14))
    throw NumericalError("spherical-harmonic interpolation matrix Y (eq. 86, degree " + to_text(M) +
                         "): reciprocal condition " + to_text(ops->condition_estimate) +
                         " <= 1e-14, the sites do not determine an interpolant");
  Mat E[6];
  Mat* all[6] = {&E[0], &E[1], &E[2], &E[3], &E[4], &E[5]};
  harmonic_matrices(eval, M, all);
  // Factored: P Y = L U and the harmonics E_q at the sample sites.
  ops->lu = to_dense(lu.matrixLU());
  {
    // Eigen's P maps row i of Y to row indices[i] of P Y.
    const auto& idx = lu.permutationP().indices();
    ops->perm.assign(static_cast<std::size_t>(idx.size()), 0);
    for (index_t i = 0; i < idx.size(); ++i) ops->perm[idx[i]] = i;
  }
  DenseMatrix* dst[6] = {&ops->id, &ops->d_l, &ops->d_t, &ops->d_ll, &ops->d_lt, &ops->d_tt};
  for (int q = 0; q < 6; ++q) *dst[q] = to_dense(E[q]);
  ops->description = "spherical harmonics, degree " + to_text(M) + ", m = " + to_text(interp.size()) +
                     " interpolation sites, n = " + to_text(eval.size()) + " evaluation sites";
  return ops;
}

void solve_coefficients(const SurfaceOperators& ops, const double* x, index_t stride, double* c) {
  // c = U^{-1} L^{-1} P x, columnwise for `stride` interleaved right-hand sides.
  const index_t m = ops.lu.rows;
  for (index_t s = 0; s < stride; ++s) {
    for (index_t i = 0; i < m; ++i) {
      double v = x[ops.perm[i] * stride + s];
      for (index_t k = 0; k < i; ++k) v -= ops.lu(i, k) * c[k * stride + s];
      c[i * stride + s] = v;
    }
    for (index_t i = m - 1; i >= 0; --i) {
      double v = c[i * stride + s];
      for (index_t k = i + 1; k < m; ++k) v -= ops.lu(i, k) * c[k * stride + s];
      c[i * stride + s] = v / ops.lu(i, i);
    }
  }
}

void apply_operators(const SurfaceOperators& ops, const std::vector<double>& X, std::vector<double> out[6]) {
  const DenseMatrix* M[6] = {&ops.id, &ops.d_l, &ops.d_t, &ops.d_ll, &ops.d_lt, &ops.d_tt};
  if (ops.factored()) {
    require(static_cast<index_t>(X.size()) == 3 * ops.n_data(), "points.size()", X.size(),
            "must be 3 x data sites (" + to_text(ops.n_data()) + ")");
    std::vector<double> c(X.size());
    solve_coefficients(ops, X.data(), 3, c.data());
    for (int q = 0; q < 6; ++q) apply_to_points(*M[q], c, out[q]);
  } else {
    for (int q = 0; q < 6; ++q) apply_to_points(*M[q], X, out[q]);
  }
}

std::vector<double> transpose_identity(const SurfaceOperators& ops, const std::vector<double>& F) {
  require(static_cast<index_t>(F.size()) == 3 * ops.n_sample(), "F.size()", F.size(),
          "must be 3 x sample sites (" + to_text(ops.n_sample()) + ")");
  std::vector<double> g(static_cast<std::size_t>(3 * ops.id.cols), 0.0);
  for (index_t i = 0; i < ops.id.rows; ++i)
    for (index_t j = 0; j < ops.id.cols; ++j)
      for (int d = 0; d < 3; ++d) g[3 * j + d] += ops.id(i, j) * F[3 * i + d];
  if (!ops.factored()) return g;
  // I = E Y^{-1}: I^T F = Y^{-T} (E^T F), with Y^T = U^T L^T P.
  const index_t m = ops.lu.rows;
  std::vector<double> h(g.size(), 0.0), t(g.size(), 0.0);
  for (int d = 0; d < 3; ++d) {
    for (index_t i = 0; i < m; ++i) {  // U^T y = g
      double v = g[3 * i + d];
      for (index_t k = 0; k < i; ++k) v -= ops.lu(k, i) * t[3 * k + d];
      t[3 * i + d] = v / ops.lu(i, i);
    }
    for (index_t i = m - 1; i >= 0; --i) {  // L^T z = y
      double v = t[3 * i + d];
      for (index_t k = i + 1; k < m; ++k) v -= ops.lu(k, i) * t[3 * k + d];
      t[3 * i + d] = v;
    }
    for (index_t i = 0; i < m; ++i) h[3 * ops.perm[i] + d] = t[3 * i + d];  // P^T z
  }
  return h;
}

std::vector<double> sh_coefficients(const SphereSites& interp, int M, const std::vector<double>& values) {
  require(interp.size() == sh_count(M), "interpolation sites", interp.size(),
          "must number (M+1)^2 = " + to_text(sh_count(M)));
  require(static_cast<index_t>(values.size()) == interp.size(), "values.size()", values.size(),
          "must equal the number of sites");
  Mat Y;
  Mat* one[6] = {&Y, nullptr, nullptr, nullptr, nullptr, nullptr};
  harmonic_matrices(interp, M, one);
  Eigen::PartialPivLU<Mat> lu(Y);
  if (!(lu.rcond() > 1e-14))
    throw NumericalError("spherical-harmonic interpolation matrix Y (eq. 86): reciprocal condition " +
                         to_text(lu.rcond()) + " <= 1e-14");
  Eigen::VectorXd c = lu.solve(Eigen::Map<const Eigen::VectorXd>(values.data(), values.size()));
  return std::vector<double>(c.data(), c.data() + c.size());
}

std::shared_ptr<const SurfaceOperators> rbf_operators(const SphereSites& data, const SphereSites& sample,
                                                      PhsBasis basis) {
  require(basis.power >= 1 && basis.power % 2 == 1, "PHS power", basis.power, "must be odd and >= 1");
  require(basis.sh_degree >= -1, "augmenting harmonic degree", basis.sh_degree, "must be >= -1");
  require_distinct(data, "RBF data sites");
  const index_t nd = data.size();
  const int np = basis.sh_degree >= 0 ? sh_count(basis.sh_degree) : 0;
  require(nd > np, "RBF data sites", nd, "must outnumber the " + to_text(np) + " augmenting harmonics");
  const int p = basis.power;
  const std::vector<double> xd = unit_sphere_points(data);

  // phi as a function of t = chi . chi_j: f(t) = (2 - 2t)^{p/2} (eq. 2.18), and f', f''.
  auto f = [p](double t, double& f0, double& f1, double& f2) {
    const double u = std::max(2.0 - 2.0 * t, 0.0);  // r^2
    f0 = std::pow(u, 0.5 * p);
    f1 = -double(p) * std::pow(u, 0.5 * (p - 2));
    f2 = p >= 3 && u > 0 ? double(p) * (p - 2) * std::pow(u, 0.5 * (p - 4)) : 0.0;
  };

  // Block matrix of eq. (2.17).
  Mat A = Mat::Zero(nd + np, nd + np);
  for (index_t i = 0; i < nd; ++i)
    for (index_t j = 0; j < nd; ++j) {
      const double t = xd[3 * i] * xd[3 * j] + xd[3 * i + 1] * xd[3 * j + 1] + xd[3 * i + 2] * xd[3 * j + 2];
      double f0, f1, f2;
      f(t, f0, f1, f2);
      A(i, j) = f0;
    }
  if (np > 0) {
    Mat P;
    Mat* one[6] = {&P, nullptr, nullptr, nullptr, nullptr, nullptr};
    harmonic_matrices(data, basis.sh_degree, one);
    A.block(0, nd, nd, np) = P;
    A.block(nd, 0, np, nd) = P.transpose();
  }
  Eigen::PartialPivLU<Mat> lu(A);
  auto ops = std::make_shared<SurfaceOperators>();
  ops->condition_estimate = lu.rcond();
  if (!(ops->condition_estimate > 1e-18))
    throw NumericalError("RBF interpolation matrix (eq. 2.17, phi = r^" + to_text(p) + ", n_d = " + to_text(nd) +
                         "): reciprocal condition " + to_text(ops->condition_estimate) + " <= 1e-18, singular");

  // [L Phi, L P] at the sample sites, for the six operators.
  const index_t ns = sample.size();
  Mat B[6];
  for (auto& b : B) b.resize(ns, nd + np);
  Mat PE[6];
  if (np > 0) {
    Mat* all[6] = {&PE[0], &PE[1], &PE[2], &PE[3], &PE[4], &PE[5]};
    harmonic_matrices(sample, basis.sh_degree, all);
  }
  for (index_t i = 0; i < ns; ++i) {
    const double la = sample.lambda[i], th = sample.theta[i];
    const double cl = std::cos(la), sl = std::sin(la), ct = std::cos(th), st = std::sin(th);
    const double x[3] = {cl * ct, sl * ct, st};
    const double xl[3] = {-sl * ct, cl * ct, 0};
    const double xt[3] = {-cl * st, -sl * st, ct};
    const double xll[3] = {-cl * ct, -sl * ct, 0};
    const double xlt[3] = {sl * st, -cl * st, 0};
    const double xtt[3] = {-cl * ct, -sl * ct, -st};
    for (index_t j = 0; j < nd; ++j) {
      const double* y = &xd[3 * j];
      auto dot = [y](const double* a) { return a[0] * y[0] + a[1] * y[1] + a[2] * y[2]; };
      const double t = dot(x), tl = dot(xl), tt = dot(xt), tll = dot(xll), tlt = dot(xlt), ttt = dot(xtt);
      double f0, f1, f2;
      f(t, f0, f1, f2);
      B[0](i, j) = f0;
      B[1](i, j) = f1 * tl;
      B[2](i, j) = f1 * tt;
      B[3](i, j) = f2 * tl * tl + f1 * tll;
      B[4](i, j) = f2 * tl * tt + f1 * tlt;
      B[5](i, j) = f2 * tt * tt + f1 * ttt;
    }
    if (np > 0)
      for (int q = 0; q < 6; ++q) B[q].block(i, nd, 1, np) = PE[q].row(i);
  }
  DenseMatrix* dst[6] = {&ops->id, &ops->d_l, &ops->d_t, &ops->d_ll, &ops->d_lt, &ops->d_tt};
  for (int q = 0; q < 6; ++q) {
    // [L *] = B A^{-1}  <=>  A [L *]^T = B^T  (A is symmetric)
    Mat LT = lu.solve(B[q].transpose());
    *dst[q] = to_dense(LT.topRows(nd).transpose());
  }
  ops->description = "PHS r^" + to_text(p) + " + harmonics of degree <= " + to_text(basis.sh_degree) +
                     ", n_d = " + to_text(nd) + " data sites, n_s = " + to_text(ns) + " sample sites";
  return ops;
}

}  // namespace rbfib::surface
