#pragma once
// The channel of the distributed tests that step the coupled problem (test_cell_owners.cpp,
// test_tethered_points.cpp): 16 x 16 x 28 um, walls in y, periodic in x and z, h = 1 um, plasma of
// 1 cP, backward-forward Euler at 0.2 us, the B3 kernel; its starting flow along z,
// u_z = W sin(pi y / L_y), W = 20 cm/s.
#include "rbfib/core/units.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <cmath>
#include <memory>

namespace rbfib::dist {

struct Channel {
  MacGrid grid = make_mac_grid(3, {16, 16, 28}, {16 * units::um, 16 * units::um, 28 * units::um},
                               {MacBoundary::periodic, MacBoundary::dirichlet, MacBoundary::periodic});
  FluidParameters fluid{1.0, units::cP};
  NavierStokesOptions options;
  sim::IbOptions ib;
  Channel() {
    options.dt = 0.2 * units::us;
    ib.kernel = ib::Kernel::bspline3;
  }
  /// The coupled step with nothing immersed, on one process (parts null) or on this rank's slab.
  sim::ImmersedBoundary empty(std::shared_ptr<const FluidDecomposition> parts) const {
    return sim::ImmersedBoundary(std::make_unique<NavierStokesStep>(grid, fluid, options, BoundaryVelocity{}, parts), ib);
  }
};

/// Sets the starting flow, whole or on this rank's slab.
inline void start_flow(sim::ImmersedBoundary& s, const FluidDecomposition* parts, const MacGrid& grid) {
  const double W = 20.0, Ly = grid.length[1];  // cm/s
  MacOperators whole(grid);
  dvec w = sample(whole.component_box(2), [=](double, double y, double) { return W * std::sin(M_PI * y / Ly); });
  s.fluid_state().u[2] = parts ? parts->extend(s.fluid().operators().component_box(2), w) : w;
}

}  // namespace rbfib::dist
