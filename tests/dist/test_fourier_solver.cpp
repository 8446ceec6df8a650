// The distributed Fourier solver (dist/fourier_solver.hpp) against the one on a single process
// (fluid/fourier_solver.hpp), on however many ranks the test runs with: the channel's pressure
// (Neumann walls, singular), its velocity components' Helmholtz operators (Dirichlet walls,
// Appendix A's correction), and a triply periodic box; sizes that split unevenly, and a rank left
// without modes after the transpose on four ranks (n_x = 6).
//
// Both solvers are exact to rounding: the FFTs err by O(eps log n) relative to the data, and the
// solve multiplies that by at most the operator's condition number on mean-free data, below
// 4 n^2 / pi^2 ~ 40 here; so max |x_dist - x_one| <= 1e-12 max |x_one| leaves a factor of about 100.
#include "../common/random_field.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/dist/fourier_solver.hpp"
#include "rbfib/fluid/fourier_solver.hpp"
#include "rbfib/grid/mac.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace rbfib::dist {
namespace {

using MB = MacBoundary;

void expect_same_as_one_process(const Box& box, Correction corr, double alpha, double beta, const std::string& what) {
  const Comm world;
  const Slabs slabs(box, world, what);
  const dvec b = testing::random_vector(box.size(), 3);
  rbfib::FourierSolver one(box, corr, alpha, beta, what);
  dvec x_one;
  one.solve(b, x_one);
  dist::FourierSolver many(slabs, corr, alpha, beta, what);
  EXPECT_EQ(many.singular(), one.singular()) << what;
  dvec x;
  many.solve(slabs.scatter(b), x);
  const host_vector<double> mine = x, want = slabs.scatter(x_one);
  double worst = 0.0, scale = 0.0;
  for (std::size_t p = 0; p < want.size(); ++p) {
    worst = std::max(worst, std::abs(mine[p] - want[p]));
    scale = std::max(scale, std::abs(want[p]));
  }
  worst = world.max(worst);
  scale = world.max(scale);
  EXPECT_GT(scale, 0.0) << what;
  EXPECT_LE(worst, 1e-12 * scale) << what << " on " << world.size() << " ranks";
}

TEST(DistributedFourier, ChannelPressureMatchesOneProcess) {
  const MacGrid g = make_mac_grid(3, {6, 8, 10}, {0.6, 0.8, 1.0}, {MB::periodic, MB::dirichlet, MB::periodic});
  expect_same_as_one_process(g.scalar(), Correction::none, 0.0, -1.0, "poisson");
}

TEST(DistributedFourier, ChannelHelmholtzMatchesOneProcessPerComponent) {
  for (MB wall : {MB::dirichlet, MB::neumann}) {
    const MacGrid g = make_mac_grid(3, {6, 8, 10}, {0.6, 0.8, 1.0}, {MB::periodic, wall, MB::periodic});
    for (int a = 0; a < 3; ++a)
      expect_same_as_one_process(g.component(a), Correction::appendix_a, 1.0, -0.05,
                                 std::string("helmholtz u") + "xyz"[a] + " " + to_string(wall));
  }
}

TEST(DistributedFourier, TriplyPeriodicMatchesOneProcess) {
  const MacGrid g = make_mac_grid(3, {6, 5, 9}, {0.6, 0.5, 0.9}, {MB::periodic, MB::periodic, MB::periodic});
  expect_same_as_one_process(g.scalar(), Correction::none, 0.0, -1.0, "periodic poisson");
  expect_same_as_one_process(g.component(2), Correction::appendix_a, 1.0, -0.05, "periodic helmholtz uz");
}

// An odd nx: the real transform keeps k_x = 0..3 of 7, which 3 and 4 ranks share unevenly.
TEST(DistributedFourier, OddXMatchesOneProcess) {
  const MacGrid g = make_mac_grid(3, {7, 8, 10}, {0.7, 0.8, 1.0}, {MB::periodic, MB::dirichlet, MB::periodic});
  expect_same_as_one_process(g.scalar(), Correction::none, 0.0, -1.0, "poisson, nx = 7");
  expect_same_as_one_process(g.component(0), Correction::appendix_a, 1.0, -0.05, "helmholtz ux, nx = 7");
}

TEST(DistributedFourier, RefusesWallsAcrossXOrZ) {
  const Comm world;
  const MacGrid g = make_mac_grid(3, {8, 8, 8}, {1, 1, 1}, {MB::dirichlet, MB::periodic, MB::periodic});
  const Slabs slabs(g.scalar(), world, "grid");
  EXPECT_THROW(dist::FourierSolver(slabs, Correction::none, 0.0, -1.0, "poisson"), InputError);
}

}  // namespace
}  // namespace rbfib::dist
