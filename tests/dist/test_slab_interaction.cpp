// Spreading and interpolation on slabs (dist/slab_interaction.hpp) against the one-process
// algorithms on the whole grid (ib/interaction.hpp): 300 points spread over a channel (n_z = 20: 5 planes per rank on 4), each owned
// by the rank whose planes hold its z moved by up to 2 h either way (as a cell's points lie beyond
// its owner's planes), points near the periodic seam z = 0 included. Spread forces and
// interpolated velocities equal the whole grid's up to the order of summation: at most 1e-13 of
// the largest value (both sum at most 4^3 products per unknown or point). A point beyond the halo
// is refused on every rank, with the message of the rank that holds it.
#include "rbfib/core/error.hpp"
#include "rbfib/dist/slab_interaction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rbfib::dist {
namespace {

using MB = MacBoundary;

struct Points {
  host_vector<double> X;  // all points, X[d n + k]
  std::vector<int> owner;
  index_t n = 0;
};

Points random_points(const MacGrid& grid, const Slabs& slabs, index_t n, double shift_planes) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Points p;
  p.n = n;
  p.X.resize(3 * n);
  p.owner.resize(n);
  const double h = grid.h(2);
  const int nz = grid.cells[2];
  for (index_t k = 0; k < n; ++k) {
    p.X[k] = grid.length[0] * U(gen);
    p.X[n + k] = grid.length[1] * (0.2 + 0.6 * U(gen));
    // every tenth point within 2h of the seam z = 0 (on either side)
    p.X[2 * n + k] = k % 10 == 0 ? (U(gen) < 0.5 ? 2 * h * U(gen) : grid.length[2] - 2 * h * U(gen)) : grid.length[2] * U(gen);
    const double moved = p.X[2 * n + k] / h + shift_planes * (2 * U(gen) - 1);
    const int plane = ((int(std::floor(moved)) % nz) + nz) % nz;
    for (int r = 0; r < slabs.comm().size(); ++r)
      if (plane >= slabs.first(r) && plane < slabs.first(r) + slabs.planes(r)) p.owner[k] = r;
  }
  return p;
}

dvec mine(const Points& p, const host_vector<double>& values, int rank) {
  std::vector<index_t> ks;
  for (index_t k = 0; k < p.n; ++k)
    if (p.owner[k] == rank) ks.push_back(k);
  const index_t m = index_t(ks.size());
  host_vector<double> out(3 * m);
  for (int d = 0; d < 3; ++d)
    for (index_t j = 0; j < m; ++j) out[d * m + j] = values[d * p.n + ks[j]];
  return dvec(out);
}

TEST(SlabInteraction, SpreadsAndInterpolatesAsTheWholeGrid) {
  const Comm world;
  const MacGrid grid = make_mac_grid(3, {8, 10, 20}, {0.8, 1.0, 2.0}, {MB::periodic, MB::dirichlet, MB::periodic});
  const ib::Kernel kernel = ib::Kernel::peskin4;
  const int ghosts = SlabInteraction::ghosts_needed(2 * grid.h(2), grid.h(2), kernel);
  EXPECT_EQ(ghosts, 5);  // 2 planes of reach, half of 4, one for the staggering
  const SlabFluid fluid(grid, world, ghosts);
  SlabInteraction slab(fluid, kernel);
  const Points p = random_points(grid, fluid.slabs(), 300, 2.0);

  std::array<Box, 3> whole{grid.component(0), grid.component(1), grid.component(2)};
  ib::Interaction one(whole, kernel);
  host_vector<double> F(3 * p.n);
  for (index_t q = 0; q < 3 * p.n; ++q) F[q] = std::sin(0.37 * double(q)) + 0.1;
  const dvec X_all = p.X, F_all = F;

  // Spreading: the owned planes of every rank, gathered, against the whole grid's field.
  std::array<dvec, 3> f_one, f_many;
  one.spread(X_all, F_all, f_one);
  const dvec X = mine(p, p.X, world.rank());
  slab.spread(X, mine(p, F, world.rank()), f_many);
  double worst = 0.0, scale = 0.0;
  for (int c = 0; c < 3; ++c) {
    const host_vector<double> got = fluid.gather(fluid.local_grid().component(c), f_many[c]), want = f_one[c];
    for (std::size_t q = 0; q < want.size(); ++q) {
      worst = std::max(worst, std::abs(got[q] - want[q]));
      scale = std::max(scale, std::abs(want[q]));
    }
  }
  EXPECT_GT(scale, 0.0);
  EXPECT_LE(world.max(worst), 1e-13 * scale) << world.size() << " ranks";

  // Interpolation of a smooth field, ghosts filled from the whole field.
  std::array<dvec, 3> u_one, u_many;
  for (int c = 0; c < 3; ++c) {
    u_one[c] = sample(whole[c], [c](double x, double y, double z) { return std::cos(7 * x + c) * y * std::sin(4 * z); });
    u_many[c] = fluid.extend(fluid.local_grid().component(c), u_one[c]);
  }
  dvec U_one, U_many;
  one.interpolate(X_all, u_one, U_one);
  slab.interpolate(X, u_many, U_many);
  const host_vector<double> got = U_many, want = mine(p, host_vector<double>(U_one), world.rank());
  double u_worst = 0.0, u_scale = 0.0;
  for (std::size_t q = 0; q < want.size(); ++q) {
    u_worst = std::max(u_worst, std::abs(got[q] - want[q]));
    u_scale = std::max(u_scale, std::abs(want[q]));
  }
  EXPECT_LE(world.max(u_worst), 1e-13 * world.max(u_scale)) << world.size() << " ranks";
}

TEST(SlabInteraction, RefusesPointsBeyondTheHaloOnEveryRank) {
  const Comm world;
  const MacGrid grid = make_mac_grid(3, {8, 10, 20}, {0.8, 1.0, 2.0}, {MB::periodic, MB::dirichlet, MB::periodic});
  const SlabFluid fluid(grid, world, 4);
  SlabInteraction slab(fluid, ib::Kernel::peskin4);
  // Rank 0 alone takes a point 4.5 planes above its top plane, beyond what 4 ghost planes allow
  // with the kernel's support (3 planes); the others take none. On one rank the slab is the whole
  // period and every point has an image inside it.
  const double h = grid.h(2);
  host_vector<double> x;
  if (world.rank() == 0) x = host_vector<double>{0.4, 0.5, (fluid.slabs().planes() + 4.5) * h};
  const dvec X = x, F(x.size(), 1.0);
  std::array<dvec, 3> f;
  if (world.size() == 1) {
    EXPECT_NO_THROW(slab.spread(X, F, f));
  } else {
    try {
      slab.spread(X, F, f);
      ADD_FAILURE() << "a point beyond the halo was spread";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("X[0].z"), std::string::npos) << e.what();  // rank 0's message on every rank
      EXPECT_NE(std::string(e.what()).find("more ghost planes are needed"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace rbfib::dist
