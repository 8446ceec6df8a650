#pragma once
// A 1D, 2D or 3D box of unknowns: the tensor product of up to three staggered axes. Storage is
// x fastest: p = i + n_x (j + n_y k).
#include "rbfib/grid/axis.hpp"

#include <array>
#include <functional>

namespace rbfib {

struct Box {
  int dims = 3;
  std::array<Axis, 3> axes{};

  int n(int d) const { return d < dims ? axes[d].unknowns() : 1; }
  index_t size() const { return index_t(n(0)) * n(1) * n(2); }
  /// Coordinate of unknown i along axis d.
  double x(int d, int i) const { return d < dims ? axes[d].x(i) : 0.0; }
  /// Throws InputError naming the axis and field when the box cannot be discretized.
  void validate() const;
};

/// Plain-data shape of a box (copyable to the device).
struct BoxShape {
  int dims = 3;
  int n[3] = {1, 1, 1};
  index_t stride[3] = {1, 1, 1};

  RBFIB_HD void split(index_t p, int i[3]) const {
    i[0] = int(p % n[0]);
    const index_t q = p / n[0];
    i[1] = int(q % n[1]);
    i[2] = int(q / n[1]);
  }
};

BoxShape shape_of(const Box& box);

/// Boundary data gamma on each face (axis d, side 0 = lower, 1 = upper), one value per unknown
/// adjacent to the face, indexed by the other axes' indices (lower axis fastest). Empty for
/// periodic axes.
struct BoundaryData {
  std::array<std::array<dvec, 2>, 3> face;
};

/// Number of values on a face normal to axis d.
index_t face_size(const Box& box, int d);

/// Samples f(x, y, z) at every unknown of the box (host side; for initial data and tests).
dvec sample(const Box& box, const std::function<double(double, double, double)>& f);

/// Samples gamma(d, side, x, y, z) at the boundary points of every non-periodic face: the point on
/// the face (x_d at the boundary) opposite each adjacent unknown.
BoundaryData sample_boundary(const Box& box,
                             const std::function<double(int, int, double, double, double)>& gamma);

}  // namespace rbfib
