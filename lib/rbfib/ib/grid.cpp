#include "rbfib/ib/grid.hpp"

#include "rbfib/core/error.hpp"

#include <cmath>

namespace rbfib::ib {

ComponentGrid make_component_grid(const Box& box, int support) {
  static const char* names[3] = {"grid.x", "grid.y", "grid.z"};
  require(box.dims == 3, "grid.dims", box.dims, "interpolation and spreading need a 3D box");
  box.validate();
  ComponentGrid grid;
  double keys = 1.0;
  for (int d = 0; d < 3; ++d) {
    const Axis& ax = box.axes[d];
    const std::string name = names[d];
    require(ax.g > 0.0 && ax.g <= 1.0, name + ".g", ax.g, "staggering must lie in (0, 1]");
    require(ax.cells >= support, name + ".cells", ax.cells,
            "the kernel support (" + std::to_string(support) + " points) is wider than the grid");
    require(std::isfinite(ax.length) && ax.length > 0.0, name + ".length", ax.length, "must be positive");
    GridAxis& a = grid.axis[d];
    a.cells = ax.cells;
    a.n = ax.unknowns();
    a.periodic = ax.periodic();
    a.origin = ax.origin;
    a.length = ax.length;
    a.h = ax.h();
    a.inv_h = 1.0 / a.h;
    a.g = ax.g;
    a.key_offset = a.periodic ? 0 : 1;
    a.key_extent = a.periodic ? ax.cells : ax.cells + 2;
    keys *= a.key_extent;
  }
  require(keys < 4294967296.0, "grid.cells", keys, "too many cells for 32-bit keys");
  grid.stride[0] = 1;
  grid.stride[1] = grid.axis[0].n;
  grid.stride[2] = index_t(grid.axis[0].n) * grid.axis[1].n;
  grid.size = grid.stride[2] * grid.axis[2].n;
  return grid;
}

std::array<Box, 3> mac_boxes(std::array<int, 3> cells, std::array<double, 3> length, std::array<bool, 3> periodic) {
  std::array<Box, 3> boxes;
  for (int c = 0; c < 3; ++c) {
    boxes[c].dims = 3;
    for (int d = 0; d < 3; ++d) {
      Axis& ax = boxes[c].axes[d];
      ax.cells = cells[d];
      ax.length = length[d];
      ax.g = (c == d) ? 1.0 : 0.5;
      ax.lower = ax.upper = periodic[d] ? BoundaryCondition::periodic() : BoundaryCondition::dirichlet();
      ax.origin = 0.0;
    }
  }
  return boxes;
}

}  // namespace rbfib::ib
