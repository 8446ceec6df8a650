#pragma once
// Max-norm error of an approximation against an exact reference, absolute and relative to the
// reference's size: the measure of the paper's eqs. (90)-(91), err = max_i |x_i - x^E_i|, with
// rel = err / max_i |x^E_i| (our normalization).
#include <vector>

namespace rbfib {

struct MaxNormError {
  double abs = 0;  ///< max_i |x_i - exact_i|
  double rel = 0;  ///< abs / max_i |exact_i|
};

/// x and exact of the same length (any layout, compared entry by entry).
MaxNormError max_norm_error(const std::vector<double>& x, const std::vector<double>& exact);

}  // namespace rbfib
