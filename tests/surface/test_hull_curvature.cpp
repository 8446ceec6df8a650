// Unit tests of the general convex hull and of the edges' mean curvature (surface/triangulation.hpp):
// interior points are no vertex of the hull, the hull of a cube is its 12 triangles, the unsigned
// edge curvature of a fine sphere is 1/r, and a dent shows where the hull leaves the surface.
#include "rbfib/core/error.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/shapes.hpp"
#include "rbfib/surface/triangulation.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace rbfib;
using namespace rbfib::surface;

TEST(ConvexHull, CubeCornersMakeTheHullAndInteriorPointsDoNot) {
  std::vector<double> p;
  for (int i = 0; i < 8; ++i) p.insert(p.end(), {double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  p.insert(p.end(), {0.5, 0.5, 0.5, 0.2, 0.7, 0.4, 0.9, 0.1, 0.3});  // inside
  const std::vector<Triangle> hull = convex_hull(p);
  EXPECT_EQ(hull.size(), 12u);
  for (const Triangle& t : hull)
    for (index_t v : t) EXPECT_LT(v, 8) << "an interior point is a hull vertex";
  double volume = 0;  // the outward triangles enclose the unit cube
  for (const Triangle& t : hull) {
    const double* a = &p[3 * t[0]];
    const double* b = &p[3 * t[1]];
    const double* c = &p[3 * t[2]];
    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
  }
  EXPECT_NEAR(volume, 1.0, 1e-14);
  EXPECT_THROW(convex_hull({0, 0, 0, 1, 0, 0, 0, 1, 0}), InputError);
  EXPECT_THROW(convex_hull({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}), NumericalError);  // coplanar
}

TEST(EdgeMeanCurvature, IsOneOverRadiusOnAFineSphere) {
  const SphereSites sites = bauer_spiral(2000);
  const std::vector<Triangle> tris = sphere_triangulation(sites);
  const double r = 3.0;
  const std::vector<double> X = ellipsoid(r, r, r).points(sites);
  const std::vector<double> H = edge_mean_curvature(tris, X);
  double mean = 0;
  for (double h : H) mean += h / double(H.size());
  EXPECT_NEAR(mean * r, 1.0, 0.01);
  // Pointwise the edges' curvature is noisy on an irregular mesh (the paper: LDSM's curvature
  // "appears discontinuous and noisy"): within 25% of 1/r here, not better.
  for (double h : H) EXPECT_NEAR(h * r, 1.0, 0.25);
}

TEST(EdgeMeanCurvature, IsExactOnTheIcosahedron) {
  // Every vertex alike: five edges of length a at the exterior angle pi - acos(-sqrt(5)/3) and a
  // third of five equilateral triangles: |H| = 5 theta a / (4 (5 sqrt(3)/12) a^2) = sqrt(3) theta / a.
  const double g = (1 + std::sqrt(5.0)) / 2;
  const double v[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<double> p, X(36);
  for (int i = 0; i < 12; ++i)
    for (int d = 0; d < 3; ++d) p.push_back(v[i][d]), X[std::size_t(d * 12 + i)] = v[i][d];
  const std::vector<Triangle> tris = convex_hull(p);
  ASSERT_EQ(tris.size(), 20u);
  const double a = 2, theta = 3.141592653589793 - std::acos(-std::sqrt(5.0) / 3);
  for (double h : edge_mean_curvature(tris, X)) EXPECT_NEAR(h, std::sqrt(3.0) * theta / a, 1e-14);
}

TEST(EdgeMeanCurvature, ADentIsOffTheHull) {
  // Push the sites near the north pole inward: they leave the convex hull, the rest stays on it.
  const SphereSites sites = bauer_spiral(500);
  const std::vector<Triangle> tris = sphere_triangulation(sites);
  std::vector<double> X = ellipsoid(1, 1, 1).points(sites);
  const std::size_t n = X.size() / 3;
  std::vector<double> p(3 * n), z0(n);
  for (std::size_t i = 0; i < n; ++i) {
    z0[i] = X[2 * n + i];
    const double s = z0[i] > 0.9 ? 0.8 : 1.0;  // the cap sinks below the plane of its rim
    for (int d = 0; d < 3; ++d) p[3 * i + d] = X[d * n + i] *= s;
  }
  std::vector<char> on(n, 0);
  for (const Triangle& t : convex_hull(p))
    for (index_t v : t) on[std::size_t(v)] = 1;
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(bool(on[i]), z0[i] <= 0.9) << "site " << i << " at z = " << z0[i];
  EXPECT_EQ(edge_mean_curvature(tris, X).size(), n);
}
