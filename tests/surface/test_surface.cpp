// Unit tests of the surface module: harmonics, point sets, interpolation operators, quadrature,
// geometry and the triangulation, against closed forms.
#include "rbfib/core/error.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/harmonics.hpp"
#include "rbfib/surface/operators.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/quadrature.hpp"
#include "rbfib/surface/shapes.hpp"
#include "rbfib/surface/triangulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

using namespace rbfib;
using namespace rbfib::surface;

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();

double legendre(int l, double x) {
  double p0 = 1, p1 = x;
  if (l == 0) return 1;
  for (int k = 2; k <= l; ++k) {
    const double p2 = ((2.0 * k - 1) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  return p1;
}
}  // namespace

TEST(Harmonics, OrthonormalUnderGaussProductRule) {
  // The product rule with 24 x 48 nodes integrates degree <= 47 exactly: products of degree <= 20
  // harmonics (degree <= 40) integrate to delta_ij up to rounding (~ n_nodes eps).
  const int M = 20, np = sh_count(M);
  std::vector<double> w;
  const SphereSites s = gauss_product_sites(24, 48, w);
  std::vector<double> G(np * np, 0.0), y(np);
  for (index_t i = 0; i < s.size(); ++i) {
    real_harmonics(M, s.lambda[i], s.theta[i], y.data());
    for (int a = 0; a < np; ++a)
      for (int b = 0; b < np; ++b) G[a * np + b] += w[i] * y[a] * y[b];
  }
  double err = 0;
  for (int a = 0; a < np; ++a)
    for (int b = 0; b < np; ++b) err = std::max(err, std::abs(G[a * np + b] - (a == b ? 1.0 : 0.0)));
  EXPECT_LT(err, 2000 * eps);
}

TEST(Harmonics, AdditionTheoremAtDegree120) {
  // sum_k Y_l^k(p) Y_l^k(q) = (2l+1)/(4 pi) P_l(p . q) holds for the orthonormal real set; at
  // l = 120 it checks the recurrences' stability (the sum has magnitude ~ (2l+1)/(4 pi) ~ 19).
  const int M = 120;
  std::vector<double> yp(sh_count(M)), yq(sh_count(M));
  const double lp = 0.3, tp = 0.7, lq = -2.1, tq = -0.4;
  real_harmonics(M, lp, tp, yp.data());
  real_harmonics(M, lq, tq, yq.data());
  double p[3], q[3];
  unit_sphere_point(lp, tp, p);
  unit_sphere_point(lq, tq, q);
  const double c = p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
  for (int l : {0, 1, 7, 50, 100, 120}) {
    double s = 0;
    for (int k = -l; k <= l; ++k) s += yp[sh_index(l, k)] * yq[sh_index(l, k)];
    EXPECT_NEAR(s, (2 * l + 1) / (4 * pi) * legendre(l, c), 1e-12 * (2 * l + 1)) << "l = " << l;
  }
}

TEST(Harmonics, DerivativesMatchFiniteDifferences) {
  // Central differences with step h have error ~ h^2 |f'''| ~ h^2 l^3 |Y| (l <= 8): 1e-8 * 512.
  const int M = 8, np = sh_count(M);
  const double h = 1e-4;
  for (double lam : {-2.5, 0.4}) {
    for (double th : {-1.2, 0.1, 1.5}) {
      std::vector<double> y(np), yl(np), yt(np), yll(np), ylt(np), ytt(np);
      real_harmonics(M, lam, th, y.data(), yl.data(), yt.data(), yll.data(), ylt.data(), ytt.data());
      std::vector<double> a(np), b(np), al(np), bl(np), at(np), bt(np);
      real_harmonics(M, lam + h, th, a.data(), al.data(), at.data());
      real_harmonics(M, lam - h, th, b.data(), bl.data(), bt.data());
      std::vector<double> c(np), d(np), ct(np), dt(np);
      real_harmonics(M, lam, th + h, c.data(), nullptr, ct.data());
      real_harmonics(M, lam, th - h, d.data(), nullptr, dt.data());
      for (int j = 0; j < np; ++j) {
        EXPECT_NEAR(yl[j], (a[j] - b[j]) / (2 * h), 1e-5);
        EXPECT_NEAR(yt[j], (c[j] - d[j]) / (2 * h), 1e-5);
        EXPECT_NEAR(yll[j], (al[j] - bl[j]) / (2 * h), 1e-5);
        EXPECT_NEAR(ylt[j], (at[j] - bt[j]) / (2 * h), 1e-5);
        EXPECT_NEAR(ytt[j], (ct[j] - dt[j]) / (2 * h), 1e-5);
      }
    }
  }
}

TEST(Harmonics, EigenfunctionsOfTheSphereLaplacianAtDegree100) {
  // Delta Y = Y_tt - tan(t) Y_t + Y_ll / cos^2 t = -l(l+1) Y: exercises every second derivative
  // at high degree. Terms are ~ l^2 |Y|; tolerance 1e-10 relative to l(l+1) * max |Y|.
  const int M = 100, np = sh_count(M);
  std::vector<double> y(np), yl(np), yt(np), yll(np), ylt(np), ytt(np);
  for (double th : {-0.9, 0.05, 1.2}) {
    real_harmonics(M, 1.3, th, y.data(), yl.data(), yt.data(), yll.data(), ylt.data(), ytt.data());
    double ymax = 0;
    for (double v : y) ymax = std::max(ymax, std::abs(v));
    for (int l = 0; l <= M; l += 11)
      for (int k = -l; k <= l; k += std::max(1, l / 5)) {
        const int j = sh_index(l, k);
        const double c = std::cos(th);
        const double lap = ytt[j] - std::tan(th) * yt[j] + yll[j] / (c * c);
        EXPECT_NEAR(lap, -l * (l + 1.0) * y[j], 1e-10 * l * (l + 1.0) * ymax + 1e-14) << l << " " << k;
      }
  }
}

TEST(PointSets, BauerSpiralIsEqualAreaInLatitudeAndAvoidsPoles) {
  const SphereSites s = bauer_spiral(400);
  ASSERT_EQ(s.size(), 400);
  for (index_t j = 0; j < s.size(); ++j) {
    EXPECT_NEAR(std::sin(s.theta[j]), -1 + (2.0 * (j + 1) - 1) / 400, 1e-15);
    EXPECT_GT(s.lambda[j], -pi - 1e-15);
    EXPECT_LE(s.lambda[j], pi);
    EXPECT_LT(std::abs(s.theta[j]), pi / 2 - 1e-3);
  }
  EXPECT_NO_THROW(require_distinct(s, "spiral"));
}

TEST(PointSets, ToroidalSpiralCoversTheTorus) {
  const SphereSites s = toroidal_spiral(100);
  ASSERT_EQ(s.size(), 100);
  EXPECT_DOUBLE_EQ(s.theta[1] - s.theta[0], 2 * pi / 100);
  EXPECT_NEAR(s.lambda[1], std::fmod(10 * 2 * pi / 100, 2 * pi), 1e-15);
  for (index_t i = 0; i < s.size(); ++i) {
    EXPECT_GE(s.lambda[i], 0);
    EXPECT_LT(s.lambda[i], 2 * pi);
  }
}

TEST(PointSets, MaxDeterminantIncreasesTheDeterminantAndGivesPositiveExactWeights) {
  const MaxDetResult r = max_determinant_points(6);
  ASSERT_EQ(r.sites.size(), 49);
  EXPECT_GT(r.log_det, r.log_det_start);
  // Square system Y^T w = sqrt(4 pi) e1 (eq. 45): the NNLS solution is exact when the unique
  // solution is positive, as conjectured for maximal-determinant points.
  const NnlsWeights q = nnls_sh_weights(r.sites, 6);
  EXPECT_LT(q.residual, 1e-12);
  double sum = 0;
  for (double w : q.w) {
    EXPECT_GE(w, 0.0);
    sum += w;
  }
  EXPECT_NEAR(sum, 4 * pi, 1e-12);
}

TEST(PointSets, MaxDeterminantConvergesToAStationaryPoint) {
  // At a local maximum of log|det Y| the gradient vanishes: L-BFGS must end far below its start.
  const MaxDetResult r = max_determinant_points(10);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.gradient_norm, 1e-3);
  // The stored sets (reference/point_sets) are written by the same generator; its weights solve
  // eq. (45) exactly and directly (square system, no active-set steps).
  const NnlsWeights q = nnls_sh_weights(r.sites, 10);
  EXPECT_EQ(q.iterations, 0);
  EXPECT_LT(q.residual, 1e-12);
}

TEST(Quadrature, SquareNnlsDirectSolveAgreesWithActiveSet) {
  // Same square system through the active-set path (one extra site makes it non-square) and the
  // direct path: on a set with a positive exact solution both give that solution.
  const MaxDetResult r = max_determinant_points(4);
  const NnlsWeights direct = nnls_sh_weights(r.sites, 4);
  SphereSites plus = r.sites;
  plus.lambda.push_back(0.123);
  plus.theta.push_back(0.456);
  const NnlsWeights active = nnls_sh_weights(plus, 4);
  EXPECT_GT(active.iterations, 0);
  EXPECT_LT(active.residual, 1e-12);
  double sum = 0;
  for (double w : direct.w) sum += w;
  EXPECT_NEAR(sum, 4 * pi, 1e-12);
  // Both integrate exp(z) to 4 pi sinh(1) within the quadrature error of degree 4 rules.
  auto integral = [](const SphereSites& s, const std::vector<double>& w) {
    double I = 0;
    for (index_t i = 0; i < s.size(); ++i) I += w[i] * std::exp(std::sin(s.theta[i]));
    return I;
  };
  EXPECT_NEAR(integral(r.sites, direct.w), 4 * pi * std::sinh(1.0), 1e-3);
  EXPECT_NEAR(integral(plus, active.w), 4 * pi * std::sinh(1.0), 1e-3);
}

TEST(PointSets, SiteFilesRoundTripAndRejectBadLines) {
  const std::string path = ::testing::TempDir() + "rbfib_sites.txt";
  const SphereSites s = bauer_spiral(50);
  write_sphere_sites(path, s, {"a test set"});
  const SphereSites r = read_sphere_sites(path);
  ASSERT_EQ(r.size(), s.size());
  for (index_t i = 0; i < s.size(); ++i) {
    double a[3], b[3];
    unit_sphere_point(s.lambda[i], s.theta[i], a);
    unit_sphere_point(r.lambda[i], r.theta[i], b);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(a[d], b[d], 4 * eps);
  }
  auto expect_error = [&](const std::string& text, const std::string& needle) {
    {
      std::FILE* f = std::fopen(path.c_str(), "w");
      std::fputs(text.c_str(), f);
      std::fclose(f);
    }
    try {
      read_sphere_sites(path);
      ADD_FAILURE() << "no error for: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_error("# header\n1 0 0\n0 1\n", "line 3");
  expect_error("1 0 0\n0 2 0\n", "not a unit vector");
  expect_error("1 0 0\n1 0 0\n0 0 1\n", "coincide");
  expect_error("# only a comment\n", "no sites");
  EXPECT_THROW(read_sphere_sites(path + ".missing"), InputError);
}

TEST(PointSets, StoredMaximalDeterminantSetsHaveExactPositiveWeights) {
  // The Chapter 3 study's evaluation sites (reference/point_sets): (N+1)^2 distinct unit vectors
  // on which eq. (45) has an exact nonnegative solution, integrating exp(z) to rule accuracy.
  for (int N : {22, 44, 67}) {
    const std::string file =
        std::string(RBFIB_SOURCE_DIR) + "/reference/point_sets/max_determinant_N" + std::to_string(N) + ".txt";
    const SphereSites s = read_sphere_sites(file);
    ASSERT_EQ(s.size(), sh_count(N)) << file;
    if (N == 67) continue;  // the study solves its 4624 x 4624 system; here the count suffices
    const NnlsWeights q = nnls_sh_weights(s, N);
    EXPECT_EQ(q.iterations, 0) << file;
    EXPECT_LT(q.residual, 1e-12) << file;
    double I = 0;
    for (index_t i = 0; i < s.size(); ++i) {
      EXPECT_GT(q.w[i], 0.5 * 4 * pi / s.size()) << file << " site " << i;
      I += q.w[i] * std::exp(std::sin(s.theta[i]));
    }
    EXPECT_NEAR(I, 4 * pi * std::sinh(1.0), 1e-12) << file;
  }
}

TEST(Interpolation, SphericalHarmonicInterpolantIsExactForTheEllipsoidFromM1) {
  // The ellipsoid's coordinates are degree-1 harmonics: m = 4 sites reproduce it (paper Sec. 4.1).
  const PerturbedEllipsoid E = ellipsoid(1.1, 1 / std::sqrt(1.1), 1 / std::sqrt(1.1));
  const MaxDetResult md = max_determinant_points(1);
  const SphereSites eval = bauer_spiral(300);
  auto ops = sh_operators(md.sites, eval, 1);
  const std::vector<Jet> J = jets_from_operators(*ops, E.points(md.sites));
  double err = 0;
  for (index_t i = 0; i < eval.size(); ++i) {
    const Jet ex = E.jet(eval.lambda[i], eval.theta[i]);
    for (int d = 0; d < 3; ++d)
      err = std::max({err, std::abs(J[i].x[d] - ex.x[d]), std::abs(J[i].xl[d] - ex.xl[d]),
                      std::abs(J[i].xt[d] - ex.xt[d]), std::abs(J[i].xll[d] - ex.xll[d]),
                      std::abs(J[i].xlt[d] - ex.xlt[d]), std::abs(J[i].xtt[d] - ex.xtt[d])});
  }
  EXPECT_LT(err, 100 * eps);
  // And the coefficients beyond degree 1 vanish at M = 3.
  const MaxDetResult md3 = max_determinant_points(3);
  std::vector<double> xs(md3.sites.size());
  for (index_t i = 0; i < md3.sites.size(); ++i) xs[i] = E.jet(md3.sites.lambda[i], md3.sites.theta[i]).x[0];
  const std::vector<double> c = sh_coefficients(md3.sites, 3, xs);
  for (int j = 4; j < 16; ++j) EXPECT_NEAR(c[j], 0.0, 1e-13);
}

TEST(Interpolation, RbfOperatorsReproduceTheAugmentingHarmonics) {
  // PHS r^7 + harmonics of degree <= 5: any harmonic of degree <= 5 is reproduced exactly, with
  // all derivatives, up to the conditioning of eq. (2.17) (tolerance 1e-9 for n_d = 200).
  const SphereSites data = bauer_spiral(200), sample = bauer_spiral(157);
  auto ops = rbf_operators(data, sample, PhsBasis{7, 5});
  const int M = 5, np = sh_count(M);
  std::vector<double> y(np);
  for (int j : {0, 3, 10, 24, 35}) {
    std::vector<double> u(data.size());
    for (index_t i = 0; i < data.size(); ++i) {
      real_harmonics(M, data.lambda[i], data.theta[i], y.data());
      u[i] = y[j];
    }
    const std::vector<ScalarJet> J = scalar_jets_from_operators(*ops, u);
    std::vector<double> v(np), vl(np), vt(np), vll(np), vlt(np), vtt(np);
    for (index_t i = 0; i < sample.size(); ++i) {
      real_harmonics(M, sample.lambda[i], sample.theta[i], v.data(), vl.data(), vt.data(), vll.data(), vlt.data(),
                     vtt.data());
      EXPECT_NEAR(J[i].u, v[j], 1e-9);
      EXPECT_NEAR(J[i].ul, vl[j], 1e-9);
      EXPECT_NEAR(J[i].ut, vt[j], 1e-9);
      EXPECT_NEAR(J[i].ull, vll[j], 1e-8);
      EXPECT_NEAR(J[i].ult, vlt[j], 1e-8);
      EXPECT_NEAR(J[i].utt, vtt[j], 1e-8);
    }
  }
}

TEST(Interpolation, CoincidentSitesAreAnInputError) {
  SphereSites s = bauer_spiral(16);
  s.lambda[5] = s.lambda[3];
  s.theta[5] = s.theta[3];
  EXPECT_THROW(sh_operators(s, bauer_spiral(10), 3), InputError);
  EXPECT_THROW(rbf_operators(s, bauer_spiral(10), PhsBasis{7, 0}), InputError);
  EXPECT_THROW(sh_operators(bauer_spiral(15), bauer_spiral(10), 3), InputError);  // not (M+1)^2
}

TEST(Quadrature, RbfWeightsSumTo4PiAndConvergeAtThirdOrderForPhiR) {
  // Eq. (2.22) with phi = r: the weights integrate f = exp(x) (exact 4 pi sinh 1) with an error
  // decreasing at ~3rd order in h ~ n^{-1/2}; we require >= 2.5 between n = 200 and 800.
  double e[2];
  int k = 0;
  for (index_t n : {200, 800}) {
    const SphereSites s = bauer_spiral(n);
    const RbfWeights q = rbf_sphere_weights(s, 1);
    double sum = 0, I = 0;
    for (index_t i = 0; i < n; ++i) {
      double x[3];
      unit_sphere_point(s.lambda[i], s.theta[i], x);
      sum += q.w[i];
      I += q.w[i] * std::exp(x[0]);
    }
    EXPECT_NEAR(sum, 4 * pi, 1e-11);
    e[k++] = std::abs(I - 4 * pi * std::sinh(1.0));
  }
  EXPECT_GT(std::log(e[0] / e[1]) / std::log(2.0), 2.5);
}

TEST(Quadrature, ReferenceShapeWeightsScaleWithTheSquaredRadius) {
  const SphereSites s = bauer_spiral(50);
  std::vector<double> w(50, 1.0), det(50);
  for (index_t i = 0; i < 50; ++i) det[i] = 9.0 * 9.0 * std::pow(std::cos(s.theta[i]), 2);  // r = 3: r^4 cos^2
  const std::vector<double> wl = reference_shape_weights(s, w, det);
  for (double v : wl) EXPECT_NEAR(v, 9.0, 1e-13);
}

TEST(Geometry, CurvatureOfSphereAndEllipsoidMatchesClosedForms) {
  const SphereSites s = bauer_spiral(200);
  // Sphere of radius 2 as an ellipsoid with a = b = c: H = -1/2, R = 2/4.
  for (const auto& g : surface_geometry(ellipsoid(2, 2, 2).jets(s), "sphere")) {
    EXPECT_NEAR(g.H, -0.5, 1e-14);
    EXPECT_NEAR(g.R, 0.5, 1e-14);
  }
  const double a = 1.1, b = 0.8, c = 0.6;
  const PerturbedEllipsoid E = ellipsoid(a, b, c);
  const auto J = E.jets(s);
  const auto G = surface_geometry(J, "ellipsoid");
  for (std::size_t i = 0; i < J.size(); ++i) {
    double H, K;
    ellipsoid_curvatures(a, b, c, J[i].x, H, K);
    EXPECT_NEAR(G[i].H, H, 1e-13 * std::abs(H));
    EXPECT_NEAR(G[i].R, 2 * K, 1e-13 * K);
  }
  // Through a degree-1 spherical-harmonic interpolant (exact for the ellipsoid).
  const MaxDetResult md = max_determinant_points(1);
  auto ops = sh_operators(md.sites, s, 1);
  const auto G2 = surface_geometry(jets_from_operators(*ops, E.points(md.sites)), "ellipsoid");
  for (std::size_t i = 0; i < J.size(); ++i) EXPECT_NEAR(G2[i].H, G[i].H, 1e-12);
}

TEST(Geometry, RbfCurvatureOfAnEllipsoidIsReproduced) {
  // PHS r^7 + degree-5 harmonics on Bauer spirals: the interpolant contains the ellipsoid, so H
  // is reproduced up to the conditioning of eq. (2.17).
  const double a = 1.1, b = 0.8, c = 0.6;
  const PerturbedEllipsoid E = ellipsoid(a, b, c);
  const SphereSites data = bauer_spiral(300), sample = bauer_spiral(500);
  auto ops = rbf_operators(data, sample, PhsBasis{7, 5});
  const auto G = surface_geometry(jets_from_operators(*ops, E.points(data)), "ellipsoid");
  for (index_t i = 0; i < sample.size(); ++i) {
    double H, K;
    const Jet j = E.jet(sample.lambda[i], sample.theta[i]);
    ellipsoid_curvatures(a, b, c, j.x, H, K);
    EXPECT_NEAR(G[i].H, H, 1e-7);
  }
}

TEST(Geometry, SurfaceLaplacianOfHarmonicsOnASphereOfRadius3) {
  // On a sphere of radius r, Delta_s Y_l = -l(l+1)/r^2 Y_l (eq. 82).
  const int M = 6;
  std::vector<double> y(sh_count(M)), yl(y.size()), yt(y.size()), yll(y.size()), ylt(y.size()), ytt(y.size());
  const PerturbedEllipsoid S = ellipsoid(3, 3, 3);
  for (double th : {-1.0, 0.3}) {
    real_harmonics(M, 0.7, th, y.data(), yl.data(), yt.data(), yll.data(), ylt.data(), ytt.data());
    const Jet J = S.jet(0.7, th);
    for (int l = 0; l <= M; ++l)
      for (int k = -l; k <= l; ++k) {
        const int j = sh_index(l, k);
        const double lap = laplace_beltrami(J, ScalarJet{y[j], yl[j], yt[j], yll[j], ylt[j], ytt[j]});
        EXPECT_NEAR(lap, -l * (l + 1.0) / 9.0 * y[j], 1e-13);
      }
  }
}

TEST(Triangulation, ClosedOutwardTriangulationOfTheSpiral) {
  const index_t n = 500;
  const SphereSites s = bauer_spiral(n);
  const auto T = sphere_triangulation(s);
  ASSERT_EQ(static_cast<index_t>(T.size()), 2 * n - 4);
  const std::vector<double> p = unit_sphere_points(s);
  double area = 0;
  for (const auto& t : T) {
    const double* a = &p[3 * t[0]];
    const double* b = &p[3 * t[1]];
    const double* c = &p[3 * t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double nrm[3];
    cross3(u, v, nrm);
    EXPECT_GT(dot3(nrm, a), 0.0);  // outward
    area += 0.5 * std::sqrt(dot3(nrm, nrm));
  }
  // The inscribed polyhedron's area is below 4 pi by O(h^2) ~ 4 pi / n.
  EXPECT_LT(area, 4 * pi);
  EXPECT_GT(area, 4 * pi * (1 - 4.0 / n));
}

TEST(Interpolation, PlateletBasisWithOnlyAConstantIsInvertibleAndReproducesConstants) {
  // Dissertation Sec. 2.3.1: r^7 with just the constant does not guarantee a unique interpolant,
  // but eq. (2.17) is invertible on the spiral; constants (the augmentation) are reproduced, and
  // their derivatives vanish, up to conditioning (1e-9).
  const SphereSites data = bauer_spiral(400), sample = bauer_spiral(123);
  auto ops = rbf_operators(data, sample, PhsBasis{7, 0});
  EXPECT_GT(ops->condition_estimate, 1e-18);
  const std::vector<ScalarJet> J = scalar_jets_from_operators(*ops, std::vector<double>(400, 2.5));
  for (const auto& j : J) {
    EXPECT_NEAR(j.u, 2.5, 1e-9);
    EXPECT_NEAR(j.ul, 0.0, 1e-8);
    EXPECT_NEAR(j.utt, 0.0, 1e-7);
  }
}

TEST(Interpolation, SingularInterpolationMatrixIsANumericalError) {
  // 9 distinct sites on the equator cannot determine the degree-2 harmonics (Y_1^0 vanishes
  // there): eq. (86) is singular and must be reported, not solved into NaN operators.
  SphereSites s;
  for (int i = 0; i < 9; ++i) {
    s.lambda.push_back(-pi + 2 * pi * (i + 0.5) / 9);
    s.theta.push_back(0.0);
  }
  try {
    sh_operators(s, bauer_spiral(10), 2);
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("eq. 86"), std::string::npos);
  }
}

TEST(Quadrature, ReferenceShapeWeightsIntegrateTheRedCellArea) {
  // Eq. (51) on the Evans-Fung red cell of dissertation Sec. 2.2 (R0 = 3.91 um = 3.91e-4 cm):
  // X = R0 (cos l cos t, sin l cos t, h(t)), h = z(cos^2 t) sin t, z(r) = 0.105 + r - 0.56 r^2.
  // X_l . X_t = 0, so det G0 = R0^4 cos^2 t (sin^2 t + h'(t)^2). The area from RBF sphere weights
  // (eq. 2.22, r^3, n = 1600) times eq. (51) must match a 60 x 120 Gauss product rule to the RBF
  // rule's accuracy on this smooth integrand (1e-6 relative).
  const double R0 = 3.91e-4;
  auto det_g0 = [R0](double t) {
    const double c = std::cos(t), s = std::sin(t), r = c * c;
    const double z = 0.105 + r - 0.56 * r * r, dz = 1 - 1.12 * r;
    const double dh = dz * (-2 * c * s) * s + z * c;
    return std::pow(R0, 4) * c * c * (s * s + dh * dh);
  };
  auto area = [&](const SphereSites& s, const std::vector<double>& w_sphere) {
    std::vector<double> det(s.size());
    for (index_t i = 0; i < s.size(); ++i) det[i] = det_g0(s.theta[i]);
    const std::vector<double> w = reference_shape_weights(s, w_sphere, det);
    double A = 0;
    for (double v : w) A += v;
    return A;
  };
  std::vector<double> wg;
  const SphereSites g = gauss_product_sites(60, 120, wg);
  const double A_ref = area(g, wg);
  const SphereSites s = bauer_spiral(1600);
  const double A = area(s, rbf_sphere_weights(s, 3).w);
  EXPECT_NEAR(A / A_ref, 1.0, 1e-6);
  EXPECT_GT(A_ref, 1.2e-6);  // ~ 135 um^2: a red cell's area is 130-140 um^2
  EXPECT_LT(A_ref, 1.5e-6);
}

/// The bound on two orders of the k-term sums of one operator row times the columns C that
/// apply_operators multiplies (F, or Y^{-1} F by the LU solve): 2 gamma_{k+2} sum_j |M_ij| |C_jc|.
/// Products of other shapes may be blocked and summed differently by BLAS.
struct SumOrderBound {
  const SurfaceOperators& ops;
  std::vector<double> Mv, Md, C;
  index_t k, nd;
  double g;
  SumOrderBound(const SurfaceOperators& o, const OperatorWorkspace& work, const std::vector<double>& F)
      : ops(o), Mv(o.value.to_host()), Md(o.derivatives.to_host()), C(o.factored() ? work.coefficients.to_host() : F),
        k(o.value.cols()), nd(o.n_data()), g(2 * (k + 2) * eps / 2 / (1 - (k + 2) * eps / 2)) {}
  double at(const std::vector<double>& M, index_t ld, index_t row, index_t c) const {
    double s = 0;
    for (index_t j = 0; j < k; ++j) s += std::abs(M[row + j * ld]) * std::abs(C[j + c * nd]);
    return g * s;
  }
  double value(index_t site, index_t c) const { return at(Mv, ops.n_sample(), site, c); }
  double derivative(index_t row, index_t c) const { return at(Md, 5 * ops.n_sample(), row, c); }
};

TEST(Interpolation, RowRangesOfTheOperatorsEqualTheirRows) {
  // apply_operators_rows on [row0, row0 + rows) equals those rows of apply_operators (one product
  // for the values, a strided batch of five for the derivatives), for an assembled RBF set and a
  // factored harmonic set; select_sample_sites makes a set whose products give the same rows.
  const SphereSites data = bauer_spiral(64), sample = bauer_spiral(150);
  const MaxDetResult md = max_determinant_points(5);
  for (const auto& ops : {rbf_operators(data, sample, PhsBasis{7, 3}), sh_operators(md.sites, sample, 5)}) {
    const index_t nd = ops->n_data(), ns = ops->n_sample(), cols = 4, row0 = 37, rows = 51;
    std::vector<double> F(static_cast<std::size_t>(nd * cols));
    for (std::size_t k = 0; k < F.size(); ++k) F[k] = std::sin(0.7 * double(k)) + 0.1 * double(k % 5);
    const linalg::DeviceMatrix Fd = linalg::DeviceMatrix::from_host(nd, cols, F.data());
    OperatorWorkspace work;
    linalg::DeviceMatrix V(ns, cols), D(5 * ns, cols), v(rows, cols), d(5 * rows, cols), v2(rows, cols), d2(5 * rows, cols);
    apply_operators(*ops, Fd.view(), V.view(), D.view(), work);
    apply_operators_rows(*ops, Fd.view(), row0, rows, v.view(), d.view(), work);
    const auto sel = select_sample_sites(*ops, row0, rows);
    apply_operators(*sel, Fd.view(), v2.view(), d2.view(), work);
    const auto Vh = V.to_host(), Dh = D.to_host(), vh = v.to_host(), dh = d.to_host(), v2h = v2.to_host(), d2h = d2.to_host();
    // The three calls multiply the same operator rows by the same columns in products of other
    // shapes (the former fixed 1e-13 max|D| was not tied to the sums).
    const SumOrderBound tol(*ops, work, F);
    for (index_t c = 0; c < cols; ++c)
      for (index_t i = 0; i < rows; ++i) {
        const double tv = tol.value(row0 + i, c);
        EXPECT_NEAR(vh[i + c * rows], Vh[row0 + i + c * ns], tv);
        EXPECT_NEAR(v2h[i + c * rows], Vh[row0 + i + c * ns], tv);
        for (int q = 0; q < 5; ++q) {
          const double td = tol.derivative(q * ns + row0 + i, c);
          EXPECT_NEAR(dh[q * rows + i + c * 5 * rows], Dh[q * ns + row0 + i + c * 5 * ns], td);
          EXPECT_NEAR(d2h[q * rows + i + c * 5 * rows], Dh[q * ns + row0 + i + c * 5 * ns], td);
        }
      }
    EXPECT_THROW(apply_operators_rows(*ops, Fd.view(), ns - 2, 5, linalg::MatrixView{}, linalg::MatrixView{}, work), InputError);
  }
}

