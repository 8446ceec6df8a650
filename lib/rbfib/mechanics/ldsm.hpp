#pragma once
// The linear discrete surface method (LDSM, paper Sec. 2.5, eqs. 53-67), for comparison.
// The energy is integrated exactly on a triangulation (eq. 64):
//   E = sum_t W(I1, I2)_t A0_t,   A0_t = (det G0_t)^{1/2} / 2,
// with G = [u_a . u_b], u_0 = X1 - X3, u_1 = X2 - X3 (eq. 59) and G0 likewise from Z (eq. 60).
// The force on vertex i is F^_i = -dE/dX_i (eqs. 65-66); per triangle
//   dW/du_a = sum_b S_ab u_b,   S = 2 W_1 G0^{-1} + 2 W_2 det C G^{-1}   (as eq. 34),
// so dE/dX1 = A0 dW/du_0, dE/dX2 = A0 dW/du_1, dE/dX3 = -(dE/dX1 + dE/dX2).
// Positions and forces: n x 3 column-major, X[d n + i] (docs/math.md).
#include "rbfib/mechanics/energy.hpp"
#include "rbfib/surface/triangulation.hpp"

#include <string>
#include <vector>

namespace rbfib::mechanics {

struct LdsmResult {
  std::vector<double> F;  ///< force (not density) at each vertex
  double energy = 0;
};

/// Throws NumericalError naming the cell and triangle for a degenerate (zero-area) or inverted
/// (normal flipped with respect to the reference) triangle, InputError for a vertex out of range.
LdsmResult ldsm_forces(const std::string& cell, const std::vector<surface::Triangle>& tris,
                       const std::vector<double>& Z, const std::vector<double>& X, const EnergyDensity& energy);
/// The same for a sum of energies (e.g. neo-Hookean + tension, paper Sec. 4.2) in one pass: W, W_1
/// and W_2 are sums over the energies.
LdsmResult ldsm_forces(const std::string& cell, const std::vector<surface::Triangle>& tris,
                       const std::vector<double>& Z, const std::vector<double>& X, const std::vector<EnergyDensity>& energies);

/// Vertex area weights, eq. (67): one third of the reference areas of the triangles around it
/// (the printed eq. 67 omits the 1/2 of the triangle area; we use the area, as its text says).
std::vector<double> ldsm_area_weights(const std::vector<surface::Triangle>& tris, const std::vector<double>& Z);

}  // namespace rbfib::mechanics
