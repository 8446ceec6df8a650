#pragma once
// Discrete operators on the MAC grid (Section 2.1), matrix-free:
//   divergence  (D u)_c = sum_a (u_a(x_c + h_a/2 e_a) - u_a(x_c - h_a/2 e_a)) / h_a   at cell centres,
//   gradient    (G q)_a = (q(x + h_a/2 e_a) - q(x - h_a/2 e_a)) / h_a               at the u_a unknowns,
//   advection   N(u)_a = sum_b D_b[(A_a u_b)(A_b u_a)]                                (eq. 2.5),
// with D_a the centred difference and A_a the centred average of the seed. On a wall the normal
// velocity is boundary data (not an unknown), so that with zero data D = -G^T exactly (the grid
// weights h^d cancel), and D G is the cell-centred Laplacian with homogeneous Neumann data (eq. 2.9).
//
// Units: velocity in cm/s gives divergence and advection (per unit density) in 1/s and cm/s^2.
#include "rbfib/fluid/mac_kernels.hpp"
#include "rbfib/grid/mac.hpp"

#include <array>
#include <functional>

namespace rbfib {

/// Boundary data per velocity component: gamma[a].face[d][side] holds, for every unknown of
/// component a next to face (d, side), the Dirichlet value or the Neumann inward derivative of the
/// MacGrid's condition at the boundary point (see MacGrid::velocity_condition).
using VelocityBoundaryData = std::array<BoundaryData, 3>;

/// Samples value(a, d, side, x, y, z) on every wall face of every component.
VelocityBoundaryData sample_velocity_boundary(
    const MacGrid& grid, const std::function<double(int, int, int, double, double, double)>& value);

/// Zero data on every wall face.
VelocityBoundaryData zero_velocity_boundary(const MacGrid& grid);

class MacOperators {
 public:
  explicit MacOperators(const MacGrid& grid);

  const MacGrid& grid() const { return grid_; }
  const Box& component_box(int a) const { return comp_[a]; }
  const Box& scalar_box() const { return scalar_; }
  int dims() const { return grid_.dims; }

  /// out = D u, the normal velocity on walls from gamma (nullptr: zero).
  void divergence(const VectorField& u, const VelocityBoundaryData* gamma, dvec& out) const;
  /// out = G q.
  void gradient(const dvec& q, VectorField& out) const;
  /// out = N(u), eq. 2.5, the ghosts from the boundary data gamma (values at the same time as u).
  void advection(const VectorField& u, const VelocityBoundaryData& gamma, VectorField& out) const;

  /// Net discrete outflow sum over wall faces of (u_b . n_out) dA of the normal boundary data.
  double boundary_outflow(const VelocityBoundaryData& gamma) const;
  /// Shifts the normal boundary data on every wall face by a constant so that the discrete outflow
  /// vanishes (the compatibility condition of the Neumann problem 2.9). Returns the shift (cm/s).
  double make_compatible(VelocityBoundaryData& gamma) const;

 private:
  void check(const VectorField& u, const char* what) const;

  MacGrid grid_;
  std::array<Box, 3> comp_;
  Box scalar_;
  std::array<BoxShape, 3> shape_;
  BoxShape scalar_shape_;
  std::array<kernels::PaddedShape, 3> pad_;
  std::array<std::array<std::array<AxisEnd, 2>, 3>, 3> ends_;  // [component][axis][side]
  mutable std::array<dvec, 3> padded_;
};

}  // namespace rbfib
