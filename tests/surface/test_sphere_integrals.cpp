// Exact integrals over S^2 against Gauss product quadrature (exact for harmonics of its degree):
// exp(a . x) to rounding at modest degree (its harmonic coefficients fall like |a|^l / l!), and
// |x - y|^p exactly for even p (a polynomial of degree p/2 in x . y); the RBF weights of eq.
// (2.22) integrate exp(a . x) to their order.
#include "rbfib/core/constants.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/quadrature.hpp"
#include "rbfib/surface/sphere_integrals.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::surface {
namespace {

TEST(SphereIntegrals, ExponentialMatchesGaussProductQuadrature) {
  std::vector<double> w;
  const SphereSites s = gauss_product_sites(20, 40, w);
  EXPECT_EQ(sphere_integral_exp({0, 0, 0}), 4 * pi);
  for (const std::array<double, 3>& a : {std::array<double, 3>{1, 0, 0}, {0.3, -0.8, 0.5}, {0, 0, 2}})
    EXPECT_LT(exp_quadrature_error(s, w, a), 1e-13) << a[0] << " " << a[1] << " " << a[2];  // ~10 eps of e^2 4 pi
}

TEST(SphereIntegrals, EvenDistancePowersAreIntegratedExactly) {
  std::vector<double> w;
  const SphereSites s = gauss_product_sites(6, 12, w);  // exact to degree 11
  const double y[3] = {0.36, 0.48, 0.8};
  for (int p : {0, 2, 4, 6}) {
    double I = 0;
    for (index_t i = 0; i < s.size(); ++i) {
      double x[3];
      unit_sphere_point(s.lambda[i], s.theta[i], x);
      const double r2 = (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]);
      I += w[i] * std::pow(r2, p / 2);
    }
    const double exact = sphere_integral_distance_power(p);
    EXPECT_NEAR(I, exact, 1e-13 * exact) << "p = " << p;
  }
  EXPECT_DOUBLE_EQ(sphere_integral_distance_power(2), 8 * pi);  // int (2 - 2 x . y) = 8 pi
  EXPECT_THROW(sphere_integral_distance_power(-2), InputError);
}

TEST(SphereIntegrals, RbfWeightsIntegrateTheExponential) {
  const SphereSites s = bauer_spiral(200);
  const RbfWeights q = rbf_sphere_weights(s, 3);
  EXPECT_LT(exp_quadrature_error(s, q.w, {0.3, -0.8, 0.5}), 1e-5);  // 1.1e-6 worst over four directions
  EXPECT_THROW(exp_quadrature_error(s, std::vector<double>(3, 1.0), {1, 0, 0}), InputError);
}

}  // namespace
}  // namespace rbfib::surface
