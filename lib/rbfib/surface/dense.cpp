#include "rbfib/surface/dense.hpp"

#include "rbfib/core/error.hpp"

namespace rbfib::surface {

void apply_to_points(const DenseMatrix& A, const std::vector<double>& in, std::vector<double>& out) {
  require(static_cast<index_t>(in.size()) == 3 * A.cols, "points.size()", in.size(),
          "must be 3 x operator columns (" + to_text(A.cols) + ")");
  out.assign(static_cast<std::size_t>(3 * A.rows), 0.0);
  // A plain loop: three right-hand sides are too few for a threaded GEMM to pay off.
  const index_t n = A.cols;
  for (index_t i = 0; i < A.rows; ++i) {
    const double* a = &A.a[static_cast<std::size_t>(i * n)];
    double sx = 0, sy = 0, sz = 0;
    for (index_t j = 0; j < n; ++j) {
      sx += a[j] * in[3 * j];
      sy += a[j] * in[3 * j + 1];
      sz += a[j] * in[3 * j + 2];
    }
    out[3 * i] = sx;
    out[3 * i + 1] = sy;
    out[3 * i + 2] = sz;
  }
}

void apply_to_scalars(const DenseMatrix& A, const std::vector<double>& in, std::vector<double>& out) {
  require(static_cast<index_t>(in.size()) == A.cols, "values.size()", in.size(),
          "must equal operator columns (" + to_text(A.cols) + ")");
  out.assign(static_cast<std::size_t>(A.rows), 0.0);
  const index_t n = A.cols;
  for (index_t i = 0; i < A.rows; ++i) {
    const double* a = &A.a[static_cast<std::size_t>(i * n)];
    double s = 0;
    for (index_t j = 0; j < n; ++j) s += a[j] * in[j];
    out[i] = s;
  }
}

}  // namespace rbfib::surface
