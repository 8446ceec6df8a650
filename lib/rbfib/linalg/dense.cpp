#include "rbfib/linalg/dense.hpp"

#include "rbfib/core/error.hpp"

#include <thrust/copy.h>

#include <algorithm>
#include <cmath>
#include <type_traits>

#if defined(RBFIB_BACKEND_CUDA)
#include <cublas_v2.h>
#include <cuda_runtime.h>
#include <cusolverDn.h>
#else
#include <cblas.h>
#include <omp.h>
// LAPACK (OpenBLAS exports its own optimized getrf/getrs); the trailing length is the hidden
// Fortran string length of `trans`.
extern "C" {
void dgetrf_(const int* m, const int* n, double* a, const int* lda, int* ipiv, int* info);
void dgetrs_(const char* trans, const int* n, const int* nrhs, const double* a, const int* lda, const int* ipiv,
             double* b, const int* ldb, int* info, std::size_t trans_len);
}
#endif

namespace rbfib::linalg {

template <class T>
Matrix<T> Matrix<T>::from_host(index_t rows, index_t cols, const T* column_major) {
  Matrix m(rows, cols);
  thrust::copy(column_major, column_major + rows * cols, m.a_.begin());
  return m;
}

template <class T>
void Matrix<T>::resize(index_t rows, index_t cols) {
  rows_ = rows;
  cols_ = cols;
  a_.resize(static_cast<std::size_t>(rows * cols));
}

template <class T>
std::vector<T> Matrix<T>::to_host() const {
  std::vector<T> h(a_.size());
  thrust::copy(a_.begin(), a_.end(), h.begin());
  return h;
}

template class Matrix<double>;
template class Matrix<float>;

namespace {
int to_int(index_t v, const char* what) {
  require(v >= 0 && v <= index_t(2147483647), what, v, "must fit a 32-bit BLAS integer");
  return static_cast<int>(v);
}
int ld_of(index_t ld) { return to_int(std::max<index_t>(ld, 1), "leading dimension"); }

template <class T>
void check_gemm(Op op_a, Op op_b, const ConstView<T>& A, const ConstView<T>& B, const View<T>& C, index_t& m, index_t& n,
                index_t& k) {
  m = op_a == Op::none ? A.rows : A.cols;
  k = op_a == Op::none ? A.cols : A.rows;
  const index_t kb = op_b == Op::none ? B.rows : B.cols;
  n = op_b == Op::none ? B.cols : B.rows;
  require(kb == k, "gemm: inner dimension of op(B)", kb, "must equal that of op(A) (" + to_text(k) + ")");
  require(C.rows == m && C.cols == n, "gemm: C shape", to_text(C.rows) + " x " + to_text(C.cols),
          "must be " + to_text(m) + " x " + to_text(n));
  require(A.ld >= std::max<index_t>(A.rows, 1) && B.ld >= std::max<index_t>(B.rows, 1) &&
              C.ld >= std::max<index_t>(C.rows, 1),
          "gemm: leading dimension", to_text(A.ld) + ", " + to_text(B.ld) + ", " + to_text(C.ld),
          "must be >= the row counts");
}

#if defined(RBFIB_BACKEND_CUDA)
void cuda_check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw NumericalError(Cause::solver, std::string(what) + ": " + cudaGetErrorString(e));
}
void cublas_check(cublasStatus_t s, const char* what) {
  if (s != CUBLAS_STATUS_SUCCESS) throw NumericalError(Cause::solver, std::string(what) + ": cuBLAS status " + to_text(int(s)));
}
void cusolver_check(cusolverStatus_t s, const char* what) {
  if (s != CUSOLVER_STATUS_SUCCESS) throw NumericalError(Cause::solver, std::string(what) + ": cuSOLVER status " + to_text(int(s)));
}
cublasHandle_t cublas() {
  static cublasHandle_t h = [] {
    cublasHandle_t x;
    cublas_check(cublasCreate(&x), "cublasCreate");
    return x;
  }();
  return h;
}
cusolverDnHandle_t cusolver() {
  static cusolverDnHandle_t h = [] {
    cusolverDnHandle_t x;
    cusolver_check(cusolverDnCreate(&x), "cusolverDnCreate");
    return x;
  }();
  return h;
}
cublasOperation_t cu_op(Op o) { return o == Op::none ? CUBLAS_OP_N : CUBLAS_OP_T; }
int read_info(const device_vector<int>& info) { return info[0]; }
#else
CBLAS_TRANSPOSE cblas_op(Op o) { return o == Op::none ? CblasNoTrans : CblasTrans; }
#endif
}  // namespace

namespace {
bool split_rows = true;  // set_rows_per_thread
}  // namespace

void set_rows_per_thread(bool on) { split_rows = on; }
bool rows_per_thread() { return split_rows; }

namespace {
#if !defined(RBFIB_BACKEND_CUDA)
/// A product worth splitting by rows among `team` threads: op(A) far taller than C is wide, so that
/// each thread's block of rows still fills the GEMM kernel's panels.
bool tall_and_narrow(index_t m, index_t n, int team) { return 4 * n <= m && m >= 64 * index_t(team); }

/// The first row of thread t's block when m rows are split among T threads, on multiples of 8
/// (whole SIMD registers of the kernel's row panels).
index_t split_row(index_t m, index_t t, index_t T) {
  if (t >= T) return m;
  return std::min(m, (m * t / T) / 8 * 8);
}
#endif

/// C_k = alpha op(A_k) op(B_k) + beta C_k for k < count, in double (dgemm) or float (sgemm).
template <class T>
void gemm_batch(Op op_a, Op op_b, T alpha, ConstView<T> A, index_t stride_a, ConstView<T> B, index_t stride_b, T beta,
                View<T> C, index_t stride_c, index_t count) {
  constexpr bool dp = std::is_same_v<T, double>;
  index_t m, n, k;
  check_gemm(op_a, op_b, A, B, C, m, n, k);
  require(count >= 0, "gemm: batch count", count, "must be >= 0");
  if (m == 0 || n == 0 || count == 0) return;
  const int im = to_int(m, "gemm: rows"), in = to_int(n, "gemm: columns"), ik = to_int(k, "gemm: inner dimension");
#if defined(RBFIB_BACKEND_CUDA)
  if (count == 1) {
    if constexpr (dp)
      cublas_check(cublasDgemm(cublas(), cu_op(op_a), cu_op(op_b), im, in, ik, &alpha, A.data, ld_of(A.ld), B.data,
                               ld_of(B.ld), &beta, C.data, ld_of(C.ld)),
                   "cublasDgemm");
    else
      cublas_check(cublasSgemm(cublas(), cu_op(op_a), cu_op(op_b), im, in, ik, &alpha, A.data, ld_of(A.ld), B.data,
                               ld_of(B.ld), &beta, C.data, ld_of(C.ld)),
                   "cublasSgemm");
    return;
  }
  const int ic = to_int(count, "gemm: batch count");
  if constexpr (dp)
    cublas_check(cublasDgemmStridedBatched(cublas(), cu_op(op_a), cu_op(op_b), im, in, ik, &alpha, A.data, ld_of(A.ld),
                                           stride_a, B.data, ld_of(B.ld), stride_b, &beta, C.data, ld_of(C.ld), stride_c, ic),
                 "cublasDgemmStridedBatched");
  else
    cublas_check(cublasSgemmStridedBatched(cublas(), cu_op(op_a), cu_op(op_b), im, in, ik, &alpha, A.data, ld_of(A.ld),
                                           stride_a, B.data, ld_of(B.ld), stride_b, &beta, C.data, ld_of(C.ld), stride_c, ic),
                 "cublasSgemmStridedBatched");
#else
  if (n == 1) {
    // A product with one column is a matrix-vector product: gemv streams A once, where OpenBLAS's
    // gemm first packs A and then runs its kernel on a padded panel (about twice the time for an
    // operator of tens of MB, as a surface's jets or bending derivatives of one cell).
    const int ar = to_int(A.rows, "gemm: rows of A"), ac = to_int(A.cols, "gemm: columns of A");
    const int incx = op_b == Op::none ? 1 : ld_of(B.ld);  // op(B) = B's column, or B's row
    for (index_t b = 0; b < count; ++b) {
      if constexpr (dp)
        cblas_dgemv(CblasColMajor, cblas_op(op_a), ar, ac, alpha, A.data + b * stride_a, ld_of(A.ld), B.data + b * stride_b,
                    incx, beta, C.data + b * stride_c, 1);
      else
        cblas_sgemv(CblasColMajor, cblas_op(op_a), ar, ac, alpha, A.data + b * stride_a, ld_of(A.ld), B.data + b * stride_b,
                    incx, beta, C.data + b * stride_c, 1);
    }
    return;
  }
  // Rows [r0, r0 + rows) of op(A) (op(A) = A: a row offset is a pointer offset) into those of C.
  auto rows_of = [&](index_t b, index_t r0, int rows) {
    if constexpr (dp)
      cblas_dgemm(CblasColMajor, cblas_op(op_a), cblas_op(op_b), rows, in, ik, alpha, A.data + b * stride_a + r0, ld_of(A.ld),
                  B.data + b * stride_b, ld_of(B.ld), beta, C.data + b * stride_c + r0, ld_of(C.ld));
    else
      cblas_sgemm(CblasColMajor, cblas_op(op_a), cblas_op(op_b), rows, in, ik, alpha, A.data + b * stride_a + r0, ld_of(A.ld),
                  B.data + b * stride_b, ld_of(B.ld), beta, C.data + b * stride_c + r0, ld_of(C.ld));
  };
  const int team = omp_in_parallel() ? 1 : omp_get_max_threads();
  if (split_rows && team > 1 && op_a == Op::none && tall_and_narrow(m, n, team)) {
    // A tall operator times a few columns (the surfaces' jets): each thread takes its own block of
    // rows of every product through a one-thread GEMM (OpenBLAS runs one thread inside a parallel
    // region), so each thread packs only its rows of the constant operator, once. Left to
    // OpenBLAS's own threading, these shapes gain 1.3x from two threads (bench_cells). Each entry
    // of C is the same dot product either way (the same kernel over the same inner blocks).
#pragma omp parallel num_threads(team)
    {
      const index_t t = omp_get_thread_num(), threads = omp_get_num_threads();
      const index_t r0 = split_row(m, t, threads), r1 = split_row(m, t + 1, threads);
      for (index_t b = 0; b < count && r1 > r0; ++b) rows_of(b, r0, int(r1 - r0));
    }
    return;
  }
  for (index_t b = 0; b < count; ++b) rows_of(b, 0, im);
#endif
}

/// B = A converted element by element (same shapes; blocks allowed).
template <class From, class To>
void convert(ConstView<From> A, View<To> B, const char* what) {
  require(A.rows == B.rows && A.cols == B.cols, what, to_text(B.rows) + " x " + to_text(B.cols),
          "must equal the source's " + to_text(A.rows) + " x " + to_text(A.cols));
  const From* a = A.data;
  To* b = B.data;
  const index_t rows = A.rows, lda = A.ld, ldb = B.ld;
  for_each_index(A.rows * A.cols, [=] RBFIB_HD (index_t k) {
    const index_t i = k % rows, j = k / rows;
    b[i + j * ldb] = static_cast<To>(a[i + j * lda]);
  });
}
}  // namespace

void gemm(Op op_a, Op op_b, double alpha, ConstMatrixView A, ConstMatrixView B, double beta, MatrixView C) {
  gemm_batch(op_a, op_b, alpha, A, 0, B, 0, beta, C, 0, 1);
}

void gemm_strided_batched(Op op_a, Op op_b, double alpha, ConstMatrixView A, index_t stride_a, ConstMatrixView B,
                          index_t stride_b, double beta, MatrixView C, index_t stride_c, index_t count) {
  gemm_batch(op_a, op_b, alpha, A, stride_a, B, stride_b, beta, C, stride_c, count);
}

void gemm(Op op_a, Op op_b, float alpha, ConstFloatView A, ConstFloatView B, float beta, FloatView C) {
  gemm_batch(op_a, op_b, alpha, A, 0, B, 0, beta, C, 0, 1);
}

void gemm_strided_batched(Op op_a, Op op_b, float alpha, ConstFloatView A, index_t stride_a, ConstFloatView B,
                          index_t stride_b, float beta, FloatView C, index_t stride_c, index_t count) {
  gemm_batch(op_a, op_b, alpha, A, stride_a, B, stride_b, beta, C, stride_c, count);
}

void narrow(ConstMatrixView A, FloatView B) { convert(A, B, "narrow to float: destination shape"); }
void widen(ConstFloatView A, MatrixView B) { convert(A, B, "widen to double: destination shape"); }

LuFactors lu_factor(const DeviceMatrix& A, const char* what) {
  require(A.rows() == A.cols(), std::string(what) + ": LU of a non-square matrix, rows", A.rows(),
          "must equal columns (" + to_text(A.cols()) + ")");
  LuFactors f;
  f.lu = A;
  const int n = to_int(A.rows(), "LU order");
  f.ipiv.resize(static_cast<std::size_t>(n));
  if (n == 0) return f;
  int info = 0;
#if defined(RBFIB_BACKEND_CUDA)
  int lwork = 0;
  cusolver_check(cusolverDnDgetrf_bufferSize(cusolver(), n, n, ptr(f.lu.storage()), n, &lwork), "getrf buffer");
  dvec work(static_cast<std::size_t>(std::max(lwork, 1)));
  device_vector<int> dinfo(1, 0);
  cusolver_check(cusolverDnDgetrf(cusolver(), n, n, ptr(f.lu.storage()), n, ptr(work), ptr(f.ipiv), ptr(dinfo)),
                 "cusolverDnDgetrf");
  info = read_info(dinfo);
#else
  dgetrf_(&n, &n, ptr(f.lu.storage()), &n, ptr(f.ipiv), &info);
#endif
  if (info != 0)
    throw NumericalError(Cause::solver, std::string(what) + ": LU factorization failed (getrf info = " + to_text(info) +
                         (info > 0 ? ", U is exactly singular)" : ")"));
  return f;
}

LuFactors lu_from_host(index_t n, const double* lu_column_major, const std::vector<index_t>& perm) {
  require(static_cast<index_t>(perm.size()) == n, "LU row permutation size", perm.size(), "must equal " + to_text(n));
  LuFactors f;
  f.lu = DeviceMatrix::from_host(n, n, lu_column_major);
  // Row i of P A is row perm[i] of A: swap it into place, in order (LAPACK's interchanges).
  std::vector<index_t> at(n), where(n);
  for (index_t i = 0; i < n; ++i) at[i] = where[i] = i;
  std::vector<int> ipiv(n);
  for (index_t i = 0; i < n; ++i) {
    require(perm[i] >= 0 && perm[i] < n, "LU row permutation entry", perm[i], "must lie in [0, " + to_text(n) + ")");
    const index_t j = where[perm[i]];
    std::swap(at[i], at[j]);
    where[at[i]] = i;
    where[at[j]] = j;
    ipiv[i] = static_cast<int>(j + 1);
  }
  f.ipiv.assign(ipiv.begin(), ipiv.end());
  return f;
}

void lu_solve(const LuFactors& f, Op op, MatrixView B) {
  require(B.rows == f.n(), "LU solve: right-hand side rows", B.rows, "must equal the order " + to_text(f.n()));
  if (B.rows == 0 || B.cols == 0) return;
  const int n = to_int(f.n(), "LU order"), nrhs = to_int(B.cols, "LU solve: right-hand sides"), ldb = ld_of(B.ld);
  int info = 0;
#if defined(RBFIB_BACKEND_CUDA)
  device_vector<int> dinfo(1, 0);
  cusolver_check(cusolverDnDgetrs(cusolver(), cu_op(op), n, nrhs, ptr(f.lu.storage()), n, ptr(f.ipiv), B.data, ldb,
                                  ptr(dinfo)),
                 "cusolverDnDgetrs");
  info = read_info(dinfo);
#else
  const char trans = op == Op::none ? 'N' : 'T';
  dgetrs_(&trans, &n, &nrhs, ptr(f.lu.storage()), &n, ptr(f.ipiv), B.data, &ldb, &info, 1);
#endif
  if (info != 0) throw NumericalError(Cause::solver, "LU solve (getrs): info = " + to_text(info));
}

double lu_rcond(const LuFactors& f, double norm1) {
  const index_t n = f.n();
  if (n == 0) return 1.0;
  if (!(norm1 > 0)) return 0.0;
  // Hager (1984), Higham (1988): maximize ||A^{-1} x||_1 over ||x||_1 = 1 by a gradient step to a
  // vertex e_j; then compare with the alternating vector b_i = (-1)^i (1 + i / (n - 1)).
  DeviceMatrix v(n, 1);
  auto solve = [&](const std::vector<double>& x, Op op) {
    thrust::copy(x.begin(), x.end(), v.storage().begin());
    lu_solve(f, op, v.view());
    return v.to_host();
  };
  auto norm = [](const std::vector<double>& y) {
    double s = 0;
    for (double a : y) s += std::abs(a);
    return s;
  };
  std::vector<double> x(static_cast<std::size_t>(n), 1.0 / double(n));
  double estimate = 0;
  index_t last = -1;
  for (int iteration = 0; iteration < 5; ++iteration) {
    const std::vector<double> y = solve(x, Op::none);
    const double e = norm(y);
    if (iteration > 0 && e <= estimate) break;  // no progress
    estimate = e;
    std::vector<double> sign(y.size());
    for (std::size_t i = 0; i < y.size(); ++i) sign[i] = y[i] >= 0 ? 1.0 : -1.0;
    const std::vector<double> z = solve(sign, Op::transpose);
    index_t j = 0;
    double zx = 0;
    for (index_t i = 0; i < n; ++i) {
      if (std::abs(z[i]) > std::abs(z[j])) j = i;
      zx += z[i] * x[i];
    }
    if (std::abs(z[j]) <= zx || j == last) break;  // a local maximum
    std::fill(x.begin(), x.end(), 0.0);
    x[j] = 1.0;
    last = j;
  }
  std::vector<double> b(static_cast<std::size_t>(n));
  for (index_t i = 0; i < n; ++i) b[i] = (i % 2 ? -1.0 : 1.0) * (1.0 + (n > 1 ? double(i) / double(n - 1) : 0.0));
  estimate = std::max(estimate, 2.0 * norm(solve(b, Op::none)) / (3.0 * double(n)));
  return std::isfinite(estimate) ? 1.0 / (norm1 * estimate) : 0.0;
}

void copy(ConstMatrixView A, MatrixView B) {
  require(A.rows == B.rows && A.cols == B.cols, "matrix copy: destination shape", to_text(B.rows) + " x " + to_text(B.cols),
          "must equal the source's " + to_text(A.rows) + " x " + to_text(A.cols));
  if (A.ld == A.rows && B.ld == B.rows) {
    thrust::copy(thrust::device_pointer_cast(A.data), thrust::device_pointer_cast(A.data + A.rows * A.cols),
                 thrust::device_pointer_cast(B.data));
    return;
  }
  const double* a = A.data;
  double* b = B.data;
  const index_t rows = A.rows, lda = A.ld, ldb = B.ld;
  for_each_index(A.rows * A.cols, [=] RBFIB_HD (index_t k) {
    const index_t i = k % rows, j = k / rows;
    b[i + j * ldb] = a[i + j * lda];
  });
}

std::string dense_backend_name() {
#if defined(RBFIB_BACKEND_CUDA)
  return "cuBLAS/cuSOLVER";
#else
  std::string s = openblas_get_config();
  return "OpenBLAS (" + s + "), core " + openblas_get_corename();
#endif
}

}  // namespace rbfib::linalg
