#pragma once
// Exact integrals over the unit sphere S^2 that test quadrature weights on it:
//   int_{S^2} exp(a . x) dA = 4 pi sinh|a| / |a|              (4 pi for a = 0),
//   int_{S^2} |x - y|^p dA(x) = 2 pi 2^(p+2) / (p + 2)        (any y on S^2; p > -2),
// the second the constant L phi of dissertation eq. (2.20) for the PHS phi(r) = r^p, which
// -I_phi of eq. (2.22) approximates.
#include "rbfib/surface/sphere.hpp"

#include <array>
#include <vector>

namespace rbfib::surface {

double sphere_integral_exp(const std::array<double, 3>& a);
double sphere_integral_distance_power(int p);

/// |sum_i w_i exp(a . chi_i) - int_{S^2} exp(a . x) dA| for weights w at the sites.
double exp_quadrature_error(const SphereSites& sites, const std::vector<double>& w, const std::array<double, 3>& a);

}  // namespace rbfib::surface
