// The net force of point forces (mechanics/net_force.hpp): |sum_i F_i|_inf and max_i |F_i|_inf on
// forces whose sum is known exactly.
#include "rbfib/mechanics/net_force.hpp"

#include <gtest/gtest.h>

namespace rbfib::mechanics {
namespace {

TEST(NetForce, SumAndLargestComponent) {
  // three points, n x 3 column-major: x = (1, -1, 0.5), y = (2, -2, 0), z = (-4, 1, 0.25)
  const std::vector<double> F = {1, -1, 0.5, 2, -2, 0, -4, 1, 0.25};
  EXPECT_EQ(net_force_inf(F), 2.75);  // sums 0.5, 0, -2.75
  EXPECT_EQ(max_force_inf(F), 4);
  EXPECT_EQ(net_force_inf({1, -1, 2, -2, 3, -3}), 0);  // balanced pairs
}

}  // namespace
}  // namespace rbfib::mechanics
