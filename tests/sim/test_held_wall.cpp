// A wall held exactly by a solve (sim/held_wall.hpp): in a channel sheared by its top wall, a
// plane of markers 2h apart above the bottom wall does not slip (the velocity interpolated at the
// markers after each step is zero to the rounding of the solve, where unheld it would be the
// shear's), the flow below it comes to rest, and at steady state the force the markers exert
// balances the shear stress over them; the mobility is built once per step size. Bad input is named.
#include "rbfib/core/error.hpp"
#include "rbfib/core/units.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/scene/scene.hpp"
#include "rbfib/sim/flow_profile.hpp"
#include "rbfib/sim/ib_step.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

namespace rbfib::sim {
namespace {

const double um = units::um;
constexpr double U_top = 0.3;  // cm/s (3 mm/s along x)

/// The 8 x 6 x 8 um channel, h = 0.5 um, its top wall at 3 mm/s along x, started as the shear.
ImmersedBoundary channel(double dt_us) {
  const scene::Scene sc = scene::parse_scene(R"(
domain:
  size: [8 um, 6 um, 8 um]
  periodic: [x, z]
  walls:
    y: {lower: [0 mm/s, 0 mm/s, 0 mm/s], upper: [3 mm/s, 0 mm/s, 0 mm/s]}
  initial_flow: shear
fluid: {density: 1 g/cm^3, viscosity: 1 cP}
grid: {cells: [16, 12, 16]}
time: {integrator: backward_forward_euler, dt: )" + std::to_string(dt_us) + R"( us, end: 1 ms}
ib: {kernel: bspline3}
)", "held wall test");
  return scene::build(sc);
}

/// Markers on the plane y = y0 every `spacing` in x and z (8 x 8 um); `dense`: the dense mobility.
HeldWall plane(double y0, double spacing, bool dense = false) {
  const int m = int(std::lround(8 * um / spacing)), n = m * m;
  host_vector<double> X(static_cast<std::size_t>(3 * n));
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < m; ++k) {
      const int p = i * m + k;
      X[p] = (i + 0.25) * spacing, X[n + p] = y0, X[2 * n + p] = (k + 0.25) * spacing;
    }
  return HeldWall{"plane", dvec(X.begin(), X.end()), dense};
}

TEST(HeldWall, MarkersDoNotSlipWhereTheShearWouldMoveThem) {
  ImmersedBoundary ib = channel(0.1);
  ib.add(plane(1.5 * um, 1.0 * um));  // 2h apart: 64 markers, 192 unknowns
  for (int s = 0; s < 5; ++s) {
    const IbStepReport r = ib.step();
    EXPECT_GT(r.seconds_held, 0.0);
    // Unheld, the markers would move with the shear: U_top y0 / Ly = 0.075 cm/s.
    EXPECT_LT(blas::norm_inf(ib.held_wall(0).velocity()), 1e-10 * U_top) << "step " << s;
  }
  EXPECT_EQ(ib.held_wall(0).mobilities(), 1u);  // one dt, one mobility
  EXPECT_TRUE(ib.held_wall(0).circulant());      // 2h apart on the periodic plane: the lattice is commensurate
}

TEST(HeldWall, CirculantMobilityHoldsAsTheDenseOneDoes) {
  // The same wall, its mobility from 3 trial steps and transforms over the lattice, and from 192
  // trial steps and an LU: the same held flow, and the same wall force but for the uniform normal
  // force, which moves no fluid between walls (the circulant solve gives it zero; the dense LU,
  // whose matrix is singular in that direction to rounding, whatever its pivot makes of it).
  ImmersedBoundary a = channel(0.1), b = channel(0.1);
  a.add(plane(1.5 * um, 1.0 * um));
  b.add(plane(1.5 * um, 1.0 * um, true));
  for (int s = 0; s < 3; ++s) a.step(), b.step();
  ASSERT_TRUE(a.held_wall(0).circulant());
  ASSERT_FALSE(b.held_wall(0).circulant());
  EXPECT_LT(blas::norm_inf(a.held_wall(0).velocity()), 1e-10 * U_top);
  std::vector<double> Fa(a.held_wall(0).force().begin(), a.held_wall(0).force().end());
  std::vector<double> Fb(b.held_wall(0).force().begin(), b.held_wall(0).force().end());
  const std::size_t n = Fa.size() / 3;
  for (std::vector<double>* F : {&Fa, &Fb}) {  // remove the mean normal (y) force
    double mean = 0;
    for (std::size_t k = 0; k < n; ++k) mean += (*F)[n + k] / double(n);
    for (std::size_t k = 0; k < n; ++k) (*F)[n + k] -= mean;
  }
  double diff = 0, size = 0;
  for (std::size_t k = 0; k < Fa.size(); ++k) diff = std::max(diff, std::abs(Fa[k] - Fb[k])), size = std::max(size, std::abs(Fb[k]));
  EXPECT_GT(size, 0.0);
  EXPECT_LT(diff, 1e-12 * size);  // measured 2.1e-15
  // The flows they leave agree to the same digits.
  const std::vector<double> ua = velocity_profile(a, {1, 0, 0}), ub = velocity_profile(b, {1, 0, 0});
  for (std::size_t j = 0; j < ua.size(); ++j) EXPECT_NEAR(ua[j], ub[j], 1e-10 * U_top) << "row " << j;
}

TEST(HeldWall, OnlyACommensurateLatticeOnAPeriodicPlaneIsCirculant) {
  const MacGrid grid = make_mac_grid(3, {16, 12, 16}, {8 * um, 6 * um, 8 * um}, {MacBoundary::periodic, MacBoundary::dirichlet, MacBoundary::periodic});
  const auto host = [](const HeldWall& w) { return std::vector<double>(w.X.begin(), w.X.end()); };
  const std::optional<MarkerLattice> L = commensurate_lattice(host(plane(1.5 * um, 1.0 * um)), grid);
  ASSERT_TRUE(L.has_value());
  EXPECT_EQ(L->normal, 1);
  EXPECT_EQ(L->n[0], 8);
  EXPECT_EQ(L->n[1], 8);
  EXPECT_TRUE(commensurate_lattice(host(plane(1.5 * um, 0.5 * um)), grid).has_value());    // one cell apart
  EXPECT_FALSE(commensurate_lattice(host(plane(1.5 * um, 8 * um / 6)), grid).has_value());  // 2.67 cells apart
  std::vector<double> X = host(plane(1.5 * um, 1.0 * um));
  X[64 + 5] += 0.01 * um;  // one marker off the plane
  EXPECT_FALSE(commensurate_lattice(X, grid).has_value());
  X = host(plane(1.5 * um, 1.0 * um));
  X[128 + 3] = X[128 + 2];  // z: two markers on one lattice point, one lattice point empty
  EXPECT_FALSE(commensurate_lattice(X, grid).has_value());
  // A plane normal to x (x periodic, but y is a wall axis): not translation invariant.
  std::vector<double> Y = host(plane(1.5 * um, 1.0 * um));
  std::swap_ranges(Y.begin(), Y.begin() + 64, Y.begin() + 64);
  EXPECT_FALSE(commensurate_lattice(Y, grid).has_value());
}

TEST(HeldWall, SteadyShearAboveItAndRestBelowIt) {
  // Backward Euler in the viscous term: 10 us steps reach the steady state of the 4.5 um gap
  // (slowest mode decays by 1 / (1 + nu k^2 dt) = 1/5.9 per step) in 30 steps to 1e-20.
  ImmersedBoundary ib = channel(10);
  const double y0 = 1.5 * um, Ly = 6 * um;
  ib.add(plane(y0, 1.0 * um));
  for (int s = 0; s < 30; ++s) ib.step();
  EXPECT_LT(blas::norm_inf(ib.held_wall(0).velocity()), 1e-10 * U_top);
  const std::vector<double> u = velocity_profile(ib, {1, 0, 0});  // x-z means per cell row
  // Below the markers the flow is brought to rest: the rows whose centres lie more than the
  // kernel's half-support (2h = 1 um) below the plane (measured: -0.6% of U_top at y = 0.25 um).
  EXPECT_LT(std::abs(u[0]), 0.02 * U_top) << "row y = 0.25 um";
  // Above, the shear between the plane and the top wall: linear in y through the held plane
  // within the kernel's smearing of where the wall sits (the effective plane within 2h of y0;
  // measured: 0.15 um above the markers, u = 0.2137 U_top here).
  const double lo = U_top * (4.75 * um - (y0 + 1 * um)) / (Ly - (y0 + 1 * um));
  const double hi = U_top * (4.75 * um - (y0 - 1 * um)) / (Ly - (y0 - 1 * um));
  EXPECT_GT(u[9], lo) << "row y = 4.75 um";
  EXPECT_LT(u[9], hi) << "row y = 4.75 um";
  // The markers' force balances the shear stress mu U / (Ly - y0) over the plane's 64 um^2 (the
  // same smearing bounds the gap): its sum is the force on the fluid, against the top wall's drag
  // (measured 4.87e-6 dyn: the stress above, 4.42e-6 at the measured slope, and the small one of
  // the flow below, which the markers also hold).
  const std::vector<double> F(ib.held_wall(0).force().begin(), ib.held_wall(0).force().end());
  double Fx = 0;
  for (std::size_t p = 0; p < F.size() / 3; ++p) Fx += F[p];
  const double mu = 0.01, area = 64 * um * um;
  EXPECT_LT(-Fx, mu * U_top / (Ly - (y0 + 1 * um)) * area);
  EXPECT_GT(-Fx, mu * U_top / (Ly - (y0 - 1 * um)) * area);
}

TEST(HeldWall, BadMarkersAndASecondWallAreNamed) {
  ImmersedBoundary ib = channel(0.1);
  EXPECT_THROW(ib.add(HeldWall{"empty", dvec()}), InputError);
  EXPECT_THROW(ib.add(HeldWall{"ragged", dvec(4, 1e-4)}), InputError);
  ib.add(plane(1.5 * um, 1.0 * um));
  EXPECT_THROW(ib.add(plane(2.5 * um, 1.0 * um)), InputError);
}

}  // namespace
}  // namespace rbfib::sim
