// The studies' fits (studies/common/study.hpp): slopes and the order of a power law.
#include "common/study.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::study {
namespace {

TEST(StudyFits, SlopeAndPowerLawOrder) {
  EXPECT_NEAR(slope({0, 1, 2, 3}, {1, 3, 5, 7}), 2, 1e-12);
  EXPECT_NEAR(power_law_order({10, 20, 40}, {1e-2, 2.5e-3, 6.25e-4}), 2, 1e-12);
  EXPECT_TRUE(std::isnan(slope({1}, {1})));
}

}  // namespace
}  // namespace rbfib::study
