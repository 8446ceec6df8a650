#pragma once
// Periodic cubic-spline restriction of a MAC velocity component from a grid to the grid twice as
// coarse (the "cubic spline of u_{h/2} evaluated at the points of grid h" of the seed's Sec. 4.2.2.1,
// Tables 4.3 and 4.4, for errors between successive grids). Host-side; x fastest.
#include <vector>

namespace rbfib {

/// Values at the midpoints x_{i+1/2} of the periodic cubic spline through y_0..y_{n-1} (spacing h):
/// the second derivatives solve the cyclic system M_{i-1} + 4 M_i + M_{i+1} = 6 (y_{i-1} - 2 y_i
/// + y_{i+1}) / h^2 (Sherman-Morrison on the Thomas algorithm), and
/// s(x_{i+1/2}) = (y_i + y_{i+1}) / 2 - h^2 (M_i + M_{i+1}) / 16.
std::vector<double> periodic_spline_midpoints(const std::vector<double>& y, double h);

/// MAC component a on the periodic n_f^3 grid (spacing h_f) at the points of the same component on
/// the n_f/2 grid: along its own axis a coarse face is fine face 2 i + 1; along the others a coarse
/// centre is the midpoint of fine centres 2 i and 2 i + 1, taken from the periodic cubic spline.
std::vector<double> restrict_mac_component(const std::vector<double>& fine, int nf, double hf, int a);

}  // namespace rbfib
