// Unit tests of the mechanics module: energy densities, the continuous force (eq. 35), bending
// (eq. 84), LDSM (eq. 66) and tethers (eq. 2.10): forces are minus the derivative of the discrete
// energy, translation-invariant forces sum to zero, closed forms hold, bad surfaces raise errors.
#include "rbfib/core/error.hpp"
#include "rbfib/core/constants.hpp"
#include "rbfib/mechanics/ldsm.hpp"
#include "rbfib/mechanics/shell.hpp"
#include "rbfib/surface/harmonics.hpp"
#include "rbfib/surface/point_sets.hpp"
#include "rbfib/surface/shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace rbfib;
using namespace rbfib::surface;
using namespace rbfib::mechanics;

namespace {

std::vector<EnergyDensity> all_energies() {
  return {EnergyDensity::skalak(1.0, 3.0), EnergyDensity::neo_hookean_dissertation(1.0, 2.0),
          EnergyDensity::neo_hookean_paper(1.0, 1.0), EnergyDensity::surface_tension(1.0)};
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

/// Central-difference gradient of f at x (step h) in the first `count` components (others 0;
/// all when count = 0). Points are n x 3 column-major, so count = n takes the x components.
std::vector<double> fd_gradient(const std::function<double(const std::vector<double>&)>& f, std::vector<double> x,
                                double h, std::size_t count = 0) {
  std::vector<double> g(x.size(), 0.0);
  for (std::size_t i = 0; i < (count ? count : x.size()); ++i) {
    const double x0 = x[i];
    x[i] = x0 + h;
    const double fp = f(x);
    x[i] = x0 - h;
    const double fm = f(x);
    x[i] = x0;
    g[i] = (fp - fm) / (2 * h);
  }
  return g;
}

/// A smooth spherical-harmonic cell: M = 6 on maximal-determinant sites, evaluated on a
/// 20 x 40 Gauss product rule (spectrally accurate quadrature) with the unit sphere as reference.
struct ShCell {
  int M = 6;
  SphereSites interp, eval;
  std::vector<double> w;
  std::shared_ptr<const SurfaceOperators> ops, at_data;
  std::vector<Jet> Z;
  ShCell() {
    interp = max_determinant_points(M).sites;
    eval = gauss_product_sites(20, 40, w);
    ops = sh_operators(interp, eval, M);
    at_data = sh_operators(interp, interp, M);
    Z = unit_sphere_jets(eval);
  }
  /// I^T F^: the generalized force on the data sites, to compare with -dE/dX_data.
  std::vector<double> project(const std::vector<double>& Fhat) const { return transpose_identity(*ops, Fhat); }
};
}  // namespace

TEST(Energy, DerivativesMatchFiniteDifferences) {
  // Central differences, h = 1e-5: truncation ~ h^2 |W'''| ~ 1e-10, rounding ~ eps |W| / h ~ 1e-11.
  const double h = 1e-5;
  for (const auto& e : all_energies()) {
    for (double I1 : {-0.2, 0.0, 0.7})
      for (double I2 : {-0.3, 0.0, 0.5}) {
        const auto d = e.evaluate(I1, I2);
        ASSERT_TRUE(d.valid);
        const auto p1 = e.evaluate(I1 + h, I2), m1 = e.evaluate(I1 - h, I2);
        const auto p2 = e.evaluate(I1, I2 + h), m2 = e.evaluate(I1, I2 - h);
        EXPECT_NEAR(d.W1, (p1.W - m1.W) / (2 * h), 1e-8) << e.name();
        EXPECT_NEAR(d.W2, (p2.W - m2.W) / (2 * h), 1e-8) << e.name();
        EXPECT_NEAR(d.W11, (p1.W1 - m1.W1) / (2 * h), 1e-8) << e.name();
        EXPECT_NEAR(d.W12, (p2.W1 - m2.W1) / (2 * h), 1e-8) << e.name();
        EXPECT_NEAR(d.W22, (p2.W2 - m2.W2) / (2 * h), 1e-8) << e.name();
      }
  }
}

TEST(Energy, DissertationAndPaperNeoHookeanAgreeAndVanishAtRest) {
  const auto a = EnergyDensity::neo_hookean_dissertation(2.0, 6.0);
  const auto b = EnergyDensity::neo_hookean_paper(2.0, 3.0);  // Gs = E, A = G/E
  for (double I1 : {-0.1, 0.4})
    for (double I2 : {-0.2, 0.3}) EXPECT_NEAR(a.evaluate(I1, I2).W, b.evaluate(I1, I2).W, 1e-14);
  for (const auto& e : all_energies()) {
    if (e.kind != EnergyKind::surface_tension) {
      EXPECT_EQ(e.evaluate(0, 0).W, 0.0) << e.name();
    }
  }
  EXPECT_FALSE(EnergyDensity::neo_hookean_paper(1, 1).evaluate(0, -1.5).valid);
}

TEST(ContinuousForce, SurfaceTensionEqualsTwiceMeanCurvatureTimesNormal) {
  // Eq. (35) with W = sigma sqrt(I2 + 1) equals eq. (74), sigma 2H n sqrt(det G/det G0), exactly
  // in exact arithmetic; the two evaluations agree to rounding (1e-12 relative).
  const SphereSites s = bauer_spiral(300);
  const std::vector<Jet> Z = unit_sphere_jets(s);
  for (const PerturbedEllipsoid& shape : {ellipsoid(1.1, 1 / std::sqrt(1.1), 1 / std::sqrt(1.1)),
                                          paper_perturbed_ellipsoid()}) {
    const std::vector<Jet> X = shape.jets(s);
    const std::vector<double> F = elastic_force_density("test", X, Z, EnergyDensity::surface_tension(1.0));
    const double scale = max_abs(F);
    for (index_t i = 0; i < s.size(); ++i) {
      const PointGeometry g = point_geometry(X[i]), g0 = point_geometry(Z[i]);
      for (int d = 0; d < 3; ++d)
        EXPECT_NEAR(F[d * s.size() + i], 2 * g.H * g.n[d] * std::sqrt(g.det_g / g0.det_g), 1e-12 * scale);
    }
  }
}

TEST(ContinuousForce, UndeformedSurfaceHasZeroElasticForce) {
  const SphereSites s = bauer_spiral(100);
  const std::vector<Jet> Z = paper_perturbed_ellipsoid().jets(s);
  for (const auto& e : all_energies()) {
    if (e.kind == EnergyKind::surface_tension) continue;
    EXPECT_LT(max_abs(elastic_force_density("rest", Z, Z, e)), 1e-12) << e.name();
  }
}

TEST(ContinuousForce, IsMinusTheDerivativeOfTheDiscreteEnergy) {
  // E_h(X_data) = sum_i W_i dA0_i at the evaluation sites; by eq. (8), -dE_h/dX_data = I^T F^ up
  // to the quadrature error of the 20 x 40 Gauss rule on a smooth integrand (spectrally small)
  // and the finite-difference error (h = 1e-6: ~1e-10 relative). Tolerance 1e-7 relative.
  ShCell cell;
  const PerturbedEllipsoid shape{1.1, 0.9, 1.0, 0.1, 1.0};
  const std::vector<double> X0 = shape.points(cell.interp);
  for (const auto& e : all_energies()) {
    auto energy = [&](const std::vector<double>& X) {
      return elastic_energy("fd", jets_from_operators(*cell.ops, X), cell.Z, e, cell.w);
    };
    const std::vector<double> g = fd_gradient(energy, X0, 1e-6);
    const std::vector<double> F = forces_from_density(
        elastic_force_density("fd", jets_from_operators(*cell.ops, X0), cell.Z, e), cell.w);
    const std::vector<double> p = cell.project(F);
    const double scale = max_abs(p);
    ASSERT_GT(scale, 1e-3);
    for (std::size_t i = 0; i < g.size(); ++i) EXPECT_NEAR(p[i], -g[i], 1e-7 * scale) << e.name() << " " << i;
  }
}

TEST(ContinuousForce, TranslationInvariantForcesIntegrateToZero) {
  // sum_i F^_i = 0 in the continuum; with the Gauss product rule the remainder is the quadrature
  // error, which must be < 1e-10 of sum |F^| on a 32 x 64 rule for this smooth shape, and not
  // larger than on a 12 x 24 rule (it may already be at rounding there).
  const PerturbedEllipsoid shape{1.1, 0.9, 1.0, 0.1, 1.0};
  for (const auto& e : all_energies()) {
    double r[2];
    int k = 0;
    for (int nt : {12, 32}) {
      std::vector<double> w;
      const SphereSites s = gauss_product_sites(nt, 2 * nt, w);
      const std::vector<double> F = forces_from_density(
          elastic_force_density("sum", shape.jets(s), unit_sphere_jets(s), e), w);
      double sum[3] = {0, 0, 0}, tot = 0;
      for (index_t i = 0; i < s.size(); ++i)
        for (int d = 0; d < 3; ++d) {
          sum[d] += F[d * s.size() + i];
          tot += std::abs(F[d * s.size() + i]);
        }
      r[k++] = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]) / tot;
    }
    EXPECT_LT(r[1], std::max(r[0], 1e-15)) << e.name();
    EXPECT_LT(r[1], 1e-10) << e.name();
  }
}

TEST(ContinuousForce, DegenerateSurfacesRaiseNamedErrors) {
  const SphereSites s = bauer_spiral(50);
  const std::vector<Jet> Z = unit_sphere_jets(s);
  std::vector<Jet> X = Z;
  for (int d = 0; d < 3; ++d) X[7].xt[d] = 0;  // collapsed metric
  try {
    elastic_force_density("rbc-3", X, Z, EnergyDensity::skalak(1, 1));
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("rbc-3"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("site 7"), std::string::npos);
  }
  // A rotation by 180 degrees reverses every normal against the reference and is no error (a
  // tumbling cell); the energy and the force density are those of the reference, zero.
  X = Z;
  for (auto& j : X)
    for (double* v : {j.x, j.xl, j.xt, j.xll, j.xlt, j.xtt}) {
      v[0] = -v[0];
      v[2] = -v[2];
    }
  const std::vector<double> F = elastic_force_density("rbc-3", X, Z, EnergyDensity::skalak(1, 1));
  EXPECT_LT(max_abs(F), 1e-12);
}

TEST(Dissipation, IsMinusTheVelocityDerivativeOfTheRayleighFunctional) {
  // Phi(U_data) = sum_i W_dissip,i dA0_i is quadratic in U, so central differences are exact up to
  // rounding; -dPhi/dU_data = I^T F^ up to the spectrally small quadrature error (1e-7 relative).
  ShCell cell;
  const PerturbedEllipsoid shape{1.1, 0.9, 1.0, 0.1, 1.0};
  const std::vector<double> X0 = shape.points(cell.interp);
  const std::vector<Jet> XJ = jets_from_operators(*cell.ops, X0);
  std::vector<double> U0(X0.size());
  for (std::size_t i = 0; i < U0.size(); ++i) U0[i] = std::sin(1.7 * i) + 0.3 * X0[i] * X0[i];
  auto phi = [&](const std::vector<double>& U) {
    return dissipation("fd", XJ, jets_from_operators(*cell.ops, U), cell.Z, 2.0, cell.w);
  };
  const std::vector<double> g = fd_gradient(phi, U0, 1e-4);
  const std::vector<double> p = cell.project(
      forces_from_density(dissipative_force_density("fd", XJ, jets_from_operators(*cell.ops, U0), cell.Z, 2.0), cell.w));
  const double scale = max_abs(p);
  ASSERT_GT(scale, 1e-3);
  for (std::size_t i = 0; i < g.size(); ++i) EXPECT_NEAR(p[i], -g[i], 1e-7 * scale) << i;
  // A rigid rotation U = w x X dissipates nothing.
  std::vector<double> R(X0.size());
  const std::size_t n = X0.size() / 3;
  for (std::size_t i = 0; i < n; ++i) {
    R[i] = -0.5 * X0[n + i];
    R[n + i] = 0.5 * X0[i];
    R[2 * n + i] = 0.0;
  }
  EXPECT_LT(std::abs(phi(R)), 1e-14);
}

TEST(Bending, SphereIsInEquilibriumWithAndWithoutSpontaneousCurvature) {
  // Eq. (84): 8H^3 - 4HR = 0 and lap H = 0 on a sphere; with H' = H the energy density vanishes.
  ShCell cell;
  const std::vector<double> X = ellipsoid(2, 2, 2).points(cell.interp);
  for (double H0 : {0.0, -0.5}) {
    const auto F = bending_force_density("sphere", *cell.at_data, *cell.ops, X, cell.Z, BendingModel{1.0, H0, {}});
    EXPECT_LT(max_abs(F), 1e-11) << H0;
  }
  const auto F = bending_force_density("sphere", *cell.at_data, *cell.ops, X, cell.Z, BendingModel{1.0, -1.0, {}});
  EXPECT_GT(max_abs(F), 0.1);  // H' != H: a nonzero normal force
}

TEST(Bending, IsMinusTheDerivativeOfTheBendingEnergy) {
  // Near-spherical shape X = sphere + eps * (smooth perturbation), eps = 1e-2: H is reconstructed
  // from its values at the 49 data sites, whose interpolation error is O(eps^2) while the force is
  // O(eps), so agreement to a few percent of the largest component is what the method promises.
  // A sign or factor error in eq. (84) or in the H' terms shows up as an O(1) mismatch.
  ShCell cell;
  const PerturbedEllipsoid shape{1.01, 1.0, 0.99, 0.01, 1.0};
  const std::vector<double> X0 = shape.points(cell.interp);
  for (double H0 : {0.0, -0.7}) {
    const BendingModel m{1.0, H0, {}};
    auto energy = [&](const std::vector<double>& X) {
      return bending_energy("fd", jets_from_operators(*cell.ops, X), cell.Z, m, cell.w);
    };
    const std::vector<double> g = fd_gradient(energy, X0, 1e-6, X0.size() / 3);
    const std::vector<double> p = cell.project(
        forces_from_density(bending_force_density("fd", *cell.at_data, *cell.ops, X0, cell.Z, m), cell.w));
    const double scale = max_abs(g);
    ASSERT_GT(scale, 1e-4);
    double err = 0;
    for (std::size_t i = 0; i < g.size() / 3; ++i) err = std::max(err, std::abs(p[i] + g[i]));
    EXPECT_LT(err, 0.05 * scale) << "H' = " << H0;
  }
}

TEST(Bending, PerSiteSpontaneousCurvatureIsMinusTheDerivativeOfItsEnergy) {
  // H' a material field (a platelet prefers its reference curvature): the force gains lap_s H'
  // and a tangential term 2 (H - H') grad_s H'. Same shape and tolerance as the constant-H' test;
  // the tangential term alone is checked to matter, so dropping it would fail.
  ShCell cell;
  const PerturbedEllipsoid shape{1.01, 1.0, 0.99, 0.01, 1.0};
  const std::vector<double> X0 = shape.points(cell.interp);
  BendingModel m{1.0, 0.0, {}};
  for (index_t i = 0; i < cell.interp.size(); ++i)
    m.H0_data.push_back(-0.7 + 0.4 * std::sin(cell.interp.theta[i]) +
                        0.3 * std::cos(cell.interp.lambda[i]) * std::cos(cell.interp.theta[i]));
  auto energy = [&](const std::vector<double>& X) {
    return bending_energy("fd", jets_from_operators(*cell.ops, X), cell.Z, m, cell.w, cell.ops.get());
  };
  const std::vector<double> g = fd_gradient(energy, X0, 1e-6);
  const std::vector<double> F = bending_force_density("fd", *cell.at_data, *cell.ops, X0, cell.Z, m);
  const std::vector<double> p = cell.project(forces_from_density(F, cell.w));
  const double scale = max_abs(g);
  ASSERT_GT(scale, 1e-3);
  double err = 0;
  for (std::size_t i = 0; i < g.size(); ++i) err = std::max(err, std::abs(p[i] + g[i]));
  EXPECT_LT(err, 0.05 * scale);
  // Without the tangential term the mismatch is O(1).
  std::vector<double> Fn = F;
  const std::vector<Jet> Xs = jets_from_operators(*cell.ops, X0);
  const std::size_t ns = Xs.size();
  for (std::size_t i = 0; i < ns; ++i) {
    const PointGeometry gi = point_geometry(Xs[i]);
    const double fn = Fn[i] * gi.n[0] + Fn[ns + i] * gi.n[1] + Fn[2 * ns + i] * gi.n[2];
    for (std::size_t d = 0; d < 3; ++d) Fn[d * ns + i] = fn * gi.n[d];
  }
  const std::vector<double> pn = cell.project(forces_from_density(Fn, cell.w));
  double err_normal_only = 0;
  for (std::size_t i = 0; i < g.size(); ++i) err_normal_only = std::max(err_normal_only, std::abs(pn[i] + g[i]));
  EXPECT_GT(err_normal_only, 0.2 * scale);
  // Wrong length of the per-site field: a named input error.
  BendingModel bad = m;
  bad.H0_data.pop_back();
  EXPECT_THROW(bending_force_density("bad", *cell.at_data, *cell.ops, X0, cell.Z, bad), InputError);
}

TEST(Ldsm, ForceIsMinusTheDerivativeOfTheTriangulatedEnergy) {
  // Eq. (66) is the exact gradient of eq. (64): central differences (h = 1e-6) agree to ~1e-9.
  const SphereSites s = bauer_spiral(60);
  const auto T = sphere_triangulation(s);
  const std::vector<double> Z = ellipsoid(1, 1, 1).points(s);
  const std::vector<double> X0 = paper_perturbed_ellipsoid().points(s);
  for (const auto& e : all_energies()) {
    auto energy = [&](const std::vector<double>& X) { return ldsm_forces("fd", T, Z, X, e).energy; };
    const std::vector<double> g = fd_gradient(energy, X0, 1e-6);
    const LdsmResult r = ldsm_forces("fd", T, Z, X0, e);
    const double scale = max_abs(r.F);
    double sum[3] = {0, 0, 0};
    for (std::size_t i = 0; i < g.size(); ++i) {
      EXPECT_NEAR(r.F[i], -g[i], 1e-7 * scale) << e.name();
      sum[i / s.size()] += r.F[i];
    }
    // Translation invariance: forces sum to zero to rounding (n eps scale).
    for (double v : sum) EXPECT_LT(std::abs(v), 1e-12 * scale * 60);
  }
}

TEST(Ldsm, AreaWeightsSumToThePolyhedronArea) {
  const SphereSites s = bauer_spiral(200);
  const auto T = sphere_triangulation(s);
  const std::vector<double> w = ldsm_area_weights(T, ellipsoid(1, 1, 1).points(s));
  double sum = 0;
  for (double v : w) sum += v;
  EXPECT_LT(sum, 4 * pi);
  EXPECT_GT(sum, 4 * pi * (1 - 4.0 / 200));
}

TEST(Ldsm, DegenerateAndInvertedTrianglesRaiseNamedErrors) {
  const SphereSites s = bauer_spiral(40);
  const auto T = sphere_triangulation(s);
  const std::vector<double> Z = ellipsoid(1, 1, 1).points(s);
  std::vector<double> X = Z;
  const auto t = T[5];
  for (index_t d = 0; d < 3; ++d) X[d * s.size() + t[1]] = X[d * s.size() + t[0]];  // coincident vertices
  try {
    ldsm_forces("platelet-1", T, Z, X, EnergyDensity::surface_tension(1));
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("platelet-1"), std::string::npos);
  }
  X = Z;
  for (index_t i = 0; i < s.size(); ++i) X[2 * s.size() + i] = -Z[2 * s.size() + i];  // mirror z -> -z flips equatorial triangles
  EXPECT_THROW(ldsm_forces("platelet-1", T, Z, X, EnergyDensity::surface_tension(1)), NumericalError);
}

TEST(Tether, DampedSpringForceIsMinusTheEnergyGradient) {
  // W = k/2 |X - X'|^2 + eta/2 |U - U'|^2 (eq. 2.10): F = -dW/dX - dW/dU.
  const std::vector<double> X = {1, 2, 3}, Xp = {0.5, 2.5, 3}, U = {0.1, 0, -0.2}, Up = {0, 0, 0};
  const auto F = tether_force_density(X, Xp, U, Up, 2.0, 0.5);
  for (int d = 0; d < 3; ++d) EXPECT_DOUBLE_EQ(F[d], -2.0 * (X[d] - Xp[d]) - 0.5 * (U[d] - Up[d]));
  EXPECT_THROW(tether_force_density(X, Xp, {}, {}, -1.0, 0.0), InputError);
}

namespace rbfib::mechanics {
namespace {

TEST(EnergyLaws, NameTheirShearModulusAndParametersAsTheSceneDoes) {
  // Skalak (2.11) and neo-Hookean (2.12): E is the shear modulus, G the bulk; (68): Gs and A;
  // a tension law (72) resists no shear.
  EXPECT_EQ(EnergyDensity::skalak(2.5e-3, 2.5e-1).shear_modulus(), 2.5e-3);
  EXPECT_EQ(EnergyDensity::neo_hookean_dissertation(4e-3, 1e-1).shear_modulus(), 4e-3);
  EXPECT_EQ(EnergyDensity::neo_hookean_paper(3e-3, 2.0).shear_modulus(), 3e-3);
  EXPECT_EQ(EnergyDensity::surface_tension(4e-2).shear_modulus(), 0.0);
  const std::vector<EnergyDensity::Parameter> p = EnergyDensity::skalak(2.5e-3, 2.5e-1).parameters();
  ASSERT_EQ(p.size(), 2u);
  EXPECT_STREQ(p[1].name, "G");
  EXPECT_EQ(p[1].value, 2.5e-1);
  EXPECT_STREQ(p[1].units, "dyn/cm");
  EXPECT_STREQ(EnergyDensity::neo_hookean_paper(3e-3, 2.0).parameters()[1].units, "");
  EXPECT_STREQ(EnergyDensity::surface_tension(4e-2).parameters()[0].name, "sigma");
}

}  // namespace
}  // namespace rbfib::mechanics
