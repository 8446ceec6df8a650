#include "cases.hpp"

#include "rbfib/core/units.hpp"
#include "rbfib/fluid/exact_solutions.hpp"

namespace rbfib::study {

using MB = MacBoundary;

// Seed, Section 2 opening: plasma rho = 1 g/cm^3, mu = 0.1 cP (the value the seed states).
static FluidParameters plasma() { return FluidParameters{1.0 * units::g / (units::cm * units::cm * units::cm), 0.1 * units::cP}; }

ExactProblem taylor_green(int n, int nz) {
  ExactProblem p;
  p.name = "taylor_green";
  const double L = 16 * units::um;
  p.grid = make_mac_grid(3, {n, n, nz}, {L, L, L}, {MB::periodic, MB::periodic, MB::periodic});
  p.fluid = plasma();
  exact::TaylorGreen tg{L, 1.0 * units::cm / units::s, p.fluid.viscosity / p.fluid.density, p.fluid.density};
  p.velocity = [tg](int a, double t, double x, double y, double z) { return tg.velocity(a, t, x, y, z); };
  p.pressure = [tg](double t, double x, double y, double z) { return tg.pressure(t, x, y, z); };
  p.t0 = 0.0;
  p.t1 = 4 * units::us;
  return p;
}

ExactProblem couette(int ny, int nxz) {
  ExactProblem p;
  p.name = "couette";
  const double H = 12 * units::um, U = 12 * units::mm / units::s;
  p.grid = make_mac_grid(3, {nxz, ny, nxz}, {16 * units::um, H, 16 * units::um}, {MB::periodic, MB::dirichlet, MB::periodic});
  p.fluid = plasma();
  exact::Couette c{H, U, p.fluid.viscosity / p.fluid.density};
  p.velocity = [c](int a, double t, double x, double y, double z) { return c.velocity(a, t, x, y, z); };
  p.boundary = [U](int a, int d, int side, double, double, double, double) {
    return (a == 0 && d == 1 && side == 1) ? U : 0.0;  // top wall moves in x
  };
  // Start from the series at t0 = 10 us (the data at t = 0 jump at the moving wall, which limits
  // any scheme's order); compare at t1 = 20 us.
  p.t0 = 10 * units::us;
  p.t1 = 20 * units::us;
  return p;
}

ExactProblem manufactured(int n) {
  ExactProblem p;
  p.name = "manufactured";
  p.grid = make_mac_grid(3, {n, n, n}, {1.0, 1.0, 1.0}, {MB::periodic, MB::dirichlet, MB::dirichlet});
  p.fluid = FluidParameters{1.0, 0.1};
  exact::Manufactured m;
  m.rho = p.fluid.density;
  m.mu = p.fluid.viscosity;
  p.velocity = [m](int a, double t, double x, double y, double z) { return m.velocity(a, t, x, y, z); };
  p.pressure = [m](double t, double x, double y, double z) { return m.pressure(t, x, y, z); };
  p.force = [m](int a, double t, double x, double y, double z) { return m.force(a, t, x, y, z); };
  p.boundary = [m](int a, int, int, double t, double x, double y, double z) { return m.velocity(a, t, x, y, z); };
  p.t0 = 0.0;
  p.t1 = 0.04;
  return p;
}

}  // namespace rbfib::study
