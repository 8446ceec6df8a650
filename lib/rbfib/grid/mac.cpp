#include "rbfib/grid/mac.hpp"

#include "rbfib/core/error.hpp"

#include <cmath>

namespace rbfib {

const char* to_string(MacBoundary b) {
  switch (b) {
    case MacBoundary::periodic: return "periodic";
    case MacBoundary::dirichlet: return "dirichlet";
    case MacBoundary::neumann: return "neumann";
  }
  return "?";
}

static const char* axis_name(int d) { return d == 0 ? "x" : d == 1 ? "y" : "z"; }

void MacGrid::validate(const std::string& name) const {
  require(dims == 2 || dims == 3, name + ".dims", dims, "must be 2 or 3");
  for (int d = 0; d < dims; ++d) {
    const std::string f = name + "." + axis_name(d);
    require(cells[d] >= min_cells, f + ".cells", cells[d],
            "needs at least " + std::to_string(min_cells) + " cells (staggered normal velocity and advection stencil)");
    require(std::isfinite(length[d]) && length[d] > 0.0, f + ".length", length[d], "must be positive and finite");
    require(std::isfinite(origin[d]), f + ".origin", origin[d], "must be finite");
    const bool lo_p = lower[d] == MacBoundary::periodic, hi_p = upper[d] == MacBoundary::periodic;
    require(lo_p == hi_p, f + ".upper", to_string(upper[d]),
            std::string("must be periodic exactly when the lower end is (lower is ") + to_string(lower[d]) + ")");
  }
}

BoundaryCondition MacGrid::velocity_condition(int a, int d, int side) const {
  const MacBoundary b = side ? upper[d] : lower[d];
  switch (b) {
    case MacBoundary::periodic: return BoundaryCondition::periodic();
    case MacBoundary::dirichlet: return BoundaryCondition::dirichlet();
    case MacBoundary::neumann: return a == d ? BoundaryCondition::dirichlet() : BoundaryCondition::neumann();
  }
  return BoundaryCondition::periodic();
}


namespace {

// The box of a MAC grid with staggering g_d and end conditions bc(d, side) on each axis.
template <class Staggering, class Condition>
Box mac_box(const MacGrid& grid, Staggering g, Condition bc) {
  Box box;
  box.dims = grid.dims;
  for (int d = 0; d < grid.dims; ++d)
    box.axes[d] = Axis{grid.cells[d], grid.length[d], g(d), bc(d, 0), bc(d, 1), grid.origin[d]};
  box.validate();
  return box;
}

}  // namespace

Box MacGrid::component(int a) const {
  validate();
  require(a >= 0 && a < dims, "grid.component", a, "must be a velocity component index below dims");
  return mac_box(*this, [a](int d) { return d == a ? 1.0 : 0.5; },
                 [this, a](int d, int side) { return velocity_condition(a, d, side); });
}

Box MacGrid::scalar() const {
  validate();
  return mac_box(*this, [](int) { return 0.5; }, [this](int d, int) {
    return periodic(d) ? BoundaryCondition::periodic() : BoundaryCondition::neumann();
  });
}

MacGrid make_mac_grid(int dims, std::array<int, 3> cells, std::array<double, 3> length,
                      std::array<MacBoundary, 3> boundary) {
  MacGrid g;
  g.dims = dims;
  g.cells = cells;
  g.length = length;
  g.lower = boundary;
  g.upper = boundary;
  g.validate();
  return g;
}

VectorField zero_vector_field(const MacGrid& grid) {
  VectorField u;
  for (int a = 0; a < grid.dims; ++a) u[a] = dvec(grid.component(a).size(), 0.0);
  return u;
}

}  // namespace rbfib
