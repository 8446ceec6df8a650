// The initialization of dissertation Sec. 5.2.1 (scene/packing.hpp).
#include "rbfib/cells/measure.hpp"
#include "rbfib/scene/packing.hpp"
#include "rbfib/cells/presets.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace rbfib;
using namespace rbfib::scene;

namespace {

const double um = 1e-4;
const Domain bumpy{16 * um, 12 * um, 16 * um, scene::EndotheliumSurface{0.75 * um, 1 * um, 16 * um, 16 * um}};

std::vector<double> sites_of(const ReferenceSites& r, const cells::Placement& p) { return cells::placed(r.X, r.n, p, "cell"); }

}  // namespace

TEST(Packing, ReferenceNormalsPointOutOfTheShape) {
  // The platelet is the ellipsoid 1.55 x 1.55 x 0.5 um: its outward normal is grad(x^2/a^2 + ...).
  const ReferenceSites p = reference_sites(cells::platelet_spec(400, 400));
  const double a = 1.55 * um, c = 0.5 * um;
  for (index_t i = 0; i < p.n; ++i) {
    const double x = p.X[std::size_t(i)], y = p.X[std::size_t(p.n + i)], z = p.X[std::size_t(2 * p.n + i)];
    double g[3] = {x / (a * a), y / (a * a), z / (c * c)};
    const double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(p.normals[std::size_t(d * p.n + i)], g[d] / gn, 1e-6) << i;
  }
}

TEST(Packing, TheRedCellsKeepTwoHApartAndTheLayoutIsReproducible) {
  const ReferenceSites r = reference_sites(cells::red_cell_spec(400, 1600));
  LayoutSpec spec;
  spec.h = 0.2 * um;
  std::mt19937_64 a(7), b(7);
  const Layout L = red_cell_layout(r, bumpy, spec, a), M = red_cell_layout(r, bumpy, spec, b);
  ASSERT_EQ(L.red_cells.size(), 8u);
  EXPECT_EQ(L.moved, 8);  // every cell got a random motion
  EXPECT_GE(L.closest, 2 * spec.h);
  // At a coarse grid (2h = 0.8 um, the rows leave 0.89 um) the moves shrink until they fit.
  std::mt19937_64 c(7);
  LayoutSpec coarse = spec;
  coarse.h = 0.4 * um;
  const Layout K = red_cell_layout(r, bumpy, coarse, c);
  EXPECT_EQ(K.moved, 8);
  EXPECT_GE(K.closest, 2 * coarse.h);
  for (std::size_t c = 0; c < 8; ++c) {
    for (int d = 0; d < 3; ++d) EXPECT_EQ(L.red_cells[c].center[std::size_t(d)], M.red_cells[c].center[std::size_t(d)]);
    EXPECT_NEAR(L.red_cells[c].center[1], 6 * um, spec.max_shift + 1e-12);
  }
  for (std::size_t x = 0; x < 8; ++x)
    for (std::size_t y = x + 1; y < 8; ++y)
      EXPECT_GE(cell_distance(sites_of(r, L.red_cells[x]), r.n, sites_of(r, L.red_cells[y]), r.n, bumpy), 2 * spec.h) << x << " " << y;
}

TEST(Packing, PlateletsFaceTheEndotheliumAtTheDrawnGap) {
  const ReferenceSites r = reference_sites(cells::red_cell_spec(400, 1600)), p = reference_sites(cells::platelet_spec(400, 400));
  LayoutSpec ls;
  ls.h = 0.2 * um;
  std::mt19937_64 rng(11);
  const Layout L = red_cell_layout(r, bumpy, ls, rng);
  const std::vector<double> red = batch_layout(r, L.red_cells);  // n x 3N, X[(d N + c) n + i]
  // An endothelium of 4,096 points on the bumpy surface (a lattice is enough here).
  std::vector<double> E(3 * 4096);
  for (int i = 0; i < 64; ++i)
    for (int k = 0; k < 64; ++k) {
      const std::size_t q = std::size_t(i * 64 + k);
      E[q] = (i + 0.5) * 0.25 * um, E[2 * 4096 + q] = (k + 0.5) * 0.25 * um;
      E[4096 + q] = bumpy.endothelium.height(E[q], E[2 * 4096 + q]);
    }
  PlateletSpec ps;
  const PlateletPlacement P = place_platelets(p, bumpy, E, red, r.n, 2, ps, rng);
  ASSERT_EQ(P.platelets.size(), 2u);
  for (std::size_t c = 0; c < 2; ++c) {
    const std::vector<double> Y = sites_of(p, P.platelets[c]);
    EXPECT_GE(P.gaps[c], 0.3 * um);
    EXPECT_LE(P.gaps[c], 1.0 * um);
    // Its closest approach to the endothelium is at most the drawn gap (the chosen point is there),
    // and it keeps 0.4 um from every red cell.
    EXPECT_LE(sheet_distance(Y, p.n, E, bumpy), P.gaps[c] + 1e-9);
    EXPECT_GT(sheet_distance(Y, p.n, E, bumpy), 0.0);
    for (std::size_t k = 0; k < 8; ++k)
      EXPECT_GE(cell_distance(Y, p.n, sites_of(r, L.red_cells[k]), r.n, bumpy), ps.red_cell_clearance);
  }
  // The two platelets sit over endothelium points at least 3.9 um apart: they are far apart.
  EXPECT_GT(cell_distance(sites_of(p, P.platelets[0]), p.n, sites_of(p, P.platelets[1]), p.n, bumpy), 0.5 * um);
}

TEST(Packing, ClosestCellsOfABatchIsTheSmallestPairDistance) {
  const ReferenceSites r = reference_sites(cells::red_cell_spec(400, 1600));
  LayoutSpec spec;
  spec.h = 0.2 * um;
  std::mt19937_64 rng(5);
  const Layout L = red_cell_layout(r, bumpy, spec, rng);
  const std::vector<double> X = batch_layout(r, L.red_cells);
  EXPECT_EQ(closest_cells(X, r.n, 8, bumpy), L.closest);
  const std::vector<double> Y = cells::cell_points(X, r.n, 8, 3), Z = sites_of(r, L.red_cells[3]);
  EXPECT_EQ(Y, Z);
}

TEST(Packing, StartingTimesFollowTheSettlingTime) {
  std::mt19937_64 rng(3);
  const std::vector<double> t = starting_times(17e-3, 3e-3, 1000, rng);
  EXPECT_GT(t.front(), 17e-3);
  for (std::size_t k = 1; k < t.size(); ++k) EXPECT_GT(t[k], t[k - 1]);
  EXPECT_NEAR((t.back() - 17e-3) / 1000, 3e-3, 0.3e-3);  // the mean gap, within 10%
}
