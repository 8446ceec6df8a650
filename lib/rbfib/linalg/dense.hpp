#pragma once
// Dense linear algebra on the execution device, in BLAS/LAPACK form: column-major matrices with a
// leading dimension, A(i, j) = data[i + j ld]. One interface for both backends:
//   CPU build:  OpenBLAS (its OpenMP variant, with run-time CPU dispatch: the products use
//               AVX2/FMA although the library itself is compiled for x86-64-v2);
//   CUDA build: cuBLAS and cuSOLVER (one handle each, made on first use).
// Operators are built on the host (Eigen) and uploaded once; every product and solve of a time
// step then runs here on device memory, with no host copies.
#include "rbfib/core/exec.hpp"

#include <string>
#include <vector>

namespace rbfib::linalg {

/// A column-major view of device memory: A(i, j) = data[i + j * ld], ld >= rows (T = double, or
/// float for operators stored in single precision).
template <class T>
struct View {
  T* data = nullptr;
  index_t rows = 0, cols = 0, ld = 0;
  /// The block of rows [r0, r0 + nr) and columns [c0, c0 + nc).
  View block(index_t r0, index_t c0, index_t nr, index_t nc) const { return {data + r0 + c0 * ld, nr, nc, ld}; }
};
template <class T>
struct ConstView {
  const T* data = nullptr;
  index_t rows = 0, cols = 0, ld = 0;
  ConstView() = default;
  ConstView(const T* d, index_t r, index_t c, index_t l) : data(d), rows(r), cols(c), ld(l) {}
  ConstView(const View<T>& v) : data(v.data), rows(v.rows), cols(v.cols), ld(v.ld) {}
  ConstView block(index_t r0, index_t c0, index_t nr, index_t nc) const { return {data + r0 + c0 * ld, nr, nc, ld}; }
};
using MatrixView = View<double>;
using ConstMatrixView = ConstView<double>;
using FloatView = View<float>;
using ConstFloatView = ConstView<float>;

/// A dense column-major matrix that owns device storage (ld = rows); Matrix<double> and
/// Matrix<float> are instantiated.
template <class T>
class Matrix {
 public:
  Matrix() = default;
  Matrix(index_t rows, index_t cols) : rows_(rows), cols_(cols), a_(static_cast<std::size_t>(rows * cols), T(0)) {}
  /// Uploads a host column-major array of rows * cols values.
  static Matrix from_host(index_t rows, index_t cols, const T* column_major);

  index_t rows() const { return rows_; }
  index_t cols() const { return cols_; }
  index_t ld() const { return rows_; }
  bool empty() const { return rows_ == 0 || cols_ == 0; }
  /// Resizes (contents undefined after a change of shape).
  void resize(index_t rows, index_t cols);
  View<T> view() { return {ptr(a_), rows_, cols_, rows_}; }
  ConstView<T> view() const { return {ptr(a_), rows_, cols_, rows_}; }
  device_vector<T>& storage() { return a_; }
  const device_vector<T>& storage() const { return a_; }
  /// Downloads to a host column-major array.
  std::vector<T> to_host() const;
  /// Device bytes held.
  std::size_t bytes() const { return a_.size() * sizeof(T); }

 private:
  index_t rows_ = 0, cols_ = 0;
  device_vector<T> a_;
};
using DeviceMatrix = Matrix<double>;
using FloatMatrix = Matrix<float>;

enum class Op { none, transpose };

/// C = alpha op(A) op(B) + beta C (BLAS dgemm). Throws InputError on mismatched shapes.
void gemm(Op op_a, Op op_b, double alpha, ConstMatrixView A, ConstMatrixView B, double beta, MatrixView C);

/// count independent products C_k = alpha op(A_k) op(B_k) + beta C_k, where X_k starts at
/// X.data + k * stride_X (the same shapes and leading dimensions for all k): cuBLAS's
/// gemmStridedBatched; on the CPU one dgemm per k. On the CPU a tall op(A) = A times a few columns
/// (at least 4 times as many rows as C has columns: the surfaces' jets) is split by rows among
/// the OpenMP team, one one-thread dgemm per thread and product (see rows_per_thread); any other
/// shape is threaded by OpenBLAS.
void gemm_strided_batched(Op op_a, Op op_b, double alpha, ConstMatrixView A, index_t stride_a, ConstMatrixView B,
                          index_t stride_b, double beta, MatrixView C, index_t stride_c, index_t count);

/// Whether tall products are split by rows among the team (true, the default) or left to the
/// BLAS's own threading (false): a switch for the benchmarks that compare the two (bench_cells);
/// both give the same products to rounding. Without effect on the CUDA backend.
void set_rows_per_thread(bool on);
bool rows_per_thread();

/// The same in single precision (BLAS sgemm; cuBLAS Sgemm): products with an operator stored in
/// float (surface/operators.hpp), accumulated in float by the BLAS kernels.
void gemm(Op op_a, Op op_b, float alpha, ConstFloatView A, ConstFloatView B, float beta, FloatView C);
void gemm_strided_batched(Op op_a, Op op_b, float alpha, ConstFloatView A, index_t stride_a, ConstFloatView B,
                          index_t stride_b, float beta, FloatView C, index_t stride_c, index_t count);

/// B = A rounded to float, and B = A widened to double (same shapes; blocks allowed).
void narrow(ConstMatrixView A, FloatView B);
void widen(ConstFloatView A, MatrixView B);

/// LU factors with partial pivoting in LAPACK form: P A = L U with unit lower L and U packed in
/// one n x n matrix, pivots ipiv (1-based: row i was interchanged with row ipiv[i], in order).
struct LuFactors {
  DeviceMatrix lu;
  device_vector<int> ipiv;
  index_t n() const { return lu.rows(); }
  std::size_t bytes() const { return lu.bytes() + ipiv.size() * sizeof(int); }
};

/// Factors A (n x n) on the device (dgetrf). Throws NumericalError naming `what` if U has a zero
/// on its diagonal.
LuFactors lu_factor(const DeviceMatrix& A, const char* what);

/// Takes an LU factorization computed elsewhere (e.g. by Eigen on the host, to get its condition
/// estimate): the packed factors (column-major, n x n) and the row permutation of P A = L U as
/// "row i of P A is row perm[i] of A", turned into LAPACK's interchange sequence.
LuFactors lu_from_host(index_t n, const double* lu_column_major, const std::vector<index_t>& perm);

/// B = op(A)^{-1} B in place (dgetrs), for B with n rows and any number of columns.
void lu_solve(const LuFactors& f, Op op, MatrixView B);

/// Reciprocal condition number of A in the 1-norm, 1 / (||A||_1 ||A^{-1}||_1), from its factors
/// and norm1 = ||A||_1: ||A^{-1}||_1 is estimated as LAPACK's dgecon does (Hager's method with
/// Higham's refinements, a few solves with A and A^T), an estimate that is never above the
/// true value and almost always within a factor 3 of it.
double lu_rcond(const LuFactors& f, double norm1);

/// B = A (same shape; either may be a block with its own leading dimension).
void copy(ConstMatrixView A, MatrixView B);

/// Name of the dense backend ("OpenBLAS 0.3.21 (OpenMP), core Zen", "cuBLAS/cuSOLVER").
std::string dense_backend_name();

}  // namespace rbfib::linalg
