#pragma once
// Boundary data of a known function for a box's boundary conditions (Appendix A, eq. A.3 and its
// faces in 2D/3D): gamma = alpha u + beta du/dnu on every non-periodic face, nu the inward normal
// (du/dnu = du/dx_d on the lower face, -du/dx_d on the upper), at the points of sample_boundary.
#include "rbfib/grid/box.hpp"

#include <functional>

namespace rbfib {

/// u(x, y, z) and its gradient grad(d, x, y, z) = du/dx_d.
BoundaryData robin_boundary_data(const Box& box, const std::function<double(double, double, double)>& u,
                                 const std::function<double(int, double, double, double)>& grad);

}  // namespace rbfib
