#pragma once
// appendixA's quadratic exactness (seed eqs. A.16, A.19-A.22): in 2D and 3D, for every staggering
// and boundary type, the corrected operator reproduces a quadratic (L q + B gamma = I~ Lap q) and CG
// converges on the corrected Helmholtz operator to it.
#include "common/study.hpp"
#include "rbfib/grid/boundary_values.hpp"

namespace rbfib::appendix_a {

/// gamma = alpha u + beta du/dnu for a function with gradient, on the box's faces.
template <class F>
BoundaryData boundary_data_of(const Box& box, const F& u) {
  return robin_boundary_data(box, u, [&](int d, double x, double y, double z) { return u.grad(d, x, y, z); });
}

struct Quadratic {
  double operator()(double x, double y, double z) const {
    return 0.3 + x - 2 * y + 0.5 * z + 1.2 * x * x - 0.7 * y * y + 0.9 * z * z + 0.4 * x * y - 0.6 * y * z +
           0.25 * x * z;
  }
  double grad(int d, double x, double y, double z) const {
    if (d == 0) return 1 + 2.4 * x + 0.4 * y + 0.25 * z;
    if (d == 1) return -2 - 1.4 * y + 0.4 * x - 0.6 * z;
    return 0.5 + 1.8 * z - 0.6 * y + 0.25 * x;
  }
  double laplacian(int dims) const { return 2.4 - (dims > 1 ? 1.4 : 0.0) + (dims > 2 ? 1.8 : 0.0); }
};

struct QuadraticCheck {
  double operator_error = 0;  // max |L q + B gamma - I~ Lap q| / (max|q| / h_min^2)
  double steady_error = 0;    // max |x - q| / max |q| for the Helmholtz solve with solution q
  int cg_iterations = 0;
};

/// The operator's error on the quadratic and the Helmholtz solve's, on one box.
QuadraticCheck check_quadratic(const Box& box, Correction corr);

/// Every staggering g in {1/2, 1, 1/4} and boundary type in x and y, corrected and not; z is Neumann
/// at cell centres (uncorrected-exact) so every x/y case is seen in 3D too.
study::Json quadratics_table();

}  // namespace rbfib::appendix_a
