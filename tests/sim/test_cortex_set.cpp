// Unit tests of the cortex as a Lagrangian set (sim/cortex.hpp) in the coupled step: it joins only
// Chapter 3's forward Euler after its membrane; the links balance in the spread force; a step is
// eq. (104) written out; a detached region carries no force; a checkpoint carries the cortex and a
// restored step continues bit for bit.
#include "../common/errors.hpp"
#include "rbfib/fluid/periodic_stokes.hpp"
#include "rbfib/io/checkpoint.hpp"
#include "rbfib/linalg/blas.hpp"
#include "rbfib/sim/ib_step.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace rbfib;
using namespace rbfib::sim;
using rbfib::testing::field_of;
using MB = MacBoundary;

namespace {

const surface::SphereSites& sites() {
  static const surface::SphereSites s = surface::bauer_spiral(300);
  return s;
}

/// A unit LDSM membrane (neo-Hookean + tension) and a cortex of radius 0.95 under it, in [-2, 2]^3.
LdsmShell membrane() {
  LdsmShell s;
  s.name = "membrane";
  s.triangles = surface::sphere_triangulation(sites());
  s.reference = surface::ellipsoid(1, 1, 1).points(sites());
  s.X = s.reference;
  s.energies = {mechanics::EnergyDensity::neo_hookean_paper(1, 1), mechanics::EnergyDensity::surface_tension(1)};
  return s;
}

Cortex cortex() {
  Cortex c;
  c.name = "cortex";
  c.triangles = surface::sphere_triangulation(sites());
  c.reference = surface::ellipsoid(0.95, 0.95, 0.95).points(sites());
  c.X = c.reference;
  c.k = 2;
  c.k_adh = 50;
  c.xi = 4;
  return c;
}

ImmersedBoundary step_of(Coupling coupling, double dt = 1e-3) {
  MacGrid g = make_mac_grid(3, {16, 16, 16}, {4.0, 4.0, 4.0}, {MB::periodic, MB::periodic, MB::periodic});
  g.origin = {-2, -2, -2};
  IbOptions o;
  o.coupling = coupling;
  o.kernel = ib::Kernel::peskin4;
  o.stopping_condition = false;
  return ImmersedBoundary(std::make_unique<PeriodicStokesStep>(g, FluidParameters{1.0, 1.0}, dt, true), o);
}

double sum(const dvec& v) {
  double s = 0;
  for (double x : std::vector<double>(v.begin(), v.end())) s += x;
  return s;
}

}  // namespace

TEST(CortexSet, JoinsOnlyForwardEulerAfterItsMembrane) {
  ImmersedBoundary seed = step_of(Coupling::seed);
  const index_t s = seed.add(membrane());
  EXPECT_EQ(field_of([&] { seed.add(cortex(), seed.shell(s)); }), "cortex 'cortex': coupling");
  ImmersedBoundary a = step_of(Coupling::forward_euler), b = step_of(Coupling::forward_euler);
  const index_t sb = b.add(membrane());
  EXPECT_EQ(field_of([&] { a.add(cortex(), b.shell(sb)); }), "cortex 'cortex': membrane");
  Cortex bad = cortex();
  bad.xi = 0;
  EXPECT_EQ(field_of([&] { b.add(bad, b.shell(sb)); }), "cortex 'cortex': drag coefficient xi (dyn s/cm^3)");
}

TEST(CortexSet, SpreadForceHasNoNetForceAndAStepIsEq104) {
  // Every force is internal (the membrane's, the lattice's, the links' equal and opposite pairs),
  // so the spread density sums to zero; the cortex moves by dt (U + F / (xi dA)).
  ImmersedBoundary ib = step_of(Coupling::forward_euler);
  const index_t s = ib.add(membrane());
  const index_t c = ib.add(cortex(), ib.shell(s));
  const std::vector<double> X0 = ib.cortex(c).cortex().X;
  ib.step();
  const CortexSet& set = ib.cortex(c);
  double scale = 0;
  for (double f : set.force()) scale = std::max(scale, std::abs(f));
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(sum(ib.force_density()[a]) * std::pow(4.0 / 16, 3), 0.0, 1e-12 * scale) << "component " << a;
  // eq. (104) against the flow of the step, interpolated at X^n
  const MacOperators& ops = ib.fluid().operators();
  ib::Interaction I({ops.component_box(0), ops.component_box(1), ops.component_box(2)}, ib::Kernel::peskin4);
  dvec Xd(X0.begin(), X0.end()), Ud;
  I.interpolate(Xd, ib.fluid_state().u, Ud);
  const std::vector<double> U(Ud.begin(), Ud.end());
  const std::size_t n = X0.size() / 3;
  for (std::size_t i = 0; i < X0.size(); ++i) {
    const double expect = X0[i] + 1e-3 * (U[i] + set.force()[i] / (4 * set.lattice().dA[i % n]));
    EXPECT_NEAR(set.cortex().X[i], expect, 1e-14) << "entry " << i;
  }
}

TEST(CortexSet, DetachedLinksPullNeitherSide) {
  ImmersedBoundary ib = step_of(Coupling::forward_euler);
  LdsmShell m = membrane();
  for (double& x : m.X) x *= 1.02;  // every link stretched
  const index_t s = ib.add(m);
  const index_t c = ib.add(cortex(), ib.shell(s));
  const std::size_t n = sites().size();
  std::vector<char> attached(n, 1);
  for (std::size_t i = 0; i < n; ++i) attached[i] = m.reference[2 * n + i] < 0.8;  // a cap at the top detached
  ib.cortex(c).set_attached(attached);
  ib.step();
  const std::vector<double>& Fm = ib.cortex(c).membrane_force();
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      if (attached[i])
        EXPECT_NE(Fm[d * n + i], 0.0);
      else
        EXPECT_EQ(Fm[d * n + i], 0.0) << "site " << i;
    }
  EXPECT_EQ(field_of([&] { ib.cortex(c).set_attached(std::vector<char>(n - 1, 1)); }), "cortex 'cortex': adhesion links");
}

TEST(CortexSet, ACheckpointCarriesTheCortexAndARestoredStepContinuesBitForBit) {
  auto build = [] {
    auto ib = std::make_unique<ImmersedBoundary>(step_of(Coupling::forward_euler));
    LdsmShell m = membrane();
    for (double& x : m.X) x *= 1.01;
    const index_t s = ib->add(m);
    ib->add(cortex(), ib->shell(s));
    return ib;
  };
  auto a = build();
  for (int k = 0; k < 3; ++k) a->step();
  const std::string path = (std::filesystem::temp_directory_path() / "rbfib_cortex_checkpoint.h5").string();
  io::write_checkpoint(path, "cortex test", *a);
  const io::Checkpoint k = io::read_checkpoint(path);
  std::filesystem::remove(path);
  ASSERT_EQ(k.state.cortices.size(), 1u);
  EXPECT_TRUE(k.state.cortices[0] == a->cortex(0).cortex().X);
  auto b = build();
  b->restore(k.state);
  for (int s = 0; s < 2; ++s) {
    a->step();
    b->step();
  }
  EXPECT_TRUE(a->cortex(0).cortex().X == b->cortex(0).cortex().X);
  EXPECT_TRUE(a->shell(0).shell().X == b->shell(0).shell().X);
  io::Checkpoint other = k;
  other.state.cortices.clear();
  auto c = build();
  EXPECT_EQ(field_of([&] { c->restore(other.state); }), "checkpoint: cortices");
}
