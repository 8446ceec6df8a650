// Slabs along z and their halos (dist/slabs.hpp) on however many ranks the test runs with: the
// split is FFTW's and covers the box once; scatter and gather invert each other; a halo fill
// copies the periodic neighbours' planes exactly; a halo sum adds every ghost plane into its owner
// exactly once; slabs too thin for the halo are refused on every rank.
#include "../common/random_field.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/dist/slabs.hpp"
#include "rbfib/grid/mac.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::dist {
namespace {

using MB = MacBoundary;

Box channel_scalar(int nx, int ny, int nz) {
  return make_mac_grid(3, {nx, ny, nz}, {1.0, 1.0, 1.0}, {MB::periodic, MB::dirichlet, MB::periodic}).scalar();
}

TEST(Slabs, CoverTheBoxOnceInFftwBlocks) {
  const Comm world;
  for (int nz : {5, 8, 13}) {  // 5 planes on 4 ranks: 2, 2, 1, 0
    const Slabs s(channel_scalar(4, 4, nz), world, "grid");
    const int block = (nz + world.size() - 1) / world.size();
    int next = 0;
    for (int r = 0; r < world.size(); ++r) {
      EXPECT_EQ(s.first(r), std::min(nz, next));
      EXPECT_EQ(s.planes(r), std::max(0, std::min(block, nz - next)));
      next += block;
    }
    EXPECT_EQ(world.sum(s.local_size()), s.box().size());
  }
}

TEST(Slabs, ScatterAndGatherInvertEachOther) {
  const Comm world;
  const Slabs s(channel_scalar(6, 5, 11), world, "grid");
  const dvec global = testing::random_vector(s.box().size(), 7);
  const dvec local = s.scatter(global);
  ASSERT_EQ(index_t(local.size()), s.local_size());
  const host_vector<double> back = s.gather(local), want = global;
  double worst = 0.0;
  for (std::size_t p = 0; p < want.size(); ++p) worst = std::max(worst, std::abs(back[p] - want[p]));
  EXPECT_EQ(world.max(worst), 0.0);
}

// The extended slab of a field given whole, ghosts included, by periodic wrap along z.
host_vector<double> extended_from_global(const Slabs& s, int g, const host_vector<double>& global) {
  const index_t ps = s.plane_size();
  const int nz = s.box().n(2);
  host_vector<double> e(static_cast<std::size_t>((s.planes() + 2 * g) * ps));
  for (int p = 0; p < s.planes() + 2 * g; ++p) {
    const int z = ((s.first() - g + p) % nz + nz) % nz;
    for (index_t q = 0; q < ps; ++q) e[p * ps + q] = global[z * ps + q];
  }
  return e;
}

TEST(Halo, FillCopiesTheNeighboursPlanes) {
  const Comm world;
  for (int g : {1, 2}) {
    const Slabs s(channel_scalar(4, 5, 4 * world.size() + 1), world, "grid");
    const Halo halo(s, g, "halo");
    const host_vector<double> global = testing::random_vector(s.box().size(), 11);
    const host_vector<double> want = extended_from_global(s, g, global);
    host_vector<double> start = want;  // owned planes right, ghosts garbage
    for (index_t q = 0; q < halo.owned_offset(); ++q) start[q] = start[start.size() - 1 - q] = -99.0;
    dvec e = start;
    halo.fill(e);
    const host_vector<double> got = e;
    double worst = 0.0;
    for (std::size_t p = 0; p < want.size(); ++p) worst = std::max(worst, std::abs(got[p] - want[p]));
    EXPECT_EQ(world.max(worst), 0.0) << "ghost planes " << g;
  }
}

TEST(Halo, SumAddsEveryGhostIntoItsOwnerOnce) {
  const Comm world;
  for (int g : {1, 3}) {
    const Slabs s(channel_scalar(4, 4, 4 * world.size()), world, "grid");
    const Halo halo(s, g, "halo");
    const index_t ps = s.plane_size();
    const int nz = s.box().n(2);
    // Rank r writes (r + 1) + 1000 (q + 1) into every plane of its extended slab, ghosts included:
    // global plane z then receives that from every rank whose extended slab covers z.
    auto value = [](int r, index_t q) { return (r + 1) + 1000.0 * double(q + 1); };
    dvec e(static_cast<std::size_t>(halo.extended_size()));
    {
      host_vector<double> h(e.size());
      for (std::size_t p = 0; p < h.size(); ++p) h[p] = value(world.rank(), index_t(p) % ps);
      e = h;
    }
    halo.sum(e);
    const host_vector<double> got = e;
    double worst = 0.0;
    for (int p = 0; p < s.planes() + 2 * g; ++p) {
      const bool ghost = p < g || p >= g + s.planes();
      const int z = s.first() - g + p;
      for (index_t q = 0; q < ps; ++q) {
        double want = 0.0;
        if (!ghost)
          for (int r = 0; r < world.size(); ++r)
            for (int c = s.first(r) - g; c < s.first(r) + s.planes(r) + g; ++c)
              if ((c % nz + nz) % nz == z) want += value(r, q);
        worst = std::max(worst, std::abs(got[p * ps + q] - want));
      }
    }
    EXPECT_EQ(world.max(worst), 0.0) << "ghost planes " << g;
  }
}

TEST(Halo, RefusesSlabsThinnerThanTheHalo) {
  const Comm world;
  const Slabs s(channel_scalar(4, 4, 4 * world.size()), world, "grid");
  EXPECT_THROW(Halo(s, 5, "interpolation halo"), InputError);
  try {
    Halo(s, 5, "interpolation halo");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("interpolation halo: planes per rank"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rbfib::dist
