// The phase times of a run's steps (run/phase_times.hpp): sums and per-step medians of the series
// append_phases writes, and the block spread of the ratio of two runs' times.
#include "rbfib/run/phase_times.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::run {
namespace {

sim::IbStepReport step(double forces, double products, double spread, double fluid, double interp, double update) {
  sim::IbStepReport r;
  r.seconds_forces = forces;
  r.seconds_force_products = products;
  r.seconds_spreading = spread;
  r.seconds_fluid = fluid;
  r.seconds_interpolation = interp;
  r.seconds_update = update;
  return r;
}

TEST(PhaseTimes, SumsAndMediansOfTheSteps) {
  io::Series s;
  append_phases(s, step(1, 0.5, 2, 10, 1, 0.25));
  append_phases(s, step(3, 1.5, 2, 30, 1, 0.25));
  append_phases(s, step(2, 1.0, 4, 20, 3, 0.75));
  ASSERT_EQ(s.columns.size(), 6u);
  ASSERT_EQ(s.rows.size(), 3u);
  const PhaseTimes sum = phase_sums(s), med = phase_medians(s);
  EXPECT_EQ(sum.forces, 6);
  EXPECT_EQ(sum.force_products, 3);
  EXPECT_EQ(sum.solve, 60);
  EXPECT_EQ(sum.total(), 6 + 8 + 60 + 5 + 1.25);  // the products are part of the forces
  EXPECT_EQ(med.forces, 2);
  EXPECT_EQ(med.spread, 2);
  EXPECT_EQ(med.solve, 20);
  EXPECT_EQ(med.update, 0.25);
  append_phases(s, step(4, 0, 0, 0, 0, 0));
  EXPECT_EQ(phase_medians(s).forces, 2.5);  // an even count: the mean of the middle two
  EXPECT_EQ(phase_medians(io::Series{}).total(), 0);
}

TEST(PhaseTimes, BlockRatioSpread) {
  // blocks of a: 2, 4, 6 s; of b: 1, 2, 3 s: the ratio is 2 in every block
  EXPECT_EQ(block_ratio_std({2, 6, 12}, {1, 3, 6}), 0);
  // ratios 1 and 3: mean 2, sample standard deviation sqrt(2)
  EXPECT_NEAR(block_ratio_std({1, 4}, {1, 2}), std::sqrt(2.0), 1e-15);
  EXPECT_TRUE(std::isnan(block_ratio_std({1}, {1})));
  EXPECT_TRUE(std::isnan(block_ratio_std({1, 2}, {1})));
}

}  // namespace
}  // namespace rbfib::run
