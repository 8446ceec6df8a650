#pragma once
// One axis of a staggered (MAC) grid: N cells of width h = L/N on [origin, origin + L], unknowns
// at x_i = origin + h (g + i), i = 0, 1, ... (the seed's x_i = h(g + i - 1), i = 1..N, eq. A.1ff),
// with staggering g in (0, 1]. Boundary conditions gamma = alpha u + beta du/dnu at each end, nu
// the inward normal (at x = 0 this is alpha u + beta u_x, eq. A.2; at x = 1 alpha u - beta u_x,
// eq. A.3), filled by linear ghost extrapolation (eqs. A.4-A.8).
//
// For g = 1 and a non-periodic axis the last point x = origin + L lies on the boundary and plays
// the ghost of the upper end, so the axis has N - 1 unknowns; otherwise it has N.
#include "rbfib/core/exec.hpp"

#include <string>

namespace rbfib {

enum class BoundaryKind { periodic, dirichlet, neumann, robin };

const char* to_string(BoundaryKind kind);

/// gamma = alpha u + beta du/dnu on one end of an axis (nu: inward normal). The Laplacian is
/// negative semidefinite (and the Helmholtz operator positive definite) for Robin data with
/// alpha beta <= 0, the dissipative case du/dn_out + k u = g with k >= 0.
struct BoundaryCondition {
  BoundaryKind kind = BoundaryKind::periodic;
  double alpha = 0.0;
  double beta = 0.0;

  static BoundaryCondition periodic() { return {BoundaryKind::periodic, 0.0, 0.0}; }
  static BoundaryCondition dirichlet() { return {BoundaryKind::dirichlet, 1.0, 0.0}; }
  static BoundaryCondition neumann() { return {BoundaryKind::neumann, 0.0, 1.0}; }
  static BoundaryCondition robin(double alpha, double beta) { return {BoundaryKind::robin, alpha, beta}; }
};

/// Whether the boundary correction of Appendix A (eqs. A.13-A.15, A.19-A.22) is applied.
enum class Correction { none, appendix_a };

struct Axis {
  int cells = 0;             ///< N
  double length = 1.0;       ///< L (internal length unit)
  double g = 0.5;            ///< staggering in (0, 1]
  BoundaryCondition lower;   ///< at origin
  BoundaryCondition upper;   ///< at origin + L
  double origin = 0.0;

  bool periodic() const { return lower.kind == BoundaryKind::periodic; }
  double h() const { return length / cells; }
  /// Number of unknowns along this axis.
  int unknowns() const { return (!periodic() && g == 1.0) ? cells - 1 : cells; }
  /// Position of unknown i.
  double x(int i) const { return origin + h() * (g + i); }
  /// Distance from the boundary at `upper ? origin + L : origin` to the adjacent unknown, in units of h.
  double end_offset(bool upper_end) const { return (upper_end && g != 1.0) ? 1.0 - g : g; }

  /// Throws InputError naming `name.<field>` if the axis cannot be discretized.
  void validate(const std::string& name) const;
};

/// Ghost extrapolation at one end (eq. A.7): u_ghost = ghost * u_adjacent + data * gamma, and the
/// factor 1 - epsilon of eq. A.10 by which the one-sided second difference misses u_xx.
struct AxisEnd {
  double ghost = 0.0;
  double data = 0.0;
  double one_minus_eps = 1.0;
};

/// Computes the ghost coefficients of eq. A.7 and epsilon of eq. A.10 for a boundary at distance
/// s*h from the adjacent unknown.
AxisEnd axis_end(const BoundaryCondition& bc, double s, double h);

/// Plain-data description of the 1D second difference with its ghosts (copyable to the device).
struct AxisStencil {
  int n = 1;
  bool periodic = true;
  double inv_h2 = 0.0;
  AxisEnd lo, hi;
  /// Diagonal of the modified identity I~ (eq. A.14): 1 - eps at the ends when corrected, else 1.
  double w_lo = 1.0, w_hi = 1.0;

  RBFIB_HD double weight(int i) const {
    double w = 1.0;
    if (i == 0) w *= w_lo;
    if (i == n - 1) w *= w_hi;
    return w;
  }
};

AxisStencil make_stencil(const Axis& axis, Correction correction);

}  // namespace rbfib
