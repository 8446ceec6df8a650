// Shape measures of a closed surface (surface/shape_measures.hpp): vertex normals of a sphere point
// outward along the radius; a field linear in the reference angle alpha has no residual in the
// bands; a sphere is axisymmetric to the bands' resolution while one raised site is a bump; the
// front of a sphere is the cap within 45 degrees of +x, where H = -1 has no spread.
#include "rbfib/core/constants.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/shape_measures.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rbfib::surface {
namespace {

struct Sphere {
  SphereSites sites = bauer_spiral(2000);
  std::vector<Triangle> tris = sphere_triangulation(sites);
  std::vector<double> X;
  Sphere() {
    const std::size_t n = sites.lambda.size();
    X.resize(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
      double x[3];
      unit_sphere_point(sites.lambda[i], sites.theta[i], x);
      for (int d = 0; d < 3; ++d) X[d * n + i] = x[d];
    }
  }
  std::size_t n() const { return X.size() / 3; }
};

TEST(ShapeMeasures, VertexNormalsOfASpherePointAlongTheRadius) {
  const Sphere s;
  const std::vector<double> N = vertex_normals(s.tris, s.X);
  double worst = 0;
  for (std::size_t i = 0; i < s.n(); ++i) {
    double dot = 0;
    for (int d = 0; d < 3; ++d) dot += N[d * s.n() + i] * s.X[d * s.n() + i];
    worst = std::max(worst, 1 - dot);
  }
  EXPECT_LT(worst, 1e-3);  // the flat triangles' tilt, O(h^2) with h ~ 0.08
}

TEST(ShapeMeasures, BandsReproduceALineInAlpha) {
  const Sphere s;
  const AlphaBands b = alpha_bands(s.sites);
  EXPECT_EQ(b.members.size(), 18u);  // round(sqrt(2000) / 2.5)
  std::vector<double> q(s.n());
  for (std::size_t i = 0; i < s.n(); ++i) q[i] = 3 + 2 * b.alpha[i];
  const std::vector<double> r = band_residuals(b, q);
  EXPECT_LT(band_rms(b, r), 1e-12);
  std::size_t banded = 0;
  for (const auto& m : b.members) banded += m.size();
  EXPECT_NEAR(double(banded) / double(s.n()), (std::cos(pi / 12) + std::cos(pi / 12)) / 2, 0.01);  // 15-165 degrees
}

TEST(ShapeMeasures, OneRaisedSiteIsTheOnlyBump) {
  Sphere s;
  const AlphaBands b = alpha_bands(s.sites);
  const std::array<double, 3> c{0, 0, 0};
  const Axisymmetry round = axisymmetry(s.X, s.X, b, s.tris, c, 0.01);
  EXPECT_EQ(round.bumps, 0);
  EXPECT_LT(round.max, 0.005);  // a line through each band's arc: (band width)^2 / 8
  // raise the site nearest (0, 0, 1) by 0.05 along its normal
  std::size_t top = 0;
  for (std::size_t i = 0; i < s.n(); ++i)
    if (s.X[2 * s.n() + i] > s.X[2 * s.n() + top]) top = i;
  for (int d = 0; d < 3; ++d) s.X[d * s.n() + top] *= 1.05;
  const std::vector<double> N = vertex_normals(s.tris, s.X);
  const Axisymmetry bumped = axisymmetry(s.X, N, b, s.tris, c, 0.01);
  EXPECT_EQ(bumped.bumps, 1);
  EXPECT_GT(bumped.max, 0.04);
  EXPECT_GT(bumped.rms, round.rms);
}

TEST(ShapeMeasures, FrontOfASphereHasNoSpreadOfAConstant) {
  const Sphere s;
  const std::vector<std::size_t> front = facing_sites(s.X, s.X, {0, 0, 0}, +1);
  const std::vector<std::size_t> back = facing_sites(s.X, s.X, {0, 0, 0}, -1);
  const double cap = (1 - std::cos(pi / 4)) / 2;  // area fraction of a 45-degree cap
  EXPECT_NEAR(double(front.size()) / double(s.n()), cap, 0.01);
  EXPECT_NEAR(double(back.size()) / double(s.n()), cap, 0.01);
  for (std::size_t i : front) EXPECT_GT(s.X[i], std::cos(pi / 4));
  const Spread h = spread(std::vector<double>(s.n(), -1.0), front);
  EXPECT_EQ(h.count, int(front.size()));
  EXPECT_DOUBLE_EQ(h.mean, -1.0);
  EXPECT_LT(h.std, 1e-7);  // sqrt of a rounding error of mean(q^2) - mean(q)^2
  EXPECT_EQ(h.positive, 0.0);
  EXPECT_TRUE(std::isnan(spread(std::vector<double>(s.n(), 1.0), {front[0]}).mean));
  EXPECT_EQ(edge_jump(std::vector<double>(s.n(), 2.0), s.tris), 0.0);
}

}  // namespace
}  // namespace rbfib::surface
