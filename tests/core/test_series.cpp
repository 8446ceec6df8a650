// The least-squares line over a window and the longest interval of a flag (core/series.hpp).
#include "rbfib/core/series.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace rbfib;

TEST(Series, FitLineRecoversALineOverItsWindowOnly) {
  std::vector<double> x, y;
  for (int i = 0; i < 20; ++i) x.push_back(0.5 * i), y.push_back(x.back() < 3 ? 7.0 : 2 * (x.back() - 1.5));
  const LineFit f = fit_line(x, y, 3, 9.5);  // the line y = 2 (x - 1.5), zero at x = 1.5
  EXPECT_EQ(f.count, 14);
  EXPECT_NEAR(f.slope, 2, 1e-12);
  EXPECT_NEAR(f.x_intercept(), 1.5, 1e-12);
  EXPECT_NEAR(f.max_departure, 0, 1e-12);
  EXPECT_GT(fit_line(x, y, 0, 9.5).max_departure, 0.5);  // the step below x = 3 departs
  EXPECT_TRUE(std::isnan(fit_line(x, y, 3, 3.2).slope));              // one sample
}

TEST(Series, LongestIntervalSpansFirstToLastSampleOfTheLongestRun) {
  const std::vector<double> t{0, 1, 2, 3, 4, 5, 6, 7};
  EXPECT_EQ(longest_interval(t, {true, true, false, true, true, true, false, true}), 2.0);
  EXPECT_EQ(longest_interval(t, {false, false, false, false, false, true, true, true}), 2.0);  // open at the end
  EXPECT_EQ(longest_interval(t, std::vector<bool>(8, false)), 0.0);
  EXPECT_EQ(longest_interval(t, std::vector<bool>(8, true)), 7.0);
}

TEST(Series, OscillationFrequencyOfASineIgnoresTheStartAndJitter) {
  std::vector<double> t, x;
  for (int i = 0; i <= 4500; ++i) {
    t.push_back(1e-4 * i);  // 0.45 s: four periods after 0.05 s
    x.push_back(t.back() < 0.05 ? 5.0 : 2 + std::sin(2 * M_PI * 10 * t.back()) + 0.01 * ((i % 2) ? 1 : -1));
  }
  EXPECT_NEAR(oscillation_frequency(t, x, 0.05), 10, 0.1);  // 10/s about a mean of 2, the start left out
  EXPECT_TRUE(std::isnan(oscillation_frequency(t, std::vector<double>(t.size(), 1.0), 0)));  // no crossing
  EXPECT_EQ(mean_interval({1, 2, 4}), 1.5);
  EXPECT_EQ(zero_crossing({0, 1}, {-1, 3}, 1), 0.25);
}

TEST(Series, SuccessiveOrderIsExactForAPowerLawInH) {
  // u_r = u + C h_r^p with h_r = 1 / r: eps_r = |u_r - u_{r+1}| gives back p from any r.
  for (double p : {1.0, 2.0, 3.5})
    for (int r : {1, 2, 4}) {
      auto eps = [p](int k) { return std::abs(std::pow(1.0 / k, p) - std::pow(1.0 / (k + 1), p)); };
      EXPECT_NEAR(successive_order(eps(r) / eps(r + 1), r), p, 1e-9) << p << " " << r;
    }
  EXPECT_TRUE(std::isnan(successive_order(0.5, 1)));  // errors growing with refinement
}

TEST(Series, RisingCrossingInLogX) {
  // y rises through 1 between x = 10 and 40 (0.5 -> 1.5): halfway in log x, x = 20.
  EXPECT_NEAR(rising_crossing_log({5, 10, 40}, {0.2, 0.5, 1.5}, 1.0), 20.0, 1e-12);
  // The sample above is not finite: the last one at or below.
  EXPECT_EQ(rising_crossing_log({5, 10, 40}, {0.2, 0.5, INFINITY}, 1.0), 10.0);
  // Never rises through it (or starts above it): NaN.
  EXPECT_TRUE(std::isnan(rising_crossing_log({5, 10}, {0.2, 0.5}, 1.0)));
  EXPECT_TRUE(std::isnan(rising_crossing_log({5, 10}, {1.2, 1.5}, 1.0)));
}

TEST(Series, UnwrapContinuesAnglesAcrossThePeriod) {
  const std::vector<double> a = unwrap({3.0, -3.0, -0.2}, 2 * M_PI);
  EXPECT_NEAR(a[1], -3.0 + 2 * M_PI, 1e-12);
  EXPECT_NEAR(a[2], -0.2 + 2 * M_PI, 1e-12);
}

TEST(Series, SlopePowerLawOrderAndMedian) {
  EXPECT_NEAR(slope({0, 1, 2, 3}, {1, 3, 5, 7}), 2, 1e-12);
  EXPECT_NEAR(power_law_order({10, 20, 40}, {1e-2, 2.5e-3, 6.25e-4}), 2, 1e-12);
  EXPECT_TRUE(std::isnan(slope({1}, {1})));
  EXPECT_EQ(median({3, 1, 2}), 2);
  EXPECT_EQ(median({4, 1, 2, 3}), 2.5);
  EXPECT_TRUE(std::isnan(median({})));
}
