#include "rbfib/fluid/grid_norms.hpp"

#include "rbfib/linalg/blas.hpp"

#include <cmath>

namespace rbfib {

GridNorms grid_error_norms(const Box& box, const dvec& a, const dvec& b) {
  dvec e = a;
  blas::axpy(-1.0, b, e);
  double cell = 1.0;
  for (int d = 0; d < box.dims; ++d) cell *= box.axes[d].h();
  return {std::sqrt(cell) * blas::norm2(e), blas::norm_inf(e)};
}

}  // namespace rbfib
