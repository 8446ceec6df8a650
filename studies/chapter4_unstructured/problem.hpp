#pragma once
// chapter4_unstructured's test problem (seed Sec. 4.2.1): n points at random in the 16 um triply
// periodic box, tethered to their initial positions, in the shear flow u = (0, 0, gamma_dot (y - 8
// um)) sampled on the MAC grid; the time steps of main.cpp's header, timed per call.
#include "rbfib/core/units.hpp"
#include "rbfib/ib/grid.hpp"
#include "rbfib/ib/interaction.hpp"

#include <array>
#include <chrono>

namespace rbfib::unstructured {

using namespace rbfib::ib;

struct Params {
  double box = 16.0 * units::um;
  double shear_rate = 1000.0;                      // 1/s
  double spring = 1e-2 * units::dyn / units::cm;   // k
  double viscosity = 0.1 * units::cP;              // plasma, seed Sec. 1.1
  double dt = 0.1 * units::us;
  ib::Kernel kernel = ib::Kernel::bspline3;
};

/// Wall seconds since t0.
double seconds_since(std::chrono::steady_clock::time_point t0);

/// n points uniformly at random in the box [0, L)^3 (3n values, x then y then z).
host_vector<double> random_points(index_t n, double L, unsigned seed);

/// The shear flow on the MAC grid (only the z component is nonzero; it lives at y = h (j + 1/2))
/// and its background force f_bg = -mu Lap u, nonzero on the two rows next to the seam y = 0.
struct Flow {
  std::array<dvec, 3> u, f_bg;
  double max_background = 0.0;
};
Flow shear_flow(const std::array<Box, 3>& boxes, const Params& p);

struct Timing {
  double interpolate = NAN, spread = NAN;  // median seconds per call
};

/// Runs `steps` time steps of the tethered-point problem and returns the median time per call of
/// interpolation and of spreading (both components-inclusive: one call handles all three).
Timing run_steps(Interaction& ib, const Flow& flow, const host_vector<double>& X0h, const Params& p, int steps,
                 Interpolation interp, Spreading spread);

}  // namespace rbfib::unstructured
