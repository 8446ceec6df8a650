// The net force |sum_i F^_i|_inf (Sec. 4.1's quadrature error) and the largest force: column sums of the n x 3
// column-major layout; a uniform pressure on the sphere with Gauss product weights (exact for
// the degree-1 normal) sums to zero up to rounding.
#include "rbfib/core/error.hpp"
#include "rbfib/mechanics/net_force.hpp"
#include "rbfib/surface/point_sets.hpp"

#include <gtest/gtest.h>

namespace rbfib::mechanics {
namespace {

TEST(NetForce, SumsEachComponentOverTheSites) {
  // Two sites: x = (1, 2), y = (-4, 1), z = (0.5, 0.25): sums 3, -3, 0.75.
  EXPECT_EQ(net_force_inf({1, 2, -4, 1, 0.5, 0.25}), 3.0);
  EXPECT_EQ(net_force_inf({1, 2, -4, -1, 0.5, 0.25}), 5.0);
}

TEST(NetForce, UniformPressureOnTheSphereCancels) {
  std::vector<double> w;
  const surface::SphereSites s = surface::gauss_product_sites(8, 16, w);
  const std::size_t n = w.size();
  std::vector<double> F(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    double x[3];
    surface::unit_sphere_point(s.lambda[i], s.theta[i], x);
    for (int d = 0; d < 3; ++d) F[d * n + i] = -x[d] * w[i];  // F^_i = -p n_i dA_i, p = 1
  }
  EXPECT_LT(net_force_inf(F), 1e-14);  // 4 pi in all, about 100 eps
}

TEST(NetForce, SumAndLargestComponent) {
  // three points, n x 3 column-major: x = (1, -1, 0.5), y = (2, -2, 0), z = (-4, 1, 0.25)
  const std::vector<double> F = {1, -1, 0.5, 2, -2, 0, -4, 1, 0.25};
  EXPECT_EQ(net_force_inf(F), 2.75);  // sums 0.5, 0, -2.75
  EXPECT_EQ(max_force_inf(F), 4);
  EXPECT_EQ(net_force_inf({1, -1, 2, -2, 3, -3}), 0);  // balanced pairs
}

TEST(NetForce, ALengthNotAMultipleOfThreeIsAnInputError) {
  EXPECT_THROW(net_force_inf({1.0, 2.0}), InputError);
}

}  // namespace
}  // namespace rbfib::mechanics
