#pragma once
// Host dense matrices for the surface operators (row-major, rows = evaluation sites, cols = data
// sites), and the product of an operator with per-site 3-vectors. The heavy algebra (LU, solves)
// lives in .cpp files with Eigen; this header stays light.
//
// Layout of point data everywhere in surface/ and mechanics/: 3 doubles per site, site-major
// (x0, y0, z0, x1, y1, z1, ...).
#include "rbfib/core/exec.hpp"

#include <vector>

namespace rbfib::surface {

/// A dense row-major matrix A(i, j) = a[i * cols + j].
struct DenseMatrix {
  index_t rows = 0;
  index_t cols = 0;
  std::vector<double> a;

  DenseMatrix() = default;
  DenseMatrix(index_t r, index_t c) : rows(r), cols(c), a(static_cast<std::size_t>(r * c), 0.0) {}
  double& operator()(index_t i, index_t j) { return a[static_cast<std::size_t>(i * cols + j)]; }
  double operator()(index_t i, index_t j) const { return a[static_cast<std::size_t>(i * cols + j)]; }
};

/// out (rows x 3, site-major) = A (rows x cols) * in (cols x 3, site-major).
void apply_to_points(const DenseMatrix& A, const std::vector<double>& in, std::vector<double>& out);

/// out (rows) = A * in (cols): a scalar field.
void apply_to_scalars(const DenseMatrix& A, const std::vector<double>& in, std::vector<double>& out);

}  // namespace rbfib::surface
