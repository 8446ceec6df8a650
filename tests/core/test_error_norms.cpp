// The max-norm error of eqs. (90)-(91): the largest entrywise difference, relative to the
// reference's largest entry; arrays of different lengths are an InputError.
#include "rbfib/core/error.hpp"
#include "rbfib/core/error_norms.hpp"

#include <gtest/gtest.h>

namespace rbfib {
namespace {

TEST(MaxNormError, TakesTheLargestDifferenceOverTheLargestReferenceEntry) {
  const MaxNormError e = max_norm_error({1.0, -2.5, 4.0}, {1.5, -2.0, -8.0});
  EXPECT_EQ(e.abs, 12.0);  // |4 - (-8)|
  EXPECT_EQ(e.rel, 1.5);   // 12 / 8
}

TEST(MaxNormError, AnExactCopyHasNoError) {
  const std::vector<double> x = {0.1, -0.2, 0.3};
  const MaxNormError e = max_norm_error(x, x);
  EXPECT_EQ(e.abs, 0.0);
  EXPECT_EQ(e.rel, 0.0);
}

TEST(MaxNormError, DifferentLengthsAreAnInputError) {
  EXPECT_THROW(max_norm_error({1.0, 2.0}, {1.0}), InputError);
}

}  // namespace
}  // namespace rbfib
