#pragma once
// The marker-and-cell (MAC) grid of Section 2.1, in 2D or 3D, built from one staggered Axis per
// direction and component (the recursive construction of eq. A.16).
//
// The domain [origin, origin + L_d] along each axis d is cut into N_d cells of width h_d = L_d / N_d.
// Scalars (pressure p, pseudo-pressure q, divergence) live at cell centres: staggering g = 1/2 on
// every axis. Velocity component a lives at the cell faces normal to e_a: staggering g = 1 along
// axis a and g = 1/2 along the others (the seed's h g_a = h/2 (1 - e_a)), so that unknown i of
// component a along axis a sits at x = origin + h (i + 1), the upper face of cell i.
//
// Boundary type per axis (both ends of an axis must agree on periodic vs. wall):
//   periodic  - every field wraps;
//   dirichlet - a wall with prescribed velocity u_b(t) (no-slip; moving walls allowed): every
//               component gets Dirichlet data. The normal component has g = 1, so its boundary value
//               is the ghost of Axis (eps = 0); the tangential components have g = 1/2 and are
//               corrected by Appendix A (eps = 1/4);
//   neumann   - a slip wall: the normal component is Dirichlet (prescribed normal velocity, no
//               penetration for zero data), the tangential components get Neumann data
//               du_a/dnu (nu the inward normal; zero data: no shear stress).
// The scalar box gets homogeneous Neumann data on every wall (eq. 2.9), periodic otherwise.
//
// Index order of every field: x fastest (Box). Lengths in internal units (cm).
#include "rbfib/grid/box.hpp"

#include <array>
#include <string>

namespace rbfib {

enum class MacBoundary { periodic, dirichlet, neumann };

const char* to_string(MacBoundary b);

struct MacGrid {
  int dims = 3;
  std::array<int, 3> cells{{1, 1, 1}};
  std::array<double, 3> length{{1.0, 1.0, 1.0}};
  std::array<double, 3> origin{{0.0, 0.0, 0.0}};
  std::array<MacBoundary, 3> lower{{MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic}};
  std::array<MacBoundary, 3> upper{{MacBoundary::periodic, MacBoundary::periodic, MacBoundary::periodic}};

  /// Fewest cells per axis the fluid solver accepts: the normal velocity needs >= 3 interior faces
  /// across a wall axis, and the advection stencil reaches one cell beyond its neighbours.
  static constexpr int min_cells = 4;

  double h(int d) const { return length[d] / cells[d]; }
  bool periodic(int d) const { return lower[d] == MacBoundary::periodic; }
  /// Boundary condition of velocity component a at one end of axis d.
  BoundaryCondition velocity_condition(int a, int d, int side) const;
  /// The box of velocity component a (staggering g = 1 along axis a, 1/2 along the others).
  Box component(int a) const;
  /// The box of cell-centred scalars, homogeneous Neumann on walls.
  Box scalar() const;
  /// Throws InputError naming `name.<axis>.<field>` if the grid cannot be discretized.
  void validate(const std::string& name = "grid") const;
};

/// A 3D domain with one boundary type per axis: convenience for scenes.
MacGrid make_mac_grid(int dims, std::array<int, 3> cells, std::array<double, 3> length,
                      std::array<MacBoundary, 3> boundary);

/// One array per velocity component (components >= dims are empty).
using VectorField = std::array<dvec, 3>;

/// Zero velocity field on a grid.
VectorField zero_vector_field(const MacGrid& grid);

}  // namespace rbfib
