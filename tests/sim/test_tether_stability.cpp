// The tethers' explicit stability bound (sim/tether_stability.hpp) against the numbers of its
// derivation (docs/derivations/tether_stability: its numpy model, an independent implementation of
// the same 1D sliding mode), and the rule that reproduces the seed's constants.
#include "rbfib/core/error.hpp"
#include "rbfib/sim/tether_stability.hpp"

#include <gtest/gtest.h>

using namespace rbfib;
using sim::TetherSheet;

namespace {
const double um = 1e-4, ns = 1e-9, cP = 1e-2;

/// The seed's endothelium (Sec. 5.2): 16,000 points over 16 x 16 um at y = 1 um in the 12 um channel.
TetherSheet seed_sheet(double h_um, double n_per_um2, double mu) {
  return TetherSheet{h_um * um, 12 * um, 1 * um, n_per_um2 / (um * um), 1.0, mu, ib::Kernel::bspline3};
}
}  // namespace

TEST(TetherStability, SlidingMobilityMatchesTheDerivationsModel) {
  // G1 (cm s^-1 dyn^-1) from docs/derivations/tether_stability (np.linalg.solve of the same system).
  const TetherSheet s1 = seed_sheet(0.2, 62.5, 1 * cP), s01 = seed_sheet(0.2, 62.5, 0.1 * cP);
  EXPECT_NEAR(sim::sliding_mobility(s1, 50 * ns), 2568892.175842556, 1e-9 * 2568892.175842556);
  EXPECT_NEAR(sim::sliding_mobility(s1, 100 * ns), 4316599.387892999, 1e-9 * 4316599.387892999);
  EXPECT_NEAR(sim::sliding_mobility(s1, 800 * ns), 15649422.909885097, 1e-9 * 15649422.909885097);
  EXPECT_NEAR(sim::sliding_mobility(s01, 50 * ns), 3410068.4678447787, 1e-9 * 3410068.4678447787);
}

TEST(TetherStability, ThresholdsOfTheSeedsConstants) {
  // The step at which (eta + c k dt) G1 = 1 with k = 2.5 dyn/cm, eta = 2.5e-7 dyn s/cm: the
  // derivation's 62.4 ns (1 cP), 47.3 ns (0.1 cP), 271 ns at h = 0.4 um (n_A = 16 um^-2), and
  // 45.4 ns with the spring at X*; its spectral radii agree with these to 4 digits.
  const double k = 2.5, eta = 2.5e-7;
  EXPECT_NEAR(sim::tether_dt_limit(seed_sheet(0.2, 62.5, 1 * cP), k, eta, false) / ns, 62.4363, 1e-3);
  EXPECT_NEAR(sim::tether_dt_limit(seed_sheet(0.2, 62.5, 0.1 * cP), k, eta, false) / ns, 47.3065, 1e-3);
  EXPECT_NEAR(sim::tether_dt_limit(seed_sheet(0.4, 16, 1 * cP), k, eta, false) / ns, 271.060, 1e-2);
  EXPECT_NEAR(sim::tether_dt_limit(seed_sheet(0.2, 62.5, 1 * cP), k, eta, true) / ns, 45.3704, 1e-3);
  // The seed's own step is inside its bound at 1 cP, outside at 0.1 cP.
  EXPECT_LT(sim::tether_gain(seed_sheet(0.2, 62.5, 1 * cP), k, eta, 50 * ns, false), 1);
  EXPECT_GT(sim::tether_gain(seed_sheet(0.2, 62.5, 0.1 * cP), k, eta, 50 * ns, false), 1);
}

TEST(TetherStability, TheRuleGivesTheSeedsConstantsAtItsStep) {
  // Gain 0.8 with the seed's split (eta = 2 dt k) at 50 ns: k = 2.49 dyn/cm, eta = 2.49e-7 dyn s/cm.
  const TetherSheet s = seed_sheet(0.2, 62.5, 1 * cP);
  const sim::TetherConstants c = sim::tether_constants_for_step(s, 50 * ns, 0.8);
  EXPECT_NEAR(c.k, 2.491346293232764, 1e-9);
  EXPECT_NEAR(c.eta, 2.491346293232764e-7, 1e-15);
  for (double dt : {50 * ns, 200 * ns, 800 * ns}) {  // the gain is the safety at every step
    const sim::TetherConstants r = sim::tether_constants_for_step(s, dt, 0.5);
    EXPECT_NEAR(sim::tether_gain(s, r.k, r.eta, dt, false), 0.5, 1e-12);
    EXPECT_NEAR(r.eta / r.k, 2 * dt, 1e-12 * dt);
  }
}

TEST(TetherStability, BadSheetsAreNamed) {
  TetherSheet s = seed_sheet(0.2, 62.5, 1 * cP);
  s.plane = 13 * um;
  EXPECT_THROW(sim::sliding_mobility(s, 50 * ns), InputError);
  s = seed_sheet(0.2, 62.5, 1 * cP);
  s.channel = 12.1 * um;
  EXPECT_THROW(sim::sliding_mobility(s, 50 * ns), InputError);
  EXPECT_THROW(sim::tether_constants_for_step(seed_sheet(0.2, 62.5, 1 * cP), 50 * ns, 1.5), InputError);
}
