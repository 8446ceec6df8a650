#pragma once
// Norms of a grid function's error: the grid 2-norm sqrt(h_x h_y h_z sum_i e_i^2) and the max norm
// of e = a - b over the unknowns of a box (the norms of Tables A.1-A.2).
#include "rbfib/grid/box.hpp"

namespace rbfib {

struct GridNorms {
  double l2 = 0, linf = 0;
};

GridNorms grid_error_norms(const Box& box, const dvec& a, const dvec& b);

}  // namespace rbfib
