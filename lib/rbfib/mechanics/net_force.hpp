#pragma once
// The net force of a membrane's point forces F^_i = F_i dA0 (n x 3, column-major: F[d n + i]).
// A translation-invariant energy gives forces that integrate to zero, so |sum_i F^_i|_inf measures
// the quadrature error of the area weights (Chapter 3, Sec. 2.4.1 and Sec. 4.1: "O(1e-5) or less").
#include <vector>

namespace rbfib::mechanics {

/// |sum_i F^_i|_inf.
double net_force_inf(const std::vector<double>& F);

/// max_i |F^_i|_inf, the scale the net force is read against.
double max_force_inf(const std::vector<double>& F);

}  // namespace rbfib::mechanics
