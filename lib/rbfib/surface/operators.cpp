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

linalg::DeviceMatrix upload(const Mat& A) { return linalg::DeviceMatrix::from_host(A.rows(), A.cols(), A.data()); }

/// Uploads the six operators L[0..5] (n_s x k each) as value = L[0] and the stacked derivatives.
void upload_stacked(const Mat L[6], SurfaceOperators& ops) {
  const index_t ns = L[0].rows();
  Mat D(derivative_count * ns, L[0].cols());
  for (int q = 0; q < derivative_count; ++q) D.middleRows(q * ns, ns) = L[q + 1];
  ops.value = upload(L[0]);
  ops.derivatives = upload(D);
}

/// Eigen's factors (computed on the host for its condition estimate) in LAPACK form on the device.
linalg::LuFactors device_factors(const Eigen::PartialPivLU<Mat>& lu) {
  // Eigen's P maps row i of A to row indices[i] of P A.
  const auto& idx = lu.permutationP().indices();
  std::vector<index_t> perm(static_cast<std::size_t>(idx.size()));
  for (index_t i = 0; i < idx.size(); ++i) perm[idx[i]] = i;
  const Mat& packed = lu.matrixLU();
  return linalg::lu_from_host(packed.rows(), packed.data(), perm);
}
}  // namespace

std::shared_ptr<const SurfaceOperators> sh_operators(const SphereSites& interp, const SphereSites& eval, int M) {
  require(M >= 0, "harmonic degree M", M, "must be >= 0");
  require(interp.size() == sh_count(M), "interpolation sites", interp.size(),
          "must number (M+1)^2 = " + to_text(sh_count(M)) + " for degree M = " + to_text(M));
  require_distinct(interp, "interpolation sites");
  Mat Y;
  Mat* one[6] = {&Y, nullptr, nullptr, nullptr, nullptr, nullptr};
  harmonic_matrices(interp, M, one);
  // The factorization, computed once (Eigen, for its condition estimate), kept in LAPACK form.
  Eigen::PartialPivLU<Mat> lu(Y);
  auto ops = std::make_shared<SurfaceOperators>();
  ops->condition_estimate = lu.rcond();
  if (!(ops->condition_estimate > 1e-14))
    throw NumericalError(Cause::solver, "spherical-harmonic interpolation matrix Y (eq. 86, degree " + to_text(M) +
                         "): reciprocal condition " + to_text(ops->condition_estimate) +
                         " <= 1e-14, the sites do not determine an interpolant");
  ops->lu = device_factors(lu);
  Mat E[6];
  Mat* all[6] = {&E[0], &E[1], &E[2], &E[3], &E[4], &E[5]};
  harmonic_matrices(eval, M, all);
  upload_stacked(E, *ops);
  ops->data_sites = interp.size();
  ops->reproduces_constants = true;
  ops->description = "spherical harmonics, degree " + to_text(M) + ", m = " + to_text(interp.size()) +
                     " interpolation sites, n = " + to_text(eval.size()) + " evaluation sites";
  return ops;
}

namespace {
/// The columns the operators act on: F itself, or the coefficients Y^{-1} F of a factored set.
linalg::ConstMatrixView operand(const SurfaceOperators& ops, linalg::ConstMatrixView F, OperatorWorkspace& work) {
  require(F.rows == ops.n_data(), "surface operators: rows of the data-site fields", F.rows,
          "must equal the number of data sites " + to_text(ops.n_data()));
  if (!ops.factored()) return F;
  work.coefficients.resize(F.rows, F.cols);  // c = Y^{-1} F by the stored LU factors
  linalg::copy(F, work.coefficients.view());
  linalg::lu_solve(ops.lu, linalg::Op::none, work.coefficients.view());
  return work.coefficients.view();
}

/// Single precision: work.in32 = the float operand of F - s (s_j = F(0, j), kept in work.shift;
/// solved by the LU factors first for a factored set).
void single_operand(const SurfaceOperators& ops, linalg::ConstMatrixView F, OperatorWorkspace& work) {
  require(F.rows == ops.n_data(), "surface operators: rows of the data-site fields", F.rows,
          "must equal the number of data sites " + to_text(ops.n_data()));
  const index_t rows = F.rows, cols = F.cols, ld = F.ld;
  work.shift.resize(static_cast<std::size_t>(cols));
  work.coefficients.resize(rows, cols);
  work.in32.resize(rows, cols);
  if (rows == 0 || cols == 0) return;
  const double* f = F.data;
  double* s = ptr(work.shift);
  double* c = ptr(work.coefficients.storage());
  for_each_index(cols, [=] RBFIB_HD (index_t j) { s[j] = f[j * ld]; });
  for_each_index(rows * cols, [=] RBFIB_HD (index_t k) {
    const index_t i = k % rows, j = k / rows;
    c[k] = f[i + j * ld] - s[j];
  });
  if (ops.factored()) linalg::lu_solve(ops.lu, linalg::Op::none, work.coefficients.view());
  linalg::narrow(work.coefficients.view(), work.in32.view());
}

/// Single precision, after single_operand: the operator rows [row0, row0 + rows) on the first
/// `cols` columns, in float; value = V in + s on the first value.cols of them (when value.rows > 0)
/// and derivative q into rows q stride + i of derivatives (when derivatives.rows > 0).
void single_products(const SurfaceOperators& ops, index_t row0, index_t rows, index_t cols, linalg::MatrixView value,
                     linalg::MatrixView derivatives, index_t stride, OperatorWorkspace& work) {
  using linalg::Op;
  const index_t ns = ops.n_sample(), k = ops.value32.cols();
  const linalg::ConstFloatView in = work.in32.view().block(0, 0, k, cols);
  if (rows == 0 || cols == 0) return;
  if (value.rows > 0) {
    const index_t vcols = value.cols;
    work.out32.resize(rows, vcols);
    linalg::gemm(Op::none, Op::none, 1.0f, ops.value32.view().block(row0, 0, rows, k), in.block(0, 0, k, vcols), 0.0f,
                 work.out32.view());
    const float* o = ptr(work.out32.storage());
    const double* s = ptr(work.shift);
    double* v = value.data;
    const index_t ldv = value.ld;
    for_each_index(rows * vcols, [=] RBFIB_HD (index_t e) {
      const index_t i = e % rows, j = e / rows;
      v[i + j * ldv] = double(o[e]) + s[j];
    });
  }
  if (derivatives.rows > 0) {
    work.out32.resize(derivative_count * rows, cols);
    linalg::gemm_strided_batched(Op::none, Op::none, 1.0f, ops.derivatives32.view().block(row0, 0, rows, k), ns, in, 0, 0.0f,
                                 work.out32.view().block(0, 0, rows, cols), rows, derivative_count);
    for (int q = 0; q < derivative_count; ++q)
      linalg::widen(linalg::ConstFloatView(work.out32.view()).block(q * rows, 0, rows, cols),
                    derivatives.block(q * stride, 0, rows, cols));
  }
}
}  // namespace

std::shared_ptr<const SurfaceOperators> in_single_precision(const SurfaceOperators& ops) {
  require(ops.reproduces_constants, "single-precision surface operators: interpolant", ops.description,
          "must contain the constant (spherical harmonics, or an RBF set with sh_degree >= 0)");
  auto out = std::make_shared<SurfaceOperators>(ops);
  out->value32.resize(ops.value.rows(), ops.value.cols());
  out->derivatives32.resize(ops.derivatives.rows(), ops.derivatives.cols());
  linalg::narrow(ops.value.view(), out->value32.view());
  linalg::narrow(ops.derivatives.view(), out->derivatives32.view());
  out->description = ops.description + ", products in single precision";
  return out;
}

void apply_operators(const SurfaceOperators& ops, linalg::ConstMatrixView F, linalg::MatrixView value,
                     linalg::MatrixView derivatives, OperatorWorkspace& work) {
  if (ops.single_precision()) {
    single_operand(ops, F, work);
    single_products(ops, 0, ops.n_sample(), F.cols, value, derivatives, ops.n_sample(), work);
    return;
  }
  const linalg::ConstMatrixView in = operand(ops, F, work);
  if (value.rows > 0) linalg::gemm(linalg::Op::none, linalg::Op::none, 1.0, ops.value.view(), in, 0.0, value);
  if (derivatives.rows > 0)
    linalg::gemm(linalg::Op::none, linalg::Op::none, 1.0, ops.derivatives.view(), in, 0.0, derivatives);
}

void apply_operators_rows(const SurfaceOperators& ops, linalg::ConstMatrixView F, index_t row0, index_t rows,
                          linalg::MatrixView value, linalg::MatrixView derivatives, OperatorWorkspace& work) {
  const index_t ns = ops.n_sample();
  require(row0 >= 0 && rows >= 0 && row0 + rows <= ns, "surface operators: sample-site range",
          "[" + to_text(row0) + ", " + to_text(row0 + rows) + ")", "must lie in [0, " + to_text(ns) + ")");
  require(derivatives.rows == 0 || derivatives.rows == derivative_count * rows, "surface operators: derivative rows",
          derivatives.rows, "must be 5 x " + to_text(rows));
  require(value.rows == 0 || value.cols <= F.cols, "surface operators: value columns", value.cols,
          "must be at most the fields' " + to_text(F.cols));
  if (ops.single_precision()) {
    single_operand(ops, F, work);
    single_products(ops, row0, rows, F.cols, value, derivatives, rows, work);
    return;
  }
  const linalg::ConstMatrixView in = operand(ops, F, work);
  const linalg::ConstMatrixView V = ops.value.view(), D = ops.derivatives.view();
  if (value.rows > 0)
    linalg::gemm(linalg::Op::none, linalg::Op::none, 1.0, V.block(row0, 0, rows, V.cols), in.block(0, 0, in.rows, value.cols), 0.0,
                 value);
  if (derivatives.rows > 0)  // derivative q: operator rows q ns + row0 .. , output rows q rows ..
    linalg::gemm_strided_batched(linalg::Op::none, linalg::Op::none, 1.0, D.block(row0, 0, rows, D.cols), ns, in, 0, 0.0,
                                 derivatives.block(0, 0, rows, derivatives.cols), rows, derivative_count);
}

std::shared_ptr<const SurfaceOperators> select_sample_sites(const SurfaceOperators& ops, index_t row0, index_t rows) {
  const index_t ns = ops.n_sample(), k = ops.value.cols();
  require(row0 >= 0 && rows > 0 && row0 + rows <= ns, "surface operators: selected sample sites",
          "[" + to_text(row0) + ", " + to_text(row0 + rows) + ")", "must lie in [0, " + to_text(ns) + ")");
  auto out = std::make_shared<SurfaceOperators>();
  out->value.resize(rows, k);
  out->derivatives.resize(derivative_count * rows, k);
  linalg::copy(ops.value.view().block(row0, 0, rows, k), out->value.view());
  for (int q = 0; q < derivative_count; ++q)
    linalg::copy(ops.derivatives.view().block(q * ns + row0, 0, rows, k), out->derivatives.view().block(q * rows, 0, rows, k));
  out->lu = ops.lu;
  out->data_sites = ops.data_sites;
  out->reproduces_constants = ops.reproduces_constants;
  out->condition_estimate = ops.condition_estimate;
  out->description = ops.description + " (sample sites " + to_text(row0) + " .. " + to_text(row0 + rows - 1) + ")";
  return out;
}

void apply_value_transpose(const SurfaceOperators& ops, linalg::ConstMatrixView F, linalg::MatrixView G) {
  // I^T F; for the factored form I = E Y^{-1}, so I^T F = Y^{-T} (E^T F).
  linalg::gemm(linalg::Op::transpose, linalg::Op::none, 1.0, ops.value.view(), F, 0.0, G);
  if (ops.factored()) linalg::lu_solve(ops.lu, linalg::Op::transpose, G);
}

std::vector<double> transpose_identity(const SurfaceOperators& ops, const std::vector<double>& F) {
  const index_t ns = ops.n_sample(), nd = ops.n_data();
  require(static_cast<index_t>(F.size()) == 3 * ns, "F.size()", F.size(),
          "must be 3 x sample sites (" + to_text(ns) + ")");
  const linalg::DeviceMatrix Fd = linalg::DeviceMatrix::from_host(ns, 3, F.data());
  linalg::DeviceMatrix G(nd, 3);
  apply_value_transpose(ops, Fd.view(), G.view());
  return G.to_host();
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
    throw NumericalError(Cause::solver, "spherical-harmonic interpolation matrix Y (eq. 86): reciprocal condition " +
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
    if (p >= 5) {  // one power: r^{p-4}, then r^{p-2} and r^p by products
      const double a = std::pow(u, 0.5 * (p - 4));
      f2 = double(p) * (p - 2) * a;
      f1 = -double(p) * a * u;
      f0 = a * u * u;
      return;
    }
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
    throw NumericalError(Cause::solver, "RBF interpolation matrix (eq. 2.17, phi = r^" + to_text(p) + ", n_d = " + to_text(nd) +
                         "): reciprocal condition " + to_text(ops->condition_estimate) + " <= 1e-18, singular");

  // [L Phi, L P] at the sample sites for the six operators, as the columns of one right-hand
  // side B^T ((n_d + n_p) x 6 n_s, operator q in columns [q n_s, (q + 1) n_s)): [L *] = B A^{-1}
  // <=> A [L *]^T = B^T (A is symmetric), solved on the device with the factors above (the
  // O(n_d^2 n_s) step).
  const index_t ns = sample.size(), m = nd + np;
  Mat PE[6];
  if (np > 0) {
    Mat* all[6] = {&PE[0], &PE[1], &PE[2], &PE[3], &PE[4], &PE[5]};
    harmonic_matrices(sample, basis.sh_degree, all);
  }
  Mat BT(m, 6 * ns);
#pragma omp parallel for schedule(static)
  for (index_t i = 0; i < ns; ++i) {
    const double la = sample.lambda[i], th = sample.theta[i];
    const double cl = std::cos(la), sl = std::sin(la), ct = std::cos(th), st = std::sin(th);
    const double x[3] = {cl * ct, sl * ct, st};
    const double xl[3] = {-sl * ct, cl * ct, 0};
    const double xt[3] = {-cl * st, -sl * st, ct};
    const double xll[3] = {-cl * ct, -sl * ct, 0};
    const double xlt[3] = {sl * st, -cl * st, 0};
    const double xtt[3] = {-cl * ct, -sl * ct, -st};
    double* col[6];
    for (int q = 0; q < 6; ++q) col[q] = BT.data() + (q * ns + i) * m;
    for (index_t j = 0; j < nd; ++j) {
      const double* y = &xd[3 * j];
      auto dot = [y](const double* a) { return a[0] * y[0] + a[1] * y[1] + a[2] * y[2]; };
      const double t = dot(x), tl = dot(xl), tt = dot(xt), tll = dot(xll), tlt = dot(xlt), ttt = dot(xtt);
      double f0, f1, f2;
      f(t, f0, f1, f2);
      col[0][j] = f0;
      col[1][j] = f1 * tl;
      col[2][j] = f1 * tt;
      col[3][j] = f2 * tl * tl + f1 * tll;
      col[4][j] = f2 * tl * tt + f1 * tlt;
      col[5][j] = f2 * tt * tt + f1 * ttt;
    }
    for (int q = 0; q < 6; ++q)
      for (int k = 0; k < np; ++k) col[q][nd + k] = PE[q](i, k);
  }
  linalg::DeviceMatrix rhs = upload(BT);
  BT.resize(0, 0);
  linalg::lu_solve(device_factors(lu), linalg::Op::none, rhs.view());
  const std::vector<double> solved = rhs.to_host();
  const Eigen::Map<const Mat> LT(solved.data(), m, 6 * ns);
  Mat L[6];
  for (int q = 0; q < 6; ++q) L[q] = LT.block(0, q * ns, nd, ns).transpose();
  upload_stacked(L, *ops);
  ops->data_sites = nd;
  ops->reproduces_constants = basis.sh_degree >= 0;
  ops->description = "PHS r^" + to_text(p) + " + harmonics of degree <= " + to_text(basis.sh_degree) +
                     ", n_d = " + to_text(nd) + " data sites, n_s = " + to_text(ns) + " sample sites";
  return ops;
}

}  // namespace rbfib::surface
