#pragma once
// The net force |sum_i F^_i|_inf of a cell's forces (n x 3 column-major, F[d n + i]). The force
// of a translation-invariant energy integrates to zero over a closed surface, so its net force is
// the quadrature error of the area weights (the paper's measure in Sec. 4.1).
#include <vector>

namespace rbfib::mechanics {

double net_force_inf(const std::vector<double>& F);

}  // namespace rbfib::mechanics
